// glass-viewer: plays a glTF character as glass in a window, with a Dear ImGui panel over every
// parameter, presets, screenshots and a scripted mode for tests and demos.
#pragma once

#include "OrbitCamera.h"
#include "Preset.h"
#include "engine/gl/Context.h"
#include "engine/plugin/Plugin.h"
#include "engine/render/Renderer.h"
#include "engine/scene/Model.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace viewer {

struct ViewerOptions {
    std::optional<std::string> model;      ///< default: the project's generated character
    std::vector<std::string> environments; ///< --env, added to those found in the assets
    std::optional<std::string> preset;
    std::vector<std::string> plugins;
    std::vector<std::string> assignments; ///< --set KEY=VALUE, applied last
    glm::ivec2 windowSize{1280, 720};
    std::optional<int> frames; ///< scripted: advance this many fixed 1/30 s frames
    std::optional<std::filesystem::path> screenshot; ///< written after the scripted frames
    std::optional<glm::ivec2> screenshotSize;        ///< default: the window's
    bool screenshotPanel = false;                    ///< include the panel
    bool exitAfterFrames = false;
    bool restoreSession = true;
    bool force = false; ///< overwrite an existing --screenshot
    std::filesystem::path screenshotDir = ".";
};

/** A model and what draws it: replaced as a whole when another model is opened. */
struct LoadedScene {
    std::unique_ptr<scene::Model> model;
    std::unique_ptr<render::Renderer> renderer;
    render::Bounds bounds;
    std::string path;
};

/** A key press (or repeat) from the window, in arrival order. */
struct KeyEvent {
    int key = 0, mods = 0;
    bool repeat = false;
};

/** What the window's callbacks collect between frames. */
struct WindowEvents {
    std::vector<std::string> dropped;
    std::vector<KeyEvent> keys;
};

/** An environment the panel offers: the procedural sky (empty path) or an HDR file. */
struct EnvironmentEntry {
    std::string name;
    std::string path;
};

class Viewer {
public:
    /** Opens the window, the model, the environment and the plugins; applies the last session,
     *  --preset and --set. Fails (no window left open) naming what could not be loaded. */
    static core::Result<std::unique_ptr<Viewer>> create(const ViewerOptions& options);
    ~Viewer();

    /** Runs until the window closes, Ctrl+Q, or the scripted frames end with --exit. Returns
     *  the process exit status: non-zero on a failed scripted screenshot or any GL error. */
    int run();

private:
    Viewer() = default;
    friend class Panel;

    core::Result<LoadedScene> loadScene(const std::string& path);
    /** Opens another model; on failure the current one stays and the error is shown. */
    void openModel(const std::string& path);
    core::Status applyEnvironment();
    std::vector<Scope> scopes();
    plugin::Plugin* methodPlugin() const;
    /** The viewer's settings, at their defaults, for the current model's clips. */
    plugin::ParameterSet settingsForScene() const;
    float viewportAspect() const { return float(mViewport.x) / float(std::max(mViewport.y, 1)); }

    void handleInput();
    void advance(double dt);
    render::RenderSettings settings(glm::ivec2 size) const;
    core::Status renderView(glm::ivec2 size);
    core::Status screenshot(const std::filesystem::path& path, std::optional<glm::ivec2> size,
                            bool withPanel);
    std::filesystem::path nextScreenshotPath() const;
    void saveSession();

    ViewerOptions mOptions;
    std::unique_ptr<gl::Context> mContext;
    std::unique_ptr<plugin::Plugin> mRefraction;
    std::vector<plugin::LoadedPlugin> mPlugins;
    LoadedScene mScene;
    std::vector<EnvironmentEntry> mEnvironments;
    int mEnvironmentShown = -1;
    plugin::ParameterSet mSettings;
    OrbitCamera mCamera;
    double mTime = 0.0;
    render::FrameStats mStats;
    double mFrameMs = 0.0; ///< smoothed wall-clock frame time
    std::string mMessage;  ///< last error or notice, shown in the panel
    bool mMessageIsError = false;
    bool mShowPanel = true;
    glm::ivec2 mViewport{0}; ///< the 3D view: the window left of the panel
    bool mQuit = false;
    bool mDraggingDivider = false;
    WindowEvents mEvents;
    std::optional<std::filesystem::path> mPendingScreenshot;
    std::optional<glm::ivec2> mPendingScreenshotSize;
    bool mPendingScreenshotPanel = false;
};

/** Where the last session's settings live: $XDG_CONFIG_HOME/glass-viewer/last-session.json
 *  (or ~/.config/...). */
std::filesystem::path lastSessionPath();

/** The project's assets folder: $GLASS_ASSETS_DIR, else PREFIX/share/glass/assets when the
 *  viewer runs installed (PREFIX/bin), else the source tree's the build was configured with. */
std::filesystem::path assetsDir();

} // namespace viewer
