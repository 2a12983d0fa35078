// Animations: keyframe accessors into engine samplers, checked against their targets.
#include "GltfConvert.h"
#include "GltfDecode.h"

#include "LoadError.h"

#include <cmath>
#include <optional>
#include <regex>
#include <span>
#include <string>

namespace asset::detail {
namespace {

using PropertyName = std::pair<const char*, scene::PointerProperty>;

std::string n(std::size_t v) {
    return std::to_string(v);
}

scene::Interpolation parseInterpolation(const std::string& s, const std::string& what) {
    if (s.empty() || s == "LINEAR")
        return scene::Interpolation::Linear;
    if (s == "STEP")
        return scene::Interpolation::Step;
    if (s == "CUBICSPLINE")
        return scene::Interpolation::CubicSpline;
    fail(what + " has unknown interpolation \"" + s + "\"");
}

scene::AnimationPath parsePath(const std::string& s, const std::string& what) {
    if (s == "translation")
        return scene::AnimationPath::Translation;
    if (s == "rotation")
        return scene::AnimationPath::Rotation;
    if (s == "scale")
        return scene::AnimationPath::Scale;
    if (s == "weights")
        return scene::AnimationPath::Weights;
    fail(what + " has unsupported target path \"" + s + "\"");
}

/** What a pointer other than a node's names: the object's index in its list, the property
 *  and the texture slot of a texture transform. */
struct PointerTarget {
    int object = -1;
    scene::PointerProperty property = scene::PointerProperty::BaseColor;
    int slot = -1;
};

std::optional<scene::PointerProperty> propertyNamed(std::span<const PropertyName> names,
                                                    const std::string& path) {
    for (const auto& [name, property] : names)
        if (path == name)
            return property;
    return std::nullopt;
}

/** A material factor, or a texture slot's transform: `path` follows /materials/N/. */
std::optional<PointerTarget> materialTarget(int material, const std::string& path) {
    using P = scene::PointerProperty;
    static const PropertyName factors[] = {
        {"pbrMetallicRoughness/baseColorFactor", P::BaseColor},
        {"pbrMetallicRoughness/metallicFactor", P::Metallic},
        {"pbrMetallicRoughness/roughnessFactor", P::Roughness},
        {"emissiveFactor", P::Emissive},
        {"extensions/KHR_materials_emissive_strength/emissiveStrength", P::EmissiveStrength},
        {"extensions/KHR_materials_transmission/transmissionFactor", P::Transmission},
        {"extensions/KHR_materials_ior/ior", P::Ior},
        {"extensions/KHR_materials_volume/thicknessFactor", P::Thickness},
        {"extensions/KHR_materials_volume/attenuationDistance", P::AttenuationDistance},
        {"extensions/KHR_materials_volume/attenuationColor", P::AttenuationColor},
        {"extensions/KHR_materials_dispersion/dispersion", P::Dispersion},
    };
    static const PropertyName transform[] = {
        {"offset", P::TextureOffset}, {"rotation", P::TextureRotation}, {"scale", P::TextureScale}};
    if (const auto factor = propertyNamed(factors, path))
        return PointerTarget{material, *factor, -1};
    for (std::size_t slot = 0; slot < std::size(scene::kTextureSlots); ++slot) {
        const std::string prefix =
            std::string(scene::kTextureSlots[slot].path) + "/extensions/KHR_texture_transform/";
        if (path.rfind(prefix, 0) == 0)
            if (const auto part = propertyNamed(transform, path.substr(prefix.size())))
                return PointerTarget{material, *part, int(slot)};
    }
    return std::nullopt;
}

/** The target of a material, light or camera pointer; none for any other. */
std::optional<PointerTarget> pointerTarget(const std::string& pointer) {
    using P = scene::PointerProperty;
    static const std::regex object(
        R"(^/(materials|extensions/KHR_lights_punctual/lights|cameras)/(0|[1-9][0-9]{0,8})/(.+)$)");
    static const PropertyName light[] = {{"color", P::LightColor},
                                         {"intensity", P::LightIntensity},
                                         {"range", P::LightRange},
                                         {"spot/innerConeAngle", P::LightInnerCone},
                                         {"spot/outerConeAngle", P::LightOuterCone}};
    static const PropertyName camera[] = {{"perspective/yfov", P::CameraYfov}};
    std::smatch match;
    if (!std::regex_match(pointer, match, object))
        return std::nullopt;
    const int index = std::stoi(match[2].str());
    const std::string list = match[1].str(), path = match[3].str();
    if (list == "materials")
        return materialTarget(index, path);
    const auto property =
        list == "cameras" ? propertyNamed(camera, path) : propertyNamed(light, path);
    if (!property)
        return std::nullopt;
    return PointerTarget{index, *property, -1};
}

/** How many objects of the kind a pointer target names the file has, and the kind. */
std::pair<std::size_t, const char*> objectsOf(const tinygltf::Model& model,
                                              scene::PointerProperty property) {
    switch (scene::objectOf(property)) {
    case scene::PointerObject::Material:
        return {model.materials.size(), "material"};
    case scene::PointerObject::Light:
        return {model.lights.size(), "light"};
    case scene::PointerObject::Camera:
        return {model.cameras.size(), "camera"};
    }
    return {0, ""};
}

/** A KHR_animation_pointer channel (prepareForParser rewrote it), listed in anim.pointers: a
 *  material's, light's or camera's property becomes a channel of its own; a pointer the engine
 *  does not play is skipped with a warning; a channel without a pointer string, or naming an
 *  object the file lacks, is refused. False for a node's TRS or weights, which the caller
 *  converts as any channel. */
bool convertPointerChannel(const tinygltf::Model& model, const tinygltf::AnimationChannel& ch,
                           int c, const std::string& channelWhat, std::vector<int>& components,
                           std::vector<std::string>& warnings, scene::Animation& anim) {
    const std::string pointer = ch.extras.Get(kPointerExtra).Get<std::string>();
    if (ch.target_path == kMalformedPointer)
        fail(channelWhat + " has KHR_animation_pointer without a pointer string (" +
             (pointer.empty() ? std::string("none") : pointer) + ")");
    const auto target = pointerTarget(pointer);
    const bool played = ch.target_path != kSkippedPointer || target;
    anim.pointers.push_back({c, pointer, played});
    if (!played) {
        warnings.push_back(channelWhat + (anim.name.empty() ? "" : " ('" + anim.name + "')") +
                           ": KHR_animation_pointer \"" + pointer +
                           "\" is not played by this engine: skipped");
        return true;
    }
    if (!target)
        return false;
    const auto [count, kind] = objectsOf(model, target->property);
    if (std::size_t(target->object) >= count)
        fail(channelWhat + " KHR_animation_pointer " + pointer + " names " + kind + " " +
             n(std::size_t(target->object)) + ", file has " + n(count) + " " + kind +
             (count == 1 ? "" : "s"));
    scene::AnimationChannel channel;
    channel.sampler = ch.sampler;
    channel.path = scene::AnimationPath::Pointer;
    channel.object = target->object;
    channel.property = target->property;
    channel.slot = target->slot;
    const int needed = scene::componentCount(channel.property);
    int& have = components[std::size_t(ch.sampler)];
    if (have != 0 && have != needed) // a weights sampler of one target is scalar too
        fail(channelWhat + " shares sampler " + n(std::size_t(ch.sampler)) +
             " with a channel of a different value size");
    have = needed;
    anim.channels.push_back(channel);
    return true;
}

/** Sampler `ss`'s keys, with `components` floats a value (from the channels that use it;
 *  0: none does, its output is not read), weights when `isWeights`. Times must not decrease
 *  nor start below zero, the values must fill every key, and rotation keys (not tangents)
 *  must be usable quaternions, which are normalised. */
scene::AnimationSampler convertSampler(const AccessorReader& reader,
                                       const tinygltf::AnimationSampler& ss, int components,
                                       bool isWeights, const std::string& what) {
    scene::AnimationSampler sampler;
    sampler.interpolation = parseInterpolation(ss.interpolation, what);
    sampler.components = components;
    sampler.times = reader.readFloats(ss.input, 1, what + " input");
    if (sampler.times.empty())
        fail(what + " input has no keyframes");
    for (std::size_t k = 1; k < sampler.times.size(); ++k)
        if (sampler.times[k] < sampler.times[k - 1])
            fail(what + " input time " + n(k) + " decreases");
    if (sampler.times.front() < 0.0f)
        fail(what + " input starts at a negative time");
    if (sampler.components == 0)
        return sampler; // unused by any channel
    const std::vector<float> values =
        reader.readFloats(ss.output, isWeights ? 1 : sampler.components, what + " output");
    const std::size_t perKey =
        std::size_t(sampler.components) *
        (sampler.interpolation == scene::Interpolation::CubicSpline ? 3u : 1u);
    if (values.size() != sampler.times.size() * perKey)
        fail(what + " output has " + n(values.size()) + " values, expected " +
             n(sampler.times.size() * perKey) + " for " + n(sampler.times.size()) + " keys");
    sampler.values = values;
    if (sampler.components == 4 && !isWeights) {
        // Rotation keys (not tangents) must be usable quaternions.
        const std::size_t stride = perKey, offset = perKey == 12 ? 4 : 0;
        for (std::size_t k = 0; k < sampler.times.size(); ++k) {
            float* q = &sampler.values[k * stride + offset];
            const float length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
            if (!(length > 1e-8f))
                fail(what + " rotation key " + n(k) + " is a zero quaternion");
            for (int c = 0; c < 4; ++c)
                q[c] /= length;
        }
    }
    return sampler;
}

} // namespace

scene::Animation convertAnimation(const tinygltf::Model& model, const AccessorReader& reader,
                                  std::vector<std::string>& warnings, int index,
                                  const std::vector<scene::Mesh>& meshes) {
    const tinygltf::Animation& src = model.animations[std::size_t(index)];
    const std::string what = "animation " + n(std::size_t(index));
    scene::Animation anim;
    anim.name = src.name;

    // The component count of a sampler comes from the channels that use it.
    std::vector<int> components(src.samplers.size(), 0);
    std::vector<bool> drivesWeights(src.samplers.size(), false);
    for (std::size_t c = 0; c < src.channels.size(); ++c) {
        const tinygltf::AnimationChannel& ch = src.channels[c];
        const std::string channelWhat = what + " channel " + n(c);
        if (ch.extras.Has(kPointerExtra) &&
            convertPointerChannel(model, ch, int(c), channelWhat, components, warnings, anim))
            continue;
        scene::AnimationChannel channel;
        channel.sampler = ch.sampler;
        channel.node = ch.target_node;
        channel.path = parsePath(ch.target_path, channelWhat);
        int needed = 3;
        if (channel.path == scene::AnimationPath::Rotation)
            needed = 4;
        if (channel.path == scene::AnimationPath::Weights) {
            const int mesh = model.nodes[std::size_t(ch.target_node)].mesh;
            if (mesh < 0 || meshes[std::size_t(mesh)].morphTargetCount() == 0)
                fail(channelWhat + " animates the weights of node " +
                     n(std::size_t(ch.target_node)) + ", which has no morph targets");
            needed = int(meshes[std::size_t(mesh)].morphTargetCount());
        }
        int& have = components[std::size_t(ch.sampler)];
        const bool weights = channel.path == scene::AnimationPath::Weights;
        if (have != 0 && (have != needed || drivesWeights[std::size_t(ch.sampler)] != weights))
            fail(channelWhat + " shares sampler " + n(std::size_t(ch.sampler)) +
                 " with a channel of a different value size");
        have = needed;
        drivesWeights[std::size_t(ch.sampler)] = weights;
        anim.channels.push_back(channel);
    }

    for (std::size_t s = 0; s < src.samplers.size(); ++s) {
        anim.samplers.push_back(convertSampler(reader, src.samplers[s], components[s],
                                               drivesWeights[s], what + " sampler " + n(s)));
        if (!anim.samplers.back().values.empty())
            anim.duration = std::max(anim.duration, double(anim.samplers.back().times.back()));
    }
    return anim;
}

} // namespace asset::detail
