// A model's textures on the GPU (colour slots as sRGB, the rest linear), plus per-material
// binding of the material uniforms of render/opaque.frag.glsl and common/material_uv.glsl.
#pragma once

#include "engine/core/Result.h"
#include "engine/gl/Program.h"
#include "engine/gl/Registry.h"
#include "engine/gl/Texture.h"
#include "engine/scene/Model.h"

#include <vector>

namespace render {

class MaterialTextures {
public:
    /** Uploads every texture of `model` with its sampler and mipmaps. Fails naming the image
     *  when one is over GL_MAX_TEXTURE_SIZE or was not decoded. */
    static core::Result<MaterialTextures> create(const scene::Model& model);

    /** The texture slots a material binds, in the order of common/material_uv.glsl's uTexture
     *  (its SLOT_* defines come from here: sharedTable()). */
    enum Slot : int {
        BaseColor,
        MetallicRoughness,
        Normal,
        Occlusion,
        Emissive,
        Specular,
        SpecularColor,
        Clearcoat,
        ClearcoatRoughness,
        ClearcoatNormal,
        SheenColor,
        SheenRoughness,
        Iridescence,
        IridescenceThickness,
        Anisotropy,
        Transmission, ///< KHR_materials_transmission (R)
        Thickness,    ///< KHR_materials_volume (G)
        kSlotCount
    };
    static_assert(kSlotCount == int(gl::slot::kMaterial.count));

    /** Sets the uniforms of `material`, one of this model's materials or its animated copy
     *  (DrawItem::values): factors, unlit, and per slot its texture flag, texture coordinate
     *  set and KHR_texture_transform matrix; binds its textures to the units of
     *  gl::slot::kMaterial. Null is the glTF default material. */
    void bind(const gl::Program& program, const scene::Material* material) const;

    /** Texture `index` as the slots that read linear data (normals, metallic-roughness) have
     *  it; null where the model's materials never read it so. */
    /** Texture `index` as the colour slots read it (sRGB); null where none does. */
    const gl::Texture* srgb(int index) const {
        return index >= 0 && std::size_t(index) < mSrgb.size() && mSrgb[std::size_t(index)]
                   ? &mSrgb[std::size_t(index)]
                   : nullptr;
    }
    const gl::Texture* linear(int index) const {
        return index >= 0 && std::size_t(index) < mLinear.size() && mLinear[std::size_t(index)]
                   ? &mLinear[std::size_t(index)]
                   : nullptr;
    }

private:
    std::vector<gl::Texture> mLinear, mSrgb; // per texture; empty Texture where not needed
};

} // namespace render
