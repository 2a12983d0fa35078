// glass-viewer's world of characters: opening, adding, removing and saving scenes, selecting a
// character (the clip and loop settings follow it), picking it in the view, moving it, framing
// and marking it (the window and frame loop are in Viewer.cpp, the panel in Panel.cpp).
#include "Viewer.h"

#include "engine/asset/SceneFile.h"
#include "engine/render/WorldLoader.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

namespace viewer {
namespace {

/** " (N warnings: the first; ...)" for what loading the world's models skipped, or "". */
std::string loadWarnings(const scene::World& world) {
    std::vector<const scene::Model*> seen;
    std::vector<std::string> warnings;
    for (const scene::Character& c : world.characters)
        if (std::find(seen.begin(), seen.end(), c.model.get()) == seen.end()) {
            seen.push_back(c.model.get());
            for (const std::string& w : c.model->warnings)
                warnings.push_back(c.model->sourceName + ": " + w);
        }
    if (warnings.empty())
        return "";
    // Built in steps: `" (" + std::to_string(...)` can trip GCC 12's -Wrestrict false
    // positive at -O3 (GCC bug 105329).
    std::string text = " (";
    text += std::to_string(warnings.size());
    text += warnings.size() > 1 ? " warnings: " : " warning: ";
    text += warnings.front();
    text += warnings.size() > 1 ? "; the others in the log)" : ")";
    return text;
}

/** Where world point `p` lands in a viewport of `size` pixels; none behind the camera. */
std::optional<ImVec2> toScreen(const render::Camera& camera, glm::ivec2 size, glm::vec3 p) {
    const glm::vec4 clip = camera.viewProjection() * glm::vec4(p, 1.0f);
    if (clip.w <= 1e-6f)
        return std::nullopt;
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return ImVec2((ndc.x * 0.5f + 0.5f) * float(size.x), (0.5f - 0.5f * ndc.y) * float(size.y));
}

} // namespace

void Viewer::useWorldEnvironment() {
    if (!mWorld.environment || mSettings.declarations().empty())
        return;
    std::error_code ec;
    const auto same = [&](const EnvironmentEntry& e) {
        return !e.path.empty() && std::filesystem::equivalent(e.path, *mWorld.environment, ec);
    };
    auto it = std::find_if(mEnvironments.begin(), mEnvironments.end(), same);
    if (it == mEnvironments.end()) {
        mEnvironments.push_back(
            {std::filesystem::path(*mWorld.environment).stem().string() + " (scene)",
             *mWorld.environment});
        plugin::ParameterSet settings = settingsForScene(); // the new entry among the choices
        copyValues(mSettings, settings);
        mSettings = std::move(settings);
        it = std::prev(mEnvironments.end());
    }
    mSettings.setNumber("environment", double(it - mEnvironments.begin()));
}

void Viewer::worldChanged() {
    mClipBounds.clear(); // releases models no character places any more
    mViewPoseModel = nullptr; // its model may be gone: a new pose for the next
    boundsChanged();
    if (mWorld.ground && mSettings.find("ground"))
        mSettings.setNumber("ground", 1.0);
    select(std::min(mSelected, int(mWorld.characters.size()) - 1));
    if (mViewThrough) { // a character removed or replaced takes its camera with it
        const std::size_t c = mViewThrough->character;
        const std::vector<int> nodes = c < mWorld.characters.size()
                                           ? mWorld.characters[c].model->cameraNodes()
                                           : std::vector<int>{};
        if (std::ranges::find(nodes, mViewThrough->node) == nodes.end())
            mViewThrough.reset();
    }
}

void Viewer::select(int index) {
    mSelected =
        mWorld.characters.empty() ? -1 : std::clamp(index, 0, int(mWorld.characters.size()) - 1);
    if (mSettings.declarations().empty())
        return; // create() builds the settings after the world
    plugin::ParameterSet settings = settingsForScene();
    copyValues(mSettings, settings);
    if (mSelected >= 0) {
        const scene::Character& c = mWorld.characters[std::size_t(mSelected)];
        const scene::Layer first =
            c.performance.layers.empty() ? scene::Layer{} : c.performance.layers.front();
        settings.setNumber("clip", double(std::max(c.performance.finalClip(), 0)));
        settings.setNumber("loop", first.loop == scene::Loop::Clamp ? 0.0 : 1.0);
    }
    mSettings = std::move(settings);
}

bool Viewer::openWorld(const std::vector<std::string>& paths) {
    auto world = render::loadWorld(paths);
    if (!world) {
        reportStatus(world.error(), "");
        return false;
    }
    mWorld = std::move(*world);
    if (paths.size() == 1 && asset::isSceneFile(paths[0]))
        mScenePath = paths[0];
    mSelected = 0;
    worldChanged();
    useWorldEnvironment();
    mCamera.frame(mBounds, viewportAspect());
    mTime = 0.0;
    reportStatus({}, "opened " + paths[0] + loadWarnings(mWorld));
    return true;
}

bool Viewer::addCharacter(const std::string& path) {
    auto added = render::loadWorld(std::vector<std::string>{path});
    if (!added) {
        reportStatus(added.error(), "");
        return false;
    }
    scene::World joined = mWorld;
    joined.characters.insert(joined.characters.end(), added->characters.begin(),
                             added->characters.end());
    if (auto limits = asset::checkWorldLimits(joined, "the scene with " + path); !limits) {
        reportStatus(limits, "");
        return false;
    }
    const std::string warnings = loadWarnings(*added); // before its characters move
    // Right of what is there, with a fifth of its width between.
    const render::Bounds bounds = render::worldBounds(*added);
    const float gap = 0.2f * std::max(bounds.max.x - bounds.min.x, 0.1f);
    const double shift =
        mWorld.characters.empty() ? 0.0 : double(mBounds.max.x + gap - bounds.min.x);
    for (scene::Character& c : added->characters) {
        // The same file already in the scene: its model is shared, not loaded twice.
        for (const scene::Character& other : mWorld.characters)
            if (other.modelPath == c.modelPath)
                c.model = other.model;
        c.placement.translation.x += shift;
        if (!asset::isSceneFile(path))
            c.name = std::filesystem::path(c.modelPath).stem().string() + " " +
                     std::to_string(mWorld.characters.size() + 1);
        mWorld.characters.push_back(std::move(c));
    }
    mSelected = int(mWorld.characters.size()) - 1;
    worldChanged();
    reportStatus({}, "added " + path + warnings);
    return true;
}

void Viewer::removeCharacter(std::size_t index) {
    if (index >= mWorld.characters.size())
        return;
    const std::string name = mWorld.characters[index].name;
    mWorld.characters.erase(mWorld.characters.begin() + std::ptrdiff_t(index));
    worldChanged();
    reportStatus({}, "removed " + name);
}

bool Viewer::saveWorld(const std::string& path) {
    // The scene keeps what is shown: the camera, the environment (the sky: none) and the
    // ground.
    mWorld.camera = viewPlacement();
    mWorld.camera->through = mViewThrough; // a file's camera looked through, as it moves
    const std::string& environment =
        mEnvironments[std::size_t(mSettings.number("environment"))].path;
    mWorld.environment = environment.empty() ? std::nullopt : std::optional(environment);
    mWorld.ground = mSettings.flag("ground");
    auto saved = asset::saveScene(path, mWorld);
    reportStatus(saved, "saved " + path);
    if (saved)
        mScenePath = path;
    return bool(saved);
}

void Viewer::boundsChanged() {
    render::Bounds bounds;
    for (std::size_t i = 0; i < mWorld.characters.size(); ++i) {
        const render::Bounds b = characterBounds(i);
        bounds.add(b.min);
        bounds.add(b.max);
    }
    if (bounds.empty())
        bounds.add(glm::vec3(0.0f));
    if (bounds.min == mBounds.min && bounds.max == mBounds.max && !mBounds.empty())
        return;
    mBounds = bounds; // as render::worldBounds has them, from the cached clips' bounds
    mRenderer->setGround(render::GroundPlane::under(mBounds));
}

render::Bounds Viewer::characterBounds(std::size_t index) const {
    const scene::Character& c = mWorld.characters.at(index);
    return render::transformed(
        render::performanceBounds(*c.model, c.performance, mClipBounds[c.model]), c.transform());
}

std::pair<glm::vec3, glm::vec3> Viewer::viewRay(glm::vec2 pixel) const {
    const render::Camera camera = viewCamera(viewportAspect());
    const glm::vec2 ndc(2.0f * pixel.x / float(std::max(mViewport.x, 1)) - 1.0f,
                        1.0f - 2.0f * pixel.y / float(std::max(mViewport.y, 1)));
    const glm::mat4 inverse = glm::inverse(camera.viewProjection());
    const glm::vec4 nearPoint = inverse * glm::vec4(ndc, -1.0f, 1.0f);
    const glm::vec4 farPoint = inverse * glm::vec4(ndc, 1.0f, 1.0f);
    const glm::vec3 origin = glm::vec3(nearPoint) / nearPoint.w;
    return {origin, glm::normalize(glm::vec3(farPoint) / farPoint.w - origin)};
}

int Viewer::pick(glm::vec2 pixel) const {
    const auto [origin, direction] = viewRay(pixel);
    int best = -1;
    float bestT = 1e30f;
    for (std::size_t i = 0; i < mWorld.characters.size(); ++i) {
        const render::Bounds b = characterBounds(i);
        // Slab test of the ray against the character's box.
        float t0 = 0.0f, t1 = 1e30f;
        for (int axis = 0; axis < 3; ++axis) {
            const float inv = 1.0f / (std::abs(direction[axis]) > 1e-9f ? direction[axis] : 1e-9f);
            float a = (b.min[axis] - origin[axis]) * inv, c = (b.max[axis] - origin[axis]) * inv;
            if (a > c)
                std::swap(a, c);
            t0 = std::max(t0, a);
            t1 = std::min(t1, c);
        }
        if (t0 <= t1 && t0 < bestT) {
            bestT = t0;
            best = int(i);
        }
    }
    return best;
}

bool Viewer::moveSelected(glm::vec2 from, glm::vec2 to, bool vertical) {
    scene::Character& c = mWorld.characters[std::size_t(mSelected)];
    const glm::vec3 anchor(c.placement.translation);
    // Over the horizontal plane through the character's origin; vertically, over the vertical
    // plane through it that faces the camera.
    glm::vec3 normal(0.0f, 1.0f, 0.0f);
    if (vertical) {
        const glm::vec3 forward = viewRay(to).second;
        normal = glm::length(glm::vec2(forward.x, forward.z)) > 1e-4f
                     ? glm::normalize(glm::vec3(forward.x, 0.0f, forward.z))
                     : glm::vec3(0.0f, 0.0f, 1.0f);
    }
    auto hit = [&](glm::vec2 pixel) -> std::optional<glm::vec3> {
        const auto [origin, direction] = viewRay(pixel);
        const float along = glm::dot(direction, normal);
        if (std::abs(along) < 1e-4f)
            return std::nullopt; // the plane seen edge-on
        const float t = glm::dot(anchor - origin, normal) / along;
        return t > 0.0f ? std::optional(origin + t * direction) : std::nullopt;
    };
    const auto a = hit(from), b = hit(to);
    if (!a || !b)
        return false;
    glm::vec3 move = *b - *a;
    // Exactly along the plane (the intersections carry float rounding off it).
    move = vertical ? glm::vec3(0.0f, move.y, 0.0f) : glm::vec3(move.x, 0.0f, move.z);
    c.placement.translation += glm::dvec3(move);
    return true;
}

void Viewer::drawSelection() const {
    if (mSelected < 0 || mViewport.x <= 0 || (mWorld.characters.size() < 2 && !mMoving))
        return; // one character: nothing to tell apart
    const scene::Character& c = mWorld.characters[std::size_t(mSelected)];
    const render::Camera camera = viewCamera(viewportAspect());
    const auto project = [&](glm::vec3 p) { return toScreen(camera, mViewport, p); };
    // The character's origin with its ground axes (x red, z blue) and its name: what Ctrl+drag
    // moves.
    const glm::vec3 origin(c.placement.translation);
    const float arm = 0.35f * std::max(characterBounds(std::size_t(mSelected)).radius(), 0.05f);
    const auto o = project(origin);
    if (!o)
        return;
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    for (const auto& [axis, color] : {std::pair{glm::vec3(arm, 0, 0), IM_COL32(235, 80, 70, 230)},
                                      std::pair{glm::vec3(0, arm, 0), IM_COL32(90, 200, 90, 230)},
                                      std::pair{glm::vec3(0, 0, arm), IM_COL32(80, 130, 240, 230)}})
        if (const auto end = project(origin + axis))
            draw->AddLine(*o, *end, color, 2.0f);
    draw->AddCircle(*o, 5.0f, IM_COL32(255, 255, 255, 220), 12, 2.0f);
    draw->AddText(ImVec2(o->x + 8.0f, o->y + 4.0f), IM_COL32(255, 255, 255, 220), c.name.c_str());
}

void Viewer::drawSkeleton() const {
    if (mSelected < 0 || mViewport.x <= 0)
        return;
    const scene::Character& c = mWorld.characters[std::size_t(mSelected)];
    const scene::Model& model = *c.model;
    const anim::Pose pose = anim::evaluate(model, c.performance, mTime);
    const render::Camera camera = viewCamera(viewportAspect());
    std::vector<std::uint8_t> joint(model.nodes.size(), 0);
    for (const scene::Skin& skin : model.skins)
        for (int j : skin.joints)
            joint[std::size_t(j)] = 1;
    const auto at = [&](std::size_t n) {
        return toScreen(camera, mViewport,
                        glm::vec3(c.transform() * glm::dvec4(glm::dvec3(pose.world[n][3]), 1.0)));
    };
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    for (std::size_t n = 0; n < model.nodes.size(); ++n) {
        if (!joint[n])
            continue;
        const auto p = at(n);
        if (!p)
            continue;
        const int parent = model.nodes[n].parent;
        if (parent >= 0 && joint[std::size_t(parent)])
            if (const auto q = at(std::size_t(parent)))
                draw->AddLine(*q, *p, IM_COL32(255, 210, 80, 220), 2.0f);
        draw->AddCircleFilled(*p, 3.0f, IM_COL32(255, 120, 40, 240));
    }
}

render::Camera Viewer::viewCamera(float aspect) const {
    if (mViewThrough && mViewThrough->character < mWorld.characters.size()) {
        const scene::Character& c = mWorld.characters[mViewThrough->character];
        if (mViewPoseModel != c.model.get()) { // the pose kept, so that a frame allocates nothing
            mViewPose = anim::restPose(*c.model);
            mViewPoseModel = c.model.get();
        }
        anim::evaluate(*c.model, c.performance, mTime, mViewPose);
        if (auto camera =
                render::nodeCamera(*c.model, mViewPose, mViewThrough->node, c.transform(), aspect))
            return *camera;
    }
    return mCamera.camera(aspect);
}

scene::WorldCamera Viewer::viewPlacement() const {
    if (!mViewThrough)
        return mCamera.placement();
    // The file's camera where it stands, looking as far ahead as the scene's centre is.
    const render::Camera c = viewCamera(viewportAspect());
    const glm::vec3 forward = -glm::vec3(glm::inverse(c.view)[2]);
    const float ahead = std::max(glm::length(mBounds.center() - c.position), 1e-2f);
    return {c.position, c.position + forward * ahead, c.yfov};
}

void Viewer::viewThrough(std::optional<scene::CameraThrough> camera) {
    if (mViewThrough && !camera)
        mCamera.look(viewPlacement());
    mViewThrough = camera;
    mRenderer->resetHistory(); // a camera cut
}

void Viewer::frameCharacters(bool selectionOnly) {
    viewThrough(std::nullopt); // a camera cut
    if (!selectionOnly || mSelected < 0) {
        mCamera.frame(mBounds, viewportAspect());
        return;
    }
    mCamera.frame(characterBounds(std::size_t(mSelected)), viewportAspect());
}

} // namespace viewer
