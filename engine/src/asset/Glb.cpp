// The GLB container: written (engine/asset/Glb.h) and read (GlbReader.h).
#include "engine/asset/Glb.h"

#include "GlbReader.h"
#include "LoadError.h"

#include <cstring>

namespace asset {
namespace {

void appendU32(std::vector<std::uint8_t>& out, std::uint32_t value) {
    for (int shift = 0; shift < 32; shift += 8)
        out.push_back(std::uint8_t(value >> shift));
}

std::uint32_t readU32(std::span<const std::uint8_t> bytes, std::size_t offset) {
    std::uint32_t v;
    std::memcpy(&v, bytes.data() + offset, 4);
    return v; // GLB is little-endian, as is every platform this engine builds for
}

} // namespace

namespace detail {

void checkGlbContainer(std::span<const std::uint8_t> bytes) {
    if (bytes.size() < 20)
        fail("GLB is truncated: " + std::to_string(bytes.size()) +
             " bytes, the header alone needs 20");
    const std::uint32_t version = readU32(bytes, 4);
    if (version != 2)
        fail("GLB version is " + std::to_string(version) + ", only version 2 is supported");
    const std::uint32_t length = readU32(bytes, 8);
    if (length != bytes.size())
        fail("GLB header declares " + std::to_string(length) + " bytes but the file has " +
             std::to_string(bytes.size()) + (length > bytes.size() ? " (truncated)" : ""));
    std::size_t offset = 12;
    for (int chunk = 0; offset < bytes.size(); ++chunk) {
        if (bytes.size() - offset < 8)
            fail("GLB chunk " + std::to_string(chunk) + " header is truncated");
        const std::uint64_t chunkLength = readU32(bytes, offset);
        const std::uint32_t type = readU32(bytes, offset + 4);
        if (chunkLength > bytes.size() - offset - 8)
            fail("GLB chunk " + std::to_string(chunk) + " declares " + std::to_string(chunkLength) +
                 " bytes, past the end of the file");
        if (chunk == 0 && type != 0x4E4F534Au)
            fail("GLB chunk 0 is not JSON");
        if (chunk == 1 && type != 0x004E4942u)
            fail("GLB chunk 1 is not BIN");
        offset += 8 + std::size_t(chunkLength);
    }
}

GlbChunks glbChunks(std::span<const std::uint8_t> bytes) {
    const std::size_t jsonLength = readU32(bytes, 12);
    GlbChunks chunks;
    chunks.json = std::string_view(reinterpret_cast<const char*>(bytes.data()) + 20, jsonLength);
    const std::size_t bin = 20 + jsonLength;
    if (bytes.size() - bin >= 8)
        chunks.bin = bytes.subspan(bin + 8, readU32(bytes, bin));
    return chunks;
}

} // namespace detail

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
