// Checks on encoded images before decoding.
#include "ImageChecks.h"

#include "JpegDecoder.h"

#include <stb_image.h>
#include <webp/decode.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

namespace asset::detail {
namespace {

std::uint32_t bigEndian32(const std::uint8_t* p) {
    return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 |
           std::uint32_t(p[3]);
}

} // namespace

ImageKind imageKind(std::span<const std::uint8_t> bytes) {
    auto startsWith = [&](std::string_view magic) {
        return bytes.size() >= magic.size() &&
               std::memcmp(bytes.data(), magic.data(), magic.size()) == 0;
    };
    if (startsWith("\x89PNG\r\n\x1a\n"))
        return ImageKind::Png;
    if (startsWith("\xff\xd8\xff"))
        return ImageKind::Jpeg;
    if (startsWith("#?RADIANCE") || startsWith("#?RGBE"))
        return ImageKind::Radiance;
    if (bytes.size() >= 12 && std::memcmp(bytes.data(), "RIFF", 4) == 0 &&
        std::memcmp(bytes.data() + 8, "WEBP", 4) == 0)
        return ImageKind::Webp;
    if (startsWith("\xabKTX 20\xbb\r\n\x1a\n"))
        return ImageKind::Ktx2;
    return ImageKind::Other;
}

ImageHeader readImageHeader(ImageKind kind, std::span<const std::uint8_t> bytes) {
    ImageHeader header;
    if (kind == ImageKind::Jpeg) {
        const Jpeg jpeg = jpegHeader(bytes);
        header = {jpeg.width, jpeg.height, jpeg.error};
    } else if (kind == ImageKind::Webp) {
        // libwebp reads a file cut short as far as it goes (for streaming): the RIFF header's
        // size is checked here, so that every tool, decoding or not, refuses such a file.
        const std::uint64_t declared = std::uint64_t(bytes[4]) | std::uint64_t(bytes[5]) << 8 |
                                       std::uint64_t(bytes[6]) << 16 |
                                       std::uint64_t(bytes[7]) << 24;
        if (declared + 8 > bytes.size())
            header.unreadable = "its RIFF header declares " + std::to_string(declared + 8) +
                                " bytes, the image has " + std::to_string(bytes.size());
        else if (!WebPGetInfo(bytes.data(), bytes.size(), &header.width, &header.height))
            header.unreadable = "not a valid WebP image";
    } else if (kind == ImageKind::Png) {
        // The size from IHDR itself: stb refuses sizes it finds implausible with a reason that
        // a later format's probe overwrites ("unknown image type"), while the limits below
        // have a message of their own.
        if (bytes.size() < 24 || std::memcmp(bytes.data() + 12, "IHDR", 4) != 0) {
            header.unreadable = "a PNG without an IHDR chunk first";
        } else {
            const std::uint32_t width = bigEndian32(&bytes[16]), height = bigEndian32(&bytes[20]);
            header.width = int(std::min<std::uint32_t>(width, INT32_MAX));
            header.height = int(std::min<std::uint32_t>(height, INT32_MAX));
        }
    } else {
        int components = 0;
        if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &header.width, &header.height,
                                   &components))
            header.unreadable = stbi_failure_reason() ? stbi_failure_reason() : "unknown format";
    }
    return header;
}

std::optional<std::string> implausibleSize(int width, int height, std::size_t encodedBytes) {
    const std::uint64_t pixels =
        std::uint64_t(std::max(width, 0)) * std::uint64_t(std::max(height, 0));
    if (pixels <= 16384u * std::uint64_t(encodedBytes) + 65536u)
        return std::nullopt;
    return std::to_string(width) + "x" + std::to_string(height) + " pixels cannot come from " +
           std::to_string(encodedBytes) + " bytes of image data (corrupt header)";
}

std::optional<std::string> checkPngStream(std::span<const std::uint8_t> bytes) {
    static constexpr std::array<std::uint8_t, 8> kSignature = {0x89, 'P',  'N',  'G',
                                                               '\r', '\n', 0x1A, '\n'};
    if (bytes.size() < 8 || std::memcmp(bytes.data(), kSignature.data(), 8) != 0)
        return std::nullopt;
    std::uint64_t width = 0, height = 0, bitsPerPixel = 0;
    bool interlaced = false;
    std::vector<std::uint8_t> stream;
    for (std::size_t at = 8; at + 12 <= bytes.size();) {
        const std::uint32_t length = bigEndian32(&bytes[at]);
        if (length > bytes.size() - at - 12)
            return "a PNG chunk runs past the end of the data";
        const std::uint8_t* type = &bytes[at + 4];
        const std::uint8_t* data = &bytes[at + 8];
        if (std::memcmp(type, "IHDR", 4) == 0 && length >= 13) {
            width = bigEndian32(data);
            height = bigEndian32(data + 4);
            const std::uint64_t depth = data[8];
            const int colour = data[9];
            const std::uint64_t channels = colour == 2 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 1;
            bitsPerPixel = depth * channels;
            interlaced = data[12] != 0;
        } else if (std::memcmp(type, "IDAT", 4) == 0) {
            stream.insert(stream.end(), data, data + length);
        } else if (std::memcmp(type, "IEND", 4) == 0) {
            break;
        }
        at += 12 + std::size_t(length);
    }
    if (width == 0 || height == 0 || bitsPerPixel == 0)
        return "a PNG without a valid IHDR chunk";
    // Filtered scanlines: a filter byte per row; interlacing adds at most a row per pass.
    const std::uint64_t rowBytes = (width * bitsPerPixel + 7) / 8;
    const std::uint64_t expected =
        height * (rowBytes + 1) + (interlaced ? 7 * (height + rowBytes + 2) : 0);

    z_stream z{};
    if (inflateInit(&z) != Z_OK)
        return "zlib could not start";
    std::array<std::uint8_t, 16384> scratch{};
    z.next_in = stream.data();
    z.avail_in = uInt(stream.size());
    std::uint64_t produced = 0;
    int status = Z_OK;
    while (status == Z_OK) {
        z.next_out = scratch.data();
        z.avail_out = uInt(scratch.size());
        status = inflate(&z, Z_NO_FLUSH);
        produced += scratch.size() - z.avail_out;
        if (produced > expected) {
            inflateEnd(&z);
            return "PNG image data inflates past the " + std::to_string(expected) +
                   " bytes its header needs";
        }
        if (status == Z_BUF_ERROR && z.avail_in == 0)
            break; // the input ended before the stream did
    }
    inflateEnd(&z);
    if (status != Z_STREAM_END)
        return "PNG image data is not a complete zlib stream";
    return std::nullopt;
}

} // namespace asset::detail
