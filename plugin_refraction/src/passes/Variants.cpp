// The defines each pass's program variant is keyed by (the passes ask the engine's program cache
// for their variants where they execute: FrameContext::graphics, compute): what of the glass's
// model the frame's glass uses, the layers' capture for K and textured glass, the walk's for the
// capture, method, dispersion search, lighting features, layers and textures.
#include "Passes.h"

#include "engine/gl/ProgramCache.h"
#include "engine/scene/Material.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace refraction {

std::string define(const std::string& name, int value) {
    return name + " " + std::to_string(value);
}

std::vector<std::string> concat(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

core::Result<const gl::Program*>
FrameContext::graphics(const std::string& vertex, const std::string& fragment,
                       const std::vector<std::string>& defines) const {
    auto program = frame->programs->graphics(vertex, fragment, defines);
    if (!program)
        return core::Error{"refraction: " + program.error().message};
    return program;
}

core::Result<const gl::Program*>
FrameContext::compute(const std::string& name, const std::vector<std::string>& defines) const {
    auto program = frame->programs->compute(name, defines);
    if (!program)
        return core::Error{"refraction: " + program.error().message};
    return program;
}

// The surface layers over the glass's shading (clear coat, sheen; its surfaces have no film or
// anisotropy of common/brdf.glsl's), KHR_materials_specular, the iridescent film, partial
// transmission, textures that change its surface, normal maps.
std::vector<std::string> glassDefines(const FrameContext& c) {
    int layers = 0;
    bool specular = false, film = false, partial = false;
    for (const GlassMaterialGpu& m : c.gpu->glassOptics) {
        if (m.clearcoat > 0.0f)
            layers |= scene::Material::kClearcoatLayer;
        if (std::max({m.sheenColor.r, m.sheenColor.g, m.sheenColor.b}) > 0.0f)
            layers |= scene::Material::kSheenLayer;
        specular = specular || m.specularColor != glm::vec3(1.0f) || m.specularWeight != 1.0f;
        film = film || m.iridescence > 0.0f;
        partial = partial || m.transmission < 1.0f || m.transmissionTexture.unit >= 0;
    }
    return {define("SURFACE_LAYERS", layers),
            define("GLASS_SPECULAR", specular),
            define("GLASS_FILM", film),
            define("GLASS_PARTIAL", partial),
            define("GLASS_TEXTURES", c.texturedGlass),
            define("GLASS_BASE_COLOR_TEXTURES", c.baseColorTexturedGlass),
            define("GLASS_TRANSMISSION_TEXTURES", c.transmissionTexturedGlass),
            define("TRACED_TEXTURES_USED", int(c.gpu->tracedTextures.size())),
            define("GLASS_NORMAL_MAPS", c.normalMappedGlass)};
}

std::vector<std::string> layerDefines(const FrameContext& c) {
    // The trace with several samples (or one a frame of a frame that accumulates) reads the
    // textures at their entries as at every hit, at their base level (converging to the
    // reference); with one, filtered like the walk (a pixel's texels averaged, its frame closer
    // to the reference's many rays than one texel).
    const bool baseLevel = c.settings.method == Settings::Method::Trace &&
                           (c.settings.addsSamples() || c.frame->temporal.enabled);
    return concat(c.glassModel, {define("LAYER_CAPACITY", c.settings.layerCapacity),
                                 define("TEXTURES_BASE_LEVEL", baseLevel),
                                 define("WRITE_MOTION", c.frame->temporal.enabled)});
}

std::vector<std::string> walkDefines(const FrameContext& c, Settings::Method method) {
    const int capture = c.settings.layered() ? c.settings.layerCapacity : 0; // 0: the pair
    // Dispersion: none in this frame, or the dispersion search's.
    const bool dispersion =
        std::any_of(c.gpu->glassOptics.begin(), c.gpu->glassOptics.end(),
                    [](const GlassMaterialGpu& m) { return m.ior.r != m.ior.b; });
    return concat(
        concat(c.frame->lighting.defines(), c.glassModel),
        {define("LAYER_CAPACITY", capture == 0 ? 2 : capture), define("CAPTURE_PAIR", capture == 0),
         define("LAYER_DISPERSION",
                dispersion ? int(c.settings.dispersionSearch) : Settings::kNoDispersion),
         define("WRITE_MOTION", c.frame->temporal.enabled),
         define("WALK_DEBUG", c.settings.debug != 0), define("LAYER_METHOD", int(method)),
         define("WALK_DEPTH_MAPS", c.layerDepthMaps()),
         define("SEVERAL_SAMPLES", c.severalSamples()),
         define("FRESH_SAMPLES", c.freshSamples() > 1),
         define("HYBRID_LIST", method == Settings::Method::Hybrid),
         define("NEARBY_SCENE", c.seesNearbyScene()),
         define("NEARBY_GROUND", c.seesNearbyScene() && c.frame->settings.ground),
         define("SCENE_DEPTH_TILES", c.marchesScene() && method != Settings::Method::Trace)});
}

} // namespace refraction
