// A world ready to render headless with the refraction plugin: what glass-bench and glass-soak
// set up the same way (glass-capture's CaptureSession adds cameras, plugins and references).
#pragma once

#include "engine/asset/HdrImage.h"
#include "engine/render/Renderer.h"
#include "engine/render/WorldLoader.h"
#include "refraction/RefractionPlugin.h"

#include <algorithm>
#include <memory>
#include <span>
#include <string>

namespace tool {

struct HeadlessScene {
    scene::World world;
    std::unique_ptr<gl::Context> context;
    std::unique_ptr<plugin::Plugin> glass; // the refraction plugin, before the renderer dies
    std::unique_ptr<render::Renderer> renderer;
    asset::HdrImage environment; ///< the renderer's (for more renderers of the same scene)
    /** The longest clip any character plays, in scene seconds (1 when none plays one). */
    double duration = 1.0;
    render::Bounds bounds; ///< of every character over its clip

    render::Camera camera(glm::ivec2 size, double time) const;
};

/** The camera of `world` at `size` and scene time `time`: its scene file's camera, else one
 *  framing `bounds`. */
inline render::Camera viewOf(const scene::World& world, const render::Bounds& bounds,
                             glm::ivec2 size, double time) {
    const float aspect = float(size.x) / float(size.y);
    return world.camera ? render::sceneCamera(world, time, aspect, bounds)
                        : render::frameBounds(bounds, aspect);
}

/** viewOf() the scene and its bounds. */
inline render::Camera HeadlessScene::camera(glm::ivec2 size, double time) const {
    return viewOf(world, bounds, size, time);
}

/** The longest clip of `world` in scene seconds, 1 when none plays one: the period tools sweep
 *  their times over. */
inline double sweepPeriod(const scene::World& world) {
    const double longest = world.longestPeriod();
    return longest > 1e-3 ? longest : 1.0;
}

/** Loads `paths` (render::loadWorld: a scene file, or models side by side), makes a headless
 *  context and a renderer with the scene's environment (else the procedural sky at
 *  `skyWidth`), adds the refraction plugin and places the ground under the bounds. Fails with
 *  the first step's message. */
inline core::Result<HeadlessScene> openHeadlessScene(std::span<const std::string> paths,
                                                     int skyWidth = 1024) {
    HeadlessScene s;
    auto world = render::loadWorld(paths);
    if (!world)
        return world.error();
    s.world = std::move(*world);
    asset::HdrImage environment = render::Environment::proceduralSky(skyWidth);
    if (s.world.environment) {
        auto hdr = asset::loadHdr(*s.world.environment);
        if (!hdr)
            return hdr.error();
        environment = std::move(*hdr);
    }
    auto context = gl::createHeadlessContext();
    if (!context)
        return context.error();
    s.context = std::move(*context);
    auto renderer = render::Renderer::create(environment, *s.context);
    if (!renderer)
        return renderer.error();
    s.renderer = std::move(*renderer);
    s.environment = std::move(environment);
    s.glass = refraction::createPlugin();
    if (auto added = s.renderer->addPlugin(s.glass.get()); !added)
        return added.error();
    if (auto prepared = s.renderer->prepare(s.world); !prepared)
        return prepared.error();
    s.duration = sweepPeriod(s.world);
    s.bounds = render::worldBounds(s.world);
    s.renderer->setGround(render::GroundPlane::under(s.bounds));
    return s;
}

} // namespace tool
