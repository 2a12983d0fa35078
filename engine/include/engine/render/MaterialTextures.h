// A model's textures on the GPU (base colour and emissive as sRGB, the rest linear), plus
// per-material binding of the metallic-roughness uniforms of render/pbr.frag.glsl.
#pragma once

#include "engine/core/Result.h"
#include "engine/gl/Program.h"
#include "engine/gl/Texture.h"
#include "engine/scene/Model.h"

#include <vector>

namespace render {

class MaterialTextures {
public:
    /** Uploads every texture of `model` with its sampler and mipmaps. Fails naming the image
     *  when one is over GL_MAX_TEXTURE_SIZE or was not decoded. */
    static core::Result<MaterialTextures> create(const scene::Model& model);

    /** Sets the material uniforms (factors, unlit, texture flags and KHR_texture_transform
     *  matrices `u<Slot>Uv`) and binds its textures to units
     *  `firstUnit`..`firstUnit + 6`. Material -1 is the glTF default material. */
    void bind(const gl::Program& program, const scene::Model& model, int material,
              int firstUnit) const;

private:
    std::vector<gl::Texture> mLinear, mSrgb; // per texture; empty Texture where not needed
};

} // namespace render
