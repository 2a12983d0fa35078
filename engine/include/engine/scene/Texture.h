// Engine-owned images, samplers and textures (decoded pixels, 8 or 16 bits per channel).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace scene {

/** Decoded image: width x height texels of `components` channels of `bitsPerChannel` bits,
 *  rows top to bottom. */
struct Image {
    std::string name;
    std::string uri; ///< empty for embedded images
    int width = 0, height = 0, components = 0, bitsPerChannel = 8;
    std::vector<std::uint8_t> pixels;
};

/** GL enum values as glTF stores them (e.g. 9729 LINEAR, 10497 REPEAT); -1: unspecified. */
struct Sampler {
    int magFilter = -1, minFilter = -1;
    int wrapS = 10497, wrapT = 10497;
};

struct Texture {
    int image = -1;
    int sampler = -1;
};

} // namespace scene
