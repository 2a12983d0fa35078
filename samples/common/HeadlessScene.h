// A model ready to render headless with the refraction plugin: what glass-bench and glass-soak
// set up the same way (glass-capture's CaptureSession adds cameras, plugins and references).
#pragma once

#include "engine/asset/ModelLoader.h"
#include "engine/render/Renderer.h"
#include "refraction/RefractionPlugin.h"

#include <algorithm>
#include <memory>
#include <string>

namespace tool {

struct HeadlessScene {
    std::unique_ptr<scene::Model> model; // the renderer keeps a reference: not movable itself
    std::unique_ptr<gl::Context> context;
    std::unique_ptr<plugin::Plugin> glass; // the refraction plugin, before the renderer dies
    std::unique_ptr<render::Renderer> renderer;
    int clip = -1;         ///< the first clip, or -1 (rest pose)
    double duration = 1.0; ///< of that clip, seconds (1 for the rest pose)
    render::Bounds bounds; ///< over the clip
};

/** Loads `path`, makes a headless context and a renderer with the procedural sky at
 *  `skyWidth`, adds the refraction plugin and places the ground under the clip's bounds.
 *  Fails with the first step's message. */
inline core::Result<HeadlessScene> openHeadlessScene(const std::string& path, int skyWidth = 1024) {
    HeadlessScene s;
    auto model = asset::loadModel(path);
    if (!model)
        return model.error();
    s.model = std::make_unique<scene::Model>(std::move(*model));
    auto context = gl::createHeadlessContext();
    if (!context)
        return context.error();
    s.context = std::move(*context);
    auto renderer = render::Renderer::create(*s.model, render::Environment::proceduralSky(skyWidth),
                                             *s.context);
    if (!renderer)
        return renderer.error();
    s.renderer = std::move(*renderer);
    s.glass = refraction::createPlugin();
    if (auto added = s.renderer->addPlugin(s.glass.get()); !added)
        return added.error();
    s.clip = s.model->animations.empty() ? -1 : 0;
    s.duration = s.clip < 0 ? 1.0 : std::max(s.model->animations[0].duration, 1e-3);
    s.bounds = render::animatedBounds(*s.model, s.clip);
    s.renderer->setGround({s.bounds.min.y, s.bounds.center(), 3.0f * s.bounds.radius()});
    return s;
}

} // namespace tool
