// Fuzz target: scene files from bytes (asset::parseScene). Built for libFuzzer with the "fuzz"
// preset (clang); otherwise Replay.cpp drives it over files.
#include "engine/asset/SceneFile.h"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // Model paths resolve against a folder that does not exist: only builtin: models load, so
    // the input's own bytes are what is parsed and checked.
    auto world = asset::parseScene(std::string_view(reinterpret_cast<const char*>(data), size),
                                   "/nonexistent-glass-fuzz-dir", "fuzz-input.json");
    (void)world;
    return 0;
}
