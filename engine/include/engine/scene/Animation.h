// Engine-owned animation clips: keyframe samplers and the node properties they drive.
#pragma once

#include <string>
#include <vector>

namespace scene {

enum class Interpolation { Step, Linear, CubicSpline };
/** What a channel drives: a node's TRS or morph weights, or (KHR_animation_pointer) a material
 *  factor. */
enum class AnimationPath { Translation, Rotation, Scale, Weights, Material };

/** The material factors KHR_animation_pointer channels play, each as its glTF property. */
enum class MaterialProperty {
    BaseColor,           ///< pbrMetallicRoughness/baseColorFactor (4)
    Metallic,            ///< pbrMetallicRoughness/metallicFactor
    Roughness,           ///< pbrMetallicRoughness/roughnessFactor
    Emissive,            ///< emissiveFactor (3)
    EmissiveStrength,    ///< KHR_materials_emissive_strength/emissiveStrength
    Transmission,        ///< KHR_materials_transmission/transmissionFactor
    Ior,                 ///< KHR_materials_ior/ior
    Thickness,           ///< KHR_materials_volume/thicknessFactor
    AttenuationDistance, ///< KHR_materials_volume/attenuationDistance
    AttenuationColor,    ///< KHR_materials_volume/attenuationColor (3)
    Dispersion,          ///< KHR_materials_dispersion/dispersion
};
inline constexpr int kMaterialProperties = 11;

/** The number of floats `property` holds: 4 for the base colour, 3 for colours, else 1. */
int componentCount(MaterialProperty property);

const char* toString(Interpolation interpolation);
const char* toString(AnimationPath path);

/** Keyframes: `times` strictly increasing (seconds); `values` holds `components` floats per
 *  element. CubicSpline stores three elements per key: in-tangent, value, out-tangent.
 *  Rotation values are xyzw quaternions, as in glTF. */
struct AnimationSampler {
    std::vector<float> times;
    std::vector<float> values;
    Interpolation interpolation = Interpolation::Linear;
    int components = 0; ///< 3 (translation, scale), 4 (rotation) or the morph-target count
};

struct AnimationChannel {
    int sampler = -1;
    int node = -1; ///< the node it drives; -1 for a material channel
    AnimationPath path = AnimationPath::Translation;
    int material = -1; ///< for AnimationPath::Material: the material and its factor
    MaterialProperty property = MaterialProperty::BaseColor;
};

/** A KHR_animation_pointer channel of the file: played (a node's TRS or weights, among the
 *  channels) or skipped (a pointer this engine does not play). */
struct PointerChannel {
    int channel = -1; ///< the file's index in the animation's channels
    std::string pointer;
    bool played = false;
};

struct Animation {
    std::string name;
    std::vector<AnimationSampler> samplers;
    std::vector<AnimationChannel> channels;
    double duration = 0.0;                ///< last key time over all samplers, seconds
    std::vector<PointerChannel> pointers; ///< the file's pointer channels, in its order
};

} // namespace scene
