// Private to the asset module: JPEG decoding with libjpeg-turbo. stb's JPEG decoder read far out
// of bounds on a fuzzed file (and its float path crashed on another), so JPEG never reaches it.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace asset::detail {

/** What jpegHeader or decodeJpeg found; `error` is empty on success. */
struct Jpeg {
    int width = 0, height = 0;
    std::vector<std::uint8_t> pixels; ///< decodeJpeg: rows top to bottom, `channels` bytes each
    std::string error;
};

/** Reads the size from the header only (nothing the size of the image is allocated), so that
 *  callers can check it against the limits before decoding. */
Jpeg jpegHeader(std::span<const std::uint8_t> bytes);

/** Decodes to 8-bit RGB (`channels` 3) or RGBA (4, alpha 255). Refuses a progressive stream of
 *  more than 256 scans (each costs a pass over the whole image: a small file could take minutes)
 *  and reports libjpeg's own errors; its warnings (extraneous bytes, a stream cut short, which
 *  it fills with grey) are accepted, as viewers do. */
Jpeg decodeJpeg(std::span<const std::uint8_t> bytes, int channels);

} // namespace asset::detail
