// The refraction plugin: its parameters, GL objects and the frame's choice of passes
// (recorded by the passes in src/passes/, one file each).
#include "refraction/RefractionPlugin.h"

#include "GpuState.h"
#include "passes/Passes.h"

#include "engine/core/Check.h"
#include "engine/core/Log.h"

#include <cstddef>
#include <cstdio>
#include <cstring>

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
    mGpu = std::make_unique<GpuState>();
    struct Spec {
        gl::Program* target;
        const char* vertex;
        const char* fragment;
    };
    for (const Spec& spec :
         {Spec{&mGpu->surface, "refraction/glass.vert.glsl", "refraction/surface.frag.glsl"},
          Spec{&mGpu->composite, "render/fullscreen.vert.glsl", "refraction/composite.frag.glsl"},
          Spec{&mGpu->surfaces, "refraction/glass.vert.glsl", "refraction/surfaces.frag.glsl"},
          Spec{&mGpu->resolve, "refraction/rectangle.vert.glsl", "refraction/resolve.frag.glsl"},
          Spec{&mGpu->layersOutline, "refraction/rectangle.vert.glsl",
               "refraction/layers_outline.frag.glsl"}}) {
        auto program = gl::Program::graphics(shaders, spec.vertex, spec.fragment);
        if (!program)
            return program.error();
        *spec.target = std::move(*program);
    }
    for (int lit = 0; lit < 2; ++lit)
        for (const Spec& spec :
             {Spec{&mGpu->front[lit], "refraction/glass.vert.glsl", "refraction/front.frag.glsl"},
              Spec{&mGpu->deferred[lit], "refraction/rectangle.vert.glsl",
                   "refraction/deferred.frag.glsl"}}) {
            auto program = gl::Program::graphics(shaders, spec.vertex, spec.fragment,
                                                 {"PUNCTUAL_LIGHTS " + std::to_string(lit)});
            if (!program)
                return program.error();
            *spec.target = std::move(*program);
        }
    for (auto [target, name] :
         {std::pair{&mGpu->depthRange, "refraction/depth_range.comp.glsl"},
          std::pair{&mGpu->refit, "refraction/bvh_refit.comp.glsl"},
          std::pair{&mGpu->rectangleGrow, "refraction/rectangle.comp.glsl"},
          std::pair{&mGpu->normalDistance, "refraction/normal_distance.comp.glsl"},
          std::pair{&mGpu->cageGather, "refraction/cage_gather.comp.glsl"}}) {
        auto program = gl::Program::compute(shaders, name);
        if (!program)
            return program.error();
        *target = std::move(*program);
    }
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

void RefractionPlugin::addPasses(plugin::Stage stage, fg::FrameGraph& graph,
                                 fg::Blackboard& blackboard) {
    if (stage != plugin::Stage::AfterOpaque || !mGpu)
        return;
    FrameContext c;
    c.settings = settings();
    if (c.settings.method == Settings::Method::Opaque)
        return;
    c.gpu = mGpu.get();
    c.plugin = this;
    c.frame = blackboard.get<const render::FrameInfo*>(plugin::kFrame);

    dropStaleDistances(*mGpu, c.frame->items);
    c.reflect = c.settings.tir == Settings::Tir::Reflect && c.settings.twoInterfaces();
    assignGlassIds(c);
    if (c.gpu->glassOptics.empty())
        return;
    FrameBuffers buffers = importBuffers(graph, blackboard, *mGpu);
    const SceneInputs scene = sceneInputs(blackboard);
    addGlassMaterialsPass(graph, c, buffers);
    if (c.settings.layered()) {
        // Every glass item, whatever its material, in one capture pass; then the walk.
        auto program = layerShadeProgram(*mGpu, c);
        if (!program) {
            core::logError("refraction: " + program.error().message);
            return;
        }
        c.layerShade = *program;
        if (c.settings.usesNormalDistance())
            addNormalDistancePass(graph, c, buffers);
        const fg::TextureHandle mask = addLayerCapturePass(graph, c, buffers);
        const LayerDepths depths = addLayerDepthsPass(graph, c, buffers, mask);
        const LayerShade shaded = addLayerShadePass(graph, c, buffers, scene, mask, depths);
        blackboard.put(plugin::kSceneColor, c.settings.outlineAntialiasing
                                                ? addLayerOutlinePass(graph, c, buffers, shaded)
                                                : shaded.color);
        return;
    }

    // The two-surface path's single geometry pass needs what one shading pass can serve: one glass
    // material with the same overrides on every glass item, no normal map (no UV or tangent is
    // gathered), the farthest back surface (MAX blending).
    bool oneMaterial = true;
    for (std::size_t index = 0; index < c.frame->items.size(); ++index) {
        const render::DrawItem& item = c.frame->items[index];
        if (item.owner != this)
            continue;
        if (!c.glass) {
            c.glass = &item;
            c.glassIndex = index;
        }
        oneMaterial = oneMaterial && item.model == c.glass->model &&
                      item.material == c.glass->material &&
                      item.source->overrides == c.glass->source->overrides;
    }
    const scene::Model& model = *c.glass->model;
    const bool normalMap = c.glass->material >= 0 &&
                           model.materials[std::size_t(c.glass->material)].normalTexture.present();
    const bool firstBack = c.settings.backSurface == Settings::BackSurface::First;
    c.onePass = c.settings.geometryPasses == Settings::GeometryPasses::One && oneMaterial &&
                !normalMap && !firstBack;

    if (c.settings.usesNormalDistance())
        addNormalDistancePass(graph, c, buffers);
    const SurfaceMaps maps =
        c.onePass ? addResolvePass(graph, c, buffers, scene, addGatherPass(graph, c, buffers))
                  : addSurfacePasses(graph, c, buffers, firstBack);
    if (c.settings.twoInterfaces())
        addDepthRangePass(graph, c, maps, buffers);
    blackboard.put(plugin::kSceneColor,
                   c.onePass ? addShadePass(graph, c, maps, buffers, scene)
                             : addCompositePass(graph, c, scene,
                                                addFrontFacesPass(graph, c, maps, buffers, scene)));
}

LayerStats RefractionPlugin::layerStats() const {
    LayerStats stats;
    if (!mGpu || mGpu->layers.capacity == 0)
        return stats;
    const GpuState::LayerStorage& layers = mGpu->layers;
    stats.capacity = layers.capacity;
    stats.bytesPerPixel = layerBytesPerPixel(layers.capacity, settings().outlineAntialiasing);
    stats.bytes = stats.bytesPerPixel * std::size_t(layers.size.x) * std::size_t(layers.size.y);
    const auto counter = mGpu->rectangle.download(offsetof(GlassRectangleGpu, overflowPixels),
                                                  sizeof(std::uint32_t));
    std::memcpy(&stats.overflowPixels, counter.data(), sizeof(std::uint32_t));
    return stats;
}

std::unique_ptr<plugin::Plugin> createPlugin() {
    return std::make_unique<RefractionPlugin>();
}

} // namespace refraction
