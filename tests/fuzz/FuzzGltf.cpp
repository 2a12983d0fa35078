// Fuzz target: glTF import (.gltf JSON and .glb, chosen by content like the loader) from bytes.
// Built for libFuzzer with the "fuzz" preset (clang); otherwise Replay.cpp drives it over files.
#include "engine/asset/GltfLoader.h"

#include <cstddef>
#include <cstdint>
#include <span>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // External buffers and images resolve against a folder that does not exist: only the
    // input's own bytes are parsed.
    auto model = asset::loadGltfFromMemory(std::span(data, size), "fuzz-input",
                                           "/nonexistent-glass-fuzz-dir");
    (void)model;
    return 0;
}
