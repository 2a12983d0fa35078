// glass-viewer's panel.
#include "Panel.h"

#include "Viewer.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace viewer {
namespace {

/** A collapsible section; false when it is closed (draw nothing of it). */
bool section(const char* title, bool open = true) {
    return ImGui::CollapsingHeader(title, open ? ImGuiTreeNodeFlags_DefaultOpen : 0);
}

void widget(plugin::ParameterSet& set, const char* name) {
    if (const plugin::Parameter* p = set.find(name))
        parameterWidget(set, *p);
}

/** The set's presets (plugin data, e.g. the refraction plugin's materials) as one combo. */
void presetCombo(plugin::ParameterSet& set) {
    if (set.presets().empty() || !ImGui::BeginCombo("Preset", "sets several values"))
        return;
    for (const plugin::ParameterPreset& preset : set.presets()) {
        std::string values;
        for (const auto& [name, value] : preset.values)
            values += (values.empty() ? "" : ", ") + name + ' ' + value;
        if (ImGui::Selectable(preset.name.c_str()))
            (void)set.applyPreset(preset.name); // listed from presets(): always found
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("%s", values.c_str());
    }
    ImGui::EndCombo();
}

} // namespace

bool parameterWidget(plugin::ParameterSet& set, const plugin::Parameter& p) {
    using Type = plugin::Parameter::Type;
    bool changed = false;
    const char* label = p.label.empty() ? p.name.c_str() : p.label.c_str();
    ImGui::PushID(p.name.c_str());
    switch (p.type) {
    case Type::Float: {
        float value = float(set.number(p.name));
        const bool wide = p.min >= 0.0 && p.max > 100.0 * std::max(p.min, 1.0);
        changed = ImGui::SliderFloat(label, &value, float(p.min), float(p.max), "%.3f",
                                     wide ? ImGuiSliderFlags_Logarithmic : 0);
        if (changed)
            set.setNumber(p.name, double(value));
        break;
    }
    case Type::Int: {
        int value = int(set.number(p.name));
        changed = ImGui::SliderInt(label, &value, int(p.min), int(p.max));
        if (changed)
            set.setNumber(p.name, double(value));
        break;
    }
    case Type::Bool: {
        bool value = set.flag(p.name);
        changed = ImGui::Checkbox(label, &value);
        if (changed)
            set.setNumber(p.name, value ? 1.0 : 0.0);
        break;
    }
    case Type::Enum: {
        int index = int(set.number(p.name));
        if (ImGui::BeginCombo(label, p.choices[std::size_t(index)].c_str())) {
            for (std::size_t i = 0; i < p.choices.size(); ++i)
                if (ImGui::Selectable(p.choices[i].c_str(), int(i) == index)) {
                    set.setNumber(p.name, double(i));
                    changed = true;
                }
            ImGui::EndCombo();
        }
        break;
    }
    case Type::Color: {
        const auto c = set.color(p.name);
        float rgb[3] = {float(c[0]), float(c[1]), float(c[2])};
        changed = ImGui::ColorEdit3(label, rgb);
        if (changed) {
            char text[96];
            std::snprintf(text, sizeof text, "%g,%g,%g", double(rgb[0]), double(rgb[1]),
                          double(rgb[2]));
            (void)set.set(p.name, text);
        }
        break;
    }
    }
    if (!p.help.empty() && ImGui::IsItemHovered())
        ImGui::SetTooltip("%s", p.help.c_str());
    ImGui::PopID();
    return changed;
}

void Panel::model(Viewer& v) {
    if (!section("Model"))
        return;
    static std::string path;
    ImGui::TextWrapped("%s", v.mScene.path.c_str());
    std::size_t triangles = 0, vertices = 0;
    for (const auto& mesh : v.mScene.model->meshes)
        for (const auto& primitive : mesh.primitives) {
            triangles += primitive.indices.size() / 3;
            vertices += primitive.positions.size();
        }
    std::size_t joints = 0;
    for (const auto& skin : v.mScene.model->skins)
        joints += skin.joints.size();
    ImGui::Text("%zu vertices, %zu triangles, %zu joints", vertices, triangles, joints);
    ImGui::SetNextItemWidth(-70.0f);
    const bool entered = ImGui::InputTextWithHint("##open", ".gltf or .glb (or drop a file)", &path,
                                                  ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::SameLine();
    if ((ImGui::Button("Open") || entered) && !path.empty())
        v.openModel(path);
}

void Panel::animation(Viewer& v) {
    if (!section("Animation"))
        return;
    plugin::ParameterSet& s = v.mSettings;
    const auto& clips = v.mScene.model->animations;
    if (clips.empty()) {
        ImGui::TextDisabled("no clips: the rest pose");
        return;
    }
    if (parameterWidget(s, *s.find("clip")))
        v.mTime = 0.0;
    const double duration = clips[std::size_t(s.number("clip"))].duration;
    if (ImGui::Button(s.flag("playing") ? "Pause" : "Play"))
        s.setNumber("playing", !s.flag("playing"));
    ImGui::SameLine();
    if (ImGui::ArrowButton("##back", ImGuiDir_Left)) {
        s.setNumber("playing", 0.0);
        v.advance(-1.0 / 30.0);
    }
    ImGui::SameLine();
    if (ImGui::ArrowButton("##forward", ImGuiDir_Right)) {
        s.setNumber("playing", 0.0);
        v.advance(1.0 / 30.0);
    }
    ImGui::SameLine();
    widget(s, "loop");
    float time = float(v.mTime);
    if (ImGui::SliderFloat("Time (s)", &time, 0.0f, float(duration), "%.3f"))
        v.mTime = double(time);
    widget(s, "speed");
}

void Panel::camera(Viewer& v) {
    if (!section("Camera"))
        return;
    if (ImGui::Button("Frame (F)"))
        v.mCamera.frame(v.mScene.bounds, v.viewportAspect());
    ImGui::SameLine();
    if (ImGui::Button("Reset (R)"))
        v.mCamera.reset();
    ImGui::TextDisabled("drag: orbit; right/shift-drag: pan; wheel: zoom");
}

void Panel::environment(Viewer& v) {
    if (!section("Environment"))
        return;
    for (const char* name : {"environment", "env-rotation", "exposure", "ground"})
        widget(v.mSettings, name);
}

void Panel::plugins(Viewer& v) {
    for (const Scope& scope : v.scopes()) {
        if (scope.name == "viewer")
            continue;
        if (!section(("Plugin: " + scope.name).c_str()))
            continue;
        ImGui::PushID(scope.name.c_str());
        presetCombo(*scope.parameters);
        for (const plugin::Parameter& p : scope.parameters->declarations())
            parameterWidget(*scope.parameters, p);
        plugin::Plugin* owner =
            scope.parameters == &v.mRefraction->parameters() ? v.mRefraction.get() : nullptr;
        for (const auto& loaded : v.mPlugins)
            if (scope.parameters == &loaded->parameters())
                owner = loaded.get();
        if (owner)
            owner->drawPanel(ImGui::GetCurrentContext());
        ImGui::PopID();
    }
}

void Panel::split(Viewer& v) {
    if (!section("A/B split"))
        return;
    for (const char* name : {"split", "split-method", "split-position"})
        widget(v.mSettings, name);
    if (v.mSettings.flag("split")) {
        const ImVec2 display = ImGui::GetIO().DisplaySize;
        const float x = float(v.mSettings.number("split-position")) * float(v.mViewport.x);
        ImDrawList* draw = ImGui::GetBackgroundDrawList();
        draw->AddLine(ImVec2(x, 0.0f), ImVec2(x, display.y), IM_COL32(255, 255, 255, 200), 2.0f);
        const std::string left = v.methodPlugin()->parameters().text("method");
        const std::string right = v.mSettings.text("split-method");
        draw->AddText(ImVec2(x - 8.0f - ImGui::CalcTextSize(left.c_str()).x, 8.0f),
                      IM_COL32(255, 255, 255, 230), left.c_str());
        draw->AddText(ImVec2(x + 8.0f, 8.0f), IM_COL32(255, 255, 255, 230), right.c_str());
    }
}

void Panel::timings(Viewer& v) {
    if (!section("Timings"))
        return;
    ImGui::Text("frame %.2f ms (%.0f fps)", v.mFrameMs,
                v.mFrameMs > 0.0 ? 1000.0 / v.mFrameMs : 0.0);
    ImGui::Text("GPU %.2f ms, CPU %.2f ms (left view)", v.mStats.gpuMs, v.mStats.cpuMs);
    if (ImGui::BeginTable("passes", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
        ImGui::TableSetupColumn("pass");
        ImGui::TableSetupColumn("GPU ms");
        ImGui::TableSetupColumn("CPU ms");
        ImGui::TableHeadersRow();
        for (const auto& pass : v.mStats.passes) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(pass.name.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%.2f", pass.gpuMs);
            ImGui::TableNextColumn();
            ImGui::Text("%.2f", pass.cpuMs);
        }
        ImGui::EndTable();
    }
    widget(v.mSettings, "exact-timings");
    widget(v.mSettings, "render-scale");
}

void Panel::presets(Viewer& v) {
    if (!section("Presets", false))
        return;
    static std::string path = "glass-preset.json";
    ImGui::SetNextItemWidth(-110.0f);
    ImGui::InputText("##preset", &path);
    ImGui::SameLine();
    if (ImGui::Button("Save")) {
        auto written = writePreset(path, presetJson(v.scopes(), v.mCamera.orbitState()));
        v.mMessage = written ? "saved " + path : written.error().message;
        v.mMessageIsError = !written;
    }
    ImGui::SameLine();
    if (ImGui::Button("Load")) {
        Orbit orbit = v.mCamera.orbitState();
        auto preset = readPreset(path);
        auto applied =
            preset ? applyPreset(*preset, v.scopes(), orbit, path) : core::Status(preset.error());
        if (applied)
            v.mCamera.setOrbit(orbit);
        v.mMessage = applied ? "loaded " + path : applied.error().message;
        v.mMessageIsError = !applied;
    }
}

void Panel::screenshot(Viewer& v) {
    if (!section("Screenshot", false))
        return;
    static int size[2] = {0, 0};
    static bool withPanel = false;
    ImGui::InputInt2("Size (0: window)", size);
    ImGui::Checkbox("Include panel (window size)", &withPanel);
    if (ImGui::Button("Save screenshot (F12)")) {
        v.mPendingScreenshot = v.nextScreenshotPath();
        v.mPendingScreenshotSize.reset();
        if (size[0] > 0 && size[1] > 0)
            v.mPendingScreenshotSize = glm::ivec2(std::min(size[0], 8192), std::min(size[1], 8192));
        v.mPendingScreenshotPanel = withPanel && !v.mPendingScreenshotSize;
    }
}

int Panel::width(int windowWidth) {
    return std::min(380, windowWidth * 45 / 100);
}

void Panel::draw(Viewer& v) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float width = float(Panel::width(int(display.x)));
    ImGui::SetNextWindowPos(ImVec2(display.x - width, 0.0f), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(width, display.y), ImGuiCond_Always);
    ImGui::Begin("glass", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::PushItemWidth(-130.0f);
    if (!v.mMessage.empty())
        ImGui::TextColored(v.mMessageIsError ? ImVec4(1.0f, 0.4f, 0.35f, 1.0f)
                                             : ImVec4(0.6f, 0.9f, 0.6f, 1.0f),
                           "%s", v.mMessage.c_str());
    model(v);
    animation(v);
    camera(v);
    environment(v);
    plugins(v);
    split(v);
    timings(v);
    presets(v);
    screenshot(v);
    ImGui::TextDisabled("Space play, arrows step, M/1-4 method, B split, G ground,\n"
                        "Tab panel, F12 screenshot, Esc quit");
    ImGui::PopItemWidth();
    ImGui::End();
}

} // namespace viewer
