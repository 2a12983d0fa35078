// glTF images: the loader's image callback, which bounds every image's size (its header read by
// ImageChecks.h) before decoding it with the decoder for its format (PNG: stb after zlib checks its
// stream; JPEG: libjpeg-turbo; WebP: libwebp) and keeps KTX2 images undecoded.
#include "GltfConvert.h"
#include "ImageChecks.h"
#include "JpegDecoder.h"
#include "engine/core/Limits.h"

#include <stb_image.h>
#include <webp/decode.h>

namespace asset::detail {
namespace {

/** Decodes into `image` (its size and bit depth set already): RGBA of its bit depth. Returns
 *  why it could not, or an empty string. */
std::string decodePixels(ImageKind kind, std::span<const std::uint8_t> bytes,
                         tinygltf::Image& image) {
    if (kind == ImageKind::Jpeg) {
        Jpeg jpeg = decodeJpeg(bytes, 4);
        image.image = std::move(jpeg.pixels);
        return jpeg.error;
    }
    if (kind == ImageKind::Webp) {
        image.image.resize(std::size_t(image.width) * std::size_t(image.height) * 4u);
        return WebPDecodeRGBAInto(bytes.data(), bytes.size(), image.image.data(),
                                  image.image.size(), image.width * 4)
                   ? ""
                   : "corrupt WebP data";
    }
    const int size = int(bytes.size());
    int w = 0, h = 0, c = 0;
    void* pixels =
        image.bits == 16
            ? static_cast<void*>(stbi_load_16_from_memory(bytes.data(), size, &w, &h, &c, 4))
            : static_cast<void*>(stbi_load_from_memory(bytes.data(), size, &w, &h, &c, 4));
    if (!pixels)
        return stbi_failure_reason() ? stbi_failure_reason() : "corrupt data";
    const std::size_t byteCount =
        std::size_t(w) * std::size_t(h) * 4u * std::size_t(image.bits / 8);
    image.image.assign(static_cast<unsigned char*>(pixels),
                       static_cast<unsigned char*>(pixels) + byteCount);
    stbi_image_free(pixels);
    return "";
}

} // namespace

bool decodeImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                 const unsigned char* data, int size, void* userData) {
    ImageDecoding& options = *static_cast<ImageDecoding*>(userData);
    const std::span<const std::uint8_t> bytes(data, std::size_t(size));
    const std::string name = "image " + std::to_string(index);
    const ImageKind kind = imageKind(bytes);
    if (kind == ImageKind::Ktx2) {
        options.ktx2.insert(index);
        return true;
    }
    if (kind != ImageKind::Png && kind != ImageKind::Jpeg && kind != ImageKind::Webp) {
        *err += name + " is neither PNG, JPEG, WebP nor KTX2";
        return false;
    }
    const ImageHeader header = readImageHeader(kind, bytes);
    if (!header.unreadable.empty()) {
        *err += name + " could not be decoded: " + header.unreadable;
        return false;
    }
    if (header.width <= 0 || header.height <= 0 || header.width > core::limits::kMaxTextureSize ||
        header.height > core::limits::kMaxTextureSize) {
        *err += name + " is " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                ", over the limit of " + std::to_string(core::limits::kMaxTextureSize);
        return false;
    }
    auto refuse = implausibleSize(header.width, header.height, bytes.size());
    if (!refuse)
        refuse = checkPngStream(bytes);
    if (refuse) {
        *err += name + ": " + *refuse;
        return false;
    }
    image->width = header.width;
    image->height = header.height;
    image->component = 4;
    image->bits = kind == ImageKind::Png && stbi_is_16_bit_from_memory(data, size) ? 16 : 8;
    image->pixel_type = image->bits == 16 ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                                          : TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    if (!options.decode)
        return true;
    const std::string corrupt = decodePixels(kind, bytes, *image);
    if (!corrupt.empty()) {
        image->image.clear();
        *err += name + " could not be decoded: " + corrupt;
        return false;
    }
    return true;
}

} // namespace asset::detail
