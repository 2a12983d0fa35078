// RGBA8 images on the CPU: PNG read/write (atomic) and comparison with a tolerance.
#pragma once

#include "engine/core/Result.h"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace capture {

/** RGBA8, rows top to bottom. */
struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;
};

/** `image` as PNG bytes; empty if encoding failed. */
std::vector<std::uint8_t> encodePng(const Image& image);
/** Encodes `image` as PNG and writes it atomically (no partial file on failure). */
core::Status writePng(const std::filesystem::path& path, const Image& image);
/** Reads a PNG or JPEG (any channel count, expanded to RGBA8); fails naming the file. */
core::Result<Image> readPng(const std::filesystem::path& path);

/** The images in a grid of `columns` (rows as needed), left to right then top to bottom, with
 *  a `gap` of dark grey: cells `cellWidth` wide and as high as the first image's aspect makes
 *  them, each image scaled to fit its cell whole (its aspect kept, nearest texel), centred. */
Image contactSheet(const std::vector<Image>& images, int columns, int cellWidth, int gap = 4);

struct Tolerance {
    int maxAbsDiff = 5;                ///< per channel, in 1/255
    double maxFailingFraction = 0.001; ///< of all pixels
};

struct Comparison {
    bool sizeMatches = true;
    int maxAbsDiff = 0; ///< over all pixels and channels
    std::size_t failingPixels = 0;
    double failingFraction = 0.0;
    bool passed = false;
    Image diff; ///< failing pixels red (brighter = larger), others dimmed grey
};

/** Per-pixel comparison: a pixel fails when any channel differs by more than maxAbsDiff. */
Comparison compare(const Image& actual, const Image& expected, const Tolerance& tolerance);

} // namespace capture
