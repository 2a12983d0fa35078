// glass-viewer: plays a world of glTF characters (a scene file, or models added one by one) with
// glass in a window, with a Dear ImGui panel over the scene and every parameter, presets,
// screenshots and a scripted mode for tests and demos.
#pragma once

#include "OrbitCamera.h"
#include "Preset.h"
#include "engine/anim/Pose.h"
#include "engine/gl/Context.h"
#include "engine/plugin/Plugin.h"
#include "engine/render/Renderer.h"
#include "engine/scene/Model.h"
#include "engine/scene/World.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace viewer {

struct ViewerOptions {
    /** A scene file or models (side by side); default: the last session's scene, else the
     *  project's generated character. */
    std::vector<std::string> models;
    /** --add PATH: added to the scene after it opens, as the panel's Add button does. */
    std::vector<std::string> add;
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
    std::filesystem::path uiMap; ///< --ui-map: where the panel's widgets are (UiMap.h)
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

    /** Replaces the world by `paths` (render::loadWorld); on failure the current one stays
     *  and the error is shown. */
    bool openWorld(const std::vector<std::string>& paths);
    /** Adds a character placing the model at `path` (loaded once per path) right of the
     *  others, playing its first clip, and selects it; a scene file adds its characters. */
    bool addCharacter(const std::string& path);
    void removeCharacter(std::size_t index);
    /** Writes the world to `path` (asset::saveScene: atomic). */
    bool saveWorld(const std::string& path);
    /** Selects character `index` (clamped; -1 with none): the clip and loop settings follow
     *  it. */
    void select(int index);
    /** After characters or their models change: ground under the new bounds, selection kept in
     *  range. */
    void worldChanged();
    /** The world's bounds (and the ground under them) from its characters' performances now:
     *  a clip, layer or crossfade added widens them, as glass-capture's of the saved scene. */
    void boundsChanged();
    /** The character under window pixel `pixel` of the view (nearest hit of its bounds), or -1. */
    int pick(glm::vec2 pixel) const;
    /** Character `index`'s bounds over its clip, in the world (clip bounds cached per model). */
    render::Bounds characterBounds(std::size_t index) const;
    /** The camera ray through window pixel `pixel` of the view: origin, unit direction. */
    std::pair<glm::vec3, glm::vec3> viewRay(glm::vec2 pixel) const;
    /** Moves the selected character by the cursor's motion from `from` to `to` over the ground
     *  plane through it (`vertical`: up and down); false where the plane is seen edge-on. */
    bool moveSelected(glm::vec2 from, glm::vec2 to, bool vertical);
    /** Marks the selected character in the view: its origin, axes and name. */
    void drawSelection() const;
    /** The selected character's joints, each a dot linked to its parent joint. */
    void drawSkeleton() const;
    /** Plays `clip` from now: a crossfade over the "crossfade" setting, or a snap at 0. */
    void changeClip(scene::Character& c, int clip);
    void frameCharacters(bool selectionOnly);
    /** The view's camera: the file's camera looked through, as its character poses it now,
     *  else the orbit. */
    render::Camera viewCamera(float aspect) const;
    /** Where the view's camera stands and looks, as the scene file keeps it. */
    scene::WorldCamera viewPlacement() const;
    /** Looks through a file's camera, or (none) hands the view back to the orbit where it
     *  stands. */
    void viewThrough(std::optional<scene::CameraThrough> camera);
    /** Shows the world's environment (added to the list when it is not there yet). */
    void useWorldEnvironment();
    void reportStatus(const core::Status& status, const std::string& success);
    core::Status applyEnvironment();
    std::vector<Scope> scopes();
    plugin::Plugin* methodPlugin() const;
    /** The viewer's settings, at their defaults, for the selected character's clips. */
    plugin::ParameterSet settingsForScene() const;
    float viewportAspect() const { return float(mViewport.x) / float(std::max(mViewport.y, 1)); }

    /** Files dropped on the window: they join the scene, or replace it (a scene file, Shift
     *  held, or "Drops replace"). */
    void handleDrops();
    /** Writes the pending screenshot; false (the error shown) when it fails. */
    bool takeScreenshot(glm::ivec2 window);
    void handleInput();
    void handleKeys();  ///< the keys pressed since the last frame
    void handleMouse(); ///< orbit, pan, zoom, pick, move the selection, drag the divider
    // create()'s stages: the environments offered, the window and ImGui, the renderer and its
    // plugins, the world (as given, else the last session's scene, else the project's
    // character), then the settings (the last session's, --env, --preset, --set, --add).
    void collectEnvironments(const ViewerOptions& options);
    core::Status openWindow(const ViewerOptions& options);
    core::Status createRenderer(const ViewerOptions& options);
    core::Status openWorld(const ViewerOptions& options);
    core::Status applyStartSettings(const ViewerOptions& options);
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
    std::unique_ptr<render::Renderer> mRenderer; // one for the viewer's life
    scene::World mWorld;
    render::Bounds mBounds; ///< of every character over its clip, at the last change
    int mSelected = -1;
    std::string mScenePath = "scene.json"; ///< the scene file opened or saved last
    bool mDropReplaces = false;            ///< a dropped model replaces the scene (or Shift)
    bool mMoving = false;                  ///< a Ctrl+drag is moving the selected character
    /** Per model, per clip: the bounds render::performanceBounds() keeps. */
    mutable std::map<std::shared_ptr<const scene::Model>, std::map<int, render::Bounds>>
        mClipBounds;
    std::vector<EnvironmentEntry> mEnvironments;
    int mEnvironmentShown = -1;
    plugin::ParameterSet mSettings;
    OrbitCamera mCamera;
    std::optional<scene::CameraThrough> mViewThrough; ///< a file's camera looked through
    mutable anim::Pose mViewPose;                     ///< its character's pose, for viewCamera()
    mutable const scene::Model* mViewPoseModel = nullptr;
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
/** Where the last session's scene lives: last-scene.json beside lastSessionPath(). */
std::filesystem::path lastScenePath();

/** The project's assets folder: $GLASS_ASSETS_DIR, else PREFIX/share/glass/assets when the
 *  viewer runs installed (PREFIX/bin), else the source tree's the build was configured with. */
std::filesystem::path assetsDir();

} // namespace viewer
