// glass-viewer's window, world of characters and frame loop (the panel is in Panel.cpp).
#include "Viewer.h"

#include "Panel.h"
#include "UiMap.h"
#include "engine/anim/Pose.h"
#include "engine/asset/HdrImage.h"
#include "engine/asset/ModelLoader.h"
#include "engine/asset/SceneFile.h"
#include "engine/capture/Image.h"
#include "engine/gl/Debug.h"
#include "engine/gl/Framebuffer.h"
#include "engine/render/WorldLoader.h"
#include "refraction/RefractionPlugin.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

namespace viewer {
namespace {

constexpr double kFixedStep = 1.0 / 30.0;

void dropCallback(GLFWwindow* window, int count, const char** paths) {
    auto* events = static_cast<WindowEvents*>(glfwGetWindowUserPointer(window));
    for (int i = 0; i < count; ++i)
        events->dropped.emplace_back(paths[i]);
}

// Keys are queued as events: Dear ImGui 1.86 keeps only whether a key is down at each frame,
// so a press and release within one (slow) frame would be lost.
void keyCallback(GLFWwindow* window, int key, int, int action, int mods) {
    if (action == GLFW_PRESS || action == GLFW_REPEAT)
        static_cast<WindowEvents*>(glfwGetWindowUserPointer(window))
            ->keys.push_back({key, mods, action == GLFW_REPEAT});
}

std::vector<std::string> clipNames(const scene::Model& model) {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < model.animations.size(); ++i) {
        std::string name = model.animations[i].name.empty() ? "clip " + std::to_string(i)
                                                            : model.animations[i].name;
        // Enum choices must be unique: a repeated name gets its index.
        if (std::find(names.begin(), names.end(), name) != names.end())
            name += " #" + std::to_string(i);
        names.push_back(std::move(name));
    }
    return names;
}

} // namespace

std::filesystem::path lastSessionPath() {
    if (const char* config = std::getenv("XDG_CONFIG_HOME"); config && *config)
        return std::filesystem::path(config) / "glass-viewer" / "last-session.json";
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::filesystem::path(home) / ".config" / "glass-viewer" / "last-session.json";
    return {};
}

std::filesystem::path lastScenePath() {
    const std::filesystem::path session = lastSessionPath();
    return session.empty() ? session : session.parent_path() / "last-scene.json";
}

std::filesystem::path assetsDir() {
    if (const char* dir = std::getenv("GLASS_ASSETS_DIR"); dir && *dir)
        return dir;
    // installed: PREFIX/bin/glass-viewer beside PREFIX/share/glass/assets
    std::error_code ec;
    const auto executable = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        auto installed = executable.parent_path().parent_path() / "share/glass/assets";
        if (std::filesystem::is_directory(installed, ec))
            return installed;
    }
    return GLASS_ASSETS_DIR;
}

core::Result<std::unique_ptr<Viewer>> Viewer::create(const ViewerOptions& options) {
    std::unique_ptr<Viewer> v(new Viewer());
    v->mOptions = options;
    v->collectEnvironments(options);
    core::Status ready = v->openWindow(options);
    if (ready)
        ready = v->createRenderer(options);
    if (ready)
        ready = v->openWorld(options);
    if (ready)
        ready = v->applyStartSettings(options);
    if (!ready)
        return ready.error();
    return v;
}

void Viewer::collectEnvironments(const ViewerOptions& options) {
    mEnvironments.push_back({"procedural sky", ""});
    std::vector<std::filesystem::path> found;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(assetsDir() / "env", ec))
        if (entry.path().extension() == ".hdr")
            found.push_back(entry.path());
    std::sort(found.begin(), found.end());
    for (const std::string& env : options.environments)
        found.emplace_back(env);
    for (const auto& path : found) {
        const bool known =
            std::any_of(mEnvironments.begin(), mEnvironments.end(),
                        [&](const EnvironmentEntry& e) { return e.path == path.string(); });
        if (!known) {
            std::string name = path.stem().string();
            for (const EnvironmentEntry& e : mEnvironments)
                if (e.name == name)
                    name = path.string();
            mEnvironments.push_back({name, path.string()});
        }
    }
}

core::Status Viewer::openWindow(const ViewerOptions& options) {
    gl::ContextOptions contextOptions;
    contextOptions.windowSize = options.windowSize;
    contextOptions.title = "glass-viewer";
    contextOptions.vsync = !options.frames; // scripted runs go as fast as they can
    auto context = gl::createWindowContext(contextOptions);
    if (!context)
        return core::Error{"glass-viewer needs a display (" + context.error().message +
                           "); without one use glass-capture, or run under xvfb-run"};
    mContext = std::move(*context);
    auto* window = static_cast<GLFWwindow*>(mContext->nativeWindow());
    glfwSetWindowUserPointer(window, &mEvents);
    glfwSetDropCallback(window, dropCallback);
    glfwSetKeyCallback(window, keyCallback); // before ImGui's, which calls it after its own

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr; // the layout is fixed; settings live in presets
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 450 core");
    return {};
}

core::Status Viewer::createRenderer(const ViewerOptions& options) {
    mRefraction = refraction::createPlugin();
    for (const std::string& path : options.plugins) {
        auto loaded = plugin::loadPlugin(path);
        if (!loaded)
            return loaded.error();
        mPlugins.push_back(std::move(*loaded));
    }

    auto renderer = render::Renderer::create(render::Environment::proceduralSky(), *mContext);
    if (!renderer)
        return renderer.error();
    mRenderer = std::move(*renderer);
    if (auto added = mRenderer->addPlugin(mRefraction.get()); !added)
        return added.error();
    for (const auto& loaded : mPlugins)
        if (auto added = mRenderer->addPlugin(loaded.get()); !added)
            return added.error();
    return {};
}

core::Status Viewer::openWorld(const ViewerOptions& options) {
    // The world: as given, else the last session's scene, else the project's character.
    std::vector<std::string> paths = options.models;
    const std::filesystem::path lastScene = lastScenePath();
    bool restored = false;
    if (paths.empty() && options.restoreSession && !lastScene.empty() &&
        std::filesystem::exists(lastScene)) {
        auto world = asset::loadScene(lastScene);
        if (world && !world->characters.empty()) {
            mWorld = std::move(*world);
            restored = true;
            std::printf("glass-viewer: restored the last scene (%zu characters)\n",
                        mWorld.characters.size());
        } else {
            std::fprintf(stderr, "glass-viewer: last scene not restored: %s\n",
                         world ? "no characters" : world.error().message.c_str());
        }
    }
    if (!restored) {
        if (paths.empty())
            paths.push_back((assetsDir() / "models" / "glass_figure.glb").string());
        auto world = render::loadWorld(paths);
        if (!world)
            return world.error();
        mWorld = std::move(*world);
        if (paths.size() == 1 && asset::isSceneFile(paths[0]))
            mScenePath = paths[0];
    }
    return {};
}

core::Status Viewer::applyStartSettings(const ViewerOptions& options) {
    worldChanged();
    mSelected = mWorld.characters.empty() ? -1 : 0;
    const glm::ivec2 size = mContext->framebufferSize();
    mViewport = {size.x - Panel::width(size.x), size.y};
    mCamera.frame(mBounds, viewportAspect());

    mSettings = settingsForScene();
    worldChanged(); // the clip, loop and ground settings follow the world
    // Start on the first project HDR (the default environment), or the sky.
    mSettings.setNumber("environment", mEnvironments.size() > 1 ? 1.0 : 0.0);
    // On a CPU rasteriser, half resolution keeps the glass interactive.
    if (std::string(gl::rendererString()).find("llvmpipe") != std::string::npos)
        mSettings.setNumber("render-scale", 0.5);
    mSettings.setNumber("split-method", 0.0);

    Orbit orbit = mCamera.orbitState();
    const std::filesystem::path session = lastSessionPath();
    if (options.restoreSession && !session.empty() && std::filesystem::exists(session)) {
        auto preset = readPreset(session);
        auto applied = preset ? applyPreset(*preset, scopes(), orbit, session.string())
                              : core::Status(preset.error());
        if (!applied)
            std::fprintf(stderr, "glass-viewer: last session not restored: %s\n",
                         applied.error().message.c_str());
    }
    if (mWorld.camera) { // a scene's own camera, over the last session's
        mCamera.look(*mWorld.camera);
        orbit = mCamera.orbitState();
        mViewThrough = mWorld.camera->through;
    }
    if (options.environments.empty()) {
        useWorldEnvironment();
    } else {
        const auto it = std::find_if(
            mEnvironments.begin(), mEnvironments.end(),
            [&](const EnvironmentEntry& e) { return e.path == options.environments.front(); });
        mSettings.setNumber("environment", double(it - mEnvironments.begin()));
    }
    if (options.preset) {
        auto preset = readPreset(*options.preset);
        if (!preset)
            return preset.error();
        auto applied = applyPreset(*preset, scopes(), orbit, *options.preset);
        if (!applied)
            return applied.error();
    }
    for (const std::string& assignment : options.assignments)
        if (auto set = setAssignment(scopes(), assignment); !set)
            return set.error();
    mCamera.setOrbit(orbit);
    if (auto env = applyEnvironment(); !env)
        return env.error();
    for (const std::string& path : options.add)
        if (!addCharacter(path))
            return core::Error{mMessage};
    return {};
}

Viewer::~Viewer() {
    mRenderer.reset(); // GL objects go while the context lives
    if (ImGui::GetCurrentContext()) {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
}

void Viewer::reportStatus(const core::Status& status, const std::string& success) {
    mMessage = status ? success : status.error().message;
    mMessageIsError = !status;
    if (!status)
        std::fprintf(stderr, "glass-viewer: %s\n", mMessage.c_str());
}

core::Status Viewer::applyEnvironment() {
    const int wanted = int(mSettings.number("environment"));
    if (wanted == mEnvironmentShown)
        return {};
    const EnvironmentEntry& entry = mEnvironments[std::size_t(wanted)];
    asset::HdrImage image = render::Environment::proceduralSky();
    if (!entry.path.empty()) {
        auto hdr = asset::loadHdr(entry.path);
        if (!hdr)
            return hdr.error();
        image = std::move(*hdr);
    }
    if (auto set = mRenderer->setEnvironment(image); !set)
        return set;
    mEnvironmentShown = wanted;
    return {};
}

std::vector<Scope> Viewer::scopes() {
    std::vector<Scope> all{{"viewer", &mSettings},
                           {mRefraction->name(), &mRefraction->parameters()}};
    for (const auto& loaded : mPlugins)
        all.push_back({loaded->name(), &loaded->parameters()});
    return all;
}

plugin::Plugin* Viewer::methodPlugin() const {
    return mRefraction.get();
}

plugin::ParameterSet Viewer::settingsForScene() const {
    std::vector<std::string> environments;
    for (const EnvironmentEntry& e : mEnvironments)
        environments.push_back(e.name);
    const bool any = mSelected >= 0 && std::size_t(mSelected) < mWorld.characters.size();
    return viewerParameters(any ? clipNames(*mWorld.characters[std::size_t(mSelected)].model)
                                : std::vector<std::string>{},
                            environments, methodPlugin()->parameters().find("method")->choices);
}

void Viewer::handleInput() {
    handleKeys();
    handleMouse();
}

void Viewer::handleKeys() {
    const ImGuiIO& io = ImGui::GetIO();
    plugin::ParameterSet& glass = methodPlugin()->parameters();
    const std::size_t methods = glass.find("method")->choices.size();
    for (const KeyEvent& key : std::exchange(mEvents.keys, {})) {
        if (io.WantCaptureKeyboard)
            continue;
        auto toggle = [&](const char* name) { mSettings.setNumber(name, !mSettings.flag(name)); };
        if (key.key == GLFW_KEY_RIGHT || key.key == GLFW_KEY_LEFT) {
            mSettings.setNumber("playing", 0.0);
            advance(key.key == GLFW_KEY_RIGHT ? kFixedStep : -kFixedStep);
        }
        if (key.repeat)
            continue;
        if (key.key >= GLFW_KEY_1 && key.key < GLFW_KEY_1 + int(std::min<std::size_t>(methods, 9)))
            glass.setNumber("method", double(key.key - GLFW_KEY_1));
        switch (key.key) {
        case GLFW_KEY_SPACE:
            toggle("playing");
            break;
        case GLFW_KEY_M:
            glass.setNumber("method", double((std::size_t(glass.number("method")) + 1) % methods));
            break;
        case GLFW_KEY_C: // the next clip, faded to over the crossfade setting
            if (const plugin::Parameter* clip = mSettings.find("clip"))
                mSettings.setNumber("clip", double((std::size_t(mSettings.number("clip")) + 1) %
                                                   clip->choices.size()));
            break;
        case GLFW_KEY_F:
            frameCharacters(key.mods & GLFW_MOD_SHIFT);
            break;
        case GLFW_KEY_DELETE:
            if (mSelected >= 0)
                removeCharacter(std::size_t(mSelected));
            break;
        case GLFW_KEY_R:
            viewThrough(std::nullopt); // a camera cut
            mCamera.reset();
            break;
        case GLFW_KEY_T:
            toggle("temporal");
            break;
        case GLFW_KEY_G:
            toggle("ground");
            break;
        case GLFW_KEY_B:
            toggle("split");
            break;
        case GLFW_KEY_TAB:
            mShowPanel = !mShowPanel;
            break;
        case GLFW_KEY_F12:
        case GLFW_KEY_P:
            mPendingScreenshot = nextScreenshotPath();
            mPendingScreenshotSize.reset();
            mPendingScreenshotPanel = false;
            break;
        case GLFW_KEY_ESCAPE:
            mQuit = true;
            break;
        case GLFW_KEY_Q:
            if (key.mods & GLFW_MOD_CONTROL)
                mQuit = true;
            break;
        default:
            break;
        }
    }
}

void Viewer::handleMouse() {
    const ImGuiIO& io = ImGui::GetIO();
    const float viewportWidth = float(std::max(mViewport.x, 1));
    const float dividerX = float(mSettings.number("split-position")) * viewportWidth;
    if (mDraggingDivider) {
        mSettings.setNumber("split-position", io.MousePos.x / viewportWidth);
        if (!ImGui::IsMouseDown(0))
            mDraggingDivider = false;
        return;
    }
    if (io.WantCaptureMouse || io.MousePos.x >= viewportWidth)
        return;
    if (mSettings.flag("split") && ImGui::IsMouseClicked(0) &&
        std::abs(io.MousePos.x - dividerX) < 6.0f) {
        mDraggingDivider = true;
        return;
    }
    // Ctrl+drag moves the selected character over the ground, Ctrl+Shift+drag up and down.
    if (mSelected >= 0 && io.KeyCtrl && ImGui::IsMouseDown(0)) {
        const glm::vec2 to{io.MousePos.x, io.MousePos.y}, by{io.MouseDelta.x, io.MouseDelta.y};
        if (by != glm::vec2(0.0f) && !ImGui::IsMouseClicked(0))
            mMoving = moveSelected(to - by, to, io.KeyShift) || mMoving;
        return;
    }
    if (mMoving && !ImGui::IsMouseDown(0)) {
        mMoving = false;
        worldChanged(); // the bounds and the ground follow
    }
    // A click (no drag) picks the character under the cursor.
    if (ImGui::IsMouseReleased(0) && !io.KeyShift && io.MouseDragMaxDistanceSqr[0] < 9.0f) {
        if (const int picked = pick({io.MousePos.x, io.MousePos.y}); picked >= 0)
            select(picked);
    }
    // The motion of the frame a button goes down came before the press: no drag yet.
    const bool pressed =
        ImGui::IsMouseClicked(0) || ImGui::IsMouseClicked(1) || ImGui::IsMouseClicked(2);
    const glm::vec2 delta = pressed ? glm::vec2(0.0f) : glm::vec2(io.MouseDelta.x, io.MouseDelta.y);
    const bool panning =
        ImGui::IsMouseDown(1) || ImGui::IsMouseDown(2) || (ImGui::IsMouseDown(0) && io.KeyShift);
    const bool moving =
        ((panning || ImGui::IsMouseDown(0)) && delta != glm::vec2(0.0f)) || io.MouseWheel != 0.0f;
    if (mViewThrough && moving)
        viewThrough(std::nullopt); // the orbit takes over where the file's camera stands
    if (panning)
        mCamera.pan(delta, io.DisplaySize.y);
    else if (ImGui::IsMouseDown(0))
        mCamera.orbit(delta, io.DisplaySize.y);
    if (io.MouseWheel != 0.0f)
        mCamera.zoom(io.MouseWheel);
}

void Viewer::changeClip(scene::Character& c, int clip) {
    scene::Performance& p = c.performance;
    const double fade = mSettings.number("crossfade");
    const double now = p.characterTime(mTime);
    if (fade <= 0.0 || p.pausedAt) { // a snap: the clip alone, on the first layer's clock
        p.transitions.clear();
        p.layers.front().clip = clip;
        return;
    }
    // A crossfade from what plays now; what was scheduled after now is replaced.
    std::erase_if(p.transitions, [&](const scene::Transition& t) { return t.at >= now; });
    p.transitions.push_back({now, clip, fade});
}

void Viewer::advance(double dt) {
    // The scene clock wraps at the longest clip, each character looping or holding its own,
    // unless a pose never comes back (a crossfade, a walker walking on): then it runs on.
    const double longest = mWorld.longestPeriod();
    mTime += dt;
    if (longest <= 0.0) {
        mTime = 0.0;
        return;
    }
    if (!mWorld.repeats()) {
        mTime = std::max(mTime, 0.0);
        return;
    }
    mTime = std::fmod(mTime, longest);
    if (mTime < 0.0)
        mTime += longest;
}

render::RenderSettings Viewer::settings(glm::ivec2 size) const {
    render::RenderSettings s;
    s.size = size;
    s.exposure = float(mSettings.number("exposure"));
    s.environmentRotation = float(glm::radians(mSettings.number("env-rotation")));
    s.ground = mSettings.flag("ground");
    s.shadows = mSettings.flag("shadows");
    s.shadowMapView = render::RenderSettings::ShadowMapView(int(mSettings.number("shadow-map")));
    s.exactPassTimes = mSettings.flag("exact-timings");
    // The split draws two methods a frame: one history cannot serve both.
    s.temporal.enabled = mSettings.flag("temporal") && !mSettings.flag("split");
    s.temporal.historyWeight = float(mSettings.number("history-weight"));
    s.temporal.movingJitter = float(mSettings.number("moving-jitter"));
    s.temporal.convergeStill = mSettings.flag("converge-paused");
    s.temporal.view = render::TemporalSettings::View(int(mSettings.number("temporal-view")));
    return s;
}

core::Status Viewer::renderView(glm::ivec2 size) {
    if (auto env = applyEnvironment(); !env) {
        mMessage = env.error().message;
        mMessageIsError = true;
        mSettings.setNumber("environment", double(std::max(mEnvironmentShown, 0)));
    }
    render::Renderer& renderer = *mRenderer;
    if (const int level = int(mSettings.number("subdiv")); level != renderer.subdivisionLevel()) {
        if (auto refined = renderer.setSubdivisionLevel(level); !refined) {
            mMessage = refined.error().message;
            mMessageIsError = true;
            mSettings.setNumber("subdiv", double(renderer.subdivisionLevel()));
        }
    }
    // The clip and loop settings are the selected character's.
    if (mSelected >= 0) {
        scene::Character& c = mWorld.characters[std::size_t(mSelected)];
        if (c.performance.layers.empty())
            c.play(-1);
        if (const int clip = int(mSettings.number("clip"));
            !c.model->animations.empty() && clip != c.performance.finalClip())
            changeClip(c, clip);
        scene::Layer& first = c.performance.layers.front();
        if (mSettings.flag("loop") != (first.loop != scene::Loop::Clamp)) {
            first.loop = mSettings.flag("loop") ? scene::Loop::Repeat : scene::Loop::Clamp;
            first.repetitions = 0;
        }
    }
    boundsChanged();
    const render::Camera camera = viewCamera(float(size.x) / float(size.y));
    // Rendered at render-scale of the view and scaled up when shown.
    const double scale = mSettings.number("render-scale");
    const glm::ivec2 internal = glm::max(glm::ivec2(glm::round(glm::dvec2(size) * scale)), 1);
    auto stats = renderer.render(mWorld, camera, settings(internal), mTime);
    if (!stats)
        return stats.error();
    mStats = std::move(*stats);
    const bool split = mSettings.flag("split");
    const double at = split ? mSettings.number("split-position") : 1.0;
    const int divider = int(std::lround(at * size.x));
    const int dividerInternal = int(std::lround(at * internal.x));
    renderer.presentOutput({0, 0, dividerInternal, internal.y}, {0, 0, divider, size.y});
    if (split && divider < size.x) {
        plugin::ParameterSet& glass = methodPlugin()->parameters();
        const double methodA = glass.number("method");
        glass.setNumber("method", mSettings.number("split-method"));
        auto right = renderer.render(mWorld, camera, settings(internal), mTime);
        glass.setNumber("method", methodA);
        if (!right)
            return right.error();
        renderer.presentOutput({dividerInternal, 0, internal.x - dividerInternal, internal.y},
                               {divider, 0, size.x - divider, size.y});
    }
    return {};
}

core::Status Viewer::screenshot(const std::filesystem::path& path, std::optional<glm::ivec2> size,
                                bool withPanel) {
    capture::Image image;
    if (size) {
        // Offscreen at the chosen resolution: the left (A) method, no panel.
        auto stats = mRenderer->render(mWorld, viewCamera(float(size->x) / float(size->y)),
                                       settings(*size), mTime);
        if (!stats)
            return stats.error();
        image = {size->x, size->y, mRenderer->readOutput()};
    } else {
        // The view (left of the panel) or the whole window with the panel.
        const glm::ivec2 window = withPanel ? mContext->framebufferSize() : mViewport;
        image = {window.x, window.y, gl::Framebuffer::readDefault(window)};
        for (std::size_t i = 3; i < image.rgba.size(); i += 4)
            image.rgba[i] = 255; // the window's alpha is not part of the picture
    }
    if (auto written = capture::writePng(path, image); !written)
        return written;
    mMessage = "screenshot " + path.string();
    mMessageIsError = false;
    std::printf("glass-viewer: wrote %s (%dx%d) at scene time %.6f s\n", path.string().c_str(),
                image.width, image.height, mTime);
    std::fflush(stdout);
    return {};
}

std::filesystem::path Viewer::nextScreenshotPath() const {
    for (int n = 1;; ++n) {
        char name[64];
        std::snprintf(name, sizeof name, "glass-viewer-%04d.png", n);
        std::filesystem::path path = mOptions.screenshotDir / name;
        if (!std::filesystem::exists(path))
            return path;
    }
}

void Viewer::saveSession() {
    const std::filesystem::path path = lastSessionPath();
    if (path.empty())
        return;
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
    if (auto written = writePreset(path, presetJson(scopes(), mCamera.orbitState())); !written)
        std::fprintf(stderr, "glass-viewer: session not saved: %s\n",
                     written.error().message.c_str());
    if (!saveWorld(lastScenePath().string()))
        std::fprintf(stderr, "glass-viewer: scene not saved\n");
}

void Viewer::handleDrops() {
    // A dropped model joins the scene; a scene file, or Shift (or the panel's choice), replaces
    // it.
    const bool replace =
        mDropReplaces || glfwGetKey(static_cast<GLFWwindow*>(mContext->nativeWindow()),
                                    GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
    const std::vector<std::string> dropped = std::exchange(mEvents.dropped, {});
    if (!dropped.empty() && (replace || (dropped.size() == 1 && asset::isSceneFile(dropped[0]))))
        openWorld(dropped);
    else
        for (const std::string& path : dropped)
            addCharacter(path);
}

bool Viewer::takeScreenshot(glm::ivec2 window) {
    const auto path = *std::exchange(mPendingScreenshot, std::nullopt);
    const core::Status shot = screenshot(path, mPendingScreenshotSize, mPendingScreenshotPanel);
    if (!shot) {
        mMessage = shot.error().message;
        mMessageIsError = true;
        std::fprintf(stderr, "glass-viewer: %s\n", mMessage.c_str());
    }
    gl::Framebuffer::bindDefault(window);
    return bool(shot);
}

int Viewer::run() {
    int status = 0;
    int frame = 0;
    std::vector<double> frameTimes; // wall-clock ms per frame, for the exit summary
    auto last = std::chrono::steady_clock::now();
    while (!mQuit && !mContext->shouldClose()) {
        mContext->pollEvents();
        handleDrops();
        const auto now = std::chrono::steady_clock::now();
        const double wallMs = std::chrono::duration<double, std::milli>(now - last).count();
        last = now;
        mFrameMs = frame == 0 ? wallMs : 0.9 * mFrameMs + 0.1 * wallMs;
        if (frame > 0)
            frameTimes.push_back(wallMs);
        const bool scripted = mOptions.frames && frame < *mOptions.frames;
        const double dt = scripted ? kFixedStep : std::min(wallMs * 1e-3, 0.25);

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        handleInput();
        if (mSettings.flag("playing"))
            advance(dt * mSettings.number("speed"));
        if (scripted && frame + 1 == *mOptions.frames && mOptions.screenshot) {
            mPendingScreenshot = *mOptions.screenshot;
            mPendingScreenshotSize = mOptions.screenshotSize;
            mPendingScreenshotPanel = mOptions.screenshotPanel;
        }

        const glm::ivec2 size = mContext->framebufferSize();
        mViewport = {size.x - (mShowPanel ? Panel::width(size.x) : 0), size.y};
        gl::Framebuffer::bindDefault(size);
        gl::clearColor(0, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        if (mViewport.x > 0 && mViewport.y > 0) {
            if (auto drawn = renderView(mViewport); !drawn) {
                mMessage = drawn.error().message;
                mMessageIsError = true;
                std::fprintf(stderr, "glass-viewer: %s\n", mMessage.c_str());
                if (scripted)
                    return 1;
            }
        }
        gl::Framebuffer::bindDefault(size);
        if (mShowPanel) {
            Panel::draw(*this);
            drawSelection();
            if (mSettings.flag("skeleton"))
                drawSkeleton();
        }
        uimap::publish(mOptions.uiMap);
        ImGui::Render();
        // The view's screenshot before the panel is drawn over it, the window's after.
        if (mPendingScreenshot && !mPendingScreenshotPanel && !takeScreenshot(size) && scripted)
            status = 1;
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (mPendingScreenshot && !takeScreenshot(size) && scripted)
            status = 1;
        mContext->swapBuffers();
        gl::checkErrors("glass-viewer frame");
        ++frame;
        if (mOptions.frames && frame == *mOptions.frames && mOptions.exitAfterFrames)
            break;
    }
    if (!mOptions.exitAfterFrames)
        saveSession();
    const std::uint64_t errors = gl::errorCount();
    std::sort(frameTimes.begin(), frameTimes.end());
    const double median = frameTimes.empty() ? 0.0 : frameTimes[frameTimes.size() / 2];
    std::printf("glass-viewer: %d frames, median frame %.1f ms (%dx%d window), %llu GL errors\n",
                frame, median, mContext->framebufferSize().x, mContext->framebufferSize().y,
                static_cast<unsigned long long>(errors));
    return errors > 0 ? 1 : status;
}

} // namespace viewer
