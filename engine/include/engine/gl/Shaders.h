// The engine's own GLSL files (engine/shaders/), embedded at build time.
#pragma once

#include "engine/gl/Program.h"

#include <span>

/** Every file under engine/shaders/, named by its path there ("deform/deform.comp.glsl"). */
std::span<const gl::ShaderFile> engineShaderFiles();
