// The refraction plugin: its parameters, GL objects and the frame's choice of passes
// (recorded by the passes in src/passes/, one file each).
#include "refraction/RefractionPlugin.h"

#include "GpuState.h"
#include "Shared.h"
#include "passes/Passes.h"

#include "engine/core/Check.h"
#include "engine/core/Log.h"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

std::span<const gl::ShaderFile> refractionShaderFiles();

namespace refraction {

namespace {

/** Presets of common transparent materials: refractive index n_d and Abbe number V_d
 *  (dispersion = 20 / V_d, as in KHR_materials_dispersion); the first restores the model's. */
void addMaterialPresets(plugin::ParameterSet& parameters) {
    struct Material {
        const char* name;
        double ior, abbe;
    };
    static constexpr Material kMaterials[] = {
        {"water", 1.333, 55.7},
        {"ice", 1.309, 56.0},
        {"acrylic (PMMA)", 1.491, 57.2},
        {"glass (crown, BK7)", 1.517, 64.2},
        {"fused quartz", 1.458, 67.8},
        {"polycarbonate", 1.585, 30.0},
        {"flint glass (F2)", 1.620, 36.4},
        {"sapphire", 1.770, 72.2},
        {"cubic zirconia", 2.150, 33.8},
        {"diamond", 2.417, 55.3},
    };
    auto add = [&](std::string name, std::string ior, std::string dispersion) {
        const core::Status added =
            parameters.addPreset({std::move(name), {{"ior", ior}, {"dispersion", dispersion}}});
        ENGINE_CHECK(added, "refraction material presets fit their parameters");
    };
    add("the material's own", "0", "-1");
    for (const Material& m : kMaterials) {
        char ior[16], dispersion[16];
        std::snprintf(ior, sizeof ior, "%.3f", m.ior);
        std::snprintf(dispersion, sizeof dispersion, "%.4f", 20.0 / m.abbe);
        add(std::string(m.name) + "  " + ior, ior, dispersion);
    }
}

} // namespace

RefractionPlugin::RefractionPlugin() {
    for (const plugin::Parameter& parameter : Settings::parameterTable())
        mParameters.declare(parameter);
    addMaterialPresets(mParameters);
}

RefractionPlugin::~RefractionPlugin() = default;

core::Status RefractionPlugin::initialize(gl::ShaderLibrary& shaders) {
    shaders.add(refractionShaderFiles());
    if (auto shared = shaders.share("refraction", sharedTable()); !shared)
        return shared;
    if (const std::uint32_t highest = shaders.registry().highestStorage();
        highest >= gl::maxStorageBindings())
        return core::Error{"refraction: its storage bindings reach " + std::to_string(highest) +
                           ", past this GL's GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS (" +
                           std::to_string(gl::maxStorageBindings()) + ")"};
    mGpu = std::make_unique<GpuState>(); // the passes' programs: the engine's program cache
    return {};
}

const Settings& RefractionPlugin::settings() const {
    if (!mSettings || mSettingsRevision != mParameters.revision()) {
        mSettings = std::make_unique<Settings>(Settings::decode(mParameters));
        mSettingsRevision = mParameters.revision();
    }
    return *mSettings;
}

bool RefractionPlugin::claims(const render::DrawItem& item) const {
    return mGpu && settings().isGlass(*item.model, item.material, item.source->glass);
}

namespace {

/** The pair capture's geometry passes, then its resolve. The pair's single geometry pass serves
 *  what one resolve can: one glass material with the same overrides on every glass item, no
 *  normal map and no texture the walk reads (no UV or tangent is gathered), the farthest back
 *  surface (MAX blending), and a frame that does not accumulate (MAX blending keeps no
 *  motion); else the papers' two passes. */
Capture addPairCapture(fg::FrameGraph& graph, FrameContext& c, FrameBuffers& buffers,
                       const SceneInputs& scene) {
    const render::DrawItem* first = nullptr;
    bool oneMaterial = true;
    for (std::size_t index = 0; index < c.frame->items.size(); ++index) {
        const render::DrawItem& item = c.frame->items[index];
        if (!c.isGlass(item))
            continue;
        if (!first) {
            first = &item;
            c.firstGlassId = c.gpu->glassIds[index];
        }
        // One material of one model, the same values (a character whose factors animate
        // shows its own copy).
        oneMaterial = oneMaterial && item.model == first->model &&
                      item.material == first->material && item.values == first->values &&
                      item.source->overrides == first->source->overrides;
    }
    const bool normalMap = first->values && first->values->normalTexture.present();
    const bool firstBack = c.settings.backSurface == Settings::BackSurface::First;
    c.onePass = c.settings.geometryPasses == Settings::GeometryPasses::One && oneMaterial &&
                !normalMap && !firstBack && !c.texturedGlass && !c.frame->temporal.enabled;
    const PairTargets pair = c.onePass ? addPairGatherPass(graph, c, buffers)
                                       : addPairSurfacePasses(graph, c, buffers, firstBack);
    return addPairResolvePass(graph, c, buffers, scene, pair);
}

} // namespace

bool RefractionPlugin::beginFrame(FrameContext& c, const fg::Blackboard& blackboard) const {
    c.settings = settings();
    if (c.settings.method == Settings::Method::Opaque)
        return false;
    c.gpu = mGpu.get();
    c.plugin = this;
    c.frame = blackboard.get<const render::FrameInfo*>(plugin::kFrame);
    // Still frames that accumulate anti-alias every outline by their jitter: the outline pass
    // would blur them twice (while anything moves the history keeps little of an outline).
    if (c.frame->temporal.enabled && c.frame->temporal.still)
        c.settings.outlineAntialiasing = false;
    c.reflect = c.settings.tir == Settings::Tir::Reflect && c.settings.twoInterfaces();
    assignGlassIds(c);
    if (c.gpu->glassOptics.empty())
        return false;
    c.shadowed = c.settings.glassShadows && c.frame->shadows && !c.frame->shadows->empty();
    c.caustics = c.shadowed && c.settings.focusesCaustics();
    c.glassModel = glassDefines(c);
    return true;
}

void RefractionPlugin::addPasses(plugin::Stage stage, fg::FrameGraph& graph,
                                 fg::Blackboard& blackboard) {
    if (!mGpu || stage != plugin::Stage::AfterOpaque)
        return;
    FrameContext c; // copied into every pass's callback
    if (!beginFrame(c, blackboard))
        return;
    FrameBuffers buffers = importBuffers(graph, blackboard, *mGpu);
    addGlassMaterialsPass(graph, c, buffers);
    if (c.settings.usesGlassBvh() || c.caustics)
        addGlassBvhPass(graph, c, buffers);
    // The glass's shadow and caustics, which the engine's shading, recorded before, reads as
    // the frame leaves them: the graph runs these first.
    if (c.shadowed) {
        blackboard.put(plugin::kShadowGlass,
                       addGlassShadowPass(graph, c, buffers,
                                          blackboard.get<fg::TextureHandle>(plugin::kShadowGlass)));
        if (c.caustics) {
            addCausticPhotonsPass(graph, c, buffers,
                                  blackboard.get<fg::TextureHandle>(plugin::kShadowDepth));
            blackboard.put(plugin::kShadowCaustics, addCausticResolvePass(graph, c, buffers));
        }
    }
    SceneInputs scene = sceneInputs(blackboard);
    if (c.marchesScene())
        scene.depthTiles = addSceneDepthTilesPass(graph, c, scene.depth);
    addGlassExtentPass(graph, c, buffers);
    // The capture: the layers (every glass item, whatever its material, in one geometry pass),
    // or the pair.
    Capture capture;
    if (c.settings.layered()) {
        const fg::TextureHandle mask = addLayerCapturePass(graph, c, buffers);
        addLayerOverflowPass(graph, c, buffers);
        if (c.layerDepthMaps())
            capture = addLayerDepthsPass(graph, c, buffers, mask);
        else
            capture.mask = mask; // SIR's walk reads its pixel's depths from the arrays
    } else {
        capture = addPairCapture(graph, c, buffers, scene);
    }
    Walked walked = addWalkPass(graph, c, buffers, scene, capture);
    if (c.settings.method == Settings::Method::Hybrid && c.settings.debug == 0)
        walked = addHybridTracePass(graph, c, buffers, scene, capture, walked);
    if (c.freshSamples() > 1)
        walked = addFreshSamplesPass(graph, c, buffers, scene, capture, walked);
    if (walked.motion.valid())
        blackboard.put(plugin::kSceneMotion, walked.motion);
    blackboard.put(plugin::kSceneColor, c.settings.outlinePass()
                                            ? addOutlinesPass(graph, c, buffers, scene, walked)
                                            : walked.color);
}

LayerStats RefractionPlugin::layerStats() const {
    LayerStats stats;
    if (!mGpu || mGpu->layers.capacity == 0)
        return stats;
    const LayerShape& layers = mGpu->layers;
    stats.capacity = layers.capacity;
    stats.bytesPerPixel =
        layerBytesPerPixel(layers.capacity, settings().outlinePass(), layers.surfaceSlots);
    stats.bytes = stats.bytesPerPixel * layers.pixels();
    WalkCountersGpu counts{};
    const auto bytes = mGpu->counters.download(0, sizeof counts);
    std::memcpy(&counts, bytes.data(), sizeof counts);
    stats.overflowPixels = counts.overflowPixels;
    stats.traceRays = counts.traceRays;
    stats.traceSteps = counts.traceSteps[0] | std::uint64_t(counts.traceSteps[1]) << 32;
    stats.traceMaxSteps = counts.traceMaxSteps;
    stats.walkedPixels = counts.walkedPixels;
    stats.hybridTraced = counts.hybridTraced;
    std::copy(std::begin(counts.hybridBy), std::end(counts.hybridBy), stats.hybridBy.begin());
    stats.freshPixels = counts.freshPixels;
    return stats;
}

std::unique_ptr<plugin::Plugin> createPlugin() {
    return std::make_unique<RefractionPlugin>();
}

} // namespace refraction
