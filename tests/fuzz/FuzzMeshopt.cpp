// Fuzz target: EXT_meshopt_compression. The input's first byte picks the stream's mode and filter
// and the vertex size, the next 4 bytes the element count (modulo 2^20); the rest is the
// compressed stream, wrapped in a GLB whose one primitive reads the decoded view (positions for
// ATTRIBUTES, indices for TRIANGLES and INDICES) through a fallback buffer with no data, as
// gltfpack -cf writes it.
#include "LoadGlb.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 5)
        return 0;
    static const char* const kModes[] = {"ATTRIBUTES", "TRIANGLES", "INDICES"};
    static const char* const kFilters[] = {"NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"};
    const std::string mode = kModes[(data[0] & 3) % 3];
    const std::string filter = mode == "ATTRIBUTES" ? kFilters[(data[0] >> 2) & 3] : "NONE";
    const int stride =
        mode == "ATTRIBUTES" ? 4 * (1 + ((data[0] >> 4) & 3)) : (data[0] & 64 ? 4 : 2);
    std::uint32_t count = 0;
    std::memcpy(&count, data + 1, 4);
    count %= 1u << 20;
    const std::span<const std::uint8_t> stream(data + 5, size - 5);
    const std::string decoded = std::to_string(std::uint64_t(count) * std::uint64_t(stride));
    const bool attributes = mode == "ATTRIBUTES";
    // Positions: the decoded view as VEC3 of floats (12 of a 12- or 16-byte stride) or, for a
    // 4- or 8-byte stride, as normalized shorts (KHR_mesh_quantization); indices: the view.
    const std::string positionAccessor =
        stride >= 12 ? R"({"bufferView":1,"componentType":5126,"count":)" + std::to_string(count) +
                           R"(,"type":"VEC3"})"
                     : R"({"bufferView":1,"componentType":5122,"normalized":true,"count":)" +
                           std::to_string(count) + R"(,"type":"VEC3"})";
    const std::string json =
        R"({"asset":{"version":"2.0"},)"
        R"("extensionsUsed":["EXT_meshopt_compression","KHR_mesh_quantization"],)"
        R"("extensionsRequired":["EXT_meshopt_compression","KHR_mesh_quantization"],)"
        R"("buffers":[{"byteLength":)" +
        std::to_string(stream.size()) +
        R"(},)"
        R"({"byteLength":)" +
        decoded +
        R"(,"extensions":{"EXT_meshopt_compression":)"
        R"({"fallback":true}}}],)"
        R"("bufferViews":[{"buffer":0,"byteLength":)" +
        std::to_string(stream.size()) +
        R"(},)"
        R"({"buffer":1,"byteLength":)" +
        decoded + (attributes ? R"(,"byteStride":)" + std::to_string(stride) : std::string()) +
        R"(,"extensions":{"EXT_meshopt_compression":{"buffer":0,"byteLength":)" +
        std::to_string(stream.size()) + R"(,"byteStride":)" + std::to_string(stride) +
        R"(,"count":)" + std::to_string(count) + R"(,"mode":")" + mode + R"(","filter":")" +
        filter +
        R"("}}}],)"
        R"("accessors":[)" +
        (attributes
             ? positionAccessor
             : R"({"bufferView":1,"componentType":)" + std::string(stride == 4 ? "5125" : "5123") +
                   R"(,"count":)" + std::to_string(count) +
                   R"(,"type":"SCALAR"},)"
                   R"({"componentType":5126,"count":65536,"type":"VEC3"})") +
        R"(],"meshes":[{"primitives":[{"attributes":{"POSITION":)" + (attributes ? "0" : "1") +
        "}" + (attributes ? "" : R"(,"indices":0)") +
        R"(}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
    fuzz::loadGlb(json, stream, "fuzz-meshopt.glb");
    return 0;
}
