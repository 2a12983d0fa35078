// The programs' variants a frame needs, from the engine's program cache (each compiled the
// first time a frame needs it): the captures' for K and textured glass, the glass shadow's, the
// walk's for the capture, method, dispersion search, lighting features, layers and textures,
// and the listed samples' (the hybrid's trace, the fresh samples); and the caustics'.
#include "Passes.h"

#include "engine/gl/ProgramCache.h"
#include "engine/scene/Material.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace refraction {

namespace {

std::string define(const std::string& name, int value) {
    return name + " " + std::to_string(value);
}

std::vector<std::string> concat(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

/** The layers' capture and depth maps for capacity K, or the pair's two passes and their
 *  resolve, for the frame's glass model (FrameContext::capture). */
core::Status captureVariants(FrameContext& c) {
    gl::ProgramCache& programs = *c.frame->programs;
    const std::string motion = define("WRITE_MOTION", c.frame->temporal.enabled);
    const std::string glass = "refraction/passes/glass.vert.glsl";
    const std::string rectangle = "refraction/passes/rectangle.vert.glsl";
    core::Result<const gl::Program*> first = nullptr, second = nullptr, overflow = nullptr;
    if (!c.settings.layered()) {
        first = programs.graphics(glass, "refraction/passes/pair_surface.frag.glsl",
                                  concat(c.glassModel, {motion}));
        second = programs.graphics(
            rectangle, "refraction/passes/pair_resolve.frag.glsl",
            concat(c.glassModel, {"LAYER_CAPACITY 2", "PAIR_GATHERED 0", motion}));
    } else {
        // The trace with several samples (or one a frame of a frame that accumulates) reads the
        // textures at their entries as at every hit, at their base level (converging to the
        // reference); with one, filtered like the walk (a pixel's texels averaged, its frame
        // closer to the reference's many rays than one texel).
        const bool baseLevel = c.settings.method == Settings::Method::Trace &&
                               (c.settings.addsSamples() || c.frame->temporal.enabled);
        const std::vector<std::string> defines =
            concat(c.glassModel, {define("LAYER_CAPACITY", c.settings.layerCapacity),
                                  define("TEXTURES_BASE_LEVEL", baseLevel), motion});
        first = programs.graphics(glass, "refraction/passes/layer_capture.frag.glsl", defines);
        second = programs.graphics(rectangle, "refraction/passes/layer_depths.frag.glsl", defines);
        overflow = programs.compute("refraction/passes/layer_overflow.comp.glsl", defines);
    }
    for (const auto* built : {&first, &second, &overflow})
        if (!*built)
            return built->error();
    c.capture = {*first, *second, *overflow};
    return {};
}

/** The parts of the glass's model the frame's glass uses, as defines: the surface layers over
 *  its shading (clear coat, sheen; its surfaces have no film or anisotropy of
 *  common/brdf.glsl's), KHR_materials_specular, the iridescent film, partial transmission,
 *  textures that change its surface, normal maps. */
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
            define("GLASS_NORMAL_MAPS", c.normalMappedGlass)};
}

/** The walk's defines for `method`: the capture (the pair, or the layers' K), the dispersion
 *  search, the frame's lighting features, what of the glass's model it uses, whether it writes
 *  motion, shows a debug view or takes several samples a pixel, and what of the nearby scene
 *  its rays can meet. */
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
         define("SEVERAL_SAMPLES", c.severalSamples()),
         define("HYBRID_LIST", method == Settings::Method::Hybrid),
         define("NEARBY_SCENE", c.seesNearbyScene()),
         define("NEARBY_GROUND", c.seesNearbyScene() && c.frame->settings.ground),
         define("SCENE_DEPTH_TILES", c.marchesScene() && method != Settings::Method::Trace)});
}

/** The caustics' programs, in a frame that focuses them. */
core::Status causticPrograms(FrameContext& c) {
    if (!c.caustics)
        return {};
    gl::ProgramCache& programs = *c.frame->programs;
    const std::string photons = "refraction/passes/caustic_photons.comp.glsl";
    auto grid = programs.compute(photons, {"CAUSTIC_GRID 1"});
    auto list = programs.compute(photons, {"CAUSTIC_LIST 1"});
    auto trace = programs.compute(photons, c.glassModel);
    auto resolve = programs.graphics("render/fullscreen.vert.glsl",
                                     "refraction/passes/caustic_resolve.frag.glsl");
    for (const auto* built : {&grid, &list, &trace, &resolve})
        if (!*built)
            return built->error();
    c.causticPrograms = {*grid, *list, *trace, *resolve};
    return {};
}

} // namespace

core::Status selectVariants(FrameContext& c) {
    c.glassModel = glassDefines(c);
    if (auto built = captureVariants(c); !built)
        return built;
    if (auto built = causticPrograms(c); !built)
        return built;
    auto shadow = c.frame->programs->graphics(
        "refraction/passes/glass.vert.glsl", "refraction/passes/glass_shadow.frag.glsl",
        concat(c.glassModel,
               {"PUNCTUAL_LIGHTS 0", "WRITE_MOTION 0", define("CAUSTIC_EMITTERS", c.caustics)}));
    if (!shadow)
        return shadow.error();
    c.glassShadow = *shadow;
    return {};
}

core::Status selectWalkVariants(FrameContext& c) {
    gl::ProgramCache& programs = *c.frame->programs;
    auto walk =
        programs.graphics("refraction/passes/rectangle.vert.glsl",
                          "refraction/passes/walk.frag.glsl", walkDefines(c, c.settings.method));
    if (!walk)
        return walk.error();
    c.walk = *walk;
    if (!c.settings.traces())
        return {};
    // The listed samples (listed_samples.glsl), storing the format of the walk's target: the
    // trace's variant of the walk, over the hybrid's handed-over pixels or the fresh samples',
    // each compiled where its pass runs.
    std::vector<std::string> defines = walkDefines(c, Settings::Method::Trace);
    // the trace's walk, over the hybrid's list too
    *std::find(defines.begin(), defines.end(), "HYBRID_LIST 0") = "HYBRID_LIST 1";
    defines.push_back(std::string("SHADED_FORMAT ") +
                      (c.settings.addsSamples() ? "rgba32f" : "rgba16f"));
    c.listed = {};
    if (c.settings.method == Settings::Method::Hybrid && c.settings.debug == 0) {
        auto traced = programs.compute("refraction/passes/hybrid_trace.comp.glsl", defines);
        if (!traced)
            return traced.error();
        c.listed.handedOver = *traced;
    }
    if (c.freshSamples() > 1) {
        auto fresh = programs.compute("refraction/passes/fresh_samples.comp.glsl", defines);
        if (!fresh)
            return fresh.error();
        c.listed.fresh = *fresh;
    }
    return {};
}

} // namespace refraction
