// The scene renderer: its GPU objects, and each frame's passes (render/passes/, one file each)
// recorded into a frame graph with the plugins', executed and timed.
#include "engine/render/Renderer.h"

#include "engine/core/Limits.h"

#include "RenderGpu.h"
#include "passes/Passes.h"

#include "engine/core/Log.h"
#include "engine/fg/Blackboard.h"
#include "engine/fg/FrameGraph.h"
#include "engine/gl/Debug.h"
#include "engine/gl/Query.h"
#include "engine/gl/Shaders.h"
#include "engine/render/Shared.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <map>
#include <string_view>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace render {

namespace {

/** On a CPU rasteriser (Mesa's llvmpipe), keeps the heap a frame used for the next one.
 *  llvmpipe bins each draw's triangles in heap blocks it frees when the scene is rasterised:
 *  tens of MiB a frame for a refined character drawn on both faces. glibc gives that top of the
 *  heap back to the kernel whenever the freed space lies above everything else, and the next
 *  frame faults it in again, page by page, inside the passes' time: alternating methods at
 *  subdivision level 2 made SIR's capture 3 times slower (docs/performance.md). Growing the
 *  heap 64 MiB at a time and trimming only past 512 MiB keeps a frame's peak resident.
 *  Process-wide, set once; GPU drivers do not bin on the heap and are left alone. */
void keepHeapForCpuRasteriser() {
#if defined(__GLIBC__)
    static const bool kept = [] {
        if (std::string_view(gl::rendererString()).find("llvmpipe") == std::string_view::npos)
            return false;
        mallopt(M_TOP_PAD, 64 << 20);
        mallopt(M_TRIM_THRESHOLD, 512 << 20);
        return true;
    }();
    (void)kept;
#endif
}

} // namespace

/** Pooled transient textures are plain gl::Textures, sampled nearest with clamping. */
class Renderer::TextureAllocator final : public fg::TextureAllocator {
public:
    void* allocate(const gl::TextureDesc& desc) override {
        auto* texture = new gl::Texture(desc);
        texture->setSampling(desc.levels != 1 ? gl::Filter::LinearMipmap : gl::Filter::Nearest,
                             gl::Wrap::Clamp);
        return texture;
    }
    void release(void* object) override { delete static_cast<gl::Texture*>(object); }
};

/** Pooled transient buffers are plain gl::Buffers. */
class Renderer::BufferAllocator final : public fg::BufferAllocator {
public:
    void* allocate(const gl::BufferDesc& desc) override { return new gl::Buffer(desc.size); }
    void release(void* object) override { delete static_cast<gl::Buffer*>(object); }
};

/** Timer queries per pass name, a ring of kFrames sets reused across frames. With exact pass
 *  times the frame waits for its own results; otherwise it reads the newest earlier frame's
 *  that are ready, so timing never stalls the CPU on the GPU. */
class Renderer::Timer final : public fg::PassObserver {
public:
    static constexpr std::size_t kFrames = 4;
    /** Each pass timed alone: the GPU idle before it begins and finished before it ends, the
     *  wall clock between (a timer query on a CPU rasteriser may time another pass's work). */
    bool exact = false;
    void beginFrame() {
        mSlot = (mSlot + 1) % kFrames;
        mExact.clear();
    }
    void beginPass(const std::string& name) override {
        if (exact) {
            gl::finish();
            mStart = std::chrono::steady_clock::now();
            return;
        }
        mQueries[name][mSlot].begin();
    }
    void endPass(const std::string& name) override {
        if (exact) {
            gl::finish();
            mExact[name] +=
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - mStart)
                    .count();
            return;
        }
        mQueries[name][mSlot].end();
    }
    double milliseconds(const std::string& name) {
        if (exact) {
            const auto it = mExact.find(name);
            return it == mExact.end() ? 0.0 : it->second;
        }
        const auto it = mQueries.find(name);
        if (it == mQueries.end())
            return 0.0;
        for (std::size_t age = 1; age < kFrames; ++age) {
            const auto ns = it->second[(mSlot + kFrames - age) % kFrames].resultNs(false);
            if (ns)
                return mLatest[name] = double(*ns) * 1e-6;
        }
        return mLatest[name];
    }

private:
    std::map<std::string, std::array<gl::TimerQuery, kFrames>> mQueries;
    std::map<std::string, double> mLatest, mExact;
    std::chrono::steady_clock::time_point mStart;
    std::size_t mSlot = 0;
};

Renderer::~Renderer() = default;

namespace {

/** Uploads `model` at subdivision `level` with vertex arrays over its index buffers;
 *  `materials` reused when given (they do not depend on the level). */
core::Result<std::shared_ptr<ModelGpu>> uploadModel(std::shared_ptr<const scene::Model> model,
                                                    int level,
                                                    std::shared_ptr<MaterialTextures> materials) {
    auto upload = deform::GpuModel::create(*model, level);
    if (!upload)
        return upload.error();
    auto m = std::make_shared<ModelGpu>();
    m->upload = std::move(*upload);
    if (!materials) {
        auto created = MaterialTextures::create(*model);
        if (!created)
            return created.error();
        materials = std::make_shared<MaterialTextures>(std::move(*created));
    }
    m->materials = std::move(materials);
    m->lightNodes = lightNodes(*model);
    m->vertexArrays.resize(model->meshes.size());
    for (int node : model->meshNodes()) {
        const int mesh = model->nodes[std::size_t(node)].mesh;
        auto& arrays = m->vertexArrays[std::size_t(mesh)];
        for (std::size_t p = arrays.size(); p < model->meshes[std::size_t(mesh)].primitives.size();
             ++p) {
            gl::VertexArray vao;
            vao.setIndexBuffer(m->upload->indices(mesh, p));
            arrays.push_back(std::move(vao));
        }
    }
    m->model = std::move(model);
    return m;
}

/** RenderSettings::skippedSteps as defines: "search" is SKIP_SEARCH. */
std::vector<std::string> skipDefines(const std::vector<std::string>& steps) {
    std::vector<std::string> defines;
    for (const std::string& step : steps) {
        std::string define = "SKIP_";
        for (char c : step)
            define += char(std::toupper(static_cast<unsigned char>(c)));
        defines.push_back(define);
    }
    return defines;
}

} // namespace

core::Result<std::unique_ptr<Renderer>> Renderer::create(const asset::HdrImage& environment,
                                                         gl::Context& context) {
    keepHeapForCpuRasteriser();
    std::unique_ptr<Renderer> r(new Renderer());
    r->mContext = &context;
    r->mGpu = std::make_unique<RenderGpu>();
    RenderGpu& gpu = *r->mGpu;
    r->mShaders.add(engineShaderFiles());
    if (auto shared = r->mShaders.share("render", sharedTable()); !shared)
        return shared.error();
    auto env = Environment::create(environment, r->mShaders);
    if (!env)
        return env.error();
    gpu.environment = std::move(*env);
    gpu.noShadowDepth = gl::Texture({glm::ivec2(1), gl::Format::Depth32F, 1});
    gpu.noShadowGlass = gl::Texture({glm::ivec2(1), gl::Format::RGBA16F, 1});
    gpu.noCaustics = gl::Texture({glm::ivec2(1), gl::Format::RGBA16F, 1});
    if (auto bound = gpu.framebuffer.bindTargets("no shadows", {}, &gpu.noShadowDepth); !bound)
        return bound.error();
    gl::clearDepth(1.0f);
    for (const gl::Texture* t : {&gpu.noShadowGlass, &gpu.noCaustics}) {
        if (auto bound = gpu.framebuffer.bindTargets("no shadows", {t}, nullptr); !bound)
            return bound.error();
        gl::clearColor(0, glm::vec4(0.0f, 0.0f, 0.0f, kNoGlass));
    }
    r->mPrograms = std::make_unique<gl::ProgramCache>(r->mShaders);
    r->mTextureAllocator = std::make_unique<TextureAllocator>();
    r->mTextures = std::make_unique<fg::TexturePool>(*r->mTextureAllocator);
    r->mBufferAllocator = std::make_unique<BufferAllocator>();
    r->mBuffers = std::make_unique<fg::BufferPool>(*r->mBufferAllocator);
    r->mTimer = std::make_unique<Timer>();
    return r;
}

core::Status Renderer::prepare(const scene::World& world) {
    RenderGpu& gpu = *mGpu;
    std::vector<std::shared_ptr<ModelGpu>>& used = gpu.modelsInUse; // storage kept across frames
    used.clear();
    auto modelFor = [&](const std::shared_ptr<const scene::Model>& model)
        -> core::Result<std::shared_ptr<ModelGpu>> {
        for (const auto* list : {&used, &gpu.models})
            for (const auto& m : *list)
                if (m->model == model)
                    return m;
        return uploadModel(model, mLevel, nullptr);
    };
    gpu.characters.resize(world.characters.size());
    for (std::size_t i = 0; i < world.characters.size(); ++i) {
        const scene::Character& character = world.characters[i];
        auto fail = [&](const std::string& message) {
            return core::Error{"render::Renderer::prepare(): characters[" + std::to_string(i) +
                               "] (" + character.name + "): " + message};
        };
        if (!character.model)
            return fail("no model");
        auto model = modelFor(character.model);
        if (!model)
            return fail(model.error().message);
        if (std::find(used.begin(), used.end(), *model) == used.end())
            used.push_back(*model);
        CharacterGpu& c = gpu.characters[i];
        if (c.model != *model || !c.deformer) {
            auto deformer = deform::GpuDeformer::create((*model)->upload, mShaders);
            if (!deformer)
                return fail(deformer.error().message);
            c.model = *model;
            c.deformer = std::move(*deformer);
            c.pose = anim::restPose(*character.model);
        }
    }
    std::swap(gpu.models, used);
    used.clear();
    // The sets of layers the models' materials use (and the default material's, none): the
    // opaque programs a frame may need.
    gpu.layerSets = {0};
    for (const auto& m : gpu.models)
        for (const scene::Material& material : m->model->materials)
            gpu.layerSets.push_back(material.surfaceLayers());
    std::sort(gpu.layerSets.begin(), gpu.layerSets.end());
    gpu.layerSets.erase(std::unique(gpu.layerSets.begin(), gpu.layerSets.end()),
                        gpu.layerSets.end());
    return {};
}

core::Status Renderer::setSubdivisionLevel(int level) {
    if (level == mLevel)
        return {};
    // Every model at the new level before anything changes: on failure nothing does.
    std::vector<std::shared_ptr<ModelGpu>> refined;
    for (const auto& m : mGpu->models) {
        auto upload = uploadModel(m->model, level, m->materials);
        if (!upload)
            return upload.error();
        refined.push_back(std::move(*upload));
    }
    mGpu->models = std::move(refined);
    mGpu->characters.clear(); // placed again over the new uploads by the next prepare()
    mGpu->history.requestReset();
    mLevel = level;
    return {};
}

const Environment& Renderer::environment() const {
    return *mGpu->environment;
}

std::size_t Renderer::characterCount() const {
    return mGpu->characters.size();
}

const deform::GpuDeformer& Renderer::geometry(std::size_t character) const {
    return *mGpu->characters.at(character).deformer;
}

std::span<const DrawItem> Renderer::drawItems() const {
    return mGpu->items;
}

core::Status Renderer::addPlugin(plugin::Plugin* p) {
    auto status = p->initialize(mShaders);
    if (!status)
        return core::Error{std::string("render::Renderer::addPlugin(): ") + p->name() + ": " +
                           status.error().message};
    mPlugins.push_back(p);
    return {};
}

void Renderer::planShadows(const scene::World& world, const RenderSettings& settings) {
    RenderGpu& gpu = *mGpu;
    gpu.shadows = {};
    if (!settings.shadows || gpu.lights.empty())
        return;
    // The casters' bounds: each character's over its clip, placed, a little grown.
    Bounds casters;
    for (std::size_t c = 0; c < world.characters.size(); ++c) {
        const scene::Character& character = world.characters[c];
        ModelGpu& m = *gpu.characters[c].model;
        const glm::dmat4 travel = glm::translate(glm::dmat4(1.0), gpu.characters[c].pose.travel);
        const Bounds placed =
            transformed(performanceBounds(*m.model, character.performance, m.clipBounds, 8),
                        character.transform() * travel);
        const glm::vec3 margin(0.05f * std::max(placed.radius(), 1e-3f));
        casters.add(placed.min - margin);
        casters.add(placed.max + margin);
    }
    gpu.shadows = render::planShadows(gpu.lights, casters, gl::Texture::maxSize());
    if (gpu.shadows.overLimit != gpu.reportedOverLimit) {
        if (gpu.shadows.overLimit)
            core::logWarning("render: " + std::to_string(gpu.shadows.overLimit) +
                             " lights light without shadows: at most " +
                             std::to_string(core::limits::kMaxShadowedLights) +
                             " lights cast shadows in a frame");
        gpu.reportedOverLimit = gpu.shadows.overLimit;
    }
    if (gpu.shadows.halved)
        core::logWarning("render: the shadow maps' resolutions halved " +
                         std::to_string(gpu.shadows.halved) +
                         " times to fit the GPU's largest texture");
}

namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

} // namespace

core::Result<FrameStats> Renderer::render(const scene::World& world, const Camera& camera,
                                          const RenderSettings& settings, double time) {
    const auto frameStart = std::chrono::steady_clock::now();
    if (auto prepared = prepare(world); !prepared)
        return prepared.error();
    mPrograms->setExtraDefines(skipDefines(settings.skippedSteps));
    const gl::Format outputFormat = settings.hdrOutput ? gl::Format::RGBA32F : gl::Format::RGBA8;
    if (!mOutput || mOutput.desc().size != settings.size || mOutput.desc().format != outputFormat)
        mOutput = gl::Texture({settings.size, outputFormat, 1});

    const bool opaqueGeometry = animate(world, settings, time);
    if (auto lit = light(world, settings); !lit)
        return lit.error();
    FrameInfo frame = describeFrame(world, camera, settings, time, opaqueGeometry);
    FrameStats stats;
    stats.animateMs = millisecondsSince(frameStart);

    const auto recordStart = std::chrono::steady_clock::now();
    fg::FrameGraph graph(*mTextures, *mBuffers);
    fg::Blackboard blackboard; // the graph's final reads look it up when it compiles
    if (auto recorded = record(graph, frame, blackboard); !recorded)
        return recorded.error();
    if (auto compiled = graph.compile(); !compiled)
        return compiled.error();
    stats.recordMs = millisecondsSince(recordStart);

    if (auto executed = execute(graph, frame, stats); !executed)
        return executed.error();
    stats.cpuMs = millisecondsSince(frameStart);
    return stats;
}

bool Renderer::animate(const scene::World& world, const RenderSettings& settings, double time) {
    RenderGpu& gpu = *mGpu;
    gpu.poses.clear();
    gpu.items.clear();
    gpu.lights.clear();
    bool opaqueGeometry = settings.ground;
    for (std::size_t c = 0; c < world.characters.size(); ++c) {
        const scene::Character& character = world.characters[c];
        CharacterGpu& cg = gpu.characters[c];
        const scene::Model& model = *character.model;
        anim::evaluate(model, character.performance, time, cg.pose);
        cg.deformer->keepPrevious(settings.temporal.enabled); // motion vectors
        cg.deformer->stage(cg.pose, character.transform(), gpu.poses);
        placeLights(model, cg.model->lightNodes, cg.pose, character.transform(), gpu.lights);
        opaqueGeometry = listItems(c, character, cg) || opaqueGeometry;
    }
    gpu.poses.upload(); // every character's, at once; the deform pass reads them
    return opaqueGeometry;
}

bool Renderer::listItems(std::size_t c, const scene::Character& character, CharacterGpu& cg) {
    bool unclaimed = false;
    const auto& instances = cg.deformer->instances();
    for (std::size_t i = 0; i < instances.size(); ++i)
        for (std::size_t p = 0; p < instances[i].primitives.size(); ++p) {
            const deform::GpuPrimitive& primitive = instances[i].primitives[p];
            DrawItem item;
            item.character = c;
            item.source = &character;
            item.model = character.model.get();
            item.primitive = primitive.source;
            item.material = primitive.source->materialFor(character.variant);
            item.values = anim::materialOf(*item.model, cg.pose, item.material);
            item.geometry = cg.deformer.get();
            item.instance = std::uint32_t(i);
            item.primitiveIndex = std::uint32_t(p);
            item.gpu = &primitive;
            item.vertexArray = &cg.model->vertexArrays[std::size_t(instances[i].mesh)][p];
            item.materials = cg.model->materials.get();
            item.world = instances[i].meshToWorld;
            item.previousWorld = instances[i].previousMeshToWorld;
            item.mirrored = glm::determinant(glm::mat3(item.world)) < 0.0f;
            item.key = cg.deformer->serial();
            for (const plugin::Plugin* plugin : mPlugins)
                if (plugin->claims(item)) {
                    item.owner = plugin;
                    break;
                }
            unclaimed = unclaimed || !item.owner;
            mGpu->items.push_back(item);
        }
    return unclaimed;
}

core::Status Renderer::light(const scene::World& world, const RenderSettings& settings) {
    RenderGpu& gpu = *mGpu;
    gpu.lights.insert(gpu.lights.end(), world.lights.begin(), world.lights.end());
    if (!settings.lights)
        gpu.lights.clear();
    if (gpu.lights.size() > core::limits::kMaxLights)
        return core::Error{
            "render::Renderer::render(): the scene places " + std::to_string(gpu.lights.size()) +
            " punctual lights, over the limit of " + std::to_string(core::limits::kMaxLights)};
    planShadows(world, settings);
    gpu.lighting.upload(gpu.lights, gpu.shadows); // bound for every pass of the frame
    return {};
}

FrameInfo Renderer::describeFrame(const scene::World& world, const Camera& camera,
                                  const RenderSettings& settings, double time,
                                  bool opaqueGeometry) {
    RenderGpu& gpu = *mGpu;
    std::uint64_t pluginRevision = 0;
    for (plugin::Plugin* p : mPlugins)
        pluginRevision += p->parameters().revision();
    FrameInfo frame;
    frame.temporal = gpu.history.begin(world, camera, settings, time, gpu.items, pluginRevision);
    frame.world = &world;
    frame.items = gpu.items;
    frame.lights = gpu.lights;
    frame.environment = gpu.environment.get();
    frame.shaders = &mShaders;
    frame.programs = mPrograms.get();
    frame.shadowSampler = &gpu.shadowSampler;
    frame.camera = frame.temporal.enabled
                       ? TemporalHistory::jittered(camera, frame.temporal.jitter, settings.size)
                       : camera;
    frame.settings = settings;
    frame.time = time;
    frame.ground = mGroundPlane;
    frame.opaqueGeometry = opaqueGeometry;
    frame.shadows = &gpu.shadows;
    return frame;
}

core::Status Renderer::record(fg::FrameGraph& graph, FrameInfo& frame, fg::Blackboard& blackboard) {
    RenderGpu& gpu = *mGpu;
    const fg::TextureHandle output = graph.importTexture("output", mOutput.desc(), &mOutput);
    const fg::BufferHandle vertices =
        passes::addDeform(graph, gpu, graph.importBuffer("scene.vertices", &gpu.characters));
    blackboard.put(plugin::kSceneVertices, vertices);
    blackboard.put(plugin::kFrame, static_cast<const FrameInfo*>(&frame));
    const ShadowAtlases engineShadows = recordShadows(graph, blackboard, frame, vertices);

    passes::SceneTargets scene = passes::addBackground(graph, gpu, frame);
    scene = passes::addOpaque(graph, gpu, frame, scene, vertices, blackboard);
    if (frame.settings.ground)
        scene = passes::addGround(graph, gpu, frame, scene, blackboard);
    blackboard.put(plugin::kSceneColor, scene.color);
    blackboard.put(plugin::kSceneDepth, scene.depth);
    if (scene.motion.valid()) {
        blackboard.put(plugin::kSceneMotion, scene.motion);
        blackboard.put(plugin::kHistoryColor,
                       graph.importTexture("history.color", gpu.history.previousColor().desc(),
                                           &gpu.history.previousColor()));
        blackboard.put(plugin::kHistoryMotion,
                       graph.importTexture("history.motion", gpu.history.previousMotion().desc(),
                                           &gpu.history.previousMotion()));
    }
    for (plugin::Stage stage : {plugin::Stage::AfterOpaque, plugin::Stage::BeforeTonemap})
        for (plugin::Plugin* p : mPlugins)
            p->addPasses(stage, graph, blackboard);
    // What the plugins drew into the glass and caustics atlases decides the variants of the
    // passes that shade with the lights, which pick them where they execute.
    const ShadowAtlases shadows = ShadowAtlases::of(blackboard);
    frame.lighting =
        LightingFeatures::of(gpu.lights, gpu.shadows, shadows.glass != engineShadows.glass,
                             shadows.caustics != engineShadows.caustics);

    fg::TextureHandle color = blackboard.get<fg::TextureHandle>(plugin::kSceneColor);
    if (frame.temporal.enabled)
        color = passes::addTemporal(graph, gpu, frame, gpu.history, color,
                                    blackboard.get<fg::TextureHandle>(plugin::kSceneMotion),
                                    blackboard.get<fg::TextureHandle>(plugin::kHistoryColor),
                                    blackboard.get<fg::TextureHandle>(plugin::kHistoryMotion));
    if (frame.settings.shadowMapView != RenderSettings::ShadowMapView::Off && !gpu.shadows.empty())
        color = passes::addShadowMapView(graph, gpu, frame, shadows);
    passes::addTonemap(graph, gpu, frame, color, output);
    return {};
}

ShadowAtlases Renderer::recordShadows(fg::FrameGraph& graph, fg::Blackboard& blackboard,
                                      const FrameInfo& frame, fg::BufferHandle vertices) {
    RenderGpu& gpu = *mGpu;
    ShadowAtlases shadows;
    if (gpu.shadows.empty()) {
        shadows.depth =
            graph.importTexture("scene.shadow_depth", gpu.noShadowDepth.desc(), &gpu.noShadowDepth);
        shadows.glass =
            graph.importTexture("scene.shadow_glass", gpu.noShadowGlass.desc(), &gpu.noShadowGlass);
    } else {
        shadows = passes::addShadows(graph, gpu, frame, vertices);
    }
    shadows.caustics =
        graph.importTexture("scene.shadow_caustics", gpu.noCaustics.desc(), &gpu.noCaustics);
    blackboard.put(plugin::kShadowDepth, shadows.depth);
    blackboard.put(plugin::kShadowGlass, shadows.glass);
    blackboard.put(plugin::kShadowCaustics, shadows.caustics);
    return shadows;
}

core::Status Renderer::execute(fg::FrameGraph& graph, const FrameInfo& frame, FrameStats& stats) {
    RenderGpu& gpu = *mGpu;
    mTimer->exact = frame.settings.exactPassTimes;
    mTimer->beginFrame();
    auto executed = graph.execute(*mContext, mTimer.get());
    // Unbind our framebuffers before the pool deletes idle textures: deleting a texture
    // attached to the bound framebuffer makes the driver re-validate it (a KHR_debug warning).
    gl::Framebuffer::bindDefault(frame.settings.size);
    if (!executed) {
        mTextures->endFrame();
        mBuffers->endFrame();
        return core::Error{"render::Renderer::render(): " + executed.error().message};
    }
    for (const fg::PassTiming& t : *executed) {
        stats.passes.push_back({t.name, t.cpuMs, mTimer->milliseconds(t.name)});
        stats.gpuMs += stats.passes.back().gpuMs;
    }
    if (frame.temporal.enabled)
        gpu.history.end();
    stats.historyBytes = frame.temporal.enabled ? gpu.history.bytes() : 0;
    stats.graph = graph.dump();
    stats.transientBytes = mTextures->allocatedBytes() + mBuffers->allocatedBytes();
    mTextures->endFrame();
    mBuffers->endFrame();
    return {};
}

void Renderer::presentOutput(glm::ivec4 source, glm::ivec4 destination) const {
    auto status = mPresent.attach("present", {&mOutput}, nullptr);
    ENGINE_CHECK(status.ok(), status.ok() ? "" : status.error().message);
    mPresent.blitToDefault(source, destination);
}

const gl::Texture& Renderer::lastMotion() const {
    return mGpu->history.previousMotion();
}

void Renderer::resetHistory() {
    mGpu->history.requestReset();
}

core::Status Renderer::setEnvironment(const asset::HdrImage& environment) {
    auto env = Environment::create(environment, mShaders);
    if (!env)
        return env.error();
    mGpu->environment = std::move(*env);
    mGpu->history.requestReset();
    return {};
}

std::vector<std::uint8_t> Renderer::readOutput() const {
    return gl::flipRows(mOutput.downloadRgba8(), mOutput.size());
}

std::vector<float> Renderer::readHdrOutput() const {
    return gl::flipRows(mOutput.downloadFloat(), mOutput.size());
}

} // namespace render
