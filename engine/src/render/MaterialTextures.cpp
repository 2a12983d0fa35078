// Model textures on the GPU.
#include "engine/render/MaterialTextures.h"

#include "engine/gl/Commands.h"

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
    for (const scene::Material& m : model.materials) {
        for (const scene::TextureRef* t :
             {&m.baseColorTexture, &m.emissiveTexture, &m.specularColorTexture})
            if (t->present())
                srgb[std::size_t(t->texture)] = true;
        for (const scene::TextureRef* t :
             {&m.metallicRoughnessTexture, &m.normalTexture, &m.occlusionTexture,
              &m.transmissionTexture, &m.thicknessTexture, &m.specularTexture})
            if (t->present())
                linear[std::size_t(t->texture)] = true;
    }
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
    return result;
}

void MaterialTextures::bind(const gl::Program& program, const scene::Model& model, int material,
                            int firstUnit) const {
    static const scene::Material kDefault = [] {
        scene::Material m;
        m.metallicFactor = 1.0f;
        m.roughnessFactor = 1.0f;
        return m;
    }();
    const scene::Material& m = material >= 0 ? model.materials[std::size_t(material)] : kDefault;
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
    struct Slot {
        const scene::TextureRef& ref;
        const char* sampler;
        const char* flag;
        const char* transform;
        bool srgb;
    };
    const Slot slots[] = {
        {m.baseColorTexture, "uBaseColorTexture", "uHasBaseColorTexture", "uBaseColorUv", true},
        {m.metallicRoughnessTexture, "uMetallicRoughnessTexture", "uHasMetallicRoughnessTexture",
         "uMetallicRoughnessUv", false},
        {m.normalTexture, "uNormalTexture", "uHasNormalTexture", "uNormalUv", false},
        {m.occlusionTexture, "uOcclusionTexture", "uHasOcclusionTexture", "uOcclusionUv", false},
        {m.emissiveTexture, "uEmissiveTexture", "uHasEmissiveTexture", "uEmissiveUv", true},
        {m.specularTexture, "uSpecularTexture", "uHasSpecularTexture", "uSpecularUv", false},
        {m.specularColorTexture, "uSpecularColorTexture", "uHasSpecularColorTexture",
         "uSpecularColorUv", true}};
    int unit = firstUnit, texCoords = 0;
    for (const Slot& slot : slots) {
        // Each slot reads the texture coordinate set its texCoord names (common/material_uv.glsl).
        if (slot.ref.texCoord == 1)
            texCoords |= 1 << (unit - firstUnit);
        const auto& textures = slot.srgb ? mSrgb : mLinear;
        const bool has = slot.ref.present() && textures[std::size_t(slot.ref.texture)];
        program.set(slot.flag, has ? 1 : 0);
        program.set(slot.transform, slot.ref.transform);
        program.set(slot.sampler, unit);
        if (has)
            gl::bindTexture(std::uint32_t(unit), textures[std::size_t(slot.ref.texture)]);
        ++unit;
    }
    program.set("uTexCoords", texCoords);
}

} // namespace render
