// loadGltf(): prepare, parse with tinygltf (images through GltfImages.cpp), validate, decode
// compressed geometry (GltfDecode.cpp), convert into an engine-owned scene::Model. Nodes,
// materials, textures and cameras are converted here; meshes, skins and animations in
// GltfMeshes.cpp / GltfAnimations.cpp.
#include "engine/asset/GltfLoader.h"

#include "AccessorReader.h"
#include "GlbReader.h"
#include "GltfConvert.h"
#include "GltfDecode.h"
#include "LoadError.h"
#include "engine/core/Files.h"
#include "engine/core/Limits.h"
#include "engine/core/Log.h"

#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <set>

namespace asset {
namespace detail {
namespace {

std::string n(std::size_t v) {
    return std::to_string(v);
}

/** EXT_mesh_gpu_instancing: the instance transforms of every node that lists them (TRANSLATION
 *  VEC3 float, ROTATION VEC4 float or normalized BYTE / SHORT, SCALE VEC3 float, each optional,
 *  all of one count), as T * R * S in scene::Node::instances. */
void readInstancing(const tinygltf::Model& src, const AccessorReader& reader,
                    std::vector<scene::Node>& nodes, std::vector<std::string>& warnings) {
    constexpr const char* kExtension = "EXT_mesh_gpu_instancing";
    for (std::size_t i = 0; i < src.nodes.size(); ++i) {
        const auto found = src.nodes[i].extensions.find(kExtension);
        if (found == src.nodes[i].extensions.end())
            continue;
        const std::string what = "node " + n(i) + " " + kExtension;
        if (src.nodes[i].mesh < 0) {
            warnings.push_back(what + " on a node without a mesh: ignored");
            continue;
        }
        const tinygltf::Value& ext = found->second;
        if (!ext.IsObject() || !ext.Has("attributes") || !ext.Get("attributes").IsObject())
            fail(what + " has no attributes object");
        const tinygltf::Value& attributes = ext.Get("attributes");
        std::size_t count = 0;
        bool any = false;
        auto read = [&](const char* name, int components, bool quaternion) {
            if (!attributes.Has(name))
                return std::vector<float>{};
            const tinygltf::Value& v = attributes.Get(name);
            const int index = v.IsNumber() ? v.GetNumberAsInt() : -1;
            if (index < 0 || std::size_t(index) >= src.accessors.size())
                fail(what + " " + name + " references accessor " + std::to_string(index) +
                     ", file has " + n(src.accessors.size()) + " accessors");
            const tinygltf::Accessor& a = src.accessors[std::size_t(index)];
            const bool isFloat = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
            const bool smallNormalized =
                a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                                 a.componentType == TINYGLTF_COMPONENT_TYPE_SHORT);
            if (!isFloat && !(quaternion && smallNormalized))
                fail(what + " " + name + " (accessor " + std::to_string(index) + ") must be float" +
                     (quaternion ? " or normalized BYTE or SHORT" : ""));
            std::vector<float> values = reader.readFloats(index, components, what + " " + name);
            const std::size_t instances = values.size() / std::size_t(components);
            if (any && instances != count)
                fail(what + " " + name + " has " + n(instances) + " instances, the other " +
                     "attributes " + n(count));
            count = instances;
            any = true;
            return values;
        };
        const std::vector<float> translation = read("TRANSLATION", 3, false),
                                 rotation = read("ROTATION", 4, true),
                                 scale = read("SCALE", 3, false);
        if (count > core::limits::kMaxInstancesPerNode)
            fail(what + " has " + n(count) + " instances, over the limit of " +
                 n(core::limits::kMaxInstancesPerNode));
        if (!any || count == 0) {
            warnings.push_back(what + " lists no instances: the mesh is drawn once");
            continue;
        }
        for (std::size_t k = 0; k < count; ++k) {
            scene::Trs trs;
            if (!translation.empty())
                trs.translation = glm::dvec3(glm::make_vec3(&translation[3 * k]));
            if (!rotation.empty()) {
                const glm::dquat q(rotation[4 * k + 3], rotation[4 * k], rotation[4 * k + 1],
                                   rotation[4 * k + 2]);
                if (!(glm::length(q) > 1e-6))
                    fail(what + " ROTATION of instance " + n(k) + " is not a rotation");
                trs.rotation = glm::normalize(q);
            }
            if (!scale.empty())
                trs.scale = glm::dvec3(glm::make_vec3(&scale[3 * k]));
            nodes[i].instances.push_back(trs.matrix());
        }
    }
}

/** The file's extensionsRequired, read from its JSON (chunk 0 of a GLB whose container
 *  checkGlbContainer accepted); empty where the JSON does not parse. */
std::vector<std::string> requiredExtensions(std::span<const std::uint8_t> bytes, bool isBinary) {
    const std::string_view text =
        isBinary ? glbChunks(bytes).json
                 : std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    std::vector<std::string> required;
    const nlohmann::json json = nlohmann::json::parse(text, nullptr, false);
    if (json.is_object() && json.contains("extensionsRequired") &&
        json["extensionsRequired"].is_array())
        for (const nlohmann::json& extension : json["extensionsRequired"])
            if (extension.is_string())
                required.push_back(extension.get<std::string>());
    return required;
}

double number(const tinygltf::Value& object, const char* key, double fallback) {
    if (!object.IsObject() || !object.Has(key))
        return fallback;
    const tinygltf::Value& v = object.Get(key);
    return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

/** An index or texCoord member as int; a value no int holds (huge, NaN) becomes -1, which the
 *  caller's range check then refuses. */
int intNumber(const tinygltf::Value& object, const char* key, int fallback) {
    const double v = number(object, key, double(fallback));
    return v >= double(std::numeric_limits<int>::min()) &&
                   v <= double(std::numeric_limits<int>::max())
               ? int(v)
               : -1;
}

/** KHR_texture_transform in a textureInfo's `extensions`, folded into `ref`: its texCoord
 *  override, offset, rotation and scale. */
void readTransform(const tinygltf::ExtensionMap& extensions, scene::TextureRef& ref,
                   const std::string& what) {
    const auto it = extensions.find("KHR_texture_transform");
    if (it == extensions.end())
        return;
    const tinygltf::Value& e = it->second;
    auto pair = [&](const char* key, glm::vec2 fallback) {
        if (!e.IsObject() || !e.Has(key))
            return fallback;
        const tinygltf::Value& v = e.Get(key);
        if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
            fail(what + " KHR_texture_transform " + key + " is not two numbers");
        return glm::vec2(float(v.Get(0).GetNumberAsDouble()), float(v.Get(1).GetNumberAsDouble()));
    };
    scene::UvTransform t;
    t.offset = pair("offset", glm::vec2(0.0f));
    t.scale = pair("scale", glm::vec2(1.0f));
    t.rotation = float(number(e, "rotation", 0.0));
    if (!std::isfinite(t.offset.x) || !std::isfinite(t.offset.y) || !std::isfinite(t.scale.x) ||
        !std::isfinite(t.scale.y) || !std::isfinite(t.rotation))
        fail(what + " KHR_texture_transform has a non-finite value");
    if (e.IsObject() && e.Has("texCoord"))
        ref.texCoord = intNumber(e, "texCoord", 0);
    ref.setUv(t);
}

/** A glTF textureInfo object (index, texCoord, KHR_texture_transform) at `key` of `object`,
 *  for the extensions whose texture slots tinygltf leaves as JSON values. */
scene::TextureRef textureInfo(const tinygltf::Model& m, const tinygltf::Value& object,
                              const char* key, const std::string& what) {
    scene::TextureRef ref;
    if (!object.IsObject() || !object.Has(key))
        return ref;
    const tinygltf::Value& info = object.Get(key);
    ref.texture = intNumber(info, "index", -1);
    ref.texCoord = intNumber(info, "texCoord", 0);
    if (ref.texture < 0 || std::size_t(ref.texture) >= m.textures.size())
        fail(what + " " + key + " references texture " + std::to_string(ref.texture) +
             ", file has " + n(m.textures.size()) + " textures");
    if (info.IsObject() && info.Has("extensions") && info.Get("extensions").IsObject()) {
        tinygltf::ExtensionMap extensions;
        for (const std::string& name : info.Get("extensions").Keys())
            extensions[name] = info.Get("extensions").Get(name);
        readTransform(extensions, ref, what + " " + key);
    }
    return ref;
}

/** A textureInfo that tinygltf parsed (TextureInfo, NormalTextureInfo, OcclusionTextureInfo). */
template <typename Info>
scene::TextureRef textureRef(const Info& info, double scale, const std::string& what) {
    scene::TextureRef ref{info.index, info.texCoord, float(scale)};
    readTransform(info.extensions, ref, what);
    return ref;
}

void checkRange(double value, double lo, double hi, const std::string& what) {
    if (!(value >= lo && value <= hi))
        fail(what + " is " + std::to_string(value) + ", outside [" + std::to_string(lo) + ", " +
             std::to_string(hi) + "]");
}

/** The three numbers `key` of `object` into `out` when present, each checked in [0, hi]. */
void readColor(const tinygltf::Value& object, const char* key, double hi, const std::string& what,
               glm::vec3& out) {
    if (!object.Has(key) || !object.Get(key).IsArray() || object.Get(key).ArrayLen() != 3)
        return;
    for (int c = 0; c < 3; ++c) {
        out[c] = float(object.Get(key).Get(c).GetNumberAsDouble());
        checkRange(out[c], 0.0, hi, what + " " + key);
    }
}

/** Why buffer `b` may not leave out its uri. */
std::string bufferWithoutUri(std::size_t b, bool isBinary) {
    return "buffer " + n(b) + " has no uri: only a GLB's first buffer (its BIN chunk) and a " +
           "meshopt fallback buffer may leave it out" +
           (isBinary ? "" : " (this file is not a GLB)");
}

/** Which buffer has no uri where one is needed, read from the JSON (tinygltf's error names
 *  none), or empty if the JSON does not tell. */
std::string bufferWithoutUri(std::span<const std::uint8_t> bytes, bool isBinary) {
    const std::string_view text =
        isBinary ? glbChunks(bytes).json
                 : std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    const nlohmann::json json = nlohmann::json::parse(text, nullptr, false);
    if (!json.is_object() || !json.contains("buffers") || !json["buffers"].is_array())
        return "";
    for (std::size_t b = isBinary ? 1 : 0; b < json["buffers"].size(); ++b)
        if (json["buffers"][b].is_object() && !json["buffers"][b].contains("uri"))
            return bufferWithoutUri(b, isBinary);
    return "";
}

} // namespace

std::vector<scene::Node> convertNodes(const tinygltf::Model& m) {
    std::vector<scene::Node> nodes(m.nodes.size());
    for (std::size_t i = 0; i < m.nodes.size(); ++i) {
        const tinygltf::Node& src = m.nodes[i];
        scene::Node& node = nodes[i];
        const std::string what = "node " + n(i);
        node.name = src.name;
        node.children = src.children;
        node.mesh = src.mesh;
        node.skin = src.skin;
        node.camera = src.camera;
        if (const auto it = src.extensions.find("KHR_lights_punctual");
            it != src.extensions.end()) {
            node.light = intNumber(it->second, "light", -1);
            if (node.light < 0 || std::size_t(node.light) >= m.lights.size())
                fail(what + " KHR_lights_punctual light " + std::to_string(node.light) +
                     " is not a light of the file's " + n(m.lights.size()));
        }
        for (int child : src.children)
            nodes[std::size_t(child)].parent = int(i);
        for (double w : src.weights) {
            if (!std::isfinite(w))
                fail(what + " has a non-finite morph weight");
            node.weights.push_back(float(w));
        }
        if (src.matrix.size() == 16) {
            for (double v : src.matrix)
                if (!std::isfinite(v))
                    fail(what + " matrix has a non-finite value");
            node.hasMatrix = true;
            node.restMatrix = glm::make_mat4(src.matrix.data());
            // Decompose for channels that may target the node (the spec forbids it, files do it).
            const glm::dmat4& M = node.restMatrix;
            glm::dvec3 scale(glm::length(glm::dvec3(M[0])), glm::length(glm::dvec3(M[1])),
                             glm::length(glm::dvec3(M[2])));
            if (glm::determinant(glm::dmat3(M)) < 0.0)
                scale.x = -scale.x;
            node.rest.translation = glm::dvec3(M[3]);
            node.rest.scale = scale;
            if (scale.x != 0.0 && scale.y != 0.0 && scale.z != 0.0)
                node.rest.rotation = glm::normalize(glm::quat_cast(
                    glm::dmat3(glm::dvec3(M[0]) / scale.x, glm::dvec3(M[1]) / scale.y,
                               glm::dvec3(M[2]) / scale.z)));
            continue;
        }
        if (src.translation.size() == 3)
            node.rest.translation = glm::make_vec3(src.translation.data());
        if (src.scale.size() == 3)
            node.rest.scale = glm::make_vec3(src.scale.data());
        if (src.rotation.size() == 4) {
            const glm::dquat q(src.rotation[3], src.rotation[0], src.rotation[1], src.rotation[2]);
            const double length = glm::length(q);
            if (!(length > 1e-12) || !std::isfinite(length))
                fail(what + " rotation is not a usable quaternion");
            node.rest.rotation = q / length;
        }
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(node.rest.translation[c]) || !std::isfinite(node.rest.scale[c]))
                fail(what + " has a non-finite translation or scale");
        node.restMatrix = node.rest.matrix();
    }
    return nodes;
}

scene::Texture convertTexture(const tinygltf::Model& m, int index, const std::set<int>& undecoded,
                              std::vector<std::string>& warnings) {
    const tinygltf::Texture& src = m.textures[std::size_t(index)];
    const std::string what = "texture " + n(std::size_t(index));
    scene::Texture texture{src.source, src.sampler};
    auto extensionSource = [&](const char* name) {
        const auto it = src.extensions.find(name);
        if (it == src.extensions.end())
            return -2; // not used
        const int source = intNumber(it->second, "source", -1);
        if (source < 0 || std::size_t(source) >= m.images.size())
            fail(what + " " + name + " source " + std::to_string(source) + " is not an image of " +
                 "the file's " + n(m.images.size()));
        return source;
    };
    if (const int webp = extensionSource("EXT_texture_webp"); webp >= 0)
        texture.image = webp;
    const bool basisu = extensionSource("KHR_texture_basisu") >= 0;
    if (texture.image >= 0 && !undecoded.count(texture.image))
        return texture; // decodable: PNG, JPEG or WebP (KHR_texture_basisu's fallback, say)
    if (basisu)
        warnings.push_back(what + " has only a KHR_texture_basisu (KTX2) image, which this "
                                  "engine cannot decode (Debian 12 has no KTX2 decoder): "
                                  "materials load without it");
    else if (texture.image >= 0)
        warnings.push_back(what + " uses image " + std::to_string(texture.image) +
                           ", a KTX2 image this engine cannot decode: materials load without it");
    texture.image = -1;
    return texture;
}

/** One material's extension objects, and their numbers read with range checks. */
struct ExtensionReader {
    const tinygltf::Model& m;
    const tinygltf::Material& src;
    const std::string& what;
    const tinygltf::Value* find(const char* name) const {
        const auto it = src.extensions.find(name);
        return it == src.extensions.end() ? nullptr : &it->second;
    }
    /** A number of extension `e`'s object, `fallback` when absent, checked in [lo, hi]. */
    float factor(const tinygltf::Value& e, const char* key, double fallback, double lo,
                 double hi) const {
        const float value = float(number(e, key, fallback));
        checkRange(value, lo, hi, what + " " + key);
        return value;
    }
    scene::TextureRef texture(const tinygltf::Value& e, const char* key) const {
        return textureInfo(m, e, key, what);
    }
};

/** KHR_materials_pbrSpecularGlossiness, converted to metallic-roughness as a dielectric
 *  (docs/importer.md, "glTF as shipped"): diffuse becomes the base colour, 1 - glossiness the
 *  roughness; the specular colour and the specular-glossiness texture have no counterpart
 *  there. */
void readSpecularGlossiness(const ExtensionReader& r, const tinygltf::Value& e,
                            scene::Material& mat, std::vector<std::string>& warnings) {
    mat.baseColorFactor = glm::vec4(1.0f);
    if (e.Has("diffuseFactor") && e.Get("diffuseFactor").IsArray() &&
        e.Get("diffuseFactor").ArrayLen() == 4)
        for (int c = 0; c < 4; ++c)
            mat.baseColorFactor[c] = float(e.Get("diffuseFactor").Get(c).GetNumberAsDouble());
    mat.baseColorTexture = r.texture(e, "diffuseTexture");
    mat.metallicFactor = 0.0f;
    mat.roughnessFactor = 1.0f - float(number(e, "glossinessFactor", 1.0));
    mat.metallicRoughnessTexture = {};
    checkRange(mat.roughnessFactor, 0.0, 1.0, r.what + " 1 - glossinessFactor");
    if (e.Has("specularGlossinessTexture"))
        warnings.push_back(r.what + " KHR_materials_pbrSpecularGlossiness: its "
                                    "specularGlossinessTexture is not converted (the "
                                    "glossiness factor is)");
}

/** The layers over the base: specular, clear coat, sheen, iridescence, anisotropy, and the
 *  emissive strength. */
void readLayers(const ExtensionReader& r, scene::Material& mat) {
    if (const tinygltf::Value* e = r.find("KHR_materials_emissive_strength"))
        mat.emissiveStrength = r.factor(*e, "emissiveStrength", 1.0, 0.0, 1e9);
    if (const tinygltf::Value* e = r.find("KHR_materials_specular")) {
        mat.hasSpecular = true;
        mat.specularFactor = r.factor(*e, "specularFactor", 1.0, 0.0, 1.0);
        mat.specularTexture = r.texture(*e, "specularTexture");
        readColor(*e, "specularColorFactor", 1e6, r.what, mat.specularColorFactor);
        mat.specularColorTexture = r.texture(*e, "specularColorTexture");
    }
    if (const tinygltf::Value* e = r.find("KHR_materials_clearcoat")) {
        mat.hasClearcoat = true;
        mat.clearcoatFactor = r.factor(*e, "clearcoatFactor", 0.0, 0.0, 1.0);
        mat.clearcoatTexture = r.texture(*e, "clearcoatTexture");
        mat.clearcoatRoughnessFactor = r.factor(*e, "clearcoatRoughnessFactor", 0.0, 0.0, 1.0);
        mat.clearcoatRoughnessTexture = r.texture(*e, "clearcoatRoughnessTexture");
        mat.clearcoatNormalTexture = r.texture(*e, "clearcoatNormalTexture");
        if (e->Has("clearcoatNormalTexture"))
            mat.clearcoatNormalTexture.scale =
                float(number(e->Get("clearcoatNormalTexture"), "scale", 1.0));
    }
    if (const tinygltf::Value* e = r.find("KHR_materials_sheen")) {
        mat.hasSheen = true;
        readColor(*e, "sheenColorFactor", 1.0, r.what, mat.sheenColorFactor);
        mat.sheenColorTexture = r.texture(*e, "sheenColorTexture");
        mat.sheenRoughnessFactor = r.factor(*e, "sheenRoughnessFactor", 0.0, 0.0, 1.0);
        mat.sheenRoughnessTexture = r.texture(*e, "sheenRoughnessTexture");
    }
    if (const tinygltf::Value* e = r.find("KHR_materials_iridescence")) {
        mat.hasIridescence = true;
        mat.iridescenceFactor = r.factor(*e, "iridescenceFactor", 0.0, 0.0, 1.0);
        mat.iridescenceTexture = r.texture(*e, "iridescenceTexture");
        mat.iridescenceIor = r.factor(*e, "iridescenceIor", 1.3, 1.0, 1e3);
        mat.iridescenceThicknessMinimum =
            r.factor(*e, "iridescenceThicknessMinimum", 100.0, 0.0, 1e6);
        mat.iridescenceThicknessMaximum =
            r.factor(*e, "iridescenceThicknessMaximum", 400.0, 0.0, 1e6);
        mat.iridescenceThicknessTexture = r.texture(*e, "iridescenceThicknessTexture");
    }
    if (const tinygltf::Value* e = r.find("KHR_materials_anisotropy")) {
        mat.hasAnisotropy = true;
        mat.anisotropyStrength = r.factor(*e, "anisotropyStrength", 0.0, 0.0, 1.0);
        mat.anisotropyRotation = r.factor(*e, "anisotropyRotation", 0.0, -1e6, 1e6);
        mat.anisotropyTexture = r.texture(*e, "anisotropyTexture");
    }
}

/** The glass: transmission, volume, index of refraction, dispersion. */
void readGlass(const ExtensionReader& r, scene::Material& mat) {
    if (const tinygltf::Value* e = r.find("KHR_materials_transmission")) {
        mat.hasTransmission = true;
        mat.transmissionFactor = r.factor(*e, "transmissionFactor", 0.0, 0.0, 1.0);
        mat.transmissionTexture = r.texture(*e, "transmissionTexture");
    }
    if (const tinygltf::Value* e = r.find("KHR_materials_volume")) {
        mat.hasVolume = true;
        mat.thicknessFactor = r.factor(*e, "thicknessFactor", 0.0, 0.0, 1e9);
        mat.thicknessTexture = r.texture(*e, "thicknessTexture");
        mat.attenuationDistance = float(number(*e, "attenuationDistance", double(INFINITY)));
        if (!(mat.attenuationDistance > 0.0f))
            fail(r.what + " attenuationDistance must be positive");
        readColor(*e, "attenuationColor", 1.0, r.what, mat.attenuationColor);
    }
    if (const tinygltf::Value* e = r.find("KHR_materials_ior")) {
        mat.hasIor = true;
        mat.ior = float(number(*e, "ior", 1.5));
        if (!(mat.ior == 0.0f || (mat.ior >= 1.0f && mat.ior < 1e6f)))
            fail(r.what + " ior " + std::to_string(mat.ior) + " must be 0 or at least 1");
    }
    if (const tinygltf::Value* e = r.find("KHR_materials_dispersion")) {
        mat.hasDispersion = true;
        mat.dispersion = r.factor(*e, "dispersion", 0.0, 0.0, 1e6);
    }
}

scene::Material convertMaterial(const tinygltf::Model& m, int index,
                                std::vector<std::string>& warnings) {
    const tinygltf::Material& src = m.materials[std::size_t(index)];
    const std::string what = "material " + n(std::size_t(index));
    scene::Material mat;
    mat.name = src.name;
    const auto& pbr = src.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() == 4)
        mat.baseColorFactor = glm::vec4(glm::make_vec4(pbr.baseColorFactor.data()));
    mat.baseColorTexture = textureRef(pbr.baseColorTexture, 1.0, what + " baseColorTexture");
    mat.metallicFactor = float(pbr.metallicFactor);
    mat.roughnessFactor = float(pbr.roughnessFactor);
    mat.metallicRoughnessTexture =
        textureRef(pbr.metallicRoughnessTexture, 1.0, what + " metallicRoughnessTexture");
    mat.normalTexture =
        textureRef(src.normalTexture, src.normalTexture.scale, what + " normalTexture");
    mat.occlusionTexture =
        textureRef(src.occlusionTexture, src.occlusionTexture.strength, what + " occlusionTexture");
    mat.emissiveTexture = textureRef(src.emissiveTexture, 1.0, what + " emissiveTexture");
    if (src.emissiveFactor.size() == 3)
        mat.emissiveFactor = glm::vec3(glm::make_vec3(src.emissiveFactor.data()));
    mat.alphaMode = src.alphaMode == "MASK"    ? scene::AlphaMode::Mask
                    : src.alphaMode == "BLEND" ? scene::AlphaMode::Blend
                                               : scene::AlphaMode::Opaque;
    mat.alphaCutoff = float(src.alphaCutoff);
    mat.doubleSided = src.doubleSided;

    const ExtensionReader reader{m, src, what};
    if (reader.find("KHR_materials_unlit"))
        mat.unlit = true;
    if (const tinygltf::Value* e = reader.find("KHR_materials_pbrSpecularGlossiness"))
        readSpecularGlossiness(reader, *e, mat, warnings);
    readLayers(reader, mat);
    readGlass(reader, mat);
    mat.forEachTexture([&](const scene::TextureRef& t, bool) {
        if (t.present() && (t.texCoord < 0 || t.texCoord > 1))
            fail(what + " uses TEXCOORD_" + std::to_string(t.texCoord) +
                 "; only TEXCOORD_0 and TEXCOORD_1 are supported");
    });
    return mat;
}

scene::Light convertLight(const tinygltf::Model& m, int index) {
    const tinygltf::Light& src = m.lights[std::size_t(index)];
    const std::string what = "KHR_lights_punctual light " + n(std::size_t(index));
    scene::Light light;
    light.name = src.name;
    if (src.type == "directional")
        light.type = scene::Light::Type::Directional;
    else if (src.type == "point")
        light.type = scene::Light::Type::Point;
    else if (src.type == "spot")
        light.type = scene::Light::Type::Spot;
    else
        fail(what + " type \"" + src.type + "\" is not directional, point or spot");
    if (!src.color.empty()) {
        if (src.color.size() != 3)
            fail(what + " color has " + n(src.color.size()) + " values, expected 3");
        for (int c = 0; c < 3; ++c) {
            light.color[c] = float(src.color[std::size_t(c)]);
            checkRange(light.color[c], 0.0, 1.0, what + " color");
        }
    }
    light.intensity = float(src.intensity);
    checkRange(light.intensity, 0.0, 1e12, what + " intensity");
    light.range = float(src.range);
    checkRange(light.range, 0.0, 1e12, what + " range");
    light.innerConeAngle = float(src.spot.innerConeAngle);
    light.outerConeAngle = float(src.spot.outerConeAngle);
    if (light.type == scene::Light::Type::Spot &&
        !(light.innerConeAngle >= 0.0f && light.innerConeAngle < light.outerConeAngle &&
          light.outerConeAngle <= float(M_PI / 2.0) + 1e-6f))
        fail(what + " spot cone angles (inner " + std::to_string(light.innerConeAngle) +
             ", outer " + std::to_string(light.outerConeAngle) +
             ") must satisfy 0 <= inner < outer <= pi/2");
    return light;
}

scene::Camera convertCamera(const tinygltf::Model& m, int index) {
    const tinygltf::Camera& src = m.cameras[std::size_t(index)];
    scene::Camera camera;
    if (src.type == "orthographic") {
        camera.type = scene::Camera::Type::Orthographic;
        camera.xmag = src.orthographic.xmag;
        camera.ymag = src.orthographic.ymag;
        camera.znear = src.orthographic.znear;
        camera.zfar = src.orthographic.zfar;
    } else {
        camera.yfov = src.perspective.yfov;
        camera.aspectRatio = src.perspective.aspectRatio;
        camera.znear = src.perspective.znear;
        camera.zfar = src.perspective.zfar;
        if (!(camera.yfov > 0.0 && camera.yfov < 3.14159) || !(camera.znear > 0.0))
            fail("camera " + n(std::size_t(index)) + " has an invalid yfov or znear");
    }
    return camera;
}

} // namespace detail

namespace {

using namespace detail;

/** tinygltf's parse of `bytes` into `src`; a failure is refused naming its cause: a buffer
 *  without a uri, or a required extension the engine lacks, before the parser's words. */
void parse(tinygltf::TinyGLTF& parser, tinygltf::Model& src, std::span<const std::uint8_t> bytes,
           bool isBinary, const std::string& baseDir) {
    std::string err, warn;
    const bool parsed =
        isBinary ? parser.LoadBinaryFromMemory(&src, &err, &warn, bytes.data(),
                                               unsigned(bytes.size()), baseDir)
                 : parser.LoadASCIIFromString(&src, &err, &warn,
                                              reinterpret_cast<const char*>(bytes.data()),
                                              unsigned(bytes.size()), baseDir);
    if (parsed)
        return;
    while (!err.empty() && (err.back() == '\n' || err.back() == ' '))
        err.pop_back();
    std::replace(err.begin(), err.end(), '\n', ';');
    if (err.empty())
        err = "not a valid glTF file";
    if (err.find("'uri' is missing") != std::string::npos)
        if (const std::string buffer = bufferWithoutUri(bytes, isBinary); !buffer.empty())
            fail(buffer);
    // A required extension the engine lacks (Draco, say) makes the parser stumble on what the
    // extension stores elsewhere: name the extension, not the symptom.
    for (const std::string& extension : requiredExtensions(bytes, isBinary))
        if (!supportedRequiredExtensions().count(extension) && !isMaterialExtension(extension))
            fail("extensionsRequired lists " + extension +
                 ", which this engine does not support (the parser: " + err + ")");
    fail(err);
}

/** Extensions the file uses, or requires (a material one, then), that this engine does not
 *  implement: the file loads without them (what they add is missing), with a warning each. */
void extensionWarnings(const tinygltf::Model& src, std::vector<std::string>& warnings) {
    for (const std::string& extension : src.extensionsUsed)
        if (!supportedRequiredExtensions().count(extension))
            warnings.push_back("extensionsUsed lists " + extension +
                               ", which this engine does not implement: loaded without it");
    for (const std::string& extension : src.extensionsRequired)
        if (!supportedRequiredExtensions().count(extension) &&
            std::find(src.extensionsUsed.begin(), src.extensionsUsed.end(), extension) ==
                src.extensionsUsed.end())
            warnings.push_back("extensionsRequired lists " + extension +
                               ", which this engine does not implement: loaded without it");
}

/** Each instance is drawn as a placement of its own: the instances of one node must fit the
 *  scene's vertex limit on their own (the scene's total is checked when placed). Node morph
 *  weights must match their mesh's targets. */
void checkNodes(const scene::Model& model) {
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        const scene::Node& node = model.nodes[i];
        if (node.mesh < 0)
            continue;
        const scene::Mesh& mesh = model.meshes[std::size_t(node.mesh)];
        std::size_t vertices = 0;
        for (const scene::Primitive& p : mesh.primitives)
            vertices += p.vertexCount();
        if (!node.instances.empty() &&
            vertices * node.instances.size() > core::limits::kMaxSceneVertices)
            fail("node " + n(i) + " EXT_mesh_gpu_instancing: " + n(node.instances.size()) +
                 " instances of " + n(vertices) + " vertices are over the limit of " +
                 n(core::limits::kMaxSceneVertices) + " deformed vertices");
        if (!node.weights.empty() && node.weights.size() != mesh.morphTargetCount())
            fail("node " + n(i) + " has " + n(node.weights.size()) + " morph weights, mesh " +
                 n(std::size_t(node.mesh)) + " has " + n(mesh.morphTargetCount()) + " targets");
    }
}

/** The engine's model of the parsed, checked and decoded file. */
scene::Model convertModel(tinygltf::Model& src, const AccessorReader& reader,
                          const std::set<int>& lossy, const ImageDecoding& images,
                          const std::string& file) {
    scene::Model model;
    model.sourceName = file;
    extensionWarnings(src, model.warnings);
    model.nodes = convertNodes(src);
    model.variants = variantNames(src);
    readInstancing(src, reader, model.nodes, model.warnings);
    fractionalBoundsWarnings(src, model.warnings);
    for (std::size_t i = 0; i < src.materials.size(); ++i)
        model.materials.push_back(convertMaterial(src, int(i), model.warnings));
    for (std::size_t i = 0; i < src.meshes.size(); ++i)
        model.meshes.push_back(
            convertMesh(src, reader, int(i), model.materials, lossy, model.warnings));
    for (std::size_t i = 0; i < src.skins.size(); ++i)
        model.skins.push_back(convertSkin(src, reader, int(i)));
    for (std::size_t i = 0; i < src.animations.size(); ++i)
        model.animations.push_back(
            convertAnimation(src, reader, model.warnings, int(i), model.meshes));
    for (std::size_t i = 0; i < src.cameras.size(); ++i)
        model.cameras.push_back(convertCamera(src, int(i)));
    for (std::size_t i = 0; i < src.lights.size(); ++i)
        model.lights.push_back(convertLight(src, int(i)));
    checkNodes(model);
    validateSkinnedMeshes(model);
    for (const tinygltf::Sampler& s : src.samplers)
        model.samplers.push_back({s.magFilter, s.minFilter, s.wrapS, s.wrapT});
    for (std::size_t i = 0; i < src.textures.size(); ++i)
        model.textures.push_back(convertTexture(src, int(i), images.ktx2, model.warnings));
    for (tinygltf::Image& image : src.images)
        model.images.push_back({image.name, image.uri, image.width, image.height, image.component,
                                image.bits, std::move(image.image)});
    for (const tinygltf::Scene& s : src.scenes)
        model.scenes.push_back(s.nodes);
    model.defaultScene = src.scenes.empty() ? -1 : std::max(src.defaultScene, 0);
    return model;
}

} // namespace

core::Result<scene::Model> loadGltf(const std::filesystem::path& path, const LoadOptions& options) {
    auto bytes = core::readFile(path);
    if (!bytes)
        return core::Error{"asset::loadGltf(): " + path.filename().string() + ": cannot read " +
                           path.string() + " (" + bytes.error().message + ")"};
    return loadGltfFromMemory(*bytes, path.filename().string(), path.parent_path(), options);
}

core::Result<scene::Model> loadGltfFromMemory(std::span<const std::uint8_t> data,
                                              const std::string& file,
                                              const std::filesystem::path& baseDirectory,
                                              const LoadOptions& options) {
    const std::string prefix = "asset::loadGltf(): " + file + ": ";
    try {
        if (data.size() > 0xFFFFFFFFu)
            return core::Error{prefix + "file is over 4 GiB"};
        tinygltf::TinyGLTF parser;
        ImageDecoding images{options.decodeImages, {}};
        parser.SetImageLoader(decodeImage, &images);
        const bool isBinary = data.size() >= 4 && std::memcmp(data.data(), "glTF", 4) == 0;
        if (isBinary)
            checkGlbContainer(data);
        const std::optional<std::vector<std::uint8_t>> prepared = prepareForParser(data, isBinary);
        const std::span<const std::uint8_t> bytes =
            prepared ? std::span<const std::uint8_t>(*prepared) : data;
        tinygltf::Model src;
        parse(parser, src, bytes, isBinary, baseDirectory.string());
        checkVersion(src.asset);
        // tinygltf reads a GLB's BIN chunk for any buffer without a uri, not only the first.
        for (std::size_t b = 1; isBinary && b < src.buffers.size(); ++b)
            if (src.buffers[b].uri.empty())
                fail(bufferWithoutUri(b, isBinary));
        validateStructure(src);
        const std::set<int> lossy = decodeCompressedGeometry(src);
        const AccessorReader reader(src, bytes.size());
        scene::Model model = convertModel(src, reader, lossy, images, file);
        for (const std::string& warning : model.warnings)
            core::logWarning(prefix + warning);
        return model;
    } catch (const LoadError& e) {
        return core::Error{prefix + e.what()};
    } catch (const std::bad_alloc&) {
        return core::Error{prefix +
                           "out of memory while loading (a count in the file is too large)"};
    } catch (const std::exception& e) {
        return core::Error{prefix + "unexpected error: " + e.what()};
    }
}

} // namespace asset
