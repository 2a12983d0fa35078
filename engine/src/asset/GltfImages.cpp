// glTF images: the loader's image callback, which bounds every image's size before decoding it
// with the decoder for its format (PNG: stb after zlib checks its stream; JPEG: libjpeg-turbo;
// WebP: libwebp) and keeps KTX2 images undecoded.
#include "GltfConvert.h"
#include "ImageChecks.h"
#include "JpegDecoder.h"
#include "engine/core/Limits.h"

#include <stb_image.h>
#include <webp/decode.h>

namespace asset::detail {
namespace {

/** Decodes WebP to RGBA8 with libwebp after the same size checks as the other formats. */
bool decodeWebp(tinygltf::Image* image, int index, std::string* err, const unsigned char* bytes,
                int size, bool decode) {
    int width = 0, height = 0;
    if (!WebPGetInfo(bytes, std::size_t(size), &width, &height)) {
        *err += "image " + std::to_string(index) + " is not a valid WebP image";
        return false;
    }
    if (width > core::limits::kMaxTextureSize || height > core::limits::kMaxTextureSize) {
        *err += "image " + std::to_string(index) + " is " + std::to_string(width) + "x" +
                std::to_string(height) + ", over the limit of " +
                std::to_string(core::limits::kMaxTextureSize);
        return false;
    }
    if (auto refuse = detail::implausibleSize(width, height, std::size_t(size))) {
        *err += "image " + std::to_string(index) + ": " + *refuse;
        return false;
    }
    image->width = width;
    image->height = height;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    if (!decode)
        return true;
    image->image.resize(std::size_t(width) * std::size_t(height) * 4u);
    if (!WebPDecodeRGBAInto(bytes, std::size_t(size), image->image.data(), image->image.size(),
                            width * 4)) {
        *err += "image " + std::to_string(index) + " could not be decoded: corrupt WebP data";
        return false;
    }
    return true;
}

} // namespace

bool decodeImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                 const unsigned char* bytes, int size, void* userData) {
    ImageDecoding& options = *static_cast<ImageDecoding*>(userData);
    const bool decode = options.decode;
    const detail::ImageKind kind = detail::imageKind(std::span(bytes, std::size_t(size)));
    if (kind == detail::ImageKind::Ktx2) {
        options.ktx2.insert(index);
        return true;
    }
    if (kind == detail::ImageKind::Webp)
        return decodeWebp(image, index, err, bytes, size, decode);
    if (kind != detail::ImageKind::Png && kind != detail::ImageKind::Jpeg) {
        *err += "image " + std::to_string(index) + " is neither PNG, JPEG, WebP nor KTX2";
        return false;
    }
    const std::span<const std::uint8_t> encoded(bytes, std::size_t(size));
    int width = 0, height = 0, components = 0;
    if (kind == detail::ImageKind::Jpeg) {
        const detail::Jpeg header = detail::jpegHeader(encoded);
        if (!header.error.empty()) {
            *err += "image " + std::to_string(index) + " could not be decoded: " + header.error;
            return false;
        }
        width = header.width;
        height = header.height;
    } else if (!stbi_info_from_memory(bytes, size, &width, &height, &components)) {
        *err += "image " + std::to_string(index) + " could not be decoded: " +
                (stbi_failure_reason() ? stbi_failure_reason() : "unknown format");
        return false;
    }
    if (width <= 0 || height <= 0 || width > core::limits::kMaxTextureSize ||
        height > core::limits::kMaxTextureSize) {
        *err += "image " + std::to_string(index) + " is " + std::to_string(width) + "x" +
                std::to_string(height) + ", over the limit of " +
                std::to_string(core::limits::kMaxTextureSize);
        return false;
    }
    auto refuse = detail::implausibleSize(width, height, std::size_t(size));
    if (!refuse)
        refuse = detail::checkPngStream(std::span(bytes, std::size_t(size)));
    if (refuse) {
        *err += "image " + std::to_string(index) + ": " + *refuse;
        return false;
    }
    image->width = width;
    image->height = height;
    image->component = 4;
    image->bits =
        kind == detail::ImageKind::Png && stbi_is_16_bit_from_memory(bytes, size) ? 16 : 8;
    image->pixel_type = image->bits == 16 ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                                          : TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    if (!decode)
        return true;
    if (kind == detail::ImageKind::Jpeg) {
        detail::Jpeg jpeg = detail::decodeJpeg(encoded, 4);
        if (!jpeg.error.empty()) {
            *err += "image " + std::to_string(index) + " could not be decoded: " + jpeg.error;
            return false;
        }
        image->image = std::move(jpeg.pixels);
        return true;
    }
    int w = 0, h = 0, c = 0;
    void* pixels = image->bits == 16
                       ? static_cast<void*>(stbi_load_16_from_memory(bytes, size, &w, &h, &c, 4))
                       : static_cast<void*>(stbi_load_from_memory(bytes, size, &w, &h, &c, 4));
    if (!pixels) {
        *err += "image " + std::to_string(index) + " could not be decoded: " +
                (stbi_failure_reason() ? stbi_failure_reason() : "corrupt data");
        return false;
    }
    const std::size_t byteCount =
        std::size_t(w) * std::size_t(h) * 4u * std::size_t(image->bits / 8);
    image->image.assign(static_cast<unsigned char*>(pixels),
                        static_cast<unsigned char*>(pixels) + byteCount);
    stbi_image_free(pixels);
    return true;
}

} // namespace asset::detail
