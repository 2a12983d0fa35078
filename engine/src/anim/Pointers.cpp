// KHR_animation_pointer properties: sampled, blended as three.js's PropertyMixer blends a
// node's, and written into the pose's copies of the model's materials, lights and cameras.
#include "Pointers.h"

#include "engine/anim/Sampler.h"

#include <array>

namespace anim::detail {
namespace {

using P = scene::PointerProperty;

/** Where material `m` (const or not) keeps a factor: its componentCount() floats. */
template <class M> auto* factorIn(M& m, P property) {
    switch (property) {
    case P::BaseColor:
        return &m.baseColorFactor.x;
    case P::Roughness:
        return &m.roughnessFactor;
    case P::Emissive:
        return &m.emissiveFactor.x;
    case P::EmissiveStrength:
        return &m.emissiveStrength;
    case P::Transmission:
        return &m.transmissionFactor;
    case P::Ior:
        return &m.ior;
    case P::Thickness:
        return &m.thicknessFactor;
    case P::AttenuationDistance:
        return &m.attenuationDistance;
    case P::AttenuationColor:
        return &m.attenuationColor.x;
    case P::Dispersion:
        return &m.dispersion;
    case P::Metallic:
    default: // not a factor: the callers ask for factors only
        return &m.metallicFactor;
    }
}

/** Where light `l` keeps a property. */
template <class L> auto* lightIn(L& l, P property) {
    switch (property) {
    case P::LightColor:
        return &l.color.x;
    case P::LightRange:
        return &l.range;
    case P::LightInnerCone:
        return &l.innerConeAngle;
    case P::LightOuterCone:
        return &l.outerConeAngle;
    case P::LightIntensity:
    default: // not a light's: the callers ask for a light's only
        return &l.intensity;
    }
}

/** A texture transform's part as floats (the rotation, or the offset's or scale's two). */
template <class T> auto* uvIn(T& t, P property) {
    return property == P::TextureOffset     ? &t.offset.x
           : property == P::TextureRotation ? &t.rotation
                                            : &t.scale.x;
}

/** The model's value of the property `b` blends. */
glm::dvec4 restValue(const scene::Model& model, const Pose::PointerBlend& b) {
    const std::size_t i = std::size_t(b.object);
    glm::dvec4 v(0.0);
    const auto read = [&](const float* f) {
        for (int c = 0; c < scene::componentCount(b.property); ++c)
            v[c] = double(f[c]);
    };
    switch (scene::objectOf(b.property)) {
    case scene::PointerObject::Material: {
        const scene::Material& m = model.materials[i];
        if (b.slot >= 0)
            read(uvIn((m.*scene::kTextureSlots[std::size_t(b.slot)].ref).uv, b.property));
        else
            read(factorIn(m, b.property));
        break;
    }
    case scene::PointerObject::Light:
        read(lightIn(model.lights[i], b.property));
        break;
    case scene::PointerObject::Camera:
        v[0] = model.cameras[i].yfov;
        break;
    }
    return v;
}

/** Writes `v` into the pose's copy of the property `b` blends. */
void setValue(Pose& pose, const Pose::PointerBlend& b, const glm::dvec4& v) {
    const std::size_t i = std::size_t(b.object);
    const auto write = [&](float* f) {
        for (int c = 0; c < scene::componentCount(b.property); ++c)
            f[c] = float(v[c]);
    };
    switch (scene::objectOf(b.property)) {
    case scene::PointerObject::Material: {
        scene::Material& m = pose.materials[i];
        if (b.slot < 0) {
            write(factorIn(m, b.property));
            break;
        }
        scene::TextureRef& ref = m.*scene::kTextureSlots[std::size_t(b.slot)].ref;
        scene::UvTransform t = ref.uv;
        write(uvIn(t, b.property));
        ref.setUv(t);
        break;
    }
    case scene::PointerObject::Light:
        write(lightIn(pose.lights[i], b.property));
        break;
    case scene::PointerObject::Camera:
        pose.cameras[i].yfov = v[0];
        break;
    }
}

glm::dvec4 lerp4(const glm::dvec4& a, const glm::dvec4& b, double s) {
    return a + (b - a) * s;
}

/** The blend of channel `channel`'s property, added to the pose's list if new. */
Pose::PointerBlend& blendOf(const scene::AnimationChannel& channel, Pose& pose) {
    for (Pose::PointerBlend& b : pose.pointers)
        if (b.object == channel.object && b.slot == channel.slot && b.property == channel.property)
            return b;
    Pose::PointerBlend& b = pose.pointers.emplace_back();
    b.object = channel.object;
    b.slot = channel.slot;
    b.property = channel.property;
    return b;
}

/** Copies the model's list into the pose's where `used`, empties it where not. */
template <class T> void copyWhere(bool used, const std::vector<T>& from, std::vector<T>& into) {
    if (used)
        into.assign(from.begin(), from.end());
    else
        into.clear();
}

} // namespace

void resetPointers(Pose& pose) {
    pose.pointers.clear(); // keeps its capacity: the next evaluation allocates nothing
}

void addPointer(const scene::AnimationChannel& channel, const scene::AnimationSampler& sampler,
                double clipTime, double weight, bool additive, Pose& pose) {
    const auto read = [&](double time) {
        std::array<double, 4> v{};
        sample(sampler, time, false, std::span(v.data(), std::size_t(sampler.components)));
        return glm::dvec4(v[0], v[1], v[2], v[3]);
    };
    Pose::PointerBlend& b = blendOf(channel, pose);
    if (additive) {
        b.added += (read(clipTime) - read(0.0)) * weight;
        b.addedWeight += weight;
    } else if (b.weight == 0.0) {
        b.value = read(clipTime);
        b.weight = weight;
    } else {
        b.weight += weight;
        b.value = lerp4(b.value, read(clipTime), weight / b.weight);
    }
}

void finishPointers(const scene::Model& model, Pose& pose) {
    std::array<bool, 3> played{};
    for (const Pose::PointerBlend& b : pose.pointers)
        played[std::size_t(scene::objectOf(b.property))] = true;
    copyWhere(played[std::size_t(scene::PointerObject::Material)], model.materials, pose.materials);
    copyWhere(played[std::size_t(scene::PointerObject::Light)], model.lights, pose.lights);
    copyWhere(played[std::size_t(scene::PointerObject::Camera)], model.cameras, pose.cameras);
    for (const Pose::PointerBlend& b : pose.pointers) {
        const glm::dvec4 rest = restValue(model, b);
        const glm::dvec4 v = b.weight <= 0.0  ? rest
                             : b.weight < 1.0 ? lerp4(b.value, rest, 1.0 - b.weight)
                                              : b.value;
        setValue(pose, b, v + b.added);
    }
}

} // namespace anim::detail
