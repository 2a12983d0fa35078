// glass-capture's rendering session.
#include "CaptureSession.h"

#include "engine/anim/Pose.h"
#include "engine/asset/HdrImage.h"
#include "engine/asset/ModelLoader.h"
#include "engine/asset/SceneFile.h"
#include "engine/gl/Debug.h"
#include "engine/render/CpuShading.h"
#include "engine/render/WorldLoader.h"
#include "refraction/RefractionPlugin.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

namespace capture {

namespace {

/** --clip: every character plays clip `name` alone, on its first layer's clock. */
core::Status playClip(scene::World& world, const std::string& name) {
    for (scene::Character& c : world.characters) {
        const auto clip = c.model->findAnimation(name);
        if (!clip)
            return core::Error{"glass-capture: --clip: " + c.name + " (" + c.model->sourceName +
                               ") has no clip '" + name + "'"};
        scene::Layer timing =
            c.performance.layers.empty() ? scene::Layer{} : c.performance.layers.front();
        c.play(*clip);
        timing.clip = *clip;
        timing.weight = 1.0;
        timing.additive = false;
        timing.mask.clear();
        c.performance.layers.front() = timing;
    }
    return {};
}

/** --variant: every character whose model has variant `name` shows it; none having it is an
 *  error listing the variants offered. */
core::Status chooseVariant(scene::World& world, const std::string& name) {
    std::string offered;
    bool any = false;
    for (scene::Character& c : world.characters)
        if (const auto variant = c.model->findVariant(name)) {
            c.variant = *variant;
            any = true;
        } else {
            for (const std::string& v : c.model->variants)
                offered += (offered.empty() ? "" : ", ") + v;
        }
    if (!any)
        return core::Error{"glass-capture: --variant: no character's model has a variant '" + name +
                           "' (variants: " + (offered.empty() ? "none" : offered) + ")"};
    return {};
}

/** --env, else the scene file's environment, else the procedural sky. */
core::Result<asset::HdrImage> environmentOf(const SessionOptions& options,
                                            const scene::World& world) {
    const auto& path = options.environment ? options.environment : world.environment;
    if (!path)
        return render::Environment::proceduralSky();
    auto hdr = asset::loadHdr(*path);
    if (!hdr && !options.environment) // the scene file's: name it and its key
        return core::Error{"glass-capture: " + options.models.front() +
                           ": environment: " + hdr.error().message};
    return hdr;
}

/** The refraction plugin with --refraction's parameters, then each --plugin with its own. */
core::Status addPlugins(render::Renderer& renderer, plugin::Plugin& refraction,
                        const SessionOptions& options, std::vector<plugin::LoadedPlugin>& plugins) {
    for (const auto& [key, value] : options.refraction) {
        auto set = refraction.parameters().set(key, value);
        if (!set)
            return core::Error{"glass-capture: --" + key + ": " + set.error().message};
    }
    if (auto added = renderer.addPlugin(&refraction); !added)
        return added.error();
    for (const auto& spec : options.plugins) {
        auto loaded = plugin::loadPlugin(spec.path);
        if (!loaded)
            return loaded.error();
        for (const auto& [key, value] : spec.parameters) {
            auto set = loaded->get()->parameters().set(key, value);
            if (!set)
                return core::Error{"glass-capture: plugin " + std::string(loaded->get()->name()) +
                                   ": " + set.error().message};
        }
        auto added = renderer.addPlugin(loaded->get());
        if (!added)
            return added.error();
        plugins.push_back(std::move(*loaded));
    }
    return {};
}

} // namespace

core::Result<std::unique_ptr<CaptureSession>>
CaptureSession::create(const SessionOptions& options) {
    std::unique_ptr<CaptureSession> s(new CaptureSession());
    s->mOptions = options;
    auto world = render::loadWorld(options.models);
    if (!world)
        return world.error();
    s->mWorld = std::move(*world);
    if (options.clip)
        if (auto played = playClip(s->mWorld, *options.clip); !played)
            return played.error();
    if (options.variant)
        if (auto chosen = chooseVariant(s->mWorld, *options.variant); !chosen)
            return chosen.error();
    s->mOptions.ground = options.ground || s->mWorld.ground;
    auto environment = environmentOf(options, s->mWorld);
    if (!environment)
        return environment.error();
    auto context = gl::createHeadlessContext();
    if (!context)
        return context.error();
    s->mContext = std::move(*context);
    auto renderer = render::Renderer::create(*environment, *s->mContext);
    if (!renderer)
        return renderer.error();
    s->mRenderer = std::move(*renderer);
    if (auto refined = s->mRenderer->setSubdivisionLevel(options.subdivision); !refined)
        return core::Error{"glass-capture: " + refined.error().message};
    if (auto prepared = s->mRenderer->prepare(s->mWorld); !prepared)
        return core::Error{"glass-capture: " + prepared.error().message};
    s->mRefraction = refraction::createPlugin();
    if (auto added = addPlugins(*s->mRenderer, *s->mRefraction, options, s->mPlugins); !added)
        return added.error();
    s->mBounds = render::worldBounds(s->mWorld);
    s->mRenderer->setGround(render::GroundPlane::under(s->mBounds));
    return s;
}

namespace {

/** Letters, digits, '-' and '_' kept; anything else becomes '_'. */
std::string fileNameSafe(std::string text) {
    for (char& c : text)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_')
            c = '_';
    return text;
}

} // namespace

std::string CaptureSession::clipLabel() const {
    if (mWorld.characters.size() != 1)
        return "scene";
    const scene::Character& c = mWorld.characters[0];
    const int clip = c.mainClip();
    if (clip < 0)
        return "rest";
    const std::string& name = c.model->animations[std::size_t(clip)].name;
    return fileNameSafe(name.empty() ? "clip" + std::to_string(clip) : name);
}

std::string CaptureSession::stem() const {
    const std::string& first = mOptions.models.at(0);
    if (first.rfind("builtin:", 0) == 0)
        return fileNameSafe(first);
    return fileNameSafe(std::filesystem::path(first).stem().string());
}

std::optional<render::Camera> CaptureSession::modelCamera(double time, float aspect) const {
    if (mWorld.characters.size() != 1 || asset::isSceneFile(mOptions.models.at(0)))
        return std::nullopt; // a scene places its characters: their files' cameras do not apply
    const scene::Character& c = mWorld.characters[0];
    return render::gltfCamera(*c.model, anim::evaluate(*c.model, c.performance, time), aspect);
}

render::Camera CaptureSession::cameraAt(double time) const {
    const float aspect = float(mOptions.size.x) / float(mOptions.size.y);
    render::Camera camera;
    if (mOptions.camera && mOptions.camera->position) {
        camera.position = *mOptions.camera->position;
        camera.yfov = mOptions.camera->yfov;
        camera.view = glm::lookAt(camera.position, mOptions.camera->target, glm::vec3(0, 1, 0));
        const float distance = glm::length(mOptions.camera->target - camera.position);
        camera.znear = std::max(distance * 0.01f, 1e-3f);
        camera.zfar = distance * 100.0f;
        camera.projection = glm::perspective(camera.yfov, aspect, camera.znear, camera.zfar);
    } else if (mOptions.camera) {
        camera = render::frameBounds(mBounds, aspect, mOptions.camera->yfov,
                                     mOptions.camera->azimuth, mOptions.camera->elevation);
    } else if (mWorld.camera) {
        camera = render::sceneCamera(mWorld, time, aspect, mBounds);
    } else if (auto gltf = modelCamera(time, aspect)) {
        camera = *gltf;
    } else {
        camera = render::frameBounds(mBounds, aspect);
    }
    return camera;
}

render::RenderSettings CaptureSession::settings() const {
    render::RenderSettings settings;
    settings.size = mOptions.size;
    settings.ground = mOptions.ground;
    settings.shadows = mOptions.shadows;
    settings.shadowMapView = mOptions.shadowMapView;
    settings.exposure = mOptions.exposure;
    settings.exactPassTimes = true; // captures are not real-time: report true per-pass GPU times
    settings.temporal = mOptions.temporal;
    settings.temporal.enabled = mOptions.temporal.enabled || mOptions.accumulate > 0;
    return settings;
}

core::Result<RenderedFrame> CaptureSession::render(double time) {
    if (mOptions.accumulate > 0) {
        mRenderer->resetHistory();
        for (int k = 1; k < mOptions.accumulate; ++k)
            if (auto frame = renderOnce(time); !frame)
                return frame.error();
    } else if (mOptions.temporal.enabled && !mWarmedUp) {
        for (int k = mOptions.warmup; k > 0; --k)
            if (auto frame = renderOnce(time - k * mOptions.warmupStep); !frame)
                return frame.error();
    }
    mWarmedUp = true;
    return renderOnce(time);
}

core::Result<RenderedFrame> CaptureSession::renderOnce(double time) {
    const std::uint64_t errorsBefore = gl::errorCount();
    auto stats = mRenderer->render(mWorld, cameraAt(time), settings(), time);
    if (!stats)
        return stats.error();
    RenderedFrame frame;
    frame.time = time;
    frame.stats = std::move(*stats);
    frame.image = Image{mOptions.size.x, mOptions.size.y, mRenderer->readOutput()};
    gl::checkErrors("glass-capture frame");
    if (gl::errorCount() != errorsBefore)
        return core::Error{"glass-capture: GL errors while rendering t=" + std::to_string(time) +
                           " (see log)"};
    return frame;
}

core::Result<RenderedFrame>
CaptureSession::renderReference(double time, const refraction::ReferenceOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    const render::RenderSettings frameSettings = settings();
    const auto environment = refraction::EnvironmentSampler::fromGpu(
        mRenderer->environment(), frameSettings.environmentRotation,
        frameSettings.environmentIntensity);
    auto traced =
        refraction::traceReference(mWorld, time, cameraAt(time), environment, frameSettings,
                                   mRenderer->ground(), mRefraction->parameters(), options);
    if (!traced)
        return traced.error();
    RenderedFrame frame;
    frame.time = time;
    frame.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    frame.image = Image{mOptions.size.x, mOptions.size.y,
                        render::cpu::tonemap(traced->rgba, mOptions.exposure)};
    for (std::size_t i = 3; i < traced->rgba.size(); i += 4)
        frame.glassMask.push_back(traced->rgba[i] > 0.5f);
    frame.trappedSamples = traced->trappedSamples;
    frame.surfaceHistogram = traced->surfaceHistogram;
    if (traced->trappedSamples > 0)
        std::fprintf(stderr,
                     "reference: %zu samples still in glass after the interface limit (black)\n",
                     traced->trappedSamples);
    return frame;
}

std::string secondsText(double time) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", time);
    return text;
}

std::string frameFileName(const std::string& modelStem, const std::string& clipLabel, double time) {
    return modelStem + "_" + clipLabel + "_t" + secondsText(time) + ".png";
}

nlohmann::json statsJson(const render::FrameStats& stats) {
    nlohmann::json passes = nlohmann::json::array();
    for (const auto& p : stats.passes)
        passes.push_back({{"name", p.name}, {"cpu_ms", p.cpuMs}, {"gpu_ms", p.gpuMs}});
    return {{"passes", passes}, {"frame_cpu_ms", stats.cpuMs}, {"frame_gpu_ms", stats.gpuMs}};
}

} // namespace capture

namespace capture {

nlohmann::json medianStats(const nlohmann::json& frames) {
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v.empty() ? 0.0 : v[v.size() / 2];
    };
    const std::size_t first = frames.size() > 1 ? 1 : 0;
    std::vector<double> cpu, gpu;
    std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> passes;
    std::vector<std::string> order;
    for (std::size_t i = first; i < frames.size(); ++i) {
        cpu.push_back(frames[i]["frame_cpu_ms"].get<double>());
        gpu.push_back(frames[i]["frame_gpu_ms"].get<double>());
        for (const auto& p : frames[i]["passes"]) {
            const std::string name = p["name"];
            if (!passes.count(name))
                order.push_back(name);
            passes[name].first.push_back(p["cpu_ms"].get<double>());
            passes[name].second.push_back(p["gpu_ms"].get<double>());
        }
    }
    nlohmann::json out = {{"frames", frames.size() - first},
                          {"frame_cpu_ms", median(cpu)},
                          {"frame_gpu_ms", median(gpu)},
                          {"passes", nlohmann::json::array()}};
    for (const std::string& name : order)
        out["passes"].push_back({{"name", name},
                                 {"cpu_ms", median(passes[name].first)},
                                 {"gpu_ms", median(passes[name].second)}});
    return out;
}

} // namespace capture
