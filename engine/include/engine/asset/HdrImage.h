// Equirectangular HDR environments (Radiance .hdr, or any format stb decodes) as linear floats.
#pragma once

#include "engine/core/Result.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace asset {

/** Linear RGB floats, rows top to bottom (row 0 looks up, +y), longitude along x. */
struct HdrImage {
    int width = 0, height = 0;
    std::vector<float> rgb;
};

/** Decodes an HDR image. Fails naming the file when it is missing, does not decode, is not
 *  2:1-ish (width < height) or is over core::limits::kMaxTextureSize. */
core::Result<HdrImage> loadHdr(const std::filesystem::path& path);
/** What loadHdr() checks before decoding (the file readable, its kind, size and shape), without
 *  decoding it: loadScene() checks a scene's environment so. */
core::Status checkHdr(const std::filesystem::path& path);
/** loadHdr() over bytes in memory; `file` names them in errors. */
core::Result<HdrImage> decodeHdr(std::span<const std::uint8_t> bytes, const std::string& file);

/** Encodes `image` as a Radiance RGBE file's bytes (what loadHdr reads back). */
std::vector<std::uint8_t> encodeHdr(const HdrImage& image);

} // namespace asset
