// The scene renderer's frame: passes recorded into a frame graph, executed, timed.
#include "engine/render/Renderer.h"

#include "engine/fg/Blackboard.h"
#include "engine/fg/FrameGraph.h"
#include "engine/gl/Debug.h"
#include "engine/gl/Query.h"
#include "engine/gl/Shaders.h"

#include <glm/gtc/matrix_inverse.hpp>

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

namespace {

struct TargetData {
    fg::TextureHandle color, depth;
};

gl::Cull cullFor(const scene::Model& model, int material) {
    return material >= 0 && model.materials[std::size_t(material)].doubleSided ? gl::Cull::None
                                                                               : gl::Cull::Back;
}

} // namespace

Renderer::~Renderer() = default;

core::Result<std::unique_ptr<Renderer>> Renderer::create(const scene::Model& model,
                                                         const asset::HdrImage& environment,
                                                         gl::Context& context) {
    std::unique_ptr<Renderer> r(new Renderer());
    r->mModel = &model;
    r->mContext = &context;
    r->mShaders.add(engineShaderFiles());
    auto deformer = deform::GpuDeformer::create(model, r->mShaders);
    if (!deformer)
        return deformer.error();
    r->mDeformer = std::move(*deformer);
    auto env = Environment::create(environment, r->mShaders);
    if (!env)
        return env.error();
    r->mEnvironment = std::move(*env);
    auto materials = MaterialTextures::create(model);
    if (!materials)
        return materials.error();
    r->mMaterials = std::make_unique<MaterialTextures>(std::move(*materials));
    struct ProgramSpec {
        gl::Program* target;
        const char* vertex;
        const char* fragment;
    };
    for (const ProgramSpec& spec :
         {ProgramSpec{&r->mBackground, "render/fullscreen.vert.glsl",
                      "render/background.frag.glsl"},
          ProgramSpec{&r->mOpaque, "render/mesh.vert.glsl", "render/pbr.frag.glsl"},
          ProgramSpec{&r->mGround, "render/ground.vert.glsl", "render/ground.frag.glsl"},
          ProgramSpec{&r->mTonemap, "render/fullscreen.vert.glsl", "render/tonemap.frag.glsl"}}) {
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
    mVaos.clear();
    mClaimed.clear();
    for (const auto& instance : mDeformer->instances())
        for (const auto& primitive : instance.primitives) {
            gl::VertexArray vao;
            vao.setIndexBuffer(*primitive.indices);
            mVaos.push_back(std::move(vao));
            mClaimed.push_back(0);
        }
}

core::Status Renderer::setSubdivisionLevel(int level) {
    if (level == mDeformer->subdivisionLevel())
        return {};
    auto deformer = deform::GpuDeformer::create(*mModel, mShaders, level);
    if (!deformer)
        return deformer.error();
    mDeformer = std::move(*deformer);
    makeVertexArrays();
    return {};
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

    FrameInfo frame;
    frame.model = mModel;
    frame.geometry = mDeformer.get();
    frame.environment = mEnvironment.get();
    frame.materials = mMaterials.get();
    frame.shaders = &mShaders;
    frame.camera = camera;
    frame.settings = settings;
    frame.time = time;
    frame.ground = mGroundPlane;
    // Which primitives a plugin draws instead of the opaque pass, asked once a frame.
    std::size_t flat = 0;
    frame.opaqueGeometry = settings.ground;
    for (const auto& instance : mDeformer->instances())
        for (const auto& primitive : instance.primitives) {
            const bool claimed =
                std::any_of(mPlugins.begin(), mPlugins.end(), [&](const plugin::Plugin* p) {
                    return p->drawsPrimitive(*mModel, instance.node, *primitive.source);
                });
            mClaimed[flat++] = claimed;
            frame.opaqueGeometry = frame.opaqueGeometry || !claimed;
        }

    fg::FrameGraph graph(*mPool);
    fg::Blackboard blackboard;
    const gl::TextureDesc colorDesc{settings.size, gl::Format::RGBA16F, 1};
    const gl::TextureDesc depthDesc{settings.size, gl::Format::Depth32F, 1};
    const fg::TextureHandle output = graph.importTexture("output", mOutput.desc(), &mOutput);

    struct Empty {};
    graph.addPass<Empty>(
        "deform", [](fg::Builder& b, Empty&) { b.sideEffect(); },
        [this, &pose](const fg::Resources&, const Empty&, gl::Context&) {
            mDeformer->update(pose);
        });

    const auto& background = graph.addPass<TargetData>(
        "background",
        [&](fg::Builder& b, TargetData& d) {
            d.color = b.write(b.create("scene.color", colorDesc));
            d.depth = b.write(b.create("scene.depth", depthDesc));
        },
        [this, &frame](const fg::Resources& r, const TargetData& d, gl::Context&) {
            auto status =
                mFramebuffer.attach("background", {&r.texture(d.color)}, &r.texture(d.depth));
            ENGINE_CHECK(status.ok(), status.ok() ? "" : status.error().message);
            mFramebuffer.bind();
            gl::clearDepth(1.0f);
            gl::apply({.cull = gl::Cull::None, .depthTest = false, .depthWrite = false});
            mBackground.use();
            mEnvironment->bind(mBackground, 0, frame.settings.environmentRotation,
                               frame.settings.environmentIntensity);
            mBackground.set("uInverseViewProjection", glm::inverse(frame.camera.viewProjection()));
            mBackground.set("uBackgroundBlur", frame.settings.backgroundBlur);
            mEmptyVao.bind();
            gl::drawArrays(3);
        });

    TargetData scene = background;
    if (settings.ground) {
        scene = graph.addPass<TargetData>(
            "ground",
            [&](fg::Builder& b, TargetData& d) {
                d.color = b.write(scene.color);
                d.depth = b.write(scene.depth);
            },
            [this, &frame](const fg::Resources& r, const TargetData& d, gl::Context&) {
                auto status =
                    mFramebuffer.attach("ground", {&r.texture(d.color)}, &r.texture(d.depth));
                ENGINE_CHECK(status.ok(), status.ok() ? "" : status.error().message);
                mFramebuffer.bind();
                gl::apply({.cull = gl::Cull::None});
                mGround.use();
                mEnvironment->bind(mGround, 0, frame.settings.environmentRotation,
                                   frame.settings.environmentIntensity);
                mGround.set("uViewProjection", frame.camera.viewProjection());
                mGround.set("uCameraPosition", frame.camera.position);
                mGround.set("uCenter", frame.ground.center);
                mGround.set("uHalfSize", frame.ground.halfSize);
                mGround.set("uHeight", frame.ground.height);
                mGround.set("uTileSize", frame.ground.halfSize / 8.0f);
                mEmptyVao.bind();
                gl::drawArrays(6);
            });
    }

    scene = graph.addPass<TargetData>(
        "opaque",
        [&](fg::Builder& b, TargetData& d) {
            b.after("deform");
            d.color = b.write(scene.color);
            d.depth = b.write(scene.depth);
        },
        [this, &frame](const fg::Resources& r, const TargetData& d, gl::Context&) {
            auto status = mFramebuffer.attach("opaque", {&r.texture(d.color)}, &r.texture(d.depth));
            ENGINE_CHECK(status.ok(), status.ok() ? "" : status.error().message);
            mFramebuffer.bind();
            mOpaque.use();
            mEnvironment->bind(mOpaque, 0, frame.settings.environmentRotation,
                               frame.settings.environmentIntensity);
            mOpaque.set("uViewProjection", frame.camera.viewProjection());
            mOpaque.set("uCameraPosition", frame.camera.position);
            std::size_t vao = 0;
            for (const auto& instance : mDeformer->instances()) {
                mOpaque.set("uModel", instance.meshToWorld);
                mOpaque.set("uNormalMatrix",
                            glm::inverseTranspose(glm::mat3(instance.meshToWorld)));
                for (const auto& primitive : instance.primitives) {
                    if (mClaimed[vao]) {
                        ++vao;
                        continue;
                    }
                    const int material = primitive.source->material;
                    gl::apply({.cull = cullFor(*mModel, material)});
                    mMaterials->bind(mOpaque, *mModel, material, 2);
                    gl::bindStorage(0, primitive.deformed);
                    gl::bindStorage(1, *primitive.uv0);
                    mVaos[vao++].bind();
                    gl::drawIndexed(primitive.indexCount);
                }
            }
        });

    blackboard.put(plugin::kSceneColor, scene.color);
    blackboard.put(plugin::kSceneDepth, scene.depth);
    blackboard.put(plugin::kFrame, static_cast<const FrameInfo*>(&frame));
    for (plugin::Stage stage : {plugin::Stage::AfterOpaque, plugin::Stage::BeforeTonemap})
        for (plugin::Plugin* p : mPlugins)
            p->addPasses(stage, graph, blackboard);

    struct TonemapData {
        fg::TextureHandle scene, output;
    };
    const fg::TextureHandle finalColor = blackboard.get<fg::TextureHandle>(plugin::kSceneColor);
    graph.addPass<TonemapData>(
        "tonemap",
        [&](fg::Builder& b, TonemapData& d) {
            d.scene = b.read(finalColor);
            d.output = b.write(output);
        },
        [this, &frame](const fg::Resources& r, const TonemapData& d, gl::Context&) {
            auto status = mFramebuffer.attach("tonemap", {&r.texture(d.output)}, nullptr);
            ENGINE_CHECK(status.ok(), status.ok() ? "" : status.error().message);
            mFramebuffer.bind();
            gl::apply({.cull = gl::Cull::None, .depthTest = false, .depthWrite = false});
            mTonemap.use();
            gl::bindTexture(0, r.texture(d.scene));
            mTonemap.set("uScene", 0);
            mTonemap.set("uExposure", frame.settings.exposure);
            mTonemap.set("uRaw", frame.settings.hdrOutput ? 1 : 0);
            mEmptyVao.bind();
            gl::drawArrays(3);
        });

    auto compiled = graph.compile();
    if (!compiled)
        return compiled.error();
    FrameStats stats;
    mTimer->exact = settings.exactPassTimes;
    mTimer->beginFrame();
    for (const fg::PassTiming& t : graph.execute(*mContext, mTimer.get()))
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
    // Unbind our framebuffers before the pool deletes idle textures: deleting a texture
    // attached to the bound framebuffer makes the driver re-validate it (a KHR_debug warning).
    gl::Framebuffer::bindDefault(settings.size);
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
    mEnvironment = std::move(*env);
    return {};
}

std::vector<std::uint8_t> Renderer::readOutput() const {
    return gl::flipRows(mOutput.downloadRgba8(), mOutput.size());
}

std::vector<float> Renderer::readHdrOutput() const {
    return gl::flipRows(mOutput.downloadFloat(), mOutput.size());
}

} // namespace render
