// Compressed geometry: Draco primitives (libdraco) and meshopt buffer views (libmeshoptimizer)
// decoded into plain buffers before the loader reads accessors. Every size a compressed stream
// or the JSON claims is checked before it is allocated.
#include "GltfDecode.h"

#include "AccessorReader.h"
#include "GlbReader.h"
#include "LoadError.h"
#include "engine/asset/Glb.h"
#include "engine/core/Limits.h"

#include <draco/compression/decode.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <regex>
#include <string>

namespace asset::detail {
namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";
constexpr const char* kMeshopt[] = {"EXT_meshopt_compression", "KHR_meshopt_compression"};
/** Where prepareForParser keeps a Draco primitive's indices accessor for the decoder. */
constexpr const char* kDracoIndices = "glass.indices";

/** Meshopt's codecs expand at most this much (the vertex codec spends 2 bits on 16 bytes of
 *  zeros), so a claim beyond it is refused before the output is allocated. */
constexpr std::uint64_t kMeshoptMaxRatio = 64;

std::string n(std::uint64_t v) {
    return std::to_string(v);
}

/** A member of a tinygltf object, or nullptr. */
const tinygltf::Value* member(const tinygltf::Value& object, const char* key) {
    return object.IsObject() && object.Has(key) ? &object.Get(key) : nullptr;
}

std::int64_t integer(const tinygltf::Value& object, const char* key, std::int64_t fallback,
                     const std::string& what) {
    const tinygltf::Value* v = member(object, key);
    if (!v)
        return fallback;
    // Range first: converting a double outside int64's range is undefined.
    const double d = v->IsNumber() ? v->GetNumberAsDouble() : 0.5;
    if (!(d >= -9.0e15 && d <= 9.0e15) || d != std::floor(d))
        fail(what + " " + key + " is not an integer");
    return std::int64_t(d);
}

std::string text(const tinygltf::Value& object, const char* key, const std::string& fallback) {
    const tinygltf::Value* v = member(object, key);
    return v && v->IsString() ? v->Get<std::string>() : fallback;
}

/** Keeps the running total of decoded bytes under the model limit. */
class Budget {
public:
    void take(std::uint64_t bytes, const std::string& what) {
        if (bytes > core::limits::kMaxModelBytes - mUsed)
            fail(what + " decodes to " + n(bytes) + " bytes, over the limit of " +
                 n(core::limits::kMaxModelBytes) + " for a whole model");
        mUsed += bytes;
    }

private:
    std::uint64_t mUsed = 0;
};

/** The bytes of buffer view `index`, checked against its buffer. */
std::span<const std::uint8_t> viewBytes(const tinygltf::Model& model, std::int64_t index,
                                        const std::string& what) {
    if (index < 0 || std::uint64_t(index) >= model.bufferViews.size())
        fail(what + " references bufferView " + n(std::uint64_t(index)) + ", file has " +
             n(model.bufferViews.size()));
    const tinygltf::BufferView& view = model.bufferViews[std::size_t(index)];
    if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size())
        fail("bufferView " + n(std::uint64_t(index)) + " references buffer " +
             std::to_string(view.buffer) + ", file has " + n(model.buffers.size()));
    const std::vector<unsigned char>& data = model.buffers[std::size_t(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
        fail("bufferView " + n(std::uint64_t(index)) + " runs past the end of buffer " +
             std::to_string(view.buffer) + " (" + n(data.size()) + " bytes)");
    return {data.data() + view.byteOffset, view.byteLength};
}

/** A new buffer holding `data` and a tightly packed view over all of it; returns the view's
 *  index. */
int addView(tinygltf::Model& model, std::vector<unsigned char> data) {
    tinygltf::BufferView view;
    view.buffer = int(model.buffers.size());
    view.byteOffset = 0;
    view.byteLength = data.size();
    tinygltf::Buffer buffer;
    buffer.data = std::move(data);
    model.buffers.push_back(std::move(buffer));
    model.bufferViews.push_back(view);
    return int(model.bufferViews.size()) - 1;
}

// --- EXT_meshopt_compression --------------------------------------------------------------

/** An EXT_meshopt_compression stream as its extension object describes it. */
struct MeshoptStream {
    std::int64_t buffer, byteOffset, byteLength, stride, count;
    std::string mode, filter;
};

/** The stream `ext` describes, checked: within its buffer, its count within the limit, its
 *  mode, stride and filter among those the extension allows together. */
MeshoptStream readMeshoptStream(const tinygltf::Model& model, const tinygltf::Value& ext,
                                const std::string& what) {
    const MeshoptStream s{
        integer(ext, "buffer", -1, what),     integer(ext, "byteOffset", 0, what),
        integer(ext, "byteLength", -1, what), integer(ext, "byteStride", -1, what),
        integer(ext, "count", -1, what),      text(ext, "mode", ""),
        text(ext, "filter", "NONE")};
    if (s.buffer < 0 || std::uint64_t(s.buffer) >= model.buffers.size())
        fail(what + " references buffer " + std::to_string(s.buffer) + ", file has " +
             n(model.buffers.size()));
    const std::size_t bytes = model.buffers[std::size_t(s.buffer)].data.size();
    if (s.byteOffset < 0 || s.byteLength < 0 || std::uint64_t(s.byteOffset) > bytes ||
        std::uint64_t(s.byteLength) > bytes - std::uint64_t(s.byteOffset))
        fail(what + " (offset " + std::to_string(s.byteOffset) + ", length " +
             std::to_string(s.byteLength) + ") runs past the end of buffer " +
             std::to_string(s.buffer) + " (" + n(bytes) + " bytes)");
    if (s.count < 0 || std::uint64_t(s.count) > core::limits::kMaxVerticesPerPrimitive)
        fail(what + " count " + std::to_string(s.count) + " is not within 0.." +
             n(core::limits::kMaxVerticesPerPrimitive));
    if (s.mode == "ATTRIBUTES") {
        if (s.stride < 4 || s.stride > 256 || s.stride % 4 != 0)
            fail(what + " byteStride " + std::to_string(s.stride) +
                 " must be a multiple of 4 within 4..256 for ATTRIBUTES");
    } else if (s.mode == "TRIANGLES" || s.mode == "INDICES") {
        if (s.stride != 2 && s.stride != 4)
            fail(what + " byteStride " + std::to_string(s.stride) + " must be 2 or 4 for " +
                 s.mode);
        if (s.mode == "TRIANGLES" && s.count % 3 != 0)
            fail(what + " count " + std::to_string(s.count) +
                 " is not a multiple of 3 for TRIANGLES");
        if (s.filter != "NONE")
            fail(what + " filter " + s.filter + " applies to ATTRIBUTES only");
    } else {
        fail(what + " mode '" + s.mode + "' is not ATTRIBUTES, TRIANGLES or INDICES");
    }
    if (s.filter == "OCTAHEDRAL" && s.stride != 4 && s.stride != 8)
        fail(what + " OCTAHEDRAL filter needs byteStride 4 or 8, not " + std::to_string(s.stride));
    if (s.filter == "QUATERNION" && s.stride != 8)
        fail(what + " QUATERNION filter needs byteStride 8, not " + std::to_string(s.stride));
    if (s.filter != "NONE" && s.filter != "OCTAHEDRAL" && s.filter != "QUATERNION" &&
        s.filter != "EXPONENTIAL")
        fail(what + " filter '" + s.filter +
             "' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
    return s;
}

/** Stream `s` decoded from `source` into `out` (count x stride bytes), its filter undone. */
void decodeMeshoptStream(const MeshoptStream& s, const unsigned char* source,
                         std::vector<unsigned char>& out, const std::string& what) {
    const std::size_t size = std::size_t(s.byteLength), count = std::size_t(s.count),
                      stride = std::size_t(s.stride);
    int status = 0;
    if (s.mode == "ATTRIBUTES")
        status = meshopt_decodeVertexBuffer(out.data(), count, stride, source, size);
    else if (s.mode == "TRIANGLES")
        status = meshopt_decodeIndexBuffer(out.data(), count, stride, source, size);
    else
        status = meshopt_decodeIndexSequence(out.data(), count, stride, source, size);
    if (status != 0 && s.mode == "ATTRIBUTES" && size > 0 && (source[0] & 0xF0) == 0xA0 &&
        source[0] != 0xA0)
        fail(what + ": the stream is in version " + std::to_string(source[0] & 0x0F) +
             " of meshopt's vertex codec; the libmeshoptimizer this engine is built with (" +
             std::to_string(MESHOPTIMIZER_VERSION / 1000) + "." +
             std::to_string(MESHOPTIMIZER_VERSION % 1000 / 10) + ") decodes version 0");
    if (status != 0)
        fail(what + ": the " + s.mode + " stream is corrupt (meshopt error " +
             std::to_string(status) + ")");
    if (s.filter == "OCTAHEDRAL")
        meshopt_decodeFilterOct(out.data(), count, stride);
    else if (s.filter == "QUATERNION")
        meshopt_decodeFilterQuat(out.data(), count, stride);
    else if (s.filter == "EXPONENTIAL")
        meshopt_decodeFilterExp(out.data(), count, stride);
}

void decodeMeshoptView(tinygltf::Model& model, std::size_t index, const char* extension,
                       const tinygltf::Value& ext, Budget& budget) {
    const std::string what = "bufferView " + n(index) + " " + extension;
    const MeshoptStream s = readMeshoptStream(model, ext, what);
    const std::uint64_t decodedBytes = std::uint64_t(s.count) * std::uint64_t(s.stride);
    if (decodedBytes > kMeshoptMaxRatio * std::uint64_t(s.byteLength) + 4096)
        fail(what + " claims " + n(decodedBytes) + " decoded bytes from " +
             std::to_string(s.byteLength) + " compressed ones, more than the codec can produce");
    tinygltf::BufferView& view = model.bufferViews[index];
    if (view.byteLength != decodedBytes)
        fail(what + " decodes to " + n(decodedBytes) + " bytes (count " + std::to_string(s.count) +
             " x byteStride " + std::to_string(s.stride) +
             "), but the bufferView's byteLength is " + n(view.byteLength));
    budget.take(decodedBytes, what);
    std::vector<unsigned char> out(decodedBytes);
    decodeMeshoptStream(s, model.buffers[std::size_t(s.buffer)].data.data() + s.byteOffset, out,
                        what);
    tinygltf::Buffer decoded;
    decoded.data = std::move(out);
    model.buffers.push_back(std::move(decoded));
    view.buffer = int(model.buffers.size()) - 1;
    view.byteOffset = 0;
}

// --- KHR_draco_mesh_compression ------------------------------------------------------------

/** Components of a vertex attribute's accessor type: 1 to 4, or 0 for a matrix. */
int vectorComponents(int type) {
    const int components = typeComponents(type);
    return components <= 4 && type != TINYGLTF_TYPE_MAT2 ? components : 0;
}

/** Every point of `attribute` converted to T, `components` per point, as raw bytes. */
template <typename T>
std::vector<unsigned char> convertPoints(const draco::Mesh& mesh,
                                         const draco::PointAttribute& attribute, int components,
                                         const std::string& what) {
    std::vector<unsigned char> out(std::size_t(mesh.num_points()) * std::size_t(components) *
                                   sizeof(T));
    T value[4] = {};
    for (draco::PointIndex p(0); p < mesh.num_points(); ++p) {
        if (!attribute.ConvertValue<T>(attribute.mapped_index(p), std::int8_t(components), value))
            fail(what + ": point " + n(p.value()) + " does not convert to the accessor's type");
        std::memcpy(out.data() + std::size_t(p.value()) * std::size_t(components) * sizeof(T),
                    value, std::size_t(components) * sizeof(T));
    }
    return out;
}

std::vector<unsigned char> convertAttribute(const draco::Mesh& mesh,
                                            const draco::PointAttribute& attribute,
                                            const tinygltf::Accessor& accessor,
                                            const std::string& what) {
    const int components = vectorComponents(accessor.type);
    switch (accessor.componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return convertPoints<float>(mesh, attribute, components, what);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return convertPoints<std::uint8_t>(mesh, attribute, components, what);
    case TINYGLTF_COMPONENT_TYPE_BYTE:
        return convertPoints<std::int8_t>(mesh, attribute, components, what);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return convertPoints<std::uint16_t>(mesh, attribute, components, what);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
        return convertPoints<std::int16_t>(mesh, attribute, components, what);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return convertPoints<std::uint32_t>(mesh, attribute, components, what);
    default:
        fail(what + " has componentType " + std::to_string(accessor.componentType) +
             ", which no glTF vertex attribute uses");
    }
}

tinygltf::Accessor& accessorAt(tinygltf::Model& model, std::int64_t index,
                               const std::string& what) {
    if (index < 0 || std::uint64_t(index) >= model.accessors.size())
        fail(what + " references accessor " + std::to_string(index) + ", file has " +
             n(model.accessors.size()));
    return model.accessors[std::size_t(index)];
}

/** What a Draco primitive's accessors claim it decodes to. */
struct DracoClaims {
    std::uint64_t vertices = 0, indices = 0, bytes = 0;
};

/** The sizes the JSON claims, checked (each compressed attribute listed by the primitive, one
 *  vertex count, the limits) before the decoder allocates anything. */
DracoClaims claimedSizes(tinygltf::Model& model, const tinygltf::Primitive& primitive,
                         const tinygltf::Value& attributes, const std::string& what,
                         const std::string& name) {
    DracoClaims claims;
    for (const std::string& semantic : attributes.Keys()) {
        const auto it = primitive.attributes.find(semantic);
        if (it == primitive.attributes.end())
            fail(name + " compresses " + semantic + ", which the primitive does not list");
        const tinygltf::Accessor& accessor = accessorAt(model, it->second, what + " " + semantic);
        if (vectorComponents(accessor.type) == 0)
            fail(what + " " + semantic + " accessor " + std::to_string(it->second) +
                 " is not a scalar or vector");
        if (claims.vertices != 0 && accessor.count != claims.vertices)
            fail(name + ": " + semantic + " has " + n(accessor.count) +
                 " elements, other attributes " + n(claims.vertices));
        claims.vertices = accessor.count;
        claims.bytes += std::uint64_t(accessor.count) *
                        std::uint64_t(vectorComponents(accessor.type)) *
                        std::uint64_t(componentSize(accessor.componentType));
    }
    if (claims.vertices > core::limits::kMaxVerticesPerPrimitive)
        fail(name + " claims " + n(claims.vertices) + " vertices, over the limit of " +
             n(core::limits::kMaxVerticesPerPrimitive));
    if (primitive.indices >= 0) {
        claims.indices = accessorAt(model, primitive.indices, what + " indices").count;
        if (claims.indices > 3 * core::limits::kMaxVerticesPerPrimitive)
            fail(name + " claims " + n(claims.indices) + " indices, over the limit");
        claims.bytes += claims.indices * 4;
    }
    return claims;
}

/** The Draco triangle mesh of `ext`'s bufferView, checked against what its accessors claim. */
std::unique_ptr<draco::Mesh> decodeDracoMesh(const tinygltf::Model& model,
                                             const tinygltf::Value& ext, bool indexed,
                                             const DracoClaims& claims, const std::string& name) {
    const std::span<const std::uint8_t> compressed =
        viewBytes(model, integer(ext, "bufferView", -1, name), name);
    draco::DecoderBuffer stream;
    stream.Init(reinterpret_cast<const char*>(compressed.data()), compressed.size());
    auto geometryType = draco::Decoder::GetEncodedGeometryType(&stream);
    if (!geometryType.ok() || geometryType.value() != draco::TRIANGULAR_MESH)
        fail(name + ": the stream is not a Draco triangle mesh" +
             (geometryType.ok() ? "" : " (" + geometryType.status().error_msg_string() + ")"));
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&stream);
    if (!decoded.ok())
        fail(name + ": the Draco stream does not decode (" + decoded.status().error_msg_string() +
             ")");
    std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (mesh->num_points() != claims.vertices)
        fail(name + " decodes to " + n(mesh->num_points()) + " vertices, its accessors claim " +
             n(claims.vertices));
    if (indexed && std::uint64_t(mesh->num_faces()) * 3 != claims.indices)
        fail(name + " decodes to " + n(mesh->num_faces()) + " triangles, its indices accessor " +
             "claims " + n(claims.indices) + " indices");
    return mesh;
}

/** Draco attribute `id` of `mesh` as the data of `accessor`, in a buffer view of its own. */
void replaceAttribute(tinygltf::Model& model, tinygltf::Accessor& accessor, const draco::Mesh& mesh,
                      std::int64_t id, const std::string& attributeName) {
    const draco::PointAttribute* attribute =
        id < 0 ? nullptr : mesh.GetAttributeByUniqueId(std::uint32_t(id));
    if (!attribute)
        fail(attributeName + " is Draco attribute " + std::to_string(id) +
             ", which the stream does not have");
    // glTF attributes are integers of up to 32 bits or floats; Draco's other types (a bool is
    // loaded as one, whatever byte the stream holds) have no glTF meaning.
    switch (attribute->data_type()) {
    case draco::DT_INT8:
    case draco::DT_UINT8:
    case draco::DT_INT16:
    case draco::DT_UINT16:
    case draco::DT_INT32:
    case draco::DT_UINT32:
    case draco::DT_FLOAT32:
        break;
    default:
        fail(attributeName + " has Draco data type " + std::to_string(int(attribute->data_type())) +
             ", which no glTF attribute uses");
    }
    if (attribute->num_components() < vectorComponents(accessor.type))
        fail(attributeName + " has " + std::to_string(attribute->num_components()) +
             " components in the stream, its accessor " +
             std::to_string(vectorComponents(accessor.type)));
    std::vector<unsigned char> data = convertAttribute(mesh, *attribute, accessor, attributeName);
    accessor.bufferView = addView(model, std::move(data));
    accessor.byteOffset = 0;
    accessor.sparse = {};
}

/** The mesh's triangles as `accessor`'s data, 32-bit, in a buffer view of their own. */
void replaceIndices(tinygltf::Model& model, tinygltf::Accessor& accessor, const draco::Mesh& mesh) {
    std::vector<unsigned char> data(std::size_t(mesh.num_faces()) * 3 * 4);
    for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
        for (int corner = 0; corner < 3; ++corner) {
            const std::uint32_t v = mesh.face(f)[corner].value();
            std::memcpy(data.data() + (std::size_t(f.value()) * 3 + std::size_t(corner)) * 4, &v,
                        4);
        }
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    accessor.bufferView = addView(model, std::move(data));
    accessor.byteOffset = 0;
    accessor.sparse = {};
}

void decodeDracoPrimitive(tinygltf::Model& model, tinygltf::Primitive& primitive,
                          const std::string& what, Budget& budget) {
    const std::string name = what + " " + kDraco;
    tinygltf::Value ext = primitive.extensions.at(kDraco);
    primitive.extensions.erase(kDraco);
    if (member(ext, kDracoIndices)) {
        const std::int64_t indices = integer(ext, kDracoIndices, -1, name);
        if (indices < 0 || indices > std::numeric_limits<int>::max())
            fail(what + " indices " + std::to_string(indices) + " is not an accessor index");
        primitive.indices = int(indices);
    }
    const tinygltf::Value* attributes = member(ext, "attributes");
    if (!attributes || !attributes->IsObject())
        fail(name + " has no attributes object");
    if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1)
        fail(name + " is on a primitive of mode " + std::to_string(primitive.mode) +
             "; Draco meshes are triangles");
    const DracoClaims claims = claimedSizes(model, primitive, *attributes, what, name);
    budget.take(claims.bytes, name);
    const std::unique_ptr<draco::Mesh> mesh =
        decodeDracoMesh(model, ext, primitive.indices >= 0, claims, name);
    for (const std::string& semantic : attributes->Keys())
        replaceAttribute(model, model.accessors[std::size_t(primitive.attributes.at(semantic))],
                         *mesh, integer(*attributes, semantic.c_str(), -1, name + " attributes"),
                         name + " " + semantic);
    if (primitive.indices >= 0)
        replaceIndices(model, model.accessors[std::size_t(primitive.indices)], *mesh);
}

} // namespace

namespace {

/** `/nodes/N/translation|rotation|scale|weights` as its node and path; nullopt for any other
 *  pointer (N a decimal index, not checked against the nodes here). */
std::optional<std::pair<long long, std::string>> nodePointer(const std::string& pointer) {
    static const std::regex node(
        R"(^/nodes/(0|[1-9][0-9]{0,8})/(translation|rotation|scale|weights)$)");
    std::smatch match;
    if (!std::regex_match(pointer, match, node))
        return std::nullopt;
    return std::pair{std::stoll(match[1].str()), match[2].str()};
}

/** KHR_animation_pointer channels in the terms the parser knows (it drops a channel without a
 *  target node): a node's TRS or weights become that node and path; any other pointer, or a
 *  channel without one, gets path kSkippedPointer or kMalformedPointer on node -1 for
 *  convertAnimation to skip with a warning or refuse. Each keeps its pointer in its extras. */
void rewritePointerChannels(nlohmann::json& document) {
    if (!document.contains("animations") || !document["animations"].is_array())
        return;
    for (nlohmann::json& animation : document["animations"]) {
        if (!animation.is_object() || !animation.contains("channels") ||
            !animation["channels"].is_array())
            continue;
        for (nlohmann::json& channel : animation["channels"]) {
            if (!channel.is_object() || !channel.contains("target") ||
                !channel["target"].is_object())
                continue;
            nlohmann::json& target = channel["target"];
            if (target.value("path", nlohmann::json()) != "pointer")
                continue;
            const nlohmann::json* pointer = nullptr;
            if (target.contains("extensions") && target["extensions"].is_object() &&
                target["extensions"].contains(kAnimationPointer) &&
                target["extensions"][kAnimationPointer].is_object() &&
                target["extensions"][kAnimationPointer].contains("pointer"))
                pointer = &target["extensions"][kAnimationPointer]["pointer"];
            const std::string text = pointer && pointer->is_string() ? pointer->get<std::string>()
                                     : pointer                       ? pointer->dump()
                                                                     : std::string();
            if (!channel.contains("extras") || !channel["extras"].is_object())
                channel["extras"] = nlohmann::json::object();
            channel["extras"][kPointerExtra] = text;
            if (const auto node =
                    pointer && pointer->is_string() ? nodePointer(text) : std::nullopt) {
                target["node"] = node->first;
                target["path"] = node->second;
            } else {
                target["node"] = -1;
                target["path"] = pointer && pointer->is_string() && !text.empty()
                                     ? kSkippedPointer
                                     : kMalformedPointer;
            }
        }
    }
}

/** A Draco primitive's indices accessor moved into its extension object, where
 *  decodeCompressedGeometry takes it back (the parser wants a bufferView for it). */
void moveDracoIndices(nlohmann::json& document) {
    if (!document.contains("meshes") || !document["meshes"].is_array())
        return;
    for (nlohmann::json& mesh : document["meshes"])
        if (mesh.is_object() && mesh.contains("primitives") && mesh["primitives"].is_array())
            for (nlohmann::json& primitive : mesh["primitives"]) {
                if (!primitive.is_object() || !primitive.contains("indices") ||
                    !primitive.contains("extensions") || !primitive["extensions"].is_object() ||
                    !primitive["extensions"].contains(kDraco) ||
                    !primitive["extensions"][kDraco].is_object())
                    continue;
                primitive["extensions"][kDraco][kDracoIndices] = primitive["indices"];
                primitive.erase("indices");
            }
}

} // namespace

std::optional<std::vector<std::uint8_t>> prepareForParser(std::span<const std::uint8_t> bytes,
                                                          bool isBinary) {
    const std::string_view json =
        isBinary ? glbChunks(bytes).json
                 : std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    if (json.find(kDraco) == std::string_view::npos &&
        json.find("meshopt_compression") == std::string_view::npos &&
        json.find(kAnimationPointer) == std::string_view::npos)
        return std::nullopt;
    nlohmann::json document = nlohmann::json::parse(json, nullptr, false);
    if (!document.is_object())
        return std::nullopt; // the parser reports it
    rewritePointerChannels(document);
    moveDracoIndices(document);
    std::map<std::size_t, std::string> fallbacks; // buffer index: its declared byteLength
    if (document.contains("buffers") && document["buffers"].is_array())
        for (std::size_t b = 0; b < document["buffers"].size(); ++b) {
            nlohmann::json& buffer = document["buffers"][b];
            if (!buffer.is_object() || !buffer.contains("extensions") ||
                !buffer["extensions"].is_object())
                continue;
            for (const char* name : kMeshopt) {
                const auto ext = buffer["extensions"].find(name);
                if (ext == buffer["extensions"].end() || !ext->is_object() ||
                    !ext->contains("fallback") || (*ext)["fallback"] != true)
                    continue;
                // Nothing reads a fallback buffer: every view into it is decoded from another.
                // One zero byte stands in for it (tinygltf refuses an empty data URI).
                fallbacks[b] = buffer.contains("byteLength") ? buffer["byteLength"].dump() : "?";
                buffer["uri"] = "data:application/octet-stream;base64,AA==";
                buffer["byteLength"] = 1;
            }
        }
    // A view that is not decoded from a compressed stream would read the stand-in.
    if (!fallbacks.empty() && document.contains("bufferViews") &&
        document["bufferViews"].is_array())
        for (std::size_t v = 0; v < document["bufferViews"].size(); ++v) {
            const nlohmann::json& view = document["bufferViews"][v];
            if (!view.is_object() || !view.contains("buffer") ||
                !view["buffer"].is_number_unsigned())
                continue;
            const auto fallback = fallbacks.find(view["buffer"].get<std::size_t>());
            const nlohmann::json* compressed = nullptr;
            const char* extension = nullptr;
            for (const char* name : kMeshopt)
                if (view.contains("extensions") && view["extensions"].is_object() &&
                    view["extensions"].contains(name))
                    compressed = &view["extensions"][name], extension = name;
            if (fallback != fallbacks.end() && !compressed)
                fail("bufferView " + n(v) + " reads buffer " + n(fallback->first) +
                     ", a meshopt fallback buffer (" + fallback->second +
                     " bytes declared, never loaded): only a view compressed by "
                     "EXT_meshopt_compression may point into it");
            // The compressed stream itself must come from a buffer that holds data.
            if (compressed && compressed->is_object() && compressed->contains("buffer") &&
                (*compressed)["buffer"].is_number_unsigned())
                if (const auto source = fallbacks.find((*compressed)["buffer"].get<std::size_t>());
                    source != fallbacks.end())
                    fail("bufferView " + n(v) + " " + extension +
                         " takes its compressed stream from buffer " + n(source->first) +
                         ", a meshopt fallback buffer (" + source->second +
                         " bytes declared, never loaded): the stream must be in "
                         "a buffer with data");
        }

    const std::string text = document.dump();
    if (!isBinary)
        return std::vector<std::uint8_t>(text.begin(), text.end());
    return encodeGlb(text, glbChunks(bytes).bin); // unknown chunks after BIN are dropped
}

std::set<int> decodeCompressedGeometry(tinygltf::Model& model) {
    Budget budget;
    std::set<int> lossy;
    for (std::size_t i = 0; i < model.bufferViews.size(); ++i)
        for (const char* name : kMeshopt) {
            const auto it = model.bufferViews[i].extensions.find(name);
            if (it == model.bufferViews[i].extensions.end())
                continue;
            const tinygltf::Value ext = it->second;
            model.bufferViews[i].extensions.erase(it);
            decodeMeshoptView(model, i, name, ext, budget);
        }
    for (std::size_t m = 0; m < model.meshes.size(); ++m)
        for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
            tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
            if (!primitive.extensions.count(kDraco))
                continue;
            decodeDracoPrimitive(model, primitive, "mesh " + n(m) + " primitive " + n(p), budget);
            for (const auto& [semantic, accessor] : primitive.attributes)
                lossy.insert(accessor);
        }
    return lossy;
}

} // namespace asset::detail
