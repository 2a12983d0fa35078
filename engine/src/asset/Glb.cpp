// GLB encoding (the loader decodes and checks GLB in GltfLoader.cpp).
#include "engine/asset/Glb.h"

namespace asset {
namespace {

void appendU32(std::vector<std::uint8_t>& out, std::uint32_t value) {
    for (int shift = 0; shift < 32; shift += 8)
        out.push_back(std::uint8_t(value >> shift));
}

} // namespace

std::vector<std::uint8_t> encodeGlb(const std::string& json, std::span<const std::uint8_t> bin) {
    const std::size_t jsonPadded = (json.size() + 3) / 4 * 4;
    const std::size_t binPadded = (bin.size() + 3) / 4 * 4;
    const std::size_t total = 12 + 8 + jsonPadded + (bin.empty() ? 0 : 8 + binPadded);
    std::vector<std::uint8_t> out;
    out.reserve(total);
    appendU32(out, 0x46546C67u); // "glTF"
    appendU32(out, 2);
    appendU32(out, std::uint32_t(total));
    appendU32(out, std::uint32_t(jsonPadded));
    appendU32(out, 0x4E4F534Au); // "JSON"
    out.insert(out.end(), json.begin(), json.end());
    out.resize(out.size() + jsonPadded - json.size(), ' ');
    if (!bin.empty()) {
        appendU32(out, std::uint32_t(binPadded));
        appendU32(out, 0x004E4942u); // "BIN\0"
        out.insert(out.end(), bin.begin(), bin.end());
        out.resize(out.size() + binPadded - bin.size(), 0);
    }
    return out;
}

} // namespace asset
