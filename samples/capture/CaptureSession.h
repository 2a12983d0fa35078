// What glass-capture renders: a world (a scene file, or models side by side), a camera, the
// environment and plugins, set up once and rendered at any number of times.
#pragma once

#include "engine/capture/Image.h"
#include "engine/gl/Context.h"
#include "engine/plugin/Plugin.h"
#include "engine/render/Renderer.h"
#include "engine/scene/Model.h"
#include "refraction/ReferenceTracer.h"

#include <nlohmann/json.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace capture {

/** An explicit camera (position, target) or, without a position, the automatic framing seen
 *  from other angles (radians; azimuth about +y from +z, elevation above the horizon). */
struct CameraOverride {
    std::optional<glm::vec3> position;
    glm::vec3 target{0.0f};
    float yfov = 0.7f;
    float azimuth = 0.0f, elevation = 0.15f;
};

struct SessionOptions {
    /** One scene file, or model paths placed side by side (render::loadWorld). */
    std::vector<std::string> models;
    /** Name or index, for every character; default: a scene file's clips, a model's first. */
    std::optional<std::string> clip;
    /** KHR_materials_variants: name or index, for every character whose model has it. */
    std::optional<std::string> variant;
    /** HDR path; default: the scene file's environment, else the procedural sky. */
    std::optional<std::string> environment;
    glm::ivec2 size{256, 256};
    bool ground = false; ///< also on when the scene file asks for it
    bool shadows = true; ///< RenderSettings::shadows
    /** RenderSettings::shadowMapView: a shadow atlas in place of the scene. */
    render::RenderSettings::ShadowMapView shadowMapView =
        render::RenderSettings::ShadowMapView::Off;
    float exposure = 1.0f;
    int subdivision = 0; ///< OpenSubdiv level of every mesh (Renderer::setSubdivisionLevel)
    /** Default: the scene file's camera, else one model's glTF camera, else framing. */
    std::optional<CameraOverride> camera;
    struct PluginSpec {
        std::string path;
        std::vector<std::pair<std::string, std::string>> parameters;
    };
    std::vector<PluginSpec> plugins;
    /** Parameters of the built-in refraction plugin (linked statically, always present). */
    std::vector<std::pair<std::string, std::string>> refraction;
    /** Temporal accumulation (render::TemporalSettings): the history carries across the frames
     *  a session renders. */
    render::TemporalSettings temporal;
    /** With temporal on: frames rendered before the first one asked for, at the times before it
     *  (warmupStep apart), as a playing viewer's history would hold them. */
    int warmup = 0;
    double warmupStep = 1.0 / 30.0;
    /** Above 0: every frame asked for is this many frames at its one time from a fresh history
     *  (temporal on, converging), the accumulated one returned. */
    int accumulate = 0;
};

struct RenderedFrame {
    double time = 0.0;
    Image image;
    render::FrameStats stats;
    std::vector<bool> glassMask;    ///< reference frames: pixels whose camera rays hit glass
    double milliseconds = 0.0;      ///< reference frames: tracing time
    std::size_t trappedSamples = 0; ///< reference frames: paths still in glass at the cap
    /** Reference frames: glass pixels by the number of glass surfaces on their line of sight. */
    std::vector<std::size_t> surfaceHistogram;
};

class CaptureSession {
public:
    /** Loads the world and environment, creates a headless context and the renderer, loads
     *  and configures plugins. Fails with the loader's (or GL's) message. */
    static core::Result<std::unique_ptr<CaptureSession>> create(const SessionOptions& options);

    /** The frame at `time`: one frame, or with accumulate N the last of N at that time from a
     *  fresh history; with temporal on, the first call renders the warm-up frames before it. */
    core::Result<RenderedFrame> render(double time);
    /** The Embree reference of the same frame, tonemapped like the GPU output. */
    core::Result<RenderedFrame> renderReference(double time,
                                                const refraction::ReferenceOptions& options);

    const scene::World& world() const { return mWorld; }
    /** The first character's clip for file names ("rest" without one); "scene" for a world of
     *  several characters. */
    std::string clipLabel() const;
    /** The file name stem of the frames: the model's or the scene file's. */
    std::string stem() const;

private:
    CaptureSession() = default;
    render::Camera cameraAt(double time) const;
    /** The glTF camera of one model (not of a scene file), posed at `time`. */
    std::optional<render::Camera> modelCamera(double time, float aspect) const;
    render::RenderSettings settings() const;
    core::Result<RenderedFrame> renderOnce(double time);
    SessionOptions mOptions;
    bool mWarmedUp = false;
    scene::World mWorld;
    std::unique_ptr<gl::Context> mContext;
    std::unique_ptr<plugin::Plugin> mRefraction;
    std::vector<plugin::LoadedPlugin> mPlugins;
    std::unique_ptr<render::Renderer> mRenderer;
    render::Bounds mBounds;
};

/** A time as file names spell it: seconds with 3 decimals ("1.250"). */
std::string secondsText(double time);

/** Deterministic file name of a frame: "<model>_<clip>_t<seconds with 3 decimals>.png". */
std::string frameFileName(const std::string& modelStem, const std::string& clipLabel, double time);

/** Frame statistics as JSON: per pass name, cpu_ms, gpu_ms; totals. */
nlohmann::json statsJson(const render::FrameStats& stats);

/** Medians of frame_cpu_ms, frame_gpu_ms and each pass's cpu_ms/gpu_ms over `frames` (as
 *  statsJson writes them), leaving out the first frame (shader JIT, first uploads) when there
 *  are several. */
nlohmann::json medianStats(const nlohmann::json& frames);

} // namespace capture
