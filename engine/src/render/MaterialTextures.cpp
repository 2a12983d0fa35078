// Model textures on the GPU.
#include "engine/render/MaterialTextures.h"

#include "engine/gl/Commands.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>

namespace render {
namespace {

gl::Filter filterOf(const scene::Sampler* s) {
    if (!s || s->minFilter < 0)
        return gl::Filter::LinearMipmap;
    if (s->minFilter == 9728) // NEAREST
        return gl::Filter::Nearest;
    return s->minFilter == 9729 ? gl::Filter::Linear : gl::Filter::LinearMipmap;
}

gl::Wrap wrapOf(const scene::Sampler* s) {
    if (!s)
        return gl::Wrap::Repeat;
    return s->wrapS == 33071   ? gl::Wrap::Clamp
           : s->wrapS == 33648 ? gl::Wrap::MirroredRepeat
                               : gl::Wrap::Repeat;
}

} // namespace

core::Result<MaterialTextures> MaterialTextures::create(const scene::Model& model) {
    MaterialTextures result;
    std::vector<bool> srgb(model.textures.size(), false), linear(model.textures.size(), false);
    for (const scene::Material& m : model.materials)
        m.forEachTexture([&](const scene::TextureRef& t, bool colour) {
            if (t.present())
                (colour ? srgb : linear)[std::size_t(t.texture)] = true;
        });
    result.mLinear.resize(model.textures.size());
    result.mSrgb.resize(model.textures.size());
    for (std::size_t i = 0; i < model.textures.size(); ++i) {
        if (!srgb[i] && !linear[i])
            continue;
        const int imageIndex = model.textures[i].image;
        if (imageIndex < 0)
            continue;
        const scene::Image& image = model.images[std::size_t(imageIndex)];
        const std::string name = model.sourceName + ": image " + std::to_string(imageIndex);
        if (image.pixels.empty())
            return core::Error{"render::MaterialTextures::create(): " + name + " was not decoded"};
        if (image.width > gl::Texture::maxSize() || image.height > gl::Texture::maxSize())
            return core::Error{"render::MaterialTextures::create(): " + name + " is " +
                               std::to_string(image.width) + "x" + std::to_string(image.height) +
                               ", over GL_MAX_TEXTURE_SIZE " +
                               std::to_string(gl::Texture::maxSize())};
        std::vector<std::uint8_t> rgba8;
        const std::uint8_t* pixels = image.pixels.data();
        if (image.bitsPerChannel == 16) {
            rgba8.resize(image.pixels.size() / 2);
            for (std::size_t k = 0; k < rgba8.size(); ++k)
                rgba8[k] = image.pixels[k * 2 + 1]; // high byte (little-endian 16-bit)
            pixels = rgba8.data();
        }
        const scene::Sampler* sampler =
            model.textures[i].sampler >= 0 ? &model.samplers[std::size_t(model.textures[i].sampler)]
                                           : nullptr;
        for (bool asSrgb : {true, false}) {
            if (asSrgb ? !srgb[i] : !linear[i])
                continue;
            gl::Texture texture({{image.width, image.height},
                                 asSrgb ? gl::Format::SRGB8_A8 : gl::Format::RGBA8,
                                 0});
            texture.upload(0, pixels);
            texture.generateMipmaps();
            texture.setSampling(filterOf(sampler), wrapOf(sampler));
            (asSrgb ? result.mSrgb : result.mLinear)[i] = std::move(texture);
        }
    }
    // The trace's compute passes read these levels: finished before any dispatch can (as the
    // environment's, Environment::create). Once, at load.
    if (!model.textures.empty())
        gl::finish();
    return result;
}

void MaterialTextures::bind(const gl::Program& program, const scene::Material* material) const {
    static const scene::Material kDefault = [] {
        scene::Material m;
        m.metallicFactor = 1.0f;
        m.roughnessFactor = 1.0f;
        return m;
    }();
    const scene::Material& m = material ? *material : kDefault;
    program.set("uBaseColorFactor", m.baseColorFactor);
    program.set("uMetallicFactor", m.metallicFactor);
    program.set("uRoughnessFactor", m.roughnessFactor);
    program.set("uEmissive", m.emissiveFactor * m.emissiveStrength);
    program.set("uNormalScale", m.normalTexture.scale);
    program.set("uOcclusionStrength", m.occlusionTexture.scale);
    program.set("uUnlit", m.unlit ? 1 : 0);
    // KHR_materials_specular (without it: weight 1, colour white, F0 0.04 or the ior's)
    program.set("uSpecularFactor", m.hasSpecular ? m.specularFactor : 1.0f);
    program.set("uSpecularColorFactor", m.hasSpecular ? m.specularColorFactor : glm::vec3(1.0f));
    program.set("uDielectricF0", m.dielectricF0());
    // The layers (without their extension: none, their factors 0)
    program.set("uClearcoatFactor", m.hasClearcoat ? m.clearcoatFactor : 0.0f);
    program.set("uClearcoatRoughnessFactor", m.clearcoatRoughnessFactor);
    program.set("uClearcoatNormalScale", m.clearcoatNormalTexture.scale);
    program.set("uSheenColorFactor", m.hasSheen ? m.sheenColorFactor : glm::vec3(0.0f));
    program.set("uSheenRoughnessFactor", m.sheenRoughnessFactor);
    program.set("uIridescenceFactor", m.hasIridescence ? m.iridescenceFactor : 0.0f);
    program.set("uIridescenceIor", m.iridescenceIor);
    program.set("uIridescenceThickness",
                glm::vec2(m.iridescenceThicknessMinimum, m.iridescenceThicknessMaximum));
    program.set("uAnisotropyStrength", m.hasAnisotropy ? m.anisotropyStrength : 0.0f);
    program.set("uAnisotropyRotation",
                glm::vec2(std::cos(m.anisotropyRotation), std::sin(m.anisotropyRotation)));
    // In common/material_uv.glsl's order: colour slots sample the sRGB copy.
    const std::pair<const scene::TextureRef*, bool> slots[kSlotCount] = {
        {&m.baseColorTexture, true},
        {&m.metallicRoughnessTexture, false},
        {&m.normalTexture, false},
        {&m.occlusionTexture, false},
        {&m.emissiveTexture, true},
        {&m.specularTexture, false},
        {&m.specularColorTexture, true},
        {&m.clearcoatTexture, false},
        {&m.clearcoatRoughnessTexture, false},
        {&m.clearcoatNormalTexture, false},
        {&m.sheenColorTexture, true},
        {&m.sheenRoughnessTexture, false},
        {&m.iridescenceTexture, false},
        {&m.iridescenceThicknessTexture, false},
        {&m.anisotropyTexture, false},
        {&m.transmissionTexture, false},
        {&m.thicknessTexture, false}};
    struct SlotNames {
        std::string has, transform;
    };
    static const auto names = [] {
        std::array<SlotNames, kSlotCount> n;
        for (int slot = 0; slot < kSlotCount; ++slot)
            n[std::size_t(slot)] = {gl::Program::element("uHasTexture", std::size_t(slot)),
                                    gl::Program::element("uTextureUv", std::size_t(slot))};
        return n;
    }();
    int texCoords = 0;
    for (int slot = 0; slot < kSlotCount; ++slot) {
        const auto [ref, srgb] = slots[slot];
        // Each slot reads the texture coordinate set its texCoord names.
        if (ref->texCoord == 1)
            texCoords |= 1 << slot;
        const auto& textures = srgb ? mSrgb : mLinear;
        const bool has = ref->present() && textures[std::size_t(ref->texture)];
        const SlotNames& name = names[std::size_t(slot)];
        program.set(name.has.c_str(), has ? 1 : 0);
        program.set(name.transform.c_str(), ref->transform);
        if (has)
            gl::bindTexture(gl::slot::kMaterial, textures[std::size_t(ref->texture)],
                            std::uint32_t(slot));
    }
    program.set("uTexCoords", texCoords);
}

} // namespace render
