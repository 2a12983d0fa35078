// glass-viewer: plays a world of glTF characters with glass in a window; the scene and every
// parameter live in a panel.
#include "../common/Cli.h"
#include "../common/ToolMain.h"
#include "Viewer.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace {

constexpr const char* kDescription =
    R"(glass-viewer [MODEL|SCENE [MODEL...]] [OPTIONS]: plays a world of characters with glass in a
window, with a panel over the scene and every parameter: a scene file (.json, README "Scene
files"), or models (.gltf, .glb, builtin:sphere) placed side by side; default: the last
session's scene, else the project's generated character. The scene panel lists the characters
(click one in the view to select it): add one by path, remove, move, rotate, scale, clip, speed,
phase, glass mode and overrides, save and open scene files. A file dropped on the window joins
the scene (a scene file, or Shift held, replaces it).)";

constexpr const char* kFooter =
    R"(Mouse: drag to orbit, right- or shift-drag to pan, wheel to zoom, drag the A/B divider; click a
       character to select it, Ctrl+drag to move it over the ground (Ctrl+Shift+drag: up and
       down).
Keys: Space play/pause, Left/Right step one frame, M next method, 1-6 method, C next clip,
      F frame all (Shift+F the selection), R reset the camera, Del remove the selected
      character, G ground, B A/B split, T temporal accumulation, Tab panel,
      F12 or P screenshot, Esc or Ctrl+Q quit.

Exit status: 0 success; 1 a load error, a failed screenshot or any GL error; 2 bad arguments.)";

void addOptions(CLI::App& app, viewer::ViewerOptions& o) {
    app.add_option("models", o.models, "a scene file, or glTF models placed side by side")
        ->type_name("MODEL|SCENE");
    app.add_option("--add", o.add,
                   "add a model (or a scene file's characters) after the scene opens, as the "
                   "panel's Add button does")
        ->type_name("PATH")
        ->allow_extra_args(false);
    app.add_option("--env", o.environments,
                   "add an equirectangular HDR to the environments (and start on it); the "
                   "project's assets/env/*.hdr and a procedural sky are always offered")
        ->type_name("HDR")
        ->allow_extra_args(false);
    app.add_option("--preset", o.preset, "apply a preset saved from the panel (JSON)")
        ->type_name("FILE");
    app.add_option("--plugin", o.plugins, "load a plugin module; its parameters join the panel")
        ->type_name("PATH")
        ->allow_extra_args(false);
    app.add_option("--set", o.assignments,
                   "set any panel parameter, e.g. --set method=isr --set ior=1.33 --set "
                   "exposure=1.5 --set split=on; SCOPE.KEY (viewer.*, refraction.*, <plugin>.*) "
                   "when a name is ambiguous. Applied after --preset.")
        ->type_name("KEY=VALUE")
        ->allow_extra_args(false);
    tool::addSize(app, "--size", o.windowSize, 16, 8192, "window size (default 1280x720)");
    app.add_flag_function(
        "--no-restore", [&o](std::int64_t) { o.restoreSession = false; },
        "do not restore the last session's settings and scene (saved at exit to "
        "$XDG_CONFIG_HOME/glass-viewer/last-session.json and last-scene.json)");
    app.add_option("--screenshot-dir", o.screenshotDir,
                   "where F12 screenshots go (default: the current folder)")
        ->type_name("DIR");
    app.add_option("--ui-map", o.uiMap,
                   "write where the panel's named widgets are to FILE whenever they move "
                   "(\"name<TAB>x0 y0 x1 y1\" lines, window pixels): for scripts that drive the "
                   "viewer with real input")
        ->type_name("FILE");
    const std::string scripted = "Scripted mode (tests, demos)";
    app.add_option("--frames", o.frames,
                   "advance N frames of 1/30 s each (then continue interactively)")
        ->check(tool::range(1, 1000000))
        ->type_name("N")
        ->group(scripted);
    app.add_option("--screenshot", o.screenshot,
                   "after the N frames, write the view to PATH (PNG, atomic)")
        ->type_name("PATH")
        ->group(scripted);
    tool::addSize(app, "--screenshot-size", o.screenshotSize.emplace(), 16, 8192,
                  "render that screenshot offscreen at WxH instead of the window size")
        ->group(scripted);
    app.add_flag("--screenshot-panel", o.screenshotPanel, "include the panel in the screenshot")
        ->group(scripted);
    app.add_flag("--force", o.force, "overwrite an existing screenshot file")->group(scripted);
    app.add_flag("--exit", o.exitAfterFrames,
                 "quit after the N frames (the session is then not saved)")
        ->group(scripted);
}

std::optional<int> parse(int argc, char** argv, viewer::ViewerOptions& o) {
    CLI::App app{"", "glass-viewer"};
    tool::configure(app, kDescription, kFooter);
    addOptions(app, o);
    if (const auto code = tool::parseArguments(app, argc, argv))
        return code;
    if (!app.count("--screenshot-size"))
        o.screenshotSize.reset();
    if ((o.screenshot || o.exitAfterFrames) && !o.frames)
        return tool::usageError(app, "--screenshot and --exit need --frames N");
    if ((o.screenshotSize || o.screenshotPanel) && !o.screenshot)
        return tool::usageError(app, "--screenshot-size and --screenshot-panel need --screenshot");
    if (o.screenshotSize && o.screenshotPanel)
        return tool::usageError(app, "--screenshot-panel is for window-size screenshots");
    if (o.screenshot && std::filesystem::exists(*o.screenshot) && !o.force)
        return tool::usageError(app, o.screenshot->string() + " exists (use --force to overwrite)");
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
