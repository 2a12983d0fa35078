// glass-viewer's panel.
#include "Panel.h"

#include "UiMap.h"
#include "Viewer.h"

#include "engine/core/Limits.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

namespace viewer {
namespace {

/** A collapsible section; false when it is closed (draw nothing of it). */
bool section(const char* title, bool open = true) {
    const bool shown = ImGui::CollapsingHeader(title, open ? ImGuiTreeNodeFlags_DefaultOpen : 0);
    uimap::mark(title);
    return shown;
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
        uimap::mark(label);
        if (changed)
            set.setNumber(p.name, double(value));
        break;
    }
    case Type::Int: {
        int value = int(set.number(p.name));
        changed = ImGui::SliderInt(label, &value, int(p.min), int(p.max));
        uimap::mark(label);
        if (changed)
            set.setNumber(p.name, double(value));
        break;
    }
    case Type::Bool: {
        bool value = set.flag(p.name);
        changed = ImGui::Checkbox(label, &value);
        uimap::mark(label);
        if (changed)
            set.setNumber(p.name, value ? 1.0 : 0.0);
        break;
    }
    case Type::Enum: {
        int index = int(set.number(p.name));
        const bool open = ImGui::BeginCombo(label, p.choices[std::size_t(index)].c_str());
        uimap::mark(label);
        if (open) {
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
        uimap::mark(label);
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

void Panel::scene(Viewer& v) {
    if (!section("Scene"))
        return;
    static std::string addPath, scenePath;
    if (scenePath.empty())
        scenePath = v.mScenePath;
    scene::World& world = v.mWorld;
    if (ImGui::BeginListBox(
            "##characters",
            ImVec2(-1.0f, ImGui::GetTextLineHeightWithSpacing() *
                                  float(std::min<std::size_t>(
                                      std::max<std::size_t>(world.characters.size(), 1), 6)) +
                              4.0f))) {
        for (std::size_t i = 0; i < world.characters.size(); ++i) {
            const scene::Character& c = world.characters[i];
            const std::string label = c.name + "  (" +
                                      std::filesystem::path(c.modelPath).filename().string() +
                                      ")##" + std::to_string(i);
            if (ImGui::Selectable(label.c_str(), int(i) == v.mSelected))
                v.select(int(i));
        }
        ImGui::EndListBox();
    }
    ImGui::SetNextItemWidth(-70.0f);
    const bool entered = ImGui::InputTextWithHint("##add", "model or scene path (or drop a file)",
                                                  &addPath, ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::SameLine();
    if ((ImGui::Button("Add") || entered) && !addPath.empty())
        v.addCharacter(addPath);
    if (ImGui::Button("Replace scene") && !addPath.empty())
        v.openWorld({addPath});
    ImGui::SameLine();
    ImGui::BeginDisabled(v.mSelected < 0);
    if (ImGui::Button("Remove (Del)"))
        v.removeCharacter(std::size_t(v.mSelected));
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::Checkbox("Drops replace", &v.mDropReplaces);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("a dropped model replaces the scene instead of joining it (or hold "
                          "Shift while dropping); a dropped scene file always replaces it");
    ImGui::SetNextItemWidth(-110.0f);
    ImGui::InputText("##scene", &scenePath);
    ImGui::SameLine();
    if (ImGui::Button("Save"))
        v.saveWorld(scenePath);
    ImGui::SameLine();
    if (ImGui::Button("Open"))
        v.openWorld({scenePath});
    if (v.mSelected >= 0)
        character(v, world.characters[std::size_t(v.mSelected)]);
}

void Panel::character(Viewer& v, scene::Character& c) {
    ImGui::Separator();
    std::size_t triangles = 0, vertices = 0, joints = 0;
    for (const auto& mesh : c.model->meshes)
        for (const auto& primitive : mesh.primitives) {
            triangles += primitive.indices.size() / 3;
            vertices += primitive.positions.size();
        }
    for (const auto& skin : c.model->skins)
        joints += skin.joints.size();
    ImGui::TextWrapped("%s", c.modelPath.c_str());
    ImGui::Text("%zu vertices, %zu triangles, %zu joints", vertices, triangles, joints);
    ImGui::InputText("Name", &c.name);
    glm::vec3 translation(c.placement.translation);
    if (ImGui::DragFloat3("Position", &translation.x, 0.01f))
        c.placement.translation = glm::dvec3(translation);
    // Rotation as yaw (about +y), pitch, roll in degrees.
    glm::vec3 angles = glm::degrees(glm::vec3(glm::eulerAngles(glm::quat(c.placement.rotation))));
    if (ImGui::DragFloat3("Rotation (deg)", &angles.x, 0.5f))
        c.placement.rotation = glm::dquat(glm::quat(glm::radians(angles)));
    float scale = float(c.placement.scale.x);
    if (ImGui::DragFloat("Scale", &scale, 0.01f, 0.01f, 100.0f, "%.3f",
                         ImGuiSliderFlags_Logarithmic))
        c.placement.scale = glm::dvec3(std::max(scale, 0.01f));
    if (c.model->animations.empty())
        ImGui::TextDisabled("no clips: the rest pose");
    else
        performance(v, c);
    morphWeights(c);
    if (!c.model->variants.empty()) { // KHR_materials_variants: the file's material sets
        const std::string current =
            c.variant >= 0 ? c.model->variants[std::size_t(c.variant)] : "as authored";
        if (ImGui::BeginCombo("Variant", current.c_str())) {
            if (ImGui::Selectable("as authored", c.variant < 0))
                c.variant = -1;
            for (std::size_t i = 0; i < c.model->variants.size(); ++i)
                if (ImGui::Selectable(c.model->variants[i].c_str(), c.variant == int(i)))
                    c.variant = int(i);
            ImGui::EndCombo();
        }
    }
    int mode = int(c.glass);
    if (ImGui::Combo("Glass", &mode, "as authored\0all glass\0no glass\0"))
        c.glass = scene::GlassMode(mode);
    auto overrideFloat = [](const char* label, std::optional<float>& value, float fallback,
                            float lo, float hi) {
        bool on = value.has_value();
        ImGui::PushID(label);
        if (ImGui::Checkbox("##on", &on))
            value = on ? std::optional<float>(fallback) : std::nullopt;
        ImGui::SameLine();
        ImGui::BeginDisabled(!on);
        float x = value.value_or(fallback);
        if (ImGui::SliderFloat(label, &x, lo, hi, "%.3f") && on)
            value = x;
        ImGui::EndDisabled();
        ImGui::PopID();
    };
    overrideFloat("IOR", c.overrides.ior, 1.5f, 1.0f, 3.0f);
    overrideFloat("Dispersion", c.overrides.dispersion, 0.3f, 0.0f, 2.0f);
    bool tinted = c.overrides.tint.has_value();
    if (ImGui::Checkbox("##tint", &tinted))
        c.overrides.tint = tinted ? std::optional<glm::vec3>(glm::vec3(1.0f)) : std::nullopt;
    ImGui::SameLine();
    ImGui::BeginDisabled(!tinted);
    glm::vec3 tint = c.overrides.tint.value_or(glm::vec3(1.0f));
    if (ImGui::ColorEdit3("Tint", &tint.x) && tinted)
        c.overrides.tint = tint;
    ImGui::EndDisabled();
}

namespace {

/** The clips' names for a combo (an unnamed one by its index). */
std::vector<std::string> clipNames(const scene::Model& model) {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < model.animations.size(); ++i)
        names.push_back(model.animations[i].name.empty() ? "clip " + std::to_string(i)
                                                         : model.animations[i].name);
    return names;
}

bool combo(const char* label, int& index, const std::vector<std::string>& names) {
    bool changed = false;
    const std::string shown =
        index >= 0 && index < int(names.size()) ? names[std::size_t(index)] : "-";
    if (ImGui::BeginCombo(label, shown.c_str())) {
        for (std::size_t i = 0; i < names.size(); ++i)
            if (ImGui::Selectable(names[i].c_str(), index == int(i))) {
                index = int(i);
                changed = true;
            }
        ImGui::EndCombo();
    }
    return changed;
}

} // namespace

void Panel::performance(Viewer& v, scene::Character& c) {
    plugin::ParameterSet& s = v.mSettings;
    scene::Performance& p = c.performance;
    if (p.layers.empty())
        c.play(-1);
    const std::vector<std::string> clips = clipNames(*c.model);
    widget(s, "clip");
    widget(s, "crossfade");
    widget(s, "loop");
    scene::Layer& first = p.layers.front();
    float speed = float(first.speed), phase = float(first.timeOffset);
    if (ImGui::DragFloat("Clip speed", &speed, 0.01f, -4.0f, 4.0f))
        first.speed = double(speed);
    if (ImGui::DragFloat("Phase (s)", &phase, 0.01f))
        first.timeOffset = double(phase);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("seconds added to the scene time before the clip speed");
    int root = int(p.rootMotion);
    if (ImGui::Combo("Root motion", &root, "baked\0in place\0accumulate\0"))
        p.rootMotion = scene::RootMotion(root);
    // Hold: the character keeps one clip time while the scene plays; the slider scrubs it.
    const int main = p.mainClip(*c.model);
    const double duration = main >= 0 ? c.model->animations[std::size_t(main)].duration : 0.0;
    bool held = p.pausedAt.has_value();
    if (ImGui::Checkbox("Hold", &held))
        p.pausedAt = held ? std::optional(first.clipTime(v.mTime, duration)) : std::nullopt;
    if (held) {
        ImGui::SameLine();
        float t = float(*p.pausedAt);
        if (ImGui::SliderFloat("Clip time (s)", &t, 0.0f, float(duration), "%.3f"))
            p.pausedAt = double(t);
    }
    for (std::size_t i = 0; i < p.transitions.size(); ++i) {
        const scene::Transition& t = p.transitions[i];
        ImGui::PushID(int(i));
        ImGui::BulletText("to %s at %.2f s over %.2f s",
                          t.to >= 0 && t.to < int(clips.size()) ? clips[std::size_t(t.to)].c_str()
                                                                : "-",
                          t.at, t.duration);
        ImGui::SameLine();
        const bool remove = ImGui::SmallButton("x");
        ImGui::PopID();
        if (remove) {
            p.transitions.erase(p.transitions.begin() + std::ptrdiff_t(i));
            break;
        }
    }
    layers(c, clips);
}

void Panel::layers(scene::Character& c, const std::vector<std::string>& clips) {
    scene::Performance& p = c.performance;
    if (!ImGui::TreeNode("Layers"))
        return;
    std::vector<std::string> joints{"every joint"};
    std::vector<int> jointNodes{-1};
    for (const scene::Skin& skin : c.model->skins)
        for (int j : skin.joints)
            if (std::find(jointNodes.begin(), jointNodes.end(), j) == jointNodes.end()) {
                jointNodes.push_back(j);
                const std::string& name = c.model->nodes[std::size_t(j)].name;
                joints.push_back(name.empty() ? "node " + std::to_string(j) : name);
            }
    for (std::size_t i = 1; i < p.layers.size(); ++i) {
        scene::Layer& layer = p.layers[i];
        ImGui::PushID(int(i));
        ImGui::Separator();
        combo("Clip", layer.clip, clips);
        float weight = float(layer.weight);
        if (ImGui::SliderFloat("Weight", &weight, 0.0f, 1.0f))
            layer.weight = double(weight);
        ImGui::Checkbox("Additive", &layer.additive);
        int mask =
            layer.mask.empty()
                ? 0
                : int(std::find(jointNodes.begin(), jointNodes.end(), layer.mask.front().node) -
                      jointNodes.begin());
        if (combo("Mask", mask, joints)) {
            layer.mask.clear();
            if (mask > 0)
                layer.mask.push_back({jointNodes[std::size_t(mask)], 1.0});
        }
        const bool remove = ImGui::SmallButton("Remove layer");
        ImGui::PopID();
        if (remove) {
            p.layers.erase(p.layers.begin() + std::ptrdiff_t(i));
            break;
        }
    }
    if (ImGui::Button("Add layer")) {
        scene::Layer& layer = p.layers.emplace_back();
        layer.clip = 0;
        layer.weight = 0.5;
    }
    ImGui::TreePop();
}

void Panel::morphWeights(scene::Character& c) {
    const scene::Model& model = *c.model;
    std::vector<scene::MorphSetting>& morphs = c.performance.morphs;
    bool any = false;
    for (std::size_t m = 0; m < model.meshes.size(); ++m)
        any = any || model.meshes[m].morphTargetCount() > 0;
    if (!any)
        return;
    const bool open = ImGui::TreeNode("Morph weights");
    uimap::mark("Morph weights");
    if (!open)
        return;
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        const scene::Mesh& mesh = model.meshes[m];
        for (std::size_t t = 0; t < mesh.morphTargetCount(); ++t) {
            const std::string name = t < mesh.targetNames.size() && !mesh.targetNames[t].empty()
                                         ? mesh.targetNames[t]
                                         : "target " + std::to_string(t);
            const auto found = std::find_if(morphs.begin(), morphs.end(), [&](const auto& s) {
                return (s.mesh == int(m) || s.mesh < 0) && s.target == int(t);
            });
            bool set = found != morphs.end();
            const std::string label = mesh.name + ": " + name;
            ImGui::PushID(int(m * 1000 + t));
            const bool toggled = ImGui::Checkbox("##set", &set);
            uimap::mark("set " + label);
            if (toggled) {
                if (set)
                    morphs.push_back({int(m), int(t), mesh.defaultWeights[t], false});
                else
                    morphs.erase(found);
                ImGui::PopID();
                break; // the list changed under the loop
            }
            ImGui::SameLine();
            ImGui::BeginDisabled(!set);
            float w = set ? float(found->value) : mesh.defaultWeights[t];
            const bool moved = ImGui::SliderFloat(label.c_str(), &w, 0.0f, 1.0f);
            uimap::mark(label);
            if (moved && set)
                found->value = double(w);
            ImGui::EndDisabled();
            ImGui::PopID();
        }
    }
    ImGui::TreePop();
}

void Panel::animation(Viewer& v) {
    if (!section("Animation"))
        return;
    plugin::ParameterSet& s = v.mSettings;
    const double longest = v.mWorld.longestPeriod();
    if (longest <= 0.0) {
        ImGui::TextDisabled("no clips: the rest pose");
        return;
    }
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
    float time = float(v.mTime);
    const double end = v.mWorld.repeats() ? longest : std::max(v.mWorld.timeline(), v.mTime);
    if (ImGui::SliderFloat("Scene time (s)", &time, 0.0f, float(end), "%.3f"))
        v.mTime = double(time);
    widget(s, "speed");
}

void Panel::camera(Viewer& v) {
    if (!section("Camera"))
        return;
    if (ImGui::Button("Frame all (F)"))
        v.frameCharacters(false);
    ImGui::SameLine();
    if (ImGui::Button("Frame selection (Shift+F)"))
        v.frameCharacters(true);
    if (ImGui::Button("Reset (R)")) {
        v.viewThrough(std::nullopt);
        v.mCamera.reset();
    }
    fileCameras(v);
    ImGui::TextDisabled("drag orbit, right/shift-drag pan, wheel zoom;\n"
                        "click select, ctrl-drag move (ctrl-shift: up/down)");
}

void Panel::fileCameras(Viewer& v) {
    // The characters' files' cameras: one looked through follows its node as the clip plays;
    // an orbit, pan or zoom takes the view back where it stands.
    bool any = false;
    for (std::size_t i = 0; i < v.mWorld.characters.size(); ++i) {
        const scene::Character& c = v.mWorld.characters[i];
        for (int node : c.model->cameraNodes()) {
            if (!any)
                ImGui::TextUnformatted("The files' cameras");
            any = true;
            const std::string& name = c.model->nodes[std::size_t(node)].name;
            const std::string label =
                c.name + ": " + (name.empty() ? "node " + std::to_string(node) : name);
            const scene::CameraThrough camera{i, node};
            const bool through = v.mViewThrough == camera;
            const bool chosen = ImGui::Selectable(label.c_str(), through);
            uimap::mark(label);
            if (chosen)
                v.viewThrough(through ? std::nullopt : std::optional(camera));
        }
    }
}

void Panel::environment(Viewer& v) {
    if (!section("Environment"))
        return;
    for (const char* name :
         {"environment", "env-rotation", "exposure", "ground", "shadows", "shadow-map"})
        widget(v.mSettings, name);
}

void Panel::temporal(Viewer& v) {
    if (!section("Temporal accumulation", false))
        return;
    for (const char* name :
         {"temporal", "history-weight", "moving-jitter", "converge-paused", "temporal-view"})
        widget(v.mSettings, name);
    if (v.mSettings.flag("temporal") && v.mSettings.flag("split"))
        ImGui::TextDisabled("off while the A/B split draws two methods a frame");
    else if (v.mStats.historyBytes > 0)
        ImGui::TextDisabled("history %.1f MiB", double(v.mStats.historyBytes) / 1048576.0);
}

void Panel::lights(Viewer& v) {
    if (!section("Lights", !v.mWorld.lights.empty()))
        return;
    // The characters' own (KHR_lights_punctual, on their nodes: as the files place them).
    std::size_t own = 0;
    for (const scene::Character& c : v.mWorld.characters)
        for (const scene::Node& node : c.model->nodes)
            own += node.light >= 0 ? 1 : 0;
    if (own > 0)
        ImGui::TextDisabled("%zu light(s) of the characters' files (KHR_lights_punctual)", own);
    // The scene's (saved with it, README "Scene files").
    std::vector<scene::PlacedLight>& lights = v.mWorld.lights;
    for (std::size_t i = 0; i < lights.size(); ++i) {
        scene::PlacedLight& l = lights[i];
        ImGui::PushID(int(i));
        ImGui::Separator();
        int type = int(l.light.type);
        ImGui::SetNextItemWidth(110.0f);
        ImGui::Combo("##type", &type, "directional\0point\0spot\0");
        l.light.type = scene::Light::Type(type);
        ImGui::SameLine();
        ImGui::InputText("##name", &l.light.name);
        ImGui::SameLine();
        const bool remove = ImGui::SmallButton("x");
        ImGui::ColorEdit3("Colour", &l.light.color.x);
        ImGui::DragFloat("Intensity", &l.light.intensity, 0.1f, 0.0f, 1e6f, "%.2f",
                         ImGuiSliderFlags_Logarithmic);
        if (l.light.type != scene::Light::Type::Directional) {
            ImGui::DragFloat3("Position", &l.position.x, 0.01f);
            ImGui::DragFloat("Range (0: none)", &l.light.range, 0.05f, 0.0f, 1e4f);
        }
        if (l.light.type != scene::Light::Type::Point &&
            ImGui::DragFloat3("Direction", &l.direction.x, 0.01f, -1.0f, 1.0f))
            l.direction = glm::length(l.direction) > 1e-6f ? glm::normalize(l.direction)
                                                           : glm::vec3(0.0f, -1.0f, 0.0f);
        if (l.light.type == scene::Light::Type::Spot) {
            ImGui::SliderFloat("Inner cone", &l.light.innerConeAngle, 0.0f,
                               l.light.outerConeAngle - 0.01f, "%.2f rad");
            ImGui::SliderFloat("Outer cone", &l.light.outerConeAngle,
                               l.light.innerConeAngle + 0.01f, 1.5707f, "%.2f rad");
        }
        scene::LightShadow& shadow = l.light.shadow;
        ImGui::Checkbox("Casts shadows", &shadow.enabled);
        if (shadow.enabled) {
            ImGui::SliderInt("Shadow map", &shadow.resolution, core::limits::kMinShadowResolution,
                             core::limits::kMaxShadowResolution, "%d px",
                             ImGuiSliderFlags_Logarithmic);
            ImGui::SliderFloat("Softness", &shadow.softness, 0.0f, 8.0f, "%.1f texels");
        }
        ImGui::PopID();
        if (remove) {
            lights.erase(lights.begin() + std::ptrdiff_t(i));
            break;
        }
    }
    ImGui::BeginDisabled(lights.size() >= core::limits::kMaxLights);
    if (ImGui::Button("Add a point light")) {
        // Above and in front of the camera's target, bright enough to see at its distance.
        scene::PlacedLight l;
        l.light.name = "light " + std::to_string(lights.size());
        const Orbit& orbit = v.mCamera.orbitState();
        const float distance = orbit.distance;
        l.position = orbit.target + glm::vec3(0.0f, 0.5f, 0.5f) * distance;
        l.light.intensity = 2.0f * distance * distance;
        lights.push_back(l);
    }
    ImGui::EndDisabled();
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
    if (!v.mMessage.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, v.mMessageIsError ? ImVec4(1.0f, 0.4f, 0.35f, 1.0f)
                                                               : ImVec4(0.6f, 0.9f, 0.6f, 1.0f));
        ImGui::TextWrapped("%s", v.mMessage.c_str()); // load warnings run long
        ImGui::PopStyleColor();
    }
    scene(v);
    animation(v);
    camera(v);
    environment(v);
    temporal(v);
    lights(v);
    plugins(v);
    split(v);
    timings(v);
    presets(v);
    screenshot(v);
    ImGui::TextDisabled("Space play, arrows step, M/1-4 method, B split, G ground,\n"
                        "T accumulate, F frame, Del remove, Tab panel, F12 screenshot, Esc quit");
    ImGui::PopItemWidth();
    ImGui::End();
}

} // namespace viewer
