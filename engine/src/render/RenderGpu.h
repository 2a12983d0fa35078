// The renderer's GPU objects, shared by its passes (render/passes/): deformed geometry,
// environment, material textures, programs, vertex arrays and the framebuffer they draw with.
#pragma once

#include "engine/deform/GpuDeformer.h"
#include "engine/gl/Commands.h"
#include "engine/gl/Framebuffer.h"
#include "engine/gl/Program.h"
#include "engine/render/Environment.h"
#include "engine/render/MaterialTextures.h"

#include <memory>
#include <vector>

namespace render {

struct RenderGpu {
    std::unique_ptr<deform::GpuDeformer> deformer;
    std::unique_ptr<Environment> environment;
    std::unique_ptr<MaterialTextures> materials;
    gl::Program background, opaque, ground, tonemap;
    gl::VertexArray emptyVao;
    std::vector<gl::VertexArray> vaos; ///< per instance primitive, flattened
    std::vector<char> claimed;         ///< same order: a plugin draws it (this frame)
    gl::Framebuffer framebuffer;
};

} // namespace render
