// Engine-owned animation clips: keyframe samplers and the node properties they drive.
#pragma once

#include <string>
#include <vector>

namespace scene {

enum class Interpolation { Step, Linear, CubicSpline };
/** What a channel drives: a node's TRS or morph weights, or (KHR_animation_pointer) a property
 *  of a material, a light or a camera. */
enum class AnimationPath { Translation, Rotation, Scale, Weights, Pointer };

/** The properties KHR_animation_pointer channels play besides a node's, each as its glTF
 *  property: a material's factors and its texture slots' KHR_texture_transform, a
 *  KHR_lights_punctual light's, a camera's. */
enum class PointerProperty {
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
    TextureOffset,       ///< a texture slot's KHR_texture_transform/offset (2)
    TextureRotation,     ///< a texture slot's KHR_texture_transform/rotation
    TextureScale,        ///< a texture slot's KHR_texture_transform/scale (2)
    LightColor,          ///< a light's color (3)
    LightIntensity,      ///< a light's intensity
    LightRange,          ///< a light's range
    LightInnerCone,      ///< a spot light's spot/innerConeAngle
    LightOuterCone,      ///< a spot light's spot/outerConeAngle
    CameraYfov,          ///< a camera's perspective/yfov
};

/** What a pointer property belongs to. */
enum class PointerObject { Material, Light, Camera };
PointerObject objectOf(PointerProperty property);

/** The number of floats `property` holds (1 to 4). */
int componentCount(PointerProperty property);

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
    /** For AnimationPath::Pointer: the material, light or camera (an index into the model's),
     *  its property and, for a texture transform, the texture slot (kTextureSlots). */
    int object = -1;
    PointerProperty property = PointerProperty::BaseColor;
    int slot = -1;
};

/** A KHR_animation_pointer channel of the file: played (among the channels) or skipped (a
 *  pointer this engine does not play). */
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
