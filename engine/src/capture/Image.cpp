// PNG I/O through stb and image comparison.
#include "engine/capture/Image.h"

#include "engine/core/Files.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cstdlib>

namespace capture {

std::vector<std::uint8_t> encodePng(const Image& image) {
    std::vector<std::uint8_t> png;
    const int ok = stbi_write_png_to_func(
        [](void* context, void* data, int size) {
            auto* out = static_cast<std::vector<std::uint8_t>*>(context);
            out->insert(out->end(), static_cast<std::uint8_t*>(data),
                        static_cast<std::uint8_t*>(data) + size);
        },
        &png, image.width, image.height, 4, image.rgba.data(), image.width * 4);
    if (!ok)
        png.clear();
    return png;
}

core::Status writePng(const std::filesystem::path& path, const Image& image) {
    const std::vector<std::uint8_t> png = encodePng(image);
    if (png.empty())
        return core::Error{"capture::writePng(): " + path.string() + ": PNG encoding failed"};
    return core::writeFileAtomic(path, png);
}

core::Result<Image> readPng(const std::filesystem::path& path) {
    auto bytes = core::readFile(path, std::uint64_t(1) << 30);
    if (!bytes)
        return core::Error{"capture::readPng(): " + bytes.error().message};
    int w = 0, h = 0, c = 0;
    std::uint8_t* pixels = stbi_load_from_memory(bytes->data(), int(bytes->size()), &w, &h, &c, 4);
    if (!pixels)
        return core::Error{"capture::readPng(): " + path.string() + ": not a decodable image"};
    Image image{w, h,
                std::vector<std::uint8_t>(pixels, pixels + std::size_t(w) * std::size_t(h) * 4u)};
    stbi_image_free(pixels);
    return image;
}

Comparison compare(const Image& actual, const Image& expected, const Tolerance& tolerance) {
    Comparison result;
    if (actual.width != expected.width || actual.height != expected.height) {
        result.sizeMatches = false;
        return result;
    }
    const std::size_t pixels = std::size_t(actual.width) * std::size_t(actual.height);
    result.diff = Image{actual.width, actual.height, std::vector<std::uint8_t>(pixels * 4u)};
    for (std::size_t i = 0; i < pixels; ++i) {
        int worst = 0;
        for (int c = 0; c < 4; ++c)
            worst = std::max(worst, std::abs(int(actual.rgba[i * 4 + std::size_t(c)]) -
                                             int(expected.rgba[i * 4 + std::size_t(c)])));
        result.maxAbsDiff = std::max(result.maxAbsDiff, worst);
        std::uint8_t* d = &result.diff.rgba[i * 4];
        if (worst > tolerance.maxAbsDiff) {
            ++result.failingPixels;
            d[0] = std::uint8_t(std::min(255, 128 + worst));
            d[1] = d[2] = 0;
        } else {
            const std::uint8_t grey = std::uint8_t(expected.rgba[i * 4 + 1] / 4);
            d[0] = d[1] = d[2] = grey;
        }
        d[3] = 255;
    }
    result.failingFraction = pixels ? double(result.failingPixels) / double(pixels) : 0.0;
    result.passed = result.failingFraction <= tolerance.maxFailingFraction;
    return result;
}

Image contactSheet(const std::vector<Image>& images, int columns, int cellWidth, int gap) {
    if (images.empty() || columns < 1 || cellWidth < 1)
        return {};
    const int cellHeight = std::max(1, cellWidth * images[0].height / std::max(images[0].width, 1));
    const int rows = (int(images.size()) + columns - 1) / columns;
    const int used = std::min(columns, int(images.size()));
    Image sheet{gap + used * (cellWidth + gap), gap + rows * (cellHeight + gap), {}};
    sheet.rgba.assign(std::size_t(sheet.width) * std::size_t(sheet.height) * 4u, 0);
    for (std::size_t i = 0; i < sheet.rgba.size(); i += 4)
        sheet.rgba[i] = sheet.rgba[i + 1] = sheet.rgba[i + 2] = 24, sheet.rgba[i + 3] = 255;
    for (std::size_t n = 0; n < images.size(); ++n) {
        // Each image fits its cell whole (its own aspect kept), centred.
        const Image& image = images[n];
        if (image.width < 1 || image.height < 1)
            continue;
        const double scale =
            std::min(double(cellWidth) / image.width, double(cellHeight) / image.height);
        const int w = std::max(1, int(image.width * scale)),
                  h = std::max(1, int(image.height * scale));
        const int x0 =
            gap + int(n % std::size_t(columns)) * (cellWidth + gap) + (cellWidth - w) / 2;
        const int y0 =
            gap + int(n / std::size_t(columns)) * (cellHeight + gap) + (cellHeight - h) / 2;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const int sx = std::min(image.width - 1, x * image.width / w);
                const int sy = std::min(image.height - 1, y * image.height / h);
                const std::size_t from =
                    (std::size_t(sy) * std::size_t(image.width) + std::size_t(sx)) * 4u;
                const std::size_t to =
                    (std::size_t(y0 + y) * std::size_t(sheet.width) + std::size_t(x0 + x)) * 4u;
                std::copy_n(image.rgba.begin() + std::ptrdiff_t(from), 4,
                            sheet.rgba.begin() + std::ptrdiff_t(to));
            }
    }
    return sheet;
}

} // namespace capture
