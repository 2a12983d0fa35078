// The panel's widget map for scripted input (--ui-map).
#include "UiMap.h"

#include <imgui.h>

#include <cstdio>
#include <fstream>
#include <system_error>

namespace viewer::uimap {
namespace {

std::string gFrame, gWritten; // this frame's lines; the file's

} // namespace

void mark(const std::string& name) {
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    char rect[96];
    std::snprintf(rect, sizeof rect, "\t%.0f %.0f %.0f %.0f\n", double(a.x), double(a.y),
                  double(b.x), double(b.y));
    gFrame += name + rect;
}

void publish(const std::filesystem::path& path) {
    if (!path.empty() && gFrame != gWritten) {
        std::filesystem::path partial = path;
        partial += ".partial";
        std::ofstream(partial, std::ios::binary) << gFrame;
        std::error_code ec;
        std::filesystem::rename(partial, path, ec);
        gWritten = gFrame;
    }
    gFrame.clear();
}

} // namespace viewer::uimap
