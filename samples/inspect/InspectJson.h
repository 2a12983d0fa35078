// The --json description of a model; shared keys follow ../shared/assets/INVENTORY.json.
#pragma once

#include "engine/scene/Model.h"

#include <nlohmann/json.hpp>

namespace inspect {

/** meshes, primitives, triangles, vertices (POSITION counts per primitive, as in the file),
 *  skins, joints_per_skin, max_morph_targets, animations, animation_list (name, duration_s,
 *  interpolation, channels, paths, pointer_channels: each KHR_animation_pointer channel, played
 *  or skipped), plus nodes, cameras, max_influences and the glass materials with their KHR
 *  parameters. */
nlohmann::ordered_json describe(const scene::Model& model);

} // namespace inspect
