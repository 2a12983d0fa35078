// render::LightingFeatures: from the frame's lights and shadow plan to defines.
#include "engine/render/LightingFeatures.h"

namespace render {

LightingFeatures LightingFeatures::of(std::span<const scene::PlacedLight> lights,
                                      const ShadowPlan& plan, bool glassShadows, bool caustics) {
    LightingFeatures f;
    f.lights = !lights.empty();
    for (const scene::PlacedLight& l : lights) {
        f.directional = f.directional || l.light.type == scene::Light::Type::Directional;
        f.point = f.point || l.light.type == scene::Light::Type::Point;
        f.spot = f.spot || l.light.type == scene::Light::Type::Spot;
    }
    for (std::size_t i = 0; i < lights.size() && i < plan.firstView.size(); ++i)
        if (plan.firstView[i] >= 0) {
            f.shadowMaps = true;
            f.softShadows = f.softShadows || lights[i].light.shadow.softness > 0.0f;
        }
    f.glassShadows = f.shadowMaps && glassShadows;
    f.caustics = f.shadowMaps && caustics;
    return f;
}

std::vector<std::string> LightingFeatures::defines() const {
    auto define = [](const char* name, bool on) { return std::string(name) + (on ? " 1" : " 0"); };
    return {define("PUNCTUAL_LIGHTS", lights),    define("DIRECTIONAL_LIGHTS", directional),
            define("POINT_LIGHTS", point),        define("SPOT_LIGHTS", spot),
            define("SHADOW_MAPS", shadowMaps),    define("SHADOW_SOFT", softShadows),
            define("SHADOW_GLASS", glassShadows), define("SHADOW_CAUSTICS", caustics)};
}

} // namespace render
