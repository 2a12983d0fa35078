// What the tools accept wherever a model path goes: a scene file, one model, or several models
// placed side by side.
#pragma once

#include "engine/asset/GltfLoader.h"
#include "engine/core/Result.h"
#include "engine/scene/World.h"

#include <span>
#include <string>

namespace render {

/** One scene file (asset::isSceneFile) is loaded as it is. Model paths (files or builtin:...)
 *  make a world of one character each, playing the model's first clip from scene time 0: one
 *  at the origin; several side by side along +x in the order given, centred on the origin, a
 *  fifth of the widest one's width apart (widths from each clip's bounds). A model given twice
 *  is loaded once. A scene file mixed with other paths is an error; the limits of scene files
 *  hold (asset::checkWorldLimits). Fails with the loader's message (naming the file and the
 *  element). */
core::Result<scene::World> loadWorld(std::span<const std::string> paths,
                                     const asset::LoadOptions& options = {});

} // namespace render
