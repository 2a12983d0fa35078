// The scene renderer: its GPU objects, and each frame's passes (render/passes/, one file each)
// recorded into a frame graph with the plugins', executed and timed.
#include "engine/render/Renderer.h"

#include "RenderGpu.h"
#include "passes/Passes.h"

#include "engine/fg/Blackboard.h"
#include "engine/fg/FrameGraph.h"
#include "engine/gl/Debug.h"
#include "engine/gl/Query.h"
#include "engine/gl/Shaders.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <map>

namespace render {

/** Pooled transient textures are plain gl::Textures, sampled nearest with clamping. */
class Renderer::Allocator final : public fg::TextureAllocator {
public:
    void* allocate(const gl::TextureDesc& desc) override {
        auto* texture = new gl::Texture(desc);
        texture->setSampling(desc.levels != 1 ? gl::Filter::LinearMipmap : gl::Filter::Nearest,
                             gl::Wrap::Clamp);
        return texture;
    }
    void release(void* object) override { delete static_cast<gl::Texture*>(object); }
};

/** Timer queries per pass name, a ring of kFrames sets reused across frames. With exact pass
 *  times the frame waits for its own results; otherwise it reads the newest earlier frame's
 *  that are ready, so timing never stalls the CPU on the GPU. */
class Renderer::Timer final : public fg::PassObserver {
public:
    static constexpr std::size_t kFrames = 4;
    bool exact = false;
    void beginFrame() { mSlot = (mSlot + 1) % kFrames; }
    void beginPass(const std::string& name) override { mQueries[name][mSlot].begin(); }
    void endPass(const std::string& name) override {
        if (exact)
            gl::finish();
        mQueries[name][mSlot].end();
    }
    double milliseconds(const std::string& name) {
        const auto it = mQueries.find(name);
        if (it == mQueries.end())
            return 0.0;
        if (exact) {
            const auto ns = it->second[mSlot].resultNs(true);
            return ns ? double(*ns) * 1e-6 : 0.0;
        }
        for (std::size_t age = 1; age < kFrames; ++age) {
            const auto ns = it->second[(mSlot + kFrames - age) % kFrames].resultNs(false);
            if (ns)
                return mLatest[name] = double(*ns) * 1e-6;
        }
        return mLatest[name];
    }

private:
    std::map<std::string, std::array<gl::TimerQuery, kFrames>> mQueries;
    std::map<std::string, double> mLatest;
    std::size_t mSlot = 0;
};

Renderer::~Renderer() = default;

core::Result<std::unique_ptr<Renderer>> Renderer::create(const scene::Model& model,
                                                         const asset::HdrImage& environment,
                                                         gl::Context& context) {
    std::unique_ptr<Renderer> r(new Renderer());
    r->mModel = &model;
    r->mContext = &context;
    r->mGpu = std::make_unique<RenderGpu>();
    RenderGpu& gpu = *r->mGpu;
    r->mShaders.add(engineShaderFiles());
    auto deformer = deform::GpuDeformer::create(model, r->mShaders);
    if (!deformer)
        return deformer.error();
    gpu.deformer = std::move(*deformer);
    auto env = Environment::create(environment, r->mShaders);
    if (!env)
        return env.error();
    gpu.environment = std::move(*env);
    auto materials = MaterialTextures::create(model);
    if (!materials)
        return materials.error();
    gpu.materials = std::make_unique<MaterialTextures>(std::move(*materials));
    struct ProgramSpec {
        gl::Program* target;
        const char* vertex;
        const char* fragment;
    };
    for (const ProgramSpec& spec :
         {ProgramSpec{&gpu.background, "render/fullscreen.vert.glsl",
                      "render/background.frag.glsl"},
          ProgramSpec{&gpu.opaque, "render/mesh.vert.glsl", "render/pbr.frag.glsl"},
          ProgramSpec{&gpu.ground, "render/ground.vert.glsl", "render/ground.frag.glsl"},
          ProgramSpec{&gpu.tonemap, "render/fullscreen.vert.glsl", "render/tonemap.frag.glsl"}}) {
        auto program = gl::Program::graphics(r->mShaders, spec.vertex, spec.fragment);
        if (!program)
            return core::Error{"render::Renderer::create(): " + program.error().message};
        *spec.target = std::move(*program);
    }
    r->makeVertexArrays();
    r->mAllocator = std::make_unique<Allocator>();
    r->mPool = std::make_unique<fg::TexturePool>(*r->mAllocator);
    r->mTimer = std::make_unique<Timer>();
    return r;
}

void Renderer::makeVertexArrays() {
    mGpu->vaos.clear();
    mGpu->claimed.clear();
    for (const auto& instance : mGpu->deformer->instances())
        for (const auto& primitive : instance.primitives) {
            gl::VertexArray vao;
            vao.setIndexBuffer(*primitive.indices);
            mGpu->vaos.push_back(std::move(vao));
            mGpu->claimed.push_back(0);
        }
}

core::Status Renderer::setSubdivisionLevel(int level) {
    if (level == mGpu->deformer->subdivisionLevel())
        return {};
    auto deformer = deform::GpuDeformer::create(*mModel, mShaders, level);
    if (!deformer)
        return deformer.error();
    mGpu->deformer = std::move(*deformer);
    makeVertexArrays();
    return {};
}

int Renderer::subdivisionLevel() const {
    return mGpu->deformer->subdivisionLevel();
}

const Environment& Renderer::environment() const {
    return *mGpu->environment;
}

const deform::GpuDeformer& Renderer::geometry() const {
    return *mGpu->deformer;
}

core::Status Renderer::addPlugin(plugin::Plugin* p) {
    auto status = p->initialize(mShaders);
    if (!status)
        return core::Error{std::string("render::Renderer::addPlugin(): ") + p->name() + ": " +
                           status.error().message};
    mPlugins.push_back(p);
    return {};
}

core::Result<FrameStats> Renderer::render(const anim::Pose& pose, const Camera& camera,
                                          const RenderSettings& settings, double time) {
    const auto frameStart = std::chrono::steady_clock::now();
    const gl::Format outputFormat = settings.hdrOutput ? gl::Format::RGBA32F : gl::Format::RGBA8;
    if (!mOutput || mOutput.desc().size != settings.size || mOutput.desc().format != outputFormat)
        mOutput = gl::Texture({settings.size, outputFormat, 1});

    RenderGpu& gpu = *mGpu;
    FrameInfo frame;
    frame.model = mModel;
    frame.geometry = gpu.deformer.get();
    frame.environment = gpu.environment.get();
    frame.materials = gpu.materials.get();
    frame.shaders = &mShaders;
    frame.camera = camera;
    frame.settings = settings;
    frame.time = time;
    frame.ground = mGroundPlane;
    // Which primitives a plugin draws instead of the opaque pass, asked once a frame.
    std::size_t flat = 0;
    frame.opaqueGeometry = settings.ground;
    for (const auto& instance : gpu.deformer->instances())
        for (const auto& primitive : instance.primitives) {
            const bool claimed =
                std::any_of(mPlugins.begin(), mPlugins.end(), [&](const plugin::Plugin* p) {
                    return p->drawsPrimitive(*mModel, instance.node, *primitive.source);
                });
            gpu.claimed[flat++] = claimed;
            frame.opaqueGeometry = frame.opaqueGeometry || !claimed;
        }

    fg::FrameGraph graph(*mPool);
    fg::Blackboard blackboard;
    const fg::TextureHandle output = graph.importTexture("output", mOutput.desc(), &mOutput);
    const fg::BufferHandle vertices =
        passes::addDeform(graph, gpu, graph.importBuffer("scene.vertices", gpu.deformer.get()),
                          pose);
    passes::SceneTargets scene = passes::addBackground(graph, gpu, frame);
    if (settings.ground)
        scene = passes::addGround(graph, gpu, frame, scene);
    scene = passes::addOpaque(graph, gpu, frame, scene, vertices);

    blackboard.put(plugin::kSceneColor, scene.color);
    blackboard.put(plugin::kSceneDepth, scene.depth);
    blackboard.put(plugin::kSceneVertices, vertices);
    blackboard.put(plugin::kFrame, static_cast<const FrameInfo*>(&frame));
    for (plugin::Stage stage : {plugin::Stage::AfterOpaque, plugin::Stage::BeforeTonemap})
        for (plugin::Plugin* p : mPlugins)
            p->addPasses(stage, graph, blackboard);
    passes::addTonemap(graph, gpu, frame, blackboard.get<fg::TextureHandle>(plugin::kSceneColor),
                       output);

    auto compiled = graph.compile();
    if (!compiled)
        return compiled.error();
    FrameStats stats;
    mTimer->exact = settings.exactPassTimes;
    mTimer->beginFrame();
    auto executed = graph.execute(*mContext, mTimer.get());
    // Unbind our framebuffers before the pool deletes idle textures: deleting a texture
    // attached to the bound framebuffer makes the driver re-validate it (a KHR_debug warning).
    gl::Framebuffer::bindDefault(settings.size);
    if (!executed) {
        mPool->endFrame();
        return core::Error{"render::Renderer::render(): " + executed.error().message};
    }
    for (const fg::PassTiming& t : *executed)
        stats.passes.push_back({t.name, t.cpuMs, 0.0});
    stats.cpuMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frameStart)
            .count();
    for (PassStats& p : stats.passes) {
        p.gpuMs = mTimer->milliseconds(p.name);
        stats.gpuMs += p.gpuMs;
    }
    stats.graph = graph.dump();
    stats.transientBytes = mPool->allocatedBytes();
    mPool->endFrame();
    return stats;
}

void Renderer::presentOutput(glm::ivec4 source, glm::ivec4 destination) const {
    auto status = mPresent.attach("present", {&mOutput}, nullptr);
    ENGINE_CHECK(status.ok(), status.ok() ? "" : status.error().message);
    mPresent.blitToDefault(source, destination);
}

core::Status Renderer::setEnvironment(const asset::HdrImage& environment) {
    auto env = Environment::create(environment, mShaders);
    if (!env)
        return env.error();
    mGpu->environment = std::move(*env);
    return {};
}

std::vector<std::uint8_t> Renderer::readOutput() const {
    return gl::flipRows(mOutput.downloadRgba8(), mOutput.size());
}

std::vector<float> Renderer::readHdrOutput() const {
    return gl::flipRows(mOutput.downloadFloat(), mOutput.size());
}

} // namespace render
