// The programs' variants a frame needs, compiled when first needed and kept: the captures' for
// K and textured glass, the walk's for the capture, method, dispersion search, lights and
// textures, the hybrid's trace pass's, and the caustics' (the emitters' glass shadow, the
// photons, the resolve).
#include "Passes.h"

#include <algorithm>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace refraction {

namespace {

std::string define(const std::string& name, int value) {
    return name + " " + std::to_string(value);
}

/** The layers' capture and depth maps for capacity K, or the pair's two passes and their
 *  resolve, for whether the frame's glass is textured. */
core::Status captureVariants(GpuState& gpu, const FrameContext& c) {
    const gl::ShaderLibrary& shaders = *c.frame->shaders;
    const bool textures = c.texturedGlass;
    if (!c.settings.layered()) {
        if (gpu.pairPrograms == int(textures))
            return {};
        auto surface = gl::Program::graphics(shaders, "refraction/glass.vert.glsl",
                                             "refraction/pair_surface.frag.glsl",
                                             {define("GLASS_TEXTURES", textures)});
        if (!surface)
            return surface.error();
        auto resolve = gl::Program::graphics(
            shaders, "refraction/rectangle.vert.glsl", "refraction/pair_resolve.frag.glsl",
            {"LAYER_CAPACITY 2", "PAIR_GATHERED 0", define("GLASS_TEXTURES", textures)});
        if (!resolve)
            return resolve.error();
        gpu.pairSurface = std::move(*surface);
        gpu.pairResolve[0] = std::move(*resolve);
        gpu.pairPrograms = int(textures);
        return {};
    }
    const int capacity = c.settings.layerCapacity;
    // The trace with several samples (or one a frame of a frame that accumulates) reads the
    // textures at their entries as at every hit, at their base level (converging to the
    // reference); with one, filtered like the walk (a pixel's texels averaged, its frame closer
    // to the reference's many rays than one texel).
    const bool baseLevel = c.settings.method == Settings::Method::Trace &&
                           (c.settings.addsSamples() || c.frame->temporal.enabled);
    if (gpu.layerPrograms == std::tuple{capacity, textures, baseLevel})
        return {};
    const std::vector<std::string> defines{define("LAYER_CAPACITY", capacity),
                                           define("GLASS_TEXTURES", textures),
                                           define("TEXTURES_BASE_LEVEL", baseLevel)};
    auto capture = gl::Program::graphics(shaders, "refraction/glass.vert.glsl",
                                         "refraction/layer_capture.frag.glsl", defines);
    if (!capture)
        return capture.error();
    auto depths = gl::Program::graphics(shaders, "refraction/rectangle.vert.glsl",
                                        "refraction/layer_depths.frag.glsl", defines);
    if (!depths)
        return depths.error();
    gpu.layerCapture = std::move(*capture);
    gpu.layerDepths = std::move(*depths);
    gpu.layerPrograms = {capacity, textures, baseLevel};
    return {};
}

/** The walk's defines for `method` under `key`'s capture, dispersion search, lights and
 *  textures. */
std::vector<std::string> walkDefines(const GpuState::WalkKey& key, Settings::Method method) {
    const int capture = std::get<0>(key);
    return {define("LAYER_CAPACITY", capture == 0 ? 2 : capture),
            define("CAPTURE_PAIR", capture == 0),
            define("LAYER_DISPERSION", std::get<2>(key)),
            define("PUNCTUAL_LIGHTS", std::get<3>(key)),
            define("GLASS_TEXTURES", std::get<4>(key)),
            define("LAYER_METHOD", int(method)),
            define("HYBRID_LIST", method == Settings::Method::Hybrid)};
}

/** The caustics' programs, the first frame that focuses them. */
core::Status causticPrograms(GpuState& gpu, const FrameContext& c) {
    if (!c.caustics || gpu.causticResolve.id() != 0)
        return {};
    const gl::ShaderLibrary& shaders = *c.frame->shaders;
    const std::string photons = "refraction/caustic_photons.comp.glsl";
    auto emitters = gl::Program::graphics(
        shaders, "refraction/glass.vert.glsl", "refraction/glass_shadow.frag.glsl",
        {"GLASS_TEXTURES 1", "PUNCTUAL_LIGHTS 0", "CAUSTIC_EMITTERS 1"});
    auto grid = gl::Program::compute(shaders, photons, {"CAUSTIC_GRID 1"});
    auto trace = gl::Program::compute(shaders, photons, {});
    auto resolve = gl::Program::graphics(shaders, "render/fullscreen.vert.glsl",
                                         "refraction/caustic_resolve.frag.glsl", {});
    for (const auto* built : {&emitters, &grid, &trace, &resolve})
        if (!*built)
            return built->error();
    gpu.glassShadow[1] = std::move(*emitters);
    gpu.causticGrid = std::move(*grid);
    gpu.causticPhotons = std::move(*trace);
    gpu.causticResolve = std::move(*resolve);
    return {};
}

} // namespace

core::Status selectVariants(GpuState& gpu, FrameContext& c) {
    if (auto built = captureVariants(gpu, c); !built)
        return built;
    if (auto built = causticPrograms(gpu, c); !built)
        return built;
    // Dispersion: none in this frame, or the dispersion search's.
    const bool dispersion =
        std::any_of(gpu.glassOptics.begin(), gpu.glassOptics.end(),
                    [](const GlassMaterialGpu& m) { return m.ior.r != m.ior.b; });
    const int mode = dispersion ? int(c.settings.dispersionSearch) : Settings::kNoDispersion;
    const int capture = c.settings.layered() ? c.settings.layerCapacity : 0; // 0: the pair
    auto key = [&](Settings::Method method) {
        return GpuState::WalkKey{capture, int(method), mode, c.lit(), c.texturedGlass};
    };
    if (!gpu.walkPrograms.count(key(c.settings.method))) {
        // Every method's variant at once: switching methods (the viewer's panel) then compiles
        // nothing, and the live programs do not depend on which methods ran.
        for (const Settings::Method method :
             {Settings::Method::Sir, Settings::Method::Isr, Settings::Method::Dir,
              Settings::Method::Trace, Settings::Method::Hybrid}) {
            auto walk = gl::Program::graphics(*c.frame->shaders, "refraction/rectangle.vert.glsl",
                                              "refraction/walk.frag.glsl",
                                              walkDefines(key(method), method));
            if (!walk)
                return walk.error();
            gpu.walkPrograms.insert_or_assign(key(method), std::move(*walk));
        }
    }
    c.walk = &gpu.walkPrograms.at(key(c.settings.method));
    if (!c.settings.traces())
        return {};
    // The listed samples (listed_samples.comp.glsl), storing the format of the walk's target:
    // the trace's variant of the walk, over the hybrid's handed-over pixels or the fresh
    // samples'.
    const bool addsUp = c.settings.addsSamples();
    const auto listedKey = std::pair{key(Settings::Method::Hybrid), addsUp};
    if (!gpu.listedSamples.count(listedKey)) {
        std::vector<std::string> defines = walkDefines(listedKey.first, Settings::Method::Trace);
        defines.back() = "HYBRID_LIST 1"; // the trace's walk, over the hybrid's list too
        defines.push_back(std::string("SHADED_FORMAT ") + (addsUp ? "rgba32f" : "rgba16f"));
        auto listed =
            gl::Program::compute(*c.frame->shaders, "refraction/listed_samples.comp.glsl", defines);
        if (!listed)
            return listed.error();
        gpu.listedSamples.insert_or_assign(listedKey, std::move(*listed));
    }
    c.listedSamples = &gpu.listedSamples.at(listedKey);
    return {};
}

} // namespace refraction
