// The worlds of the test matrix (MatrixTest.cpp, scripts/matrix): each crosses one feature of the
// engine and the optical model with glass, built here from the built-in sphere and box or the
// project's assets, so that every method and the reference render the same world.
#pragma once

#include "WorldRig.h"

#include "engine/asset/ModelLoader.h"
#include "engine/scene/World.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace test::matrix {

/** A glass material of its own (KHR_materials_transmission), clear and smooth. */
inline scene::Material glassMaterial(glm::vec3 baseColor = glm::vec3(1.0f),
                                     float roughness = 0.0f) {
    scene::Material m;
    m.name = "glass";
    m.baseColorFactor = glm::vec4(baseColor, 1.0f);
    m.metallicFactor = 0.0f;
    m.roughnessFactor = roughness;
    m.hasTransmission = true;
    m.transmissionFactor = 1.0f;
    return m;
}

/** An opaque metallic-roughness material. */
inline scene::Material opaqueMaterial(glm::vec3 baseColor, float metallic, float roughness) {
    scene::Material m;
    m.name = "opaque";
    m.baseColorFactor = glm::vec4(baseColor, 1.0f);
    m.metallicFactor = metallic;
    m.roughnessFactor = roughness;
    return m;
}

/** A model assembled from the built-in sphere and box: each part a mesh on a node of its own
 *  (its rest transform), with a material of the model's. */
class Composer {
public:
    Composer() { model.sourceName = "matrix"; }
    int material(scene::Material m) {
        model.materials.push_back(std::move(m));
        return int(model.materials.size()) - 1;
    }
    /** Adds a part: the sphere (segments) or the box, scaled, turned and moved, drawn with
     *  `material`; returns its node. */
    int part(bool sphere, int material, glm::dvec3 translation, glm::dvec3 scale = glm::dvec3(1.0),
             glm::dquat rotation = glm::dquat(1.0, 0.0, 0.0, 0.0)) {
        scene::Model shape = sphere ? asset::makeSphere(48) : asset::makeBox();
        scene::Mesh mesh = shape.meshes.at(0);
        for (scene::Primitive& p : mesh.primitives)
            p.material = material;
        model.meshes.push_back(std::move(mesh));
        scene::Node node;
        node.name = "part " + std::to_string(model.nodes.size());
        node.mesh = int(model.meshes.size()) - 1;
        node.rest.translation = translation;
        node.rest.scale = scale;
        node.rest.rotation = rotation;
        node.restMatrix = node.rest.matrix();
        return root(std::move(node));
    }
    /** Adds a KHR_lights_punctual light on a node of its own at `translation`, shining down
     *  the node's -z; returns the light. */
    int light(scene::Light light, glm::dvec3 translation,
              glm::dquat rotation = glm::dquat(1.0, 0.0, 0.0, 0.0)) {
        model.lights.push_back(std::move(light));
        scene::Node node;
        node.name = "light " + std::to_string(model.lights.size() - 1);
        node.light = int(model.lights.size()) - 1;
        node.rest.translation = translation;
        node.rest.rotation = rotation;
        node.restMatrix = node.rest.matrix();
        root(std::move(node));
        return int(model.lights.size()) - 1;
    }
    /** Adds `node` as a root of the model's scene; returns it. */
    int root(scene::Node node) {
        model.nodes.push_back(std::move(node));
        if (model.scenes.empty())
            model.scenes.emplace_back();
        model.scenes[0].push_back(int(model.nodes.size()) - 1);
        return int(model.nodes.size()) - 1;
    }
    /** A square texture of `size` texels from `texel(x, y)` (RGBA8), sampled linearly. */
    int texture(int size, const std::function<glm::u8vec4(int, int)>& texel) {
        scene::Image image;
        image.name = "matrix texture " + std::to_string(model.images.size());
        image.width = image.height = size;
        image.components = 4;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const glm::u8vec4 t = texel(x, y);
                image.pixels.insert(image.pixels.end(), {t.r, t.g, t.b, t.a});
            }
        model.images.push_back(std::move(image));
        model.textures.push_back({int(model.images.size()) - 1, -1});
        return int(model.textures.size()) - 1;
    }
    scene::World world(scene::GlassMode glass = scene::GlassMode::Auto) {
        scene::World w =
            scene::singleCharacterWorld(std::make_shared<const scene::Model>(std::move(model)));
        w.characters[0].glass = glass;
        return w;
    }
    scene::Model model;
};

/** A light of `type` placed in the world. */
inline scene::PlacedLight light(scene::Light::Type type, glm::vec3 position, glm::vec3 direction,
                                glm::vec3 color, float intensity) {
    scene::PlacedLight l;
    l.light.type = type;
    l.light.color = color;
    l.light.intensity = intensity;
    l.light.innerConeAngle = 0.2f;
    l.light.outerConeAngle = 0.45f;
    l.position = position;
    l.direction = glm::normalize(direction);
    return l;
}

/** The built-in sphere forced to glass. */
inline scene::World sphere() {
    Composer c;
    c.part(true, c.material(opaqueMaterial(glm::vec3(1.0f), 0.0f, 0.5f)), glm::dvec3(0.0));
    return c.world(scene::GlassMode::All);
}

/** A character of interpenetrating parts (a torso box, a head, a neck ball through both, arms
 *  and legs overlapping the torso), its materials opaque ones (`colours`: grey, tinted; or
 *  black and metallic) forced to glass, as glass-all plays a robot. */
inline scene::World robot(bool blackAndMetal) {
    Composer c;
    const int grey = c.material(opaqueMaterial({0.6f, 0.6f, 0.6f}, 0.0f, 0.5f));
    const int light = c.material(opaqueMaterial({0.85f, 0.85f, 0.8f}, 0.0f, 0.3f));
    const int tinted = c.material(opaqueMaterial({0.9f, 0.5f, 0.2f}, 0.0f, 0.6f));
    const int arm = blackAndMetal ? c.material(opaqueMaterial({0.02f, 0.02f, 0.02f}, 0.0f, 0.4f))
                                  : c.material(opaqueMaterial({0.3f, 0.55f, 0.9f}, 0.0f, 0.4f));
    const int other =
        blackAndMetal ? c.material(opaqueMaterial({0.7f, 0.7f, 0.75f}, 1.0f, 0.3f)) : grey;
    c.part(false, grey, {0.0, 1.0, 0.0}, {0.3, 0.35, 0.18});
    c.part(false, light, {0.0, 1.45, 0.0}, {0.18, 0.16, 0.16});
    c.part(true, tinted, {0.0, 1.3, 0.0}, glm::dvec3(0.16));
    c.part(false, arm, {-0.36, 1.05, 0.0}, {0.09, 0.3, 0.09});
    c.part(false, other, {0.36, 1.05, 0.0}, {0.09, 0.3, 0.09});
    c.part(false, grey, {-0.14, 0.45, 0.0}, {0.1, 0.35, 0.1});
    c.part(false, light, {0.14, 0.45, 0.0}, {0.1, 0.35, 0.1});
    return c.world(scene::GlassMode::All);
}

/** One property a test clip plays, from `from` to `to` over a second: of material, light or
 *  camera `object`, in texture slot `slot` for a texture transform. */
struct PointerKeys {
    scene::PointerProperty property;
    glm::vec4 from, to;
    int object = 0, slot = -1;
};

/** A clip of `model` playing `keys`: a KHR_animation_pointer channel each, as the loader makes
 *  them. */
inline void animatePointers(scene::Model& model, const std::vector<PointerKeys>& keys) {
    scene::Animation clip;
    clip.name = "pointers";
    clip.duration = 1.0;
    for (const PointerKeys& k : keys) {
        scene::AnimationSampler sampler;
        sampler.times = {0.0f, 1.0f};
        sampler.components = scene::componentCount(k.property);
        for (const glm::vec4& v : {k.from, k.to})
            for (int c = 0; c < sampler.components; ++c)
                sampler.values.push_back(v[c]);
        scene::AnimationChannel channel;
        channel.sampler = int(clip.samplers.size());
        channel.path = scene::AnimationPath::Pointer;
        channel.object = k.object;
        channel.property = k.property;
        channel.slot = k.slot;
        clip.samplers.push_back(std::move(sampler));
        clip.channels.push_back(channel);
    }
    model.animations.push_back(std::move(clip));
}

/** A glass sphere whose IOR (1.2 to 1.8) and transmission (1 to 0.6) a clip plays over a
 *  second, the clip playing. */
inline scene::World animatedGlass() {
    scene::World world;
    {
        Composer c;
        c.part(true, c.material(glassMaterial()), glm::dvec3(0.0));
        world = c.world();
    }
    scene::Model model = *world.characters[0].model;
    animatePointers(model,
                    {{scene::PointerProperty::Ior, glm::vec4(1.2f), glm::vec4(1.8f)},
                     {scene::PointerProperty::Transmission, glm::vec4(1.0f), glm::vec4(0.6f)}});
    world.characters[0].model = std::make_shared<const scene::Model>(std::move(model));
    world.characters[0].play(0);
    return world;
}

/** A glass sphere whose material is `m` (its own glass). */
inline scene::World glassSphere(scene::Material m) {
    Composer c;
    c.part(true, c.material(std::move(m)), glm::dvec3(0.0));
    return c.world();
}

/** Glass textures: a base colour checker, a transmission texture of stripes (opaque where
 *  dark), a roughness and metallic texture of rings; TEXCOORD_0 through a texture transform
 *  on the base colour. */
inline scene::World texturedGlass() {
    Composer c;
    scene::Material m = glassMaterial();
    m.roughnessFactor = 1.0f;
    m.metallicFactor = 1.0f;
    m.baseColorTexture.texture = c.texture(64, [](int x, int y) {
        return ((x / 8 + y / 8) % 2) ? glm::u8vec4(255, 200, 120, 255)
                                     : glm::u8vec4(120, 190, 255, 255);
    });
    m.baseColorTexture.setUv({glm::vec2(0.1f, 0.0f), 0.0f, glm::vec2(2.0f, 1.0f)});
    m.transmissionTexture.texture = c.texture(
        64, [](int x, int) { return glm::u8vec4((x / 6) % 4 == 0 ? 60 : 255, 0, 0, 255); });
    m.metallicRoughnessTexture.texture = c.texture(64, [](int, int y) {
        const std::uint8_t rough = (y / 8) % 2 ? 0 : 90, metal = (y / 16) % 3 == 0 ? 200 : 0;
        return glm::u8vec4(0, rough, metal, 255);
    });
    c.part(true, c.material(std::move(m)), glm::dvec3(0.0));
    return c.world();
}

/** A glass sphere with a normal map of bumps (the tangents the built-in sphere has). */
inline scene::World normalMapped() {
    Composer c;
    scene::Material m = glassMaterial();
    m.normalTexture.texture = c.texture(64, [](int x, int y) {
        const double u = std::sin(x * 0.6) * 0.45, v = std::sin(y * 0.6) * 0.45;
        const glm::dvec3 n = glm::normalize(glm::dvec3(u, v, 1.0));
        return glm::u8vec4(glm::round((n * 0.5 + 0.5) * 255.0), 255);
    });
    c.part(true, c.material(std::move(m)), glm::dvec3(0.0));
    return c.world();
}

/** KHR_materials_specular (a blue-tinted weight), an iridescent film, a clear coat and a sheen
 *  on `m`. */
inline void addMaterialLayers(scene::Material& m) {
    m.hasSpecular = true;
    m.specularFactor = 0.8f;
    m.specularColorFactor = {1.0f, 3.0f, 6.0f};
    m.hasIridescence = true;
    m.iridescenceFactor = 0.7f;
    m.iridescenceIor = 1.4f;
    m.iridescenceThicknessMaximum = 450.0f;
    m.hasClearcoat = true;
    m.clearcoatFactor = 0.6f;
    m.clearcoatRoughnessFactor = 0.1f;
    m.hasSheen = true;
    m.sheenColorFactor = {0.3f, 0.1f, 0.2f};
    m.sheenRoughnessFactor = 0.5f;
}

/** A glass sphere with KHR_materials_specular's colour and weight, an iridescent film, a clear
 *  coat and a sheen. */
inline scene::World layeredGlass() {
    scene::Material m = glassMaterial();
    addMaterialLayers(m);
    return glassSphere(std::move(m));
}

/** Two overlapping spheres whose KHR_materials_variants variant "tinted" turns one of them to
 *  amber glass of another index; the character plays that variant. */
inline scene::World variant() {
    Composer c;
    const int clear = c.material(glassMaterial());
    scene::Material amber = glassMaterial({1.0f, 0.7f, 0.3f});
    amber.hasIor = true;
    amber.ior = 1.7f;
    const int tinted = c.material(std::move(amber));
    c.part(true, clear, {-0.4, 0.0, 0.0}, glm::dvec3(0.6));
    const int node = c.part(true, clear, {0.4, 0.0, 0.2}, glm::dvec3(0.6));
    c.model.variants = {"tinted"};
    c.model.meshes[std::size_t(c.model.nodes[std::size_t(node)].mesh)]
        .primitives[0]
        .variantMaterials = {tinted};
    scene::World w = c.world();
    w.characters[0].variant = 0;
    return w;
}

/** One glass sphere drawn four times (EXT_mesh_gpu_instancing), overlapping on screen. */
inline scene::World instanced() {
    Composer c;
    const int node = c.part(true, c.material(glassMaterial()), glm::dvec3(0.0), glm::dvec3(0.45));
    for (const glm::dvec3 at : {glm::dvec3(-1.2, 0.0, 0.0), glm::dvec3(-0.4, 0.4, -0.8),
                                glm::dvec3(0.4, -0.3, 0.6), glm::dvec3(1.2, 0.2, -0.3)})
        c.model.nodes[std::size_t(node)].instances.push_back(glm::translate(glm::dmat4(1.0), at));
    return c.world();
}

/** Mirrored placements (negative scales: glTF reverses their winding) and a double-sided open
 *  sheet of glass in front of them. */
inline scene::World mirroredAndOpen() {
    Composer c;
    const int glass = c.material(glassMaterial());
    c.part(true, glass, {-0.5, 0.0, 0.0}, {-0.5, 0.5, 0.5});
    c.part(false, glass, {0.55, 0.0, -0.2}, {0.4, -0.4, 0.4},
           glm::angleAxis(0.5, glm::dvec3(0.0, 1.0, 0.0)));
    scene::Material sheet = glassMaterial({0.8f, 0.9f, 1.0f});
    sheet.doubleSided = true;
    const int front = c.material(std::move(sheet));
    // The box's first face alone: an open, flat square.
    const int node = c.part(false, front, {0.0, 0.1, 0.9}, {0.9, 0.5, 1.0},
                            glm::angleAxis(1.5707963, glm::dvec3(0.0, 1.0, 0.0)));
    scene::Primitive& p =
        c.model.meshes[std::size_t(c.model.nodes[std::size_t(node)].mesh)].primitives[0];
    p.indices.resize(6);
    return c.world();
}

/** A glass sphere in front of an opaque robot: two characters. */
inline scene::World besideOpaque() {
    scene::World w = robot(false);
    w.characters[0].glass = scene::GlassMode::None;
    w.characters[0].placement.translation = {0.3, -1.0, -0.8};
    scene::World glass = sphere();
    glass.characters[0].placement.scale = glm::dvec3(0.5);
    w.characters.push_back(glass.characters[0]);
    return w;
}

/** A world lit by `lights`. */
inline scene::World lit(scene::World w, std::vector<scene::PlacedLight> lights) {
    w.lights = std::move(lights);
    return w;
}

} // namespace test::matrix
