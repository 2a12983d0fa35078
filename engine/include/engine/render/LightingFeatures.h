// What a frame's lights ask of the programs that shade: the parts of common/lighting.glsl and
// common/shadows.glsl a program compiles for that frame.
#pragma once

#include "engine/render/Shadows.h"
#include "engine/scene/Light.h"

#include <span>
#include <string>
#include <vector>

namespace render {

/** The lighting parts a frame uses, each a define of the programs that shade (a CPU rasteriser
 *  runs every branch of a quad, so a part compiled in costs its whole time even where it is
 *  off). Programs built without these defines keep every part. */
struct LightingFeatures {
    bool lights = false; ///< PUNCTUAL_LIGHTS: the frame has punctual lights
    /** DIRECTIONAL_LIGHTS, POINT_LIGHTS, SPOT_LIGHTS: it has lights of that type (the code of
     *  the others, their falloffs, cube faces and perspective maps, is out). */
    bool directional = false, point = false, spot = false;
    bool shadowMaps = false;   ///< SHADOW_MAPS: one of them casts
    bool softShadows = false;  ///< SHADOW_SOFT: a casting light filters over a radius
    bool glassShadows = false; ///< SHADOW_GLASS: a plugin drew glass into the glass atlas
    bool caustics = false;     ///< SHADOW_CAUSTICS: a plugin focused caustics

    /** The features of `lights` under `plan` (which of them cast), with what the plugins drew
     *  into the glass and caustics atlases; those count only where a light casts. */
    static LightingFeatures of(std::span<const scene::PlacedLight> lights, const ShadowPlan& plan,
                               bool glassShadows, bool caustics);
    /** The defines, one per feature: "PUNCTUAL_LIGHTS 1", "SHADOW_MAPS 0", ... */
    std::vector<std::string> defines() const;
    bool operator==(const LightingFeatures&) const = default;
};

} // namespace render
