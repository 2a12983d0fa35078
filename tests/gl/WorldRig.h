// A world as the GL tests of the glass render and score it: the refraction plugin's frame (its
// parameters as KEY=VALUE) and the Embree reference's, from one camera.
#pragma once

#include "engine/asset/ModelLoader.h"
#include "engine/asset/SceneFile.h"
#include "engine/capture/Metrics.h"
#include "engine/render/Renderer.h"
#include "refraction/ReferenceTracer.h"
#include "refraction/RefractionPlugin.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace test {

inline constexpr int kWorldRigSize = 128;

#ifdef GLASS_SOURCE_DIR
/** One of the project's scene files (assets/scenes/NAME), loaded. */
inline scene::World projectScene(const std::string& name) {
    auto world = asset::loadScene(std::string(GLASS_SOURCE_DIR) + "/assets/scenes/" + name);
    EXPECT_TRUE(world.ok()) << (world.ok() ? "" : world.error().message);
    return world ? std::move(*world) : scene::World{};
}

/** A model of assets/models playing its first clip; without its normal maps where
 *  `normalMaps` is false (the parts figure has one, on its hammered head: checked). */
inline scene::World generatedWorld(const std::string& file, bool normalMaps = true) {
    auto loaded = asset::loadModel(std::string(GLASS_SOURCE_DIR) + "/assets/models/" + file);
    EXPECT_TRUE(loaded.ok()) << (loaded.ok() ? "" : loaded.error().message);
    if (!loaded)
        return {};
    std::size_t mapped = 0;
    for (scene::Material& m : loaded->materials)
        if (m.normalTexture.present()) {
            if (!normalMaps)
                m.normalTexture = {};
            ++mapped;
        }
    EXPECT_EQ(mapped, file == "glass_figure_parts.glb" ? 1u : 0u);
    scene::World world =
        scene::singleCharacterWorld(std::make_shared<const scene::Model>(std::move(*loaded)));
    world.characters[0].play(0);
    return world;
}
#endif

/** A world rendered by the refraction plugin (KEY=VALUE parameters) and traced by the
 *  reference with the same parameters; with its ground plane under it if it has one. */
class WorldRig {
public:
    /** With `environment` its light (else the procedural sky). */
    WorldRig(scene::World world, gl::Context& context, int size = kWorldRigSize,
             const asset::HdrImage* environment = nullptr)
        : mWorld(std::move(world)), mSize(size) {
        auto renderer = render::Renderer::create(
            environment ? *environment : render::Environment::proceduralSky(128), context);
        EXPECT_TRUE(renderer.ok()) << (renderer.ok() ? "" : renderer.error().message);
        mRenderer = std::move(*renderer);
        mPlugin = std::make_unique<refraction::RefractionPlugin>();
        EXPECT_TRUE(mRenderer->addPlugin(mPlugin.get()).ok());
        mCamera = render::frameBounds(render::worldBounds(mWorld), 1.0f, 0.7f, 0.0f, 0.1f, 1.0f);
        mRenderer->setGround(render::GroundPlane::under(render::worldBounds(mWorld)));
    }
    void set(const std::string& key, const std::string& value) {
        ASSERT_TRUE(mPlugin->parameters().set(key, value).ok()) << key << "=" << value;
    }
    /** The HDR frame at scene time `time` (rows top to bottom); `passes` gets the frame's pass
     *  names. */
    std::vector<float> renderHdr(double time = 0.0, std::vector<std::string>* passes = nullptr) {
        render::RenderSettings settings;
        settings.size = {mSize, mSize};
        settings.ground = mWorld.ground;
        settings.shadows = shadows;
        settings.hdrOutput = true;
        settings.temporal = temporal;
        settings.skippedSteps = skippedSteps;
        auto stats = mRenderer->render(mWorld, mCamera, settings, time);
        EXPECT_TRUE(stats.ok()) << (stats.ok() ? "" : stats.error().message);
        if (stats && passes)
            for (const render::PassStats& p : stats->passes)
                passes->push_back(p.name);
        return mRenderer->readHdrOutput();
    }
    /** renderHdr() tonemapped. */
    capture::Image render(double time = 0.0, std::vector<std::string>* passes = nullptr) {
        return {mSize, mSize, render::cpu::tonemap(renderHdr(time, passes), 1.0f)};
    }
    struct Reference {
        capture::Image image;
        std::vector<bool> mask;
        refraction::ReferenceImage traced;
    };
    /** How the reference evaluates its paths: 16 jittered rays a pixel (the ground truth), or
     *  the deterministic evaluation through each pixel's centre (what the GPU computes at one
     *  sample a pixel: ReferenceOptions::deterministic). */
    enum class Evaluation { Sampled, Deterministic };
    /** The reference's frame at `time`, with `spp` rays a pixel where sampled. */
    Reference reference(double time = 0.0, Evaluation evaluation = Evaluation::Sampled,
                        int spp = 16) const {
        render::RenderSettings settings;
        settings.size = {mSize, mSize};
        settings.ground = mWorld.ground;
        settings.shadows = shadows;
        refraction::ReferenceOptions options;
        options.samplesPerPixel = spp;
        options.deterministic = evaluation == Evaluation::Deterministic;
        options.subdivision = mSubdivision;
        const auto environment =
            refraction::EnvironmentSampler::fromGpu(mRenderer->environment(), 0.0f, 1.0f);
        auto traced =
            refraction::traceReference(mWorld, time, mCamera, environment, settings,
                                       mRenderer->ground(), mPlugin->parameters(), options);
        EXPECT_TRUE(traced.ok()) << (traced.ok() ? "" : traced.error().message);
        Reference r;
        if (!traced)
            return r;
        r.image = {mSize, mSize, render::cpu::tonemap(traced->rgba, 1.0f)};
        for (std::size_t i = 3; i < traced->rgba.size(); i += 4)
            r.mask.push_back(traced->rgba[i] > 0.5f);
        r.traced = std::move(*traced);
        return r;
    }
    /** Masked PSNR of the frame at `time` against `r`. */
    double psnrAgainst(const Reference& r, double time = 0.0) {
        return capture::score(render(time), r.image, &r.mask).psnr;
    }
    /** Masked PSNR of the frame at `time` against the reference at the same time. */
    double psnrAgainstReference(double time = 0.0) { return psnrAgainst(reference(time), time); }
    /** Refines every character to `level` (Renderer::setSubdivisionLevel), on the GPU and in
     *  the reference. */
    void setSubdivisionLevel(int level) {
        ASSERT_TRUE(mRenderer->setSubdivisionLevel(level).ok());
        mSubdivision = level;
    }
    const refraction::RefractionPlugin& plugin() const { return *mPlugin; }
    render::Renderer& renderer() { return *mRenderer; }
    const scene::World& world() const { return mWorld; }
    scene::Character& character(std::size_t i) { return mWorld.characters.at(i); }
    /** The lights cast shadows, on the GPU and in the reference (RenderSettings::shadows). */
    bool shadows = true;
    /** The frames' temporal accumulation (off unless set). */
    render::TemporalSettings temporal;
    std::vector<std::string> skippedSteps; ///< RenderSettings::skippedSteps (measurement)
    const render::Camera& camera() const { return mCamera; }
    void setCamera(const render::Camera& camera) { mCamera = camera; }
    /** The frames' width and height from the next one on. */
    void setSize(int size) { mSize = size; }
    /** Views the world from its scene file's camera instead of framing its bounds. */
    void useSceneCamera() {
        ASSERT_TRUE(mWorld.camera.has_value());
        mCamera = render::sceneCamera(mWorld, 0.0, 1.0f, render::worldBounds(mWorld));
    }

private:
    scene::World mWorld;
    std::unique_ptr<render::Renderer> mRenderer;
    std::unique_ptr<refraction::RefractionPlugin> mPlugin;
    render::Camera mCamera;
    int mSize;
    int mSubdivision = 0;
};

} // namespace test
