// glass-viewer: plays a world of glTF characters with glass in a window; the scene and every
// parameter live in a panel.
#include "../common/ToolMain.h"
#include "Viewer.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace {

const char* const kUsage =
    R"(usage: glass-viewer [MODEL|SCENE [MODEL...]] [--add PATH]... [--env HDR]... [--preset FILE]
                    [--plugin PATH]... [--set KEY=VALUE]... [--size WxH] [--no-restore]
                    [--frames N [--screenshot PATH [--screenshot-size WxH] [--screenshot-panel]
                    [--force]] [--exit]] [--screenshot-dir DIR]

Plays a world of characters with glass in a window, with a panel over the scene and every
parameter: a scene file (.json, README "Scene files"), or models (.gltf, .glb, builtin:sphere)
placed side by side; default: the last session's scene, else the project's generated
character. The scene panel lists the characters (click one in the view to select it): add one
by path, remove, move, rotate, scale, clip, speed, phase, glass mode and overrides, save and
open scene files. A file dropped on the window joins the scene (a scene file, or Shift held,
replaces it).

  --add PATH          add a model (or a scene file's characters) after the scene opens, as the
                      panel's Add button does
  --env HDR           add an equirectangular HDR to the environments (and start on it); the
                      project's assets/env/*.hdr and a procedural sky are always offered
  --preset FILE       apply a preset saved from the panel (JSON)
  --plugin PATH       load a plugin module; its parameters join the panel
  --set KEY=VALUE     set any panel parameter, e.g. --set method=isr --set ior=1.33
                      --set exposure=1.5 --set split=on; SCOPE.KEY (viewer.*, refraction.*,
                      <plugin>.*) when a name is ambiguous. Applied after --preset.
  --size WxH          window size (default 1280x720)
  --no-restore        do not restore the last session's settings and scene (saved at exit
                      to $XDG_CONFIG_HOME/glass-viewer/last-session.json and last-scene.json)
  --screenshot-dir D  where F12 screenshots go (default: the current folder)
Scripted mode (tests, demos):
  --frames N          advance N frames of 1/30 s each (then continue interactively)
  --screenshot PATH   after the N frames, write the view to PATH (PNG, atomic)
  --screenshot-size WxH  render that screenshot offscreen at WxH instead of the window size
  --screenshot-panel  include the panel in the screenshot
  --force             overwrite an existing screenshot file
  --exit              quit after the N frames (the session is then not saved)

Mouse: drag to orbit, right- or shift-drag to pan, wheel to zoom, drag the A/B divider; click a
       character to select it, Ctrl+drag to move it over the ground (Ctrl+Shift+drag: up and
       down).
Keys: Space play/pause, Left/Right step one frame, M next method, 1-4 method,
      F frame all (Shift+F the selection), R reset the camera, Del remove the selected
      character, G ground, B A/B split, T temporal accumulation, Tab panel,
      F12 or P screenshot, Esc or Ctrl+Q quit.

Exit status: 0 success; 1 a load error, a failed screenshot or any GL error; 2 bad arguments.
)";

int usageError(const std::string& message) {
    std::fprintf(stderr, "glass-viewer: %s\n\n%s", message.c_str(), kUsage);
    return 2;
}

std::optional<glm::ivec2> parseSize(const std::string& text) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 16 ||
        h < 16 || w > 8192 || h > 8192)
        return std::nullopt;
    return glm::ivec2(w, h);
}

std::optional<int> parse(int argc, char** argv, viewer::ViewerOptions& o) {
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto next = [&]() -> std::optional<std::string> {
            if (i + 1 >= argc)
                return std::nullopt;
            return std::string(argv[++i]);
        };
        if (arg == "--help" || arg == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (arg == "--exit") {
            o.exitAfterFrames = true;
        } else if (arg == "--no-restore") {
            o.restoreSession = false;
        } else if (arg == "--screenshot-panel") {
            o.screenshotPanel = true;
        } else if (arg == "--force") {
            o.force = true;
        } else if (arg == "--env" || arg == "--preset" || arg == "--plugin" || arg == "--set" ||
                   arg == "--screenshot" || arg == "--screenshot-dir" || arg == "--add") {
            const auto v = next();
            if (!v)
                return usageError(arg + " needs a value");
            if (arg == "--env")
                o.environments.push_back(*v);
            else if (arg == "--preset")
                o.preset = *v;
            else if (arg == "--plugin")
                o.plugins.push_back(*v);
            else if (arg == "--set")
                o.assignments.push_back(*v);
            else if (arg == "--add")
                o.add.push_back(*v);
            else if (arg == "--screenshot")
                o.screenshot = *v;
            else
                o.screenshotDir = *v;
        } else if (arg == "--size" || arg == "--screenshot-size") {
            const auto v = next();
            const auto size = v ? parseSize(*v) : std::nullopt;
            if (!size)
                return usageError(arg + " needs WxH, 16..8192 each");
            (arg == "--size" ? o.windowSize : o.screenshotSize.emplace()) = *size;
        } else if (arg == "--frames") {
            const auto v = next();
            char* end = nullptr;
            const long n = v ? std::strtol(v->c_str(), &end, 10) : 0;
            if (!v || *end != '\0' || n < 1 || n > 1000000)
                return usageError("--frames needs a count, 1..1000000");
            o.frames = int(n);
        } else if (!arg.empty() && arg[0] == '-') {
            return usageError("unknown option " + arg);
        } else {
            o.models.push_back(arg);
        }
    }
    if ((o.screenshot || o.exitAfterFrames) && !o.frames)
        return usageError("--screenshot and --exit need --frames N");
    if ((o.screenshotSize || o.screenshotPanel) && !o.screenshot)
        return usageError("--screenshot-size and --screenshot-panel need --screenshot");
    if (o.screenshotSize && o.screenshotPanel)
        return usageError("--screenshot-panel is for window-size screenshots");
    if (o.screenshot && std::filesystem::exists(*o.screenshot) && !o.force)
        return usageError(o.screenshot->string() + " exists (use --force to overwrite)");
    return std::nullopt;
}

} // namespace

int run(int argc, char** argv) {
    viewer::ViewerOptions options;
    if (const auto exit = parse(argc, argv, options))
        return *exit;
    auto viewer = viewer::Viewer::create(options);
    if (!viewer) {
        std::fprintf(stderr, "glass-viewer: %s\n", viewer.error().message.c_str());
        return 1;
    }
    return (*viewer)->run();
}

int main(int argc, char** argv) {
    return tool::guardedMain("glass-viewer", run, argc, argv);
}
