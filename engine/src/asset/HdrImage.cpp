// HDR environment decoding through stb_image (loadf).
#include "engine/asset/HdrImage.h"

#include "ImageChecks.h"
#include "JpegDecoder.h"
#include "engine/core/Files.h"
#include "engine/core/Limits.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <cmath>

namespace asset {

namespace {

/** What decodeHdr() checks before it decodes: the kind and size of the image. */
struct HdrHeader {
    detail::ImageKind kind;
    int width, height;
};

core::Result<HdrHeader> checkHeader(std::span<const std::uint8_t> bytes,
                                    const std::string& prefix) {
    if (bytes.size() > std::size_t(INT32_MAX))
        return core::Error{prefix + "file too large"};
    const detail::ImageKind kind = detail::imageKind(bytes);
    if (kind != detail::ImageKind::Png && kind != detail::ImageKind::Jpeg &&
        kind != detail::ImageKind::Radiance)
        return core::Error{prefix + "not a Radiance HDR, PNG or JPEG image"};
    const detail::ImageHeader header = detail::readImageHeader(kind, bytes);
    if (!header.unreadable.empty())
        return core::Error{prefix + "not a decodable image (" + header.unreadable + ")"};
    const int width = header.width, height = header.height;
    if (width > core::limits::kMaxTextureSize || height > core::limits::kMaxTextureSize)
        return core::Error{prefix + std::to_string(width) + "x" + std::to_string(height) +
                           " is over the texture limit of " +
                           std::to_string(core::limits::kMaxTextureSize)};
    if (auto refuse = detail::implausibleSize(width, height, bytes.size()))
        return core::Error{prefix + *refuse};
    if (auto refuse = detail::checkPngStream(bytes))
        return core::Error{prefix + *refuse};
    if (width < height || height < 2)
        return core::Error{prefix + std::to_string(width) + "x" + std::to_string(height) +
                           " is not an equirectangular (2:1) environment"};
    return HdrHeader{kind, width, height};
}

core::Result<std::vector<std::uint8_t>> readHdrFile(const std::filesystem::path& path) {
    auto bytes = core::readFile(path, std::uint64_t(1) << 30);
    if (!bytes)
        return core::Error{"asset::loadHdr(): " + path.filename().string() + ": " +
                           bytes.error().message};
    return bytes;
}

} // namespace

core::Result<HdrImage> loadHdr(const std::filesystem::path& path) {
    auto bytes = readHdrFile(path);
    if (!bytes)
        return bytes.error();
    return decodeHdr(*bytes, path.filename().string());
}

core::Status checkHdr(const std::filesystem::path& path) {
    auto bytes = readHdrFile(path);
    if (!bytes)
        return bytes.error();
    auto header = checkHeader(*bytes, "asset::loadHdr(): " + path.filename().string() + ": ");
    if (!header)
        return header.error();
    return {};
}

core::Result<HdrImage> decodeHdr(std::span<const std::uint8_t> data, const std::string& file) {
    const std::string prefix = "asset::loadHdr(): " + file + ": ";
    const std::span<const std::uint8_t>* bytes = &data;
    const auto header = checkHeader(data, prefix);
    if (!header)
        return header.error();
    const detail::ImageKind kind = header->kind;
    int width = header->width, height = header->height, components = 0;
    const int size = int(bytes->size());
    HdrImage image;
    image.width = width;
    image.height = height;
    const std::size_t values = std::size_t(width) * std::size_t(height) * 3u;
    if (kind == detail::ImageKind::Radiance) {
        float* pixels =
            stbi_loadf_from_memory(bytes->data(), size, &width, &height, &components, 3);
        if (!pixels)
            return core::Error{prefix + "decoding failed (" +
                               (stbi_failure_reason() ? stbi_failure_reason() : "corrupt data") +
                               ")"};
        image.rgb.assign(pixels, pixels + values);
        stbi_image_free(pixels);
    } else {
        // An 8-bit environment (PNG through stb, JPEG through libjpeg-turbo), linearised here.
        // stb's own conversion path (stbi_loadf on such files) crashed under fuzzing on a JPEG.
        std::vector<std::uint8_t> decoded;
        if (kind == detail::ImageKind::Jpeg) {
            detail::Jpeg jpeg = detail::decodeJpeg(*bytes, 3);
            if (!jpeg.error.empty())
                return core::Error{prefix + "decoding failed (" + jpeg.error + ")"};
            decoded = std::move(jpeg.pixels);
        } else {
            stbi_uc* pixels =
                stbi_load_from_memory(bytes->data(), size, &width, &height, &components, 3);
            if (!pixels)
                return core::Error{
                    prefix + "decoding failed (" +
                    (stbi_failure_reason() ? stbi_failure_reason() : "corrupt data") + ")"};
            decoded.assign(pixels, pixels + values);
            stbi_image_free(pixels);
        }
        image.rgb.resize(values);
        for (std::size_t i = 0; i < values; ++i) {
            const float c = float(decoded[i]) / 255.0f;
            image.rgb[i] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
        }
    }
    for (float& v : image.rgb)
        if (!std::isfinite(v) || v < 0.0f)
            v = 0.0f;
    return image;
}

std::vector<std::uint8_t> encodeHdr(const HdrImage& image) {
    std::vector<std::uint8_t> bytes;
    stbi_write_hdr_to_func(
        [](void* context, void* data, int size) {
            auto* out = static_cast<std::vector<std::uint8_t>*>(context);
            const auto* begin = static_cast<const std::uint8_t*>(data);
            out->insert(out->end(), begin, begin + size);
        },
        &bytes, image.width, image.height, 3, image.rgb.data());
    return bytes;
}

} // namespace asset
