// Fuzz target: KHR_draco_mesh_compression. The input's first 4 bytes are the vertex count and
// the next 4 the triangle count the glTF accessors claim (each modulo 2^20); the rest is the Draco
// stream, wrapped in a GLB whose one primitive has POSITION, NORMAL, TEXCOORD_0, JOINTS_0 and
// WEIGHTS_0 in the stream (Draco attributes 0..4) and a morph target beside it, as exporters
// write them. It goes through the loader exactly as a shipped file would.
#include "LoadGlb.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 8)
        return 0;
    std::uint32_t vertices = 0, triangles = 0;
    std::memcpy(&vertices, data, 4);
    std::memcpy(&triangles, data + 4, 4);
    vertices %= 1u << 20;
    triangles %= 1u << 20;
    const std::span<const std::uint8_t> stream(data + 8, size - 8);
    const std::string n = std::to_string(vertices);
    // Buffer: the Draco stream, then 12 bytes a vertex of zero morph deltas.
    const std::size_t deltas = std::size_t(vertices) * 12;
    const std::string json =
        R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_draco_mesh_compression"],)"
        R"("extensionsRequired":["KHR_draco_mesh_compression"],)"
        R"("buffers":[{"byteLength":)" +
        std::to_string(stream.size() + deltas) +
        R"(}],)"
        R"("bufferViews":[{"buffer":0,"byteLength":)" +
        std::to_string(stream.size()) +
        R"(},)"
        R"({"buffer":0,"byteOffset":)" +
        std::to_string(stream.size()) + R"(,"byteLength":)" + std::to_string(deltas) +
        R"(}],)"
        R"("accessors":[{"componentType":5126,"count":)" +
        n +
        R"(,"type":"VEC3"},)"
        R"({"componentType":5126,"count":)" +
        n +
        R"(,"type":"VEC3"},)"
        R"({"componentType":5126,"count":)" +
        n +
        R"(,"type":"VEC2"},)"
        R"({"componentType":5121,"count":)" +
        n +
        R"(,"type":"VEC4"},)"
        R"({"componentType":5126,"count":)" +
        n +
        R"(,"type":"VEC4"},)"
        R"({"componentType":5125,"count":)" +
        std::to_string(std::uint64_t(triangles) * 3) +
        R"(,"type":"SCALAR"},)"
        R"({"bufferView":1,"componentType":5126,"count":)" +
        n +
        R"(,"type":"VEC3"}],)"
        R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2,)"
        R"("JOINTS_0":3,"WEIGHTS_0":4},"indices":5,"targets":[{"POSITION":6}],)"
        R"("extensions":{"KHR_draco_mesh_compression":{"bufferView":0,"attributes":)"
        R"({"POSITION":0,"NORMAL":1,"TEXCOORD_0":2,"JOINTS_0":3,"WEIGHTS_0":4}}}}]}],)"
        R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
    std::vector<std::uint8_t> bin(stream.begin(), stream.end());
    bin.resize(stream.size() + deltas, 0);
    fuzz::loadGlb(json, bin, "fuzz-draco.glb");
    return 0;
}
