// Fuzz target: image decoding. The input is decoded as an HDR environment (asset::decodeHdr),
// then as a glTF texture image: wrapped in a GLB whose only image is the input's bytes, so it
// goes through the loader's bounded image decoder exactly as an embedded PNG or JPEG would.
#include "LoadGlb.h"
#include "engine/asset/HdrImage.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::uint8_t> bytes(data, size);
    (void)asset::decodeHdr(bytes, "fuzz-input.hdr");
    const std::string json =
        R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":)" + std::to_string(size) +
        R"(}],"bufferViews":[{"buffer":0,"byteLength":)" + std::to_string(size) +
        R"(}],"images":[{"bufferView":0,"mimeType":"image/png"}]})";
    fuzz::loadGlb(json, bytes, "fuzz-image.glb");
    return 0;
}
