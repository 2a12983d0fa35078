// The render module's numbers its shaders share (gl/Registry.h): the lights' types and the sheen
// table's size (common/lighting.glsl), the material texture slots (common/material_uv.glsl), the
// material layers a shading variant compiles in (common/brdf.glsl). The renderer registers them
// in its shader library as "render".
#pragma once

#include "engine/gl/Registry.h"

#include <span>

namespace render {

std::span<const gl::Shared> sharedTable();

} // namespace render
