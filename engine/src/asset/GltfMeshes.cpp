// Meshes and skins: attribute accessors into engine primitives (triangle lists), morph targets,
// skin influences (renormalised, checked), generated normals and tangents; skin matrices.
#include "GltfConvert.h"

#include "LoadError.h"
#include "MeshGeneration.h"
#include "engine/core/Limits.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace asset::detail {
namespace {

std::string n(std::size_t v) {
    return std::to_string(v);
}

template <class Vec, int N>
std::vector<Vec> readVecs(const AccessorReader& reader, int accessor, const std::string& what) {
    const std::vector<float> flat = reader.readFloats(accessor, N, what);
    std::vector<Vec> out(flat.size() / N);
    for (std::size_t i = 0; i < out.size(); ++i)
        for (int c = 0; c < N; ++c)
            out[i][c] = flat[i * N + std::size_t(c)];
    return out;
}

const char* componentName(int type) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
        return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
        return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return "FLOAT";
    default:
        return "an unknown type";
    }
}

/** Whether glTF allows accessor format (componentType `type`, `normalized`) for vertex
 *  attribute `semantic` (of a morph target when `target`): glTF 2.0 §3.7.2.1, widened for the
 *  geometry by KHR_mesh_quantization when `quantized`. Attributes glTF does not define (_FOO)
 *  take any format. */
bool formatAllowed(const std::string& semantic, int type, bool normalized, bool quantized,
                   bool target) {
    const bool isFloat = type == TINYGLTF_COMPONENT_TYPE_FLOAT;
    const bool small =
        type == TINYGLTF_COMPONENT_TYPE_BYTE || type == TINYGLTF_COMPONENT_TYPE_SHORT;
    const bool smallUnsigned = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                               type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    auto starts = [&](const char* prefix) { return semantic.rfind(prefix, 0) == 0; };
    if (semantic == "POSITION")
        return isFloat || (quantized && (small || (smallUnsigned && !target)));
    if (semantic == "NORMAL" || semantic == "TANGENT")
        return isFloat || (quantized && small && normalized);
    if (starts("TEXCOORD_"))
        return isFloat || (smallUnsigned && normalized) ||
               (quantized && (small || smallUnsigned) && (normalized || !target));
    if (starts("COLOR_") || starts("WEIGHTS_"))
        return isFloat || (smallUnsigned && normalized);
    if (starts("JOINTS_"))
        return smallUnsigned && !normalized;
    return true;
}

/** Fails when an attribute's accessor has a format glTF does not allow it (the validator's
 *  MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT): read anyway, a BYTE texture coordinate
 *  that is not normalized tiles its texture 127 times. */
void checkAttributeFormats(const tinygltf::Model& model, const tinygltf::Primitive& src,
                           const std::string& what) {
    const bool quantized = std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(),
                                     "KHR_mesh_quantization") != model.extensionsUsed.end();
    auto check = [&](const std::string& semantic, int index, const std::string& where,
                     bool target) {
        if (index < 0 || std::size_t(index) >= model.accessors.size())
            return; // the reader names it
        const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
        if (formatAllowed(semantic, a.componentType, a.normalized, quantized, target))
            return;
        const bool withQuantization =
            !quantized && formatAllowed(semantic, a.componentType, a.normalized, true, target);
        fail(where + " (accessor " + n(std::size_t(index)) + ") is " +
             componentName(a.componentType) + (a.normalized ? ", normalized" : ", not normalized") +
             ", which glTF does not allow for " + semantic +
             (withQuantization ? " unless the file uses KHR_mesh_quantization (its extensionsUsed "
                                 "does not list it)"
                               : ""));
    };
    for (const auto& [semantic, index] : src.attributes)
        check(semantic, index, what + " " + semantic, false);
    for (std::size_t t = 0; t < src.targets.size(); ++t)
        for (const auto& [semantic, index] : src.targets[t])
            check(semantic, index, what + " target " + n(t) + " " + semantic, true);
}

bool wholeNumbers(const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(),
                       [](double v) { return std::isfinite(v) && v == std::floor(v); });
}

std::string boundsText(const std::vector<double>& components) {
    std::string out = "[";
    for (std::size_t c = 0; c < components.size(); ++c) {
        char number[32];
        std::snprintf(number, sizeof number, "%g", components[c]);
        out += (c ? ", " : "") + std::string(number);
    }
    return out + "]";
}

/** A warning where an accessor's declared min or max is not what its data (`values`, as read)
 *  reaches. Bounds are in the units the file stores: a normalized accessor's are its raw
 *  integers (as the Khronos validator reads them), compared within half a step; a float's
 *  within the precision of a float written as text. An integer accessor's fractional bounds
 *  are warned of once, by fractionalBoundsWarnings. */
template <class Vec, int N>
void checkBounds(const tinygltf::Model& model, int index, const std::vector<Vec>& values,
                 const std::string& what, std::vector<std::string>& warnings) {
    const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
    if (values.empty())
        return;
    Vec lo = values[0], hi = values[0];
    for (const Vec& v : values)
        for (int c = 0; c < N; ++c)
            lo[c] = std::min(lo[c], v[c]), hi[c] = std::max(hi[c], v[c]);
    const double scale = a.normalized ? normalizedScale(a.componentType) : 1.0;
    const bool integer = a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT;
    struct Bound {
        const std::vector<double>& declared;
        Vec actual;
        const char* name;
    };
    for (const Bound& bound : {Bound{a.minValues, lo, "min"}, Bound{a.maxValues, hi, "max"}}) {
        if (bound.declared.size() != std::size_t(N) || (integer && !wholeNumbers(bound.declared)))
            continue;
        std::vector<double> actual(N);
        bool differs = false;
        for (int c = 0; c < N; ++c) {
            const double v = double(bound.actual[c]) * scale;
            actual[std::size_t(c)] = a.normalized ? std::round(v) : v;
            // glTF decodes a signed normalized integer as max(c / scale, -1): -scale - 1 is -1
            const double declared = bound.declared[std::size_t(c)];
            const double d = a.normalized ? std::max(declared, -scale) : declared;
            const double tolerance = a.normalized ? 0.5 : 1e-5 * std::max(1.0, std::abs(v));
            differs = differs || std::abs(d - v) > tolerance;
        }
        if (differs)
            warnings.push_back(what + " (accessor " + n(std::size_t(index)) + ") declares " +
                               bound.name + " " + boundsText(bound.declared) + ", its data's is " +
                               boundsText(actual) +
                               (a.normalized ? " (raw integers, as normalized bounds are)" : "") +
                               ": the data is used");
    }
}

} // namespace

void fractionalBoundsWarnings(const tinygltf::Model& model, std::vector<std::string>& warnings) {
    for (std::size_t i = 0; i < model.accessors.size(); ++i) {
        const tinygltf::Accessor& a = model.accessors[i];
        if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
            continue;
        for (const auto& [declared, name] :
             {std::pair{&a.minValues, "min"}, std::pair{&a.maxValues, "max"}})
            if (!wholeNumbers(*declared))
                warnings.push_back("accessor " + n(i) + " (" + componentName(a.componentType) +
                                   ") declares " + name + " " + boundsText(*declared) +
                                   ", but an integer accessor's bounds are whole numbers: its "
                                   "data's own are used");
    }
}

namespace {

/** A primitive's KHR_materials_variants mappings: the material of each variant (-2: its own). */
std::vector<int> variantMaterials(const tinygltf::Model& model, const tinygltf::Value& ext,
                                  std::size_t materials, const std::string& what) {
    const std::size_t count = variantNames(model).size();
    std::vector<int> result(count, -2);
    if (!ext.Has("mappings") || !ext.Get("mappings").IsArray())
        fail(what + " KHR_materials_variants has no mappings array");
    const tinygltf::Value& mappings = ext.Get("mappings");
    for (std::size_t m = 0; m < mappings.ArrayLen(); ++m) {
        const tinygltf::Value& mapping = mappings.Get(int(m));
        const std::string where = what + " KHR_materials_variants mapping " + n(m);
        const int material = mapping.Has("material") && mapping.Get("material").IsNumber()
                                 ? mapping.Get("material").GetNumberAsInt()
                                 : -1;
        if (material < 0 || std::size_t(material) >= materials)
            fail(where + " references material " + std::to_string(material) + ", file has " +
                 n(materials) + " materials");
        if (!mapping.Has("variants") || !mapping.Get("variants").IsArray())
            fail(where + " has no variants array");
        const tinygltf::Value& variants = mapping.Get("variants");
        for (std::size_t k = 0; k < variants.ArrayLen(); ++k) {
            const int variant =
                variants.Get(int(k)).IsNumber() ? variants.Get(int(k)).GetNumberAsInt() : -1;
            if (variant < 0 || std::size_t(variant) >= count)
                fail(where + " names variant " + std::to_string(variant) + ", the file has " +
                     n(count) + " variants");
            result[std::size_t(variant)] = material;
        }
    }
    return result;
}

/** Triangle-list indices from TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN. */
std::vector<std::uint32_t> toTriangleList(const std::vector<std::uint32_t>& in, int mode,
                                          const std::string& what) {
    std::vector<std::uint32_t> out;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (in.size() % 3 != 0)
            fail(what + ": " + n(in.size()) + " indices is not a multiple of 3");
        return in;
    }
    for (std::size_t i = 2; i < in.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            const bool even = i % 2 == 0;
            out.insert(out.end(), {in[i - 2], even ? in[i - 1] : in[i], even ? in[i] : in[i - 1]});
        } else {
            out.insert(out.end(), {in[0], in[i - 1], in[i]});
        }
    }
    return out;
}

const char* modeName(int mode) {
    switch (mode) {
    case TINYGLTF_MODE_POINTS:
        return "POINTS";
    case TINYGLTF_MODE_LINE:
        return "LINES";
    case TINYGLTF_MODE_LINE_LOOP:
        return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP:
        return "LINE_STRIP";
    default:
        return "unknown";
    }
}

/** Reads JOINTS_s / WEIGHTS_s pairs; renormalises the weights over all sets; rejects
 *  negative, NaN or all-zero weights and a third set. Zero-weight joints are set to 0 so no
 *  unused index can reach past a skin. */
void readInfluences(const tinygltf::Primitive& src, const AccessorReader& reader,
                    scene::Primitive& p, const std::string& what) {
    const auto& attributes = src.attributes;
    if (attributes.count("JOINTS_2") || attributes.count("WEIGHTS_2"))
        fail(what + " has JOINTS_2/WEIGHTS_2: more than " + n(core::limits::kMaxInfluences) +
             " influences per vertex, over the engine's limit");
    for (std::size_t s = 0; s < 2; ++s) {
        const std::string joints = "JOINTS_" + n(s), weights = "WEIGHTS_" + n(s);
        const bool hasJoints = attributes.count(joints) > 0;
        if (hasJoints != (attributes.count(weights) > 0))
            fail(what + " has " +
                 (hasJoints ? joints + " without " + weights : weights + " without " + joints));
        if (!hasJoints)
            continue;
        if (s == 1 && p.joints[0].empty())
            fail(what + " has JOINTS_1 without JOINTS_0");
        const std::vector<std::uint32_t> flat =
            reader.readUints(attributes.at(joints), 4, what + " " + joints);
        p.joints[s].resize(flat.size() / 4);
        for (std::size_t i = 0; i < p.joints[s].size(); ++i)
            p.joints[s][i] =
                glm::uvec4(flat[i * 4], flat[i * 4 + 1], flat[i * 4 + 2], flat[i * 4 + 3]);
        p.weights[s] = readVecs<glm::vec4, 4>(reader, attributes.at(weights), what + " " + weights);
        if (p.joints[s].size() != p.vertexCount() || p.weights[s].size() != p.vertexCount())
            fail(what + " " + joints + "/" + weights + " count differs from POSITION count " +
                 n(p.vertexCount()));
    }
    if (!p.isSkinned())
        return;
    for (std::size_t v = 0; v < p.vertexCount(); ++v) {
        double sum = 0.0;
        for (std::size_t s = 0; s < std::size_t(p.influenceSets()); ++s)
            for (int k = 0; k < 4; ++k) {
                const float w = p.weights[s][v][k];
                if (!(w >= 0.0f))
                    fail(what + " vertex " + n(v) + " has a negative or NaN weight");
                sum += double(w);
            }
        if (!(sum > 0.0) || !std::isfinite(sum))
            fail(what + " vertex " + n(v) + " has all-zero or NaN skin weights");
        for (std::size_t s = 0; s < std::size_t(p.influenceSets()); ++s)
            for (int k = 0; k < 4; ++k) {
                p.weights[s][v][k] = float(double(p.weights[s][v][k]) / sum);
                if (p.weights[s][v][k] == 0.0f)
                    p.joints[s][v][k] = 0;
            }
    }
}

/** Fails unless `got`, the elements of `attribute`, is the primitive's vertex count. */
void sameCount(std::size_t got, std::size_t count, const std::string& attribute,
               const std::string& what) {
    if (got != count)
        fail(what + " " + attribute + " has " + n(got) + " elements, POSITION has " + n(count));
}

/** The vertex attributes besides POSITION and the skin's: normals, tangents, two UV sets. */
void readSurfaceAttributes(const tinygltf::Primitive& src, const AccessorReader& reader,
                           scene::Primitive& p, const std::string& what) {
    const auto& attributes = src.attributes;
    const std::size_t count = p.vertexCount();
    if (attributes.count("NORMAL")) {
        p.normals = readVecs<glm::vec3, 3>(reader, attributes.at("NORMAL"), what + " NORMAL");
        sameCount(p.normals.size(), count, "NORMAL", what);
    }
    if (attributes.count("TANGENT")) {
        p.tangents = readVecs<glm::vec4, 4>(reader, attributes.at("TANGENT"), what + " TANGENT");
        sameCount(p.tangents.size(), count, "TANGENT", what);
    }
    if (attributes.count("TEXCOORD_0")) {
        p.uv0 = readVecs<glm::vec2, 2>(reader, attributes.at("TEXCOORD_0"), what + " TEXCOORD_0");
        sameCount(p.uv0.size(), count, "TEXCOORD_0", what);
    }
    if (attributes.count("TEXCOORD_1")) {
        p.uv1 = readVecs<glm::vec2, 2>(reader, attributes.at("TEXCOORD_1"), what + " TEXCOORD_1");
        sameCount(p.uv1.size(), count, "TEXCOORD_1", what);
    }
}

/** The primitive's triangles as a list: its indices (each checked against the vertices), or
 *  its vertices in order, in `mode`. */
std::vector<std::uint32_t> readTriangles(const tinygltf::Primitive& src,
                                         const AccessorReader& reader, std::size_t count, int mode,
                                         const std::string& what) {
    std::vector<std::uint32_t> indices;
    if (src.indices >= 0) {
        indices = reader.readUints(src.indices, 1, what + " indices");
        for (std::size_t i = 0; i < indices.size(); ++i)
            if (indices[i] >= count)
                fail(what + " index " + n(i) + " is " + n(indices[i]) + ", POSITION has " +
                     n(count) + " vertices");
    } else {
        indices.resize(count);
        for (std::size_t i = 0; i < count; ++i)
            indices[i] = std::uint32_t(i);
    }
    return toTriangleList(indices, mode, what);
}

/** The morph targets: their position, normal and tangent deltas, within the limit. */
void readTargets(const tinygltf::Model& model, const tinygltf::Primitive& src,
                 const AccessorReader& reader, scene::Primitive& p, const std::string& what,
                 std::vector<std::string>& warnings) {
    if (src.targets.size() > core::limits::kMaxMorphTargets)
        fail(what + " has " + n(src.targets.size()) + " morph targets, over the limit of " +
             n(core::limits::kMaxMorphTargets));
    for (std::size_t t = 0; t < src.targets.size(); ++t) {
        const std::string targetWhat = what + " target " + n(t);
        scene::MorphTarget target;
        for (const auto& [name, accessor] : src.targets[t]) {
            std::vector<glm::vec3> deltas =
                readVecs<glm::vec3, 3>(reader, accessor, targetWhat + " " + name);
            checkBounds<glm::vec3, 3>(model, accessor, deltas, targetWhat + " " + name, warnings);
            sameCount(deltas.size(), p.vertexCount(), "target " + n(t) + " " + name, what);
            if (name == "POSITION")
                target.positions = std::move(deltas);
            else if (name == "NORMAL")
                target.normals = std::move(deltas);
            else if (name == "TANGENT")
                target.tangents = std::move(deltas);
        }
        p.targets.push_back(std::move(target));
    }
}

/** Flat normals where the file gives none (glTF 3.7.2.1), and tangents where a normal or
 *  anisotropy map needs a frame the file does not give. */
void completeFrame(scene::Primitive& p, const std::vector<scene::Material>& materials,
                   const std::string& what) {
    if (p.normals.empty()) {
        unweld(p);
        computeFlatNormals(p);
        p.flatNormals = true;
    }
    if (p.material < 0)
        return;
    const scene::Material& m = materials[std::size_t(p.material)];
    const scene::TextureRef& map = m.normalTexture.present()            ? m.normalTexture
                                   : m.clearcoatNormalTexture.present() ? m.clearcoatNormalTexture
                                                                        : m.anisotropyTexture;
    if ((map.present() || m.hasAnisotropy) && p.tangents.empty()) {
        const auto& uv = map.texCoord == 1 ? p.uv1 : p.uv0;
        if (uv.size() == p.vertexCount())
            generateTangents(p, map.texCoord);
        else if (map.present())
            fail(what + " uses a normal or anisotropy map on TEXCOORD_" +
                 std::to_string(map.texCoord) + " but has no such attribute");
    }
}

scene::Primitive convertPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& src,
                                  const AccessorReader& reader, const std::string& what,
                                  const std::vector<scene::Material>& materials,
                                  const std::set<int>& lossy, std::vector<std::string>& warnings) {
    const int mode = src.mode < 0 ? TINYGLTF_MODE_TRIANGLES : src.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN)
        fail(what + " has mode " + std::to_string(mode) + ", which glTF does not define");
    const auto& attributes = src.attributes;
    if (!attributes.count("POSITION"))
        fail(what + " has no POSITION attribute");
    checkAttributeFormats(model, src, what);

    scene::Primitive p;
    p.material = src.material;
    if (const auto variants = src.extensions.find("KHR_materials_variants");
        variants != src.extensions.end())
        p.variantMaterials = variantMaterials(model, variants->second, materials.size(), what);
    p.positions = readVecs<glm::vec3, 3>(reader, attributes.at("POSITION"), what + " POSITION");
    if (!lossy.count(attributes.at("POSITION")))
        checkBounds<glm::vec3, 3>(model, attributes.at("POSITION"), p.positions, what + " POSITION",
                                  warnings);
    p.sourceVertexCount = p.positions.size();
    readSurfaceAttributes(src, reader, p, what);
    readInfluences(src, reader, p, what);
    p.indices = readTriangles(src, reader, p.vertexCount(), mode, what);
    readTargets(model, src, reader, p, what, warnings);
    completeFrame(p, materials, what);
    return p;
}

} // namespace

/** The file's KHR_materials_variants names (its root extension), or none. */
std::vector<std::string> variantNames(const tinygltf::Model& model) {
    std::vector<std::string> names;
    const auto ext = model.extensions.find("KHR_materials_variants");
    if (ext == model.extensions.end())
        return names;
    if (!ext->second.Has("variants") || !ext->second.Get("variants").IsArray())
        fail("KHR_materials_variants has no variants array");
    const tinygltf::Value& variants = ext->second.Get("variants");
    for (std::size_t i = 0; i < variants.ArrayLen(); ++i) {
        const tinygltf::Value& v = variants.Get(int(i));
        names.push_back(v.Has("name") && v.Get("name").IsString() ? v.Get("name").Get<std::string>()
                                                                  : "variant " + n(i));
    }
    return names;
}

scene::Mesh convertMesh(const tinygltf::Model& model, const AccessorReader& reader, int index,
                        const std::vector<scene::Material>& materials, const std::set<int>& lossy,
                        std::vector<std::string>& warnings) {
    const tinygltf::Mesh& src = model.meshes[std::size_t(index)];
    const std::string what = "mesh " + n(std::size_t(index));
    scene::Mesh mesh;
    mesh.name = src.name;
    for (std::size_t i = 0; i < src.primitives.size(); ++i) {
        const int mode = src.primitives[i].mode;
        if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE ||
            mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
            warnings.push_back(what + (src.name.empty() ? "" : " '" + src.name + "'") +
                               " primitive " + n(i) + " has mode " + modeName(mode) +
                               ": skipped (this engine draws triangles)");
            continue;
        }
        mesh.primitives.push_back(convertPrimitive(model, src.primitives[i], reader,
                                                   what + " primitive " + n(i), materials, lossy,
                                                   warnings));
    }
    // The morph target count is the file's, even where no drawn primitive is left to carry it
    // (node weights and weight channels are checked against it).
    const std::size_t targets = !mesh.primitives.empty() ? mesh.primitives[0].targets.size()
                                : src.primitives.empty() ? 0
                                                         : src.primitives[0].targets.size();
    for (std::size_t i = 0; i < mesh.primitives.size(); ++i)
        if (mesh.primitives[i].targets.size() != targets)
            fail(what + " primitive " + n(i) + " has " + n(mesh.primitives[i].targets.size()) +
                 " morph targets, primitive 0 has " + n(targets));
    if (!src.weights.empty() && src.weights.size() != targets)
        fail(what + " has " + n(src.weights.size()) + " default weights for " + n(targets) +
             " morph targets");
    mesh.defaultWeights.assign(targets, 0.0f);
    for (std::size_t t = 0; t < src.weights.size(); ++t) {
        if (!std::isfinite(src.weights[t]))
            fail(what + " default weight " + n(t) + " is not finite");
        mesh.defaultWeights[t] = float(src.weights[t]);
    }
    // Target names: the common (non-standard but widespread) extras.targetNames.
    if (src.extras.Has("targetNames") && src.extras.Get("targetNames").IsArray()) {
        const tinygltf::Value& names = src.extras.Get("targetNames");
        for (std::size_t i = 0; i < names.ArrayLen(); ++i)
            mesh.targetNames.push_back(names.Get(int(i)).IsString()
                                           ? names.Get(int(i)).Get<std::string>()
                                           : std::string());
    }
    return mesh;
}

scene::Skin convertSkin(const tinygltf::Model& model, const AccessorReader& reader, int index) {
    const tinygltf::Skin& src = model.skins[std::size_t(index)];
    const std::string what = "skin " + n(std::size_t(index));
    scene::Skin skin;
    skin.name = src.name;
    skin.joints = src.joints;
    skin.skeleton = src.skeleton;
    skin.inverseBind.assign(src.joints.size(), glm::dmat4(1.0));
    if (src.inverseBindMatrices >= 0) {
        const std::vector<float> flat =
            reader.readFloats(src.inverseBindMatrices, 16, what + " inverseBindMatrices");
        if (flat.size() / 16 < src.joints.size())
            fail(what + " inverseBindMatrices has " + n(flat.size() / 16) + " matrices for " +
                 n(src.joints.size()) + " joints");
        for (std::size_t j = 0; j < src.joints.size(); ++j)
            skin.inverseBind[j] = glm::dmat4(glm::make_mat4(&flat[j * 16]));
    }
    return skin;
}

void validateSkinnedMeshes(const scene::Model& model) {
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        const scene::Node& node = model.nodes[i];
        if (node.mesh < 0 || node.skin < 0)
            continue;
        const std::size_t joints = model.skins[std::size_t(node.skin)].joints.size();
        const scene::Mesh& mesh = model.meshes[std::size_t(node.mesh)];
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const scene::Primitive& prim = mesh.primitives[p];
            for (std::size_t s = 0; s < std::size_t(prim.influenceSets()); ++s)
                for (std::size_t v = 0; v < prim.vertexCount(); ++v)
                    for (int k = 0; k < 4; ++k)
                        if (prim.joints[s][v][k] >= joints)
                            fail("node " + n(i) + " (mesh " + n(std::size_t(node.mesh)) +
                                 " primitive " + n(p) + "): JOINTS_" + n(s) + " of vertex " + n(v) +
                                 " references joint " + n(prim.joints[s][v][k]) + ", skin " +
                                 n(std::size_t(node.skin)) + " has " + n(joints) + " joints");
        }
    }
}

} // namespace asset::detail
