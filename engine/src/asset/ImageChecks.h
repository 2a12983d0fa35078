// Checks on encoded images before a decoder sees them: stb (PNG, Radiance) trusts a file's header
// and its zlib streams, so a tiny file could otherwise make it allocate gigabytes.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace asset::detail {

/** The encodings the engine knows, by their signature: glTF images are PNG or JPEG (the core
 *  spec's two MIME types), WebP (EXT_texture_webp, decoded by libwebp) or KTX2
 *  (KHR_texture_basisu, recognised but not decoded); environments Radiance HDR, PNG or JPEG.
 *  Everything else is refused before stb sees it: its other decoders (PNM, PSD, TGA, GIF, ...)
 *  are not needed, and fuzzing found a heap overflow through its 16-bit PNM path. */
enum class ImageKind { Png, Jpeg, Radiance, Webp, Ktx2, Other };
ImageKind imageKind(std::span<const std::uint8_t> bytes);

/** The size in an image's header (PNG, Radiance: stb; JPEG: libjpeg-turbo; WebP: libwebp), read
 *  without decoding the pixels, or why it cannot be read (`unreadable` not empty). */
struct ImageHeader {
    int width = 0, height = 0;
    std::string unreadable;
};
ImageHeader readImageHeader(ImageKind kind, std::span<const std::uint8_t> bytes);

/** Refuses a width x height that no file of `encodedBytes` could hold. Real images stay far
 *  below the bound (16384 pixels per encoded byte: past deflate's 1032:1 limit on 8-bit PNG
 *  data and the run-length limit of Radiance files); a header that claims more is a lie that
 *  would cost an allocation of that size. Returns the reason, or nullopt when plausible. */
std::optional<std::string> implausibleSize(int width, int height, std::size_t encodedBytes);

/** For PNG data: inflates the concatenated IDAT chunks with zlib, without keeping the output,
 *  and refuses a stream that is corrupt, ends early, or inflates to more than the header's
 *  size can need (stb's own inflater would keep growing its buffer on such input). Returns
 *  the reason, or nullopt when the data is not PNG or is sound. */
std::optional<std::string> checkPngStream(std::span<const std::uint8_t> bytes);

} // namespace asset::detail
