// Where the panel's named widgets are in the window: written each frame they move to the file
// of --ui-map, so that a script can drive the viewer with real input events (xdotool) by name
// rather than by pixel (tests/viewer/drive_blend.sh).
#pragma once

#include <filesystem>
#include <string>

namespace viewer::uimap {

/** Records the widget ImGui drew last under `name` (its rectangle in window pixels). */
void mark(const std::string& name);

/** Writes this frame's widgets to `path`, one "name<TAB>x0 y0 x1 y1" line each, when they
 *  differ from the last written (atomically: a reader sees one frame's map whole), and
 *  starts the next frame's. */
void publish(const std::filesystem::path& path);

} // namespace viewer::uimap
