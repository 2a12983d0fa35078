// glTF's material extensions and lights against the Embree reference: each extension's
// Khronos test model (or a sphere of one layer) on the GPU and in the reference, and the same
// frame with the extension switched off, which must score well below.
#include "MatrixWorlds.h"
#include "WorldRig.h"
#include "support/GlTest.h"
#include "support/TestSupport.h"

#include "engine/asset/ModelLoader.h"
#include "engine/capture/Metrics.h"
#include "engine/scene/World.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

namespace {

using test::WorldRig;
constexpr int kSize = test::kWorldRigSize;

/** A shared Khronos model, loaded and changed by `change` (nothing when null). */
scene::World sharedWorld(const std::string& file,
                         const std::function<void(scene::Model&)>& change = {}) {
    auto loaded = asset::loadModel((test::sharedDir() / "assets/khronos" / file).string());
    EXPECT_TRUE(loaded.ok()) << (loaded.ok() ? "" : loaded.error().message);
    if (!loaded)
        return {};
    if (change)
        change(*loaded);
    return scene::singleCharacterWorld(std::make_shared<const scene::Model>(std::move(*loaded)));
}

// Floors of the material tests: each GPU frame against the reference's rays through the same
// pixel centres, measured (docs/materials.md) less a margin. Untextured surfaces agree to
// 64-99 dB; textured ones less, as the GPU filters their mip levels and the reference reads the
// full-size texels (ClearCoatTest's and LightsPunctualLamp's normal maps most).
constexpr double kClearcoatFloor = 22.0, kSheenFloor = 29.0, kSphereLayerFloor = 55.0,
                 kAnisotropyFloor = 38.0, kLightsFloor = 12.0, kNodeLightsFloor = 55.0,
                 kEmissiveFloor = 60.0, kGlassLayersFloor = 28.0, kUnlitFloor = 40.0;

class Materials : public test::GlTest {
protected:
    /** Whether pixel `px` of a `size`-square glass mask is within two pixels of glass (where
     *  the GPU's rasterised outline and the reference's may differ by a pixel). */
    static bool nearGlass(const std::vector<bool>& glass, int size, std::size_t px) {
        const int x = int(px % std::size_t(size)), y = int(px / std::size_t(size));
        for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx) {
                const int u = x + dx, v = y + dy;
                if (u >= 0 && v >= 0 && u < size && v < size &&
                    glass[std::size_t(v) * std::size_t(size) + std::size_t(u)])
                    return true;
            }
        return false;
    }

    /** Masked PSNR against the reference of `on` of the GPU's frames of `on` and of `off` (the
     *  same world with the feature under test switched off), from `on`'s camera: over the whole
     *  image, or (`changed`) over the pixels where the two frames differ; `opaqueOnly` leaves
     *  out the pixels where the reference sees glass, and their neighbours. */
    std::pair<double, double> againstReference(scene::World on, scene::World off, int size,
                                               bool changed = false, bool opaqueOnly = false) {
        WorldRig rig(std::move(on), context(), size), without(std::move(off), context(), size);
        without.setCamera(rig.camera());
        const auto reference = rig.reference(0.0, WorldRig::Evaluation::Deterministic);
        const capture::Image a = rig.render(), b = without.render();
        std::vector<bool> mask(a.rgba.size() / 4, true);
        for (std::size_t px = 0; px < mask.size(); ++px) {
            bool differs = false;
            for (int c = 0; c < 3; ++c)
                differs = differs || std::abs(int(a.rgba[px * 4 + std::size_t(c)]) -
                                              int(b.rgba[px * 4 + std::size_t(c)])) > 2;
            mask[px] =
                (differs || !changed) && !(opaqueOnly && nearGlass(reference.mask, size, px));
        }
        return {capture::score(a, reference.image, &mask).psnr,
                capture::score(b, reference.image, &mask).psnr};
    }
};

TEST_F(Materials, TexturesOnTheSecondTextureCoordinatesAreReadByTheGpuAndTheReference) {
    // MultiUVTest's emissive glTF logo reads TEXCOORD_1 (its base colour TEXCOORD_0): the GPU's
    // frame and the reference's agree, and both show the logo. Dropping the texture (as the
    // engine did while it read TEXCOORD_0 alone) moves the frame far off the reference.
    GLASS_REQUIRE_SHARED();
    const std::string file = "MultiUVTest/glTF-Binary/MultiUVTest.glb";
    const auto [both, without] = againstReference(
        sharedWorld(file,
                    [](scene::Model& m) { EXPECT_EQ(m.materials[0].emissiveTexture.texCoord, 1); }),
        sharedWorld(file, [](scene::Model& m) { m.materials[0].emissiveTexture = {}; }), kSize);
    std::printf("MultiUVTest against the reference: %.2f dB, %.2f dB without its TEXCOORD_1 "
                "texture\n",
                both, without);
    EXPECT_GE(both, 32.0); // measured 35.6 dB
    EXPECT_GT(both, without + 5.0);
}

TEST_F(Materials, GpuInstancesArePlacementsOnTheGpuAndInTheReference) {
    // SimpleInstancing draws one cube 125 times (EXT_mesh_gpu_instancing: translation, rotation
    // and scale per instance): the GPU's frame and the reference's agree, and a frame of the
    // cube drawn once, as the engine did without the extension, does not.
    GLASS_REQUIRE_SHARED();
    const std::string file = "SimpleInstancing/glTF-Binary/SimpleInstancing.glb";
    const auto [instanced, single] = againstReference(
        sharedWorld(file,
                    [](scene::Model& m) {
                        EXPECT_TRUE(m.warnings.empty());
                        EXPECT_EQ(m.nodes[0].instances.size(), 125u);
                    }),
        sharedWorld(file, [](scene::Model& m) { m.nodes[0].instances.clear(); }), kSize);
    std::printf("SimpleInstancing against the reference: %.2f dB, %.2f dB drawn once\n", instanced,
                single);
    EXPECT_GE(instanced, 45.0); // measured 50.4 dB
    EXPECT_GT(instanced, single + 5.0);
}

TEST_F(Materials, AVariantDrawsItsMaterialsOnTheGpuAndInTheReference) {
    // MaterialsVariantsShoe's "street" variant (KHR_materials_variants): black with red stripes
    // where the file's own materials are blue. The GPU's frame of the variant agrees with the
    // reference's, and the frame of the file's own materials does not.
    GLASS_REQUIRE_SHARED();
    scene::World street = sharedWorld("MaterialsVariantsShoe/glTF/MaterialsVariantsShoe.gltf");
    scene::World own = street;
    const auto variant = street.characters[0].model->findVariant("street");
    ASSERT_TRUE(variant);
    street.characters[0].variant = *variant;
    const auto [drawn, authored] = againstReference(street, own, kSize);
    std::printf("MaterialsVariantsShoe 'street' against the reference: %.2f dB, %.2f dB with the "
                "file's own materials\n",
                drawn, authored);
    EXPECT_GE(drawn, 35.0); // measured 39.1 dB
    EXPECT_GT(drawn, authored + 3.0);
}

TEST_F(Materials, SpecularWeightsAndColoursTheDielectricReflectionOnTheGpuAndInTheReference) {
    // SpecularTest's spheres (KHR_materials_specular: factor, texture, colour factor and
    // texture, a colour over 1), scored where the extension changes the GPU's frame (the
    // spheres, not the labels): the GPU's frame and the reference's agree; the same spheres
    // with the extension dropped (glTF's core F0, weight 1) do not.
    GLASS_REQUIRE_SHARED();
    const std::string file = "SpecularTest/glTF-Binary/SpecularTest.glb";
    const auto [followed, ignored] = againstReference(
        sharedWorld(file,
                    [](scene::Model& m) {
                        EXPECT_GT(
                            std::count_if(m.materials.begin(), m.materials.end(),
                                          [](const scene::Material& x) { return x.hasSpecular; }),
                            20);
                    }),
        sharedWorld(file,
                    [](scene::Model& m) {
                        for (scene::Material& x : m.materials)
                            x.hasSpecular = false;
                    }),
        256, true);
    std::printf("SpecularTest against the reference, where the extension changes the frame: "
                "%.2f dB, %.2f dB without the extension\n",
                followed, ignored);
    EXPECT_GE(followed, 55.0); // measured 68.5 dB (14.5 without the extension)
    EXPECT_GT(followed, ignored + 5.0);
}

/** Whether any material of `m` satisfies `has`. */
std::size_t countMaterials(const scene::Model& m, bool (*has)(const scene::Material&)) {
    return std::size_t(std::count_if(m.materials.begin(), m.materials.end(), has));
}

/** `world` with the lights of the default test rig: a point light in front, a warm spot from
 *  above right and a dim directional light, placed around the world's bounds. */
scene::World withTestLights(scene::World world) {
    const render::Bounds b = render::worldBounds(world);
    const glm::vec3 c = b.center();
    const float r = std::max(b.radius(), 1e-3f);
    scene::PlacedLight point, spot, sun;
    point.light.type = scene::Light::Type::Point;
    point.light.intensity = 6.0f * r * r;
    point.position = c + glm::vec3(0.0f, 0.3f, 2.0f) * r;
    spot.light.type = scene::Light::Type::Spot;
    spot.light.color = {1.0f, 0.6f, 0.4f};
    spot.light.intensity = 10.0f * r * r;
    spot.light.innerConeAngle = 0.2f;
    spot.light.outerConeAngle = 0.5f;
    spot.position = c + glm::vec3(1.5f, 1.5f, 1.5f) * r;
    spot.direction = glm::normalize(c - spot.position);
    sun.light.type = scene::Light::Type::Directional;
    sun.light.intensity = 0.8f;
    sun.direction = glm::normalize(glm::vec3(-1.0f, -1.0f, -1.0f));
    world.lights = {point, spot, sun};
    return world;
}

TEST_F(Materials, ClearcoatReflectsOverTheBaseOnTheGpuAndInTheReference) {
    // ClearCoatTest (KHR_materials_clearcoat: factor, texture, roughness, its own normal map),
    // scored where the coat changes the GPU's frame: the GPU's frame and the reference's
    // agree; the same shapes without the coat do not.
    GLASS_REQUIRE_SHARED();
    const std::string file = "ClearCoatTest/glTF-Binary/ClearCoatTest.glb";
    const auto [followed, ignored] = againstReference(
        sharedWorld(file,
                    [](scene::Model& m) {
                        EXPECT_GE(countMaterials(
                                      m, [](const scene::Material& x) { return x.hasClearcoat; }),
                                  6u);
                    }),
        sharedWorld(file,
                    [](scene::Model& m) {
                        for (scene::Material& x : m.materials)
                            x.hasClearcoat = false;
                    }),
        256, true);
    std::printf("ClearCoatTest against the reference, where the coat changes the frame: %.2f dB, "
                "%.2f dB without it\n",
                followed, ignored);
    EXPECT_GE(followed, kClearcoatFloor);
    EXPECT_GT(followed, ignored + 3.0);
}

TEST_F(Materials, SheenLightsTheVelvetOnTheGpuAndInTheReference) {
    // SheenChair's velvet (KHR_materials_sheen: colour and roughness) under the test lights.
    GLASS_REQUIRE_SHARED();
    const std::string file = "SheenChair/glTF/SheenChair.gltf";
    const auto [followed, ignored] = againstReference(
        withTestLights(sharedWorld(
            file,
            [](scene::Model& m) {
                EXPECT_EQ(countMaterials(m, [](const scene::Material& x) { return x.hasSheen; }),
                          2u);
            })),
        withTestLights(sharedWorld(file,
                                   [](scene::Model& m) {
                                       for (scene::Material& x : m.materials)
                                           x.hasSheen = false;
                                   })),
        kSize, true);
    std::printf("SheenChair against the reference, where the sheen changes the frame: %.2f dB, "
                "%.2f dB without it\n",
                followed, ignored);
    EXPECT_GE(followed, kSheenFloor);
    EXPECT_GT(followed, ignored + 3.0);
}

/** builtin:sphere made opaque (a grey dielectric, roughness 0.3) and then changed by
 *  `change`, in a world of its own. */
scene::World sphereWorld(const std::function<void(scene::Model&)>& change) {
    auto loaded = asset::loadModel("builtin:sphere");
    EXPECT_TRUE(loaded.ok());
    scene::Model model = std::move(*loaded);
    scene::Material& m = model.materials.at(0);
    m.hasTransmission = false;
    m.transmissionFactor = 0.0f;
    m.baseColorFactor = glm::vec4(0.6f, 0.6f, 0.6f, 1.0f);
    m.roughnessFactor = 0.3f;
    change(model);
    return scene::singleCharacterWorld(std::make_shared<const scene::Model>(std::move(model)));
}

TEST_F(Materials, EachLayerOnASphereAgreesWithTheReference) {
    // Each layer alone on an untextured sphere under the test lights, where nothing but the
    // layer differs from the reference's model: a clear coat, a sheen, a thin film on a metal
    // and on a dielectric (KHR_materials_iridescence; IridescenceLamp's film is on thin parts
    // that touch its glass globe, its golden shows it). Each alike on both, and far off
    // without it.
    const std::pair<const char*, std::function<void(scene::Material&)>> layers[] = {
        {"a clear coat",
         [](scene::Material& m) {
             m.baseColorFactor = glm::vec4(0.6f, 0.1f, 0.1f, 1.0f);
             m.roughnessFactor = 0.7f;
             m.hasClearcoat = true;
             m.clearcoatFactor = 0.9f;
             m.clearcoatRoughnessFactor = 0.05f;
         }},
        {"a sheen",
         [](scene::Material& m) {
             m.baseColorFactor = glm::vec4(0.1f, 0.1f, 0.3f, 1.0f);
             m.roughnessFactor = 0.9f;
             m.hasSheen = true;
             m.sheenColorFactor = {1.0f, 0.5f, 0.2f};
             m.sheenRoughnessFactor = 0.4f;
         }},
        {"a film on a metal",
         [](scene::Material& m) {
             m.metallicFactor = 1.0f;
             m.baseColorFactor = glm::vec4(0.9f, 0.8f, 0.6f, 1.0f);
             m.hasIridescence = true;
             m.iridescenceFactor = 1.0f;
             m.iridescenceIor = 1.6f;
             m.iridescenceThicknessMaximum = 480.0f;
         }},
        {"a film on a dielectric", [](scene::Material& m) {
             m.metallicFactor = 0.0f;
             m.hasIridescence = true;
             m.iridescenceFactor = 0.8f;
             m.iridescenceIor = 1.3f;
             m.iridescenceThicknessMaximum = 350.0f;
         }}};
    for (const auto& entry : layers) {
        const char* name = entry.first;
        const std::function<void(scene::Material&)>& layer = entry.second;
        auto sphere = [&layer](bool on) {
            return withTestLights(sphereWorld([&](scene::Model& model) {
                scene::Material& m = model.materials[0];
                layer(m);
                if (!on)
                    m.hasClearcoat = m.hasSheen = m.hasIridescence = false;
            }));
        };
        const auto [followed, ignored] = againstReference(sphere(true), sphere(false), kSize, true);
        std::printf("a sphere with %s against the reference, where it changes the frame: %.2f dB, "
                    "%.2f dB without it\n",
                    name, followed, ignored);
        EXPECT_GE(followed, kSphereLayerFloor) << name;
        EXPECT_GT(followed, ignored + 5.0) << name;
    }
}

TEST_F(Materials, PunctualLightsOnNodesLightTheSphereOnTheGpuAndInTheReference) {
    // KHR_lights_punctual as a file has it: a point light and a spot on nodes of the model (the
    // spot looks down its node's -z), placed by the node transforms.
    auto sphere = [](bool lights) {
        return sphereWorld([lights](scene::Model& model) {
            if (!lights)
                return;
            scene::Light point, spot;
            point.intensity = 8.0f;
            point.color = {1.0f, 0.8f, 0.6f};
            spot.type = scene::Light::Type::Spot;
            spot.intensity = 20.0f;
            spot.innerConeAngle = 0.1f;
            spot.outerConeAngle = 0.3f;
            spot.range = 10.0f;
            model.lights = {point, spot};
            for (int k = 0; k < 2; ++k) {
                scene::Node node;
                node.light = k;
                node.rest.translation =
                    k == 0 ? glm::dvec3(1.5, 1.5, 1.5) : glm::dvec3(0.3, 0.0, 3.0);
                model.nodes.push_back(node);
                model.scenes[0].push_back(int(model.nodes.size()) - 1);
            }
        });
    };
    const auto [lit, unlit] = againstReference(sphere(true), sphere(false), kSize, true);
    std::printf("a sphere lit by a point light and a spot on nodes against the reference, where "
                "they change the frame: %.2f dB, %.2f dB without them\n",
                lit, unlit);
    EXPECT_GE(lit, kNodeLightsFloor);
    EXPECT_GT(lit, unlit + 5.0);
}

TEST_F(Materials, AnisotropyStretchesTheHighlightsOnTheGpuAndInTheReference) {
    // AnisotropyStrengthTest's spheres (KHR_materials_anisotropy strength 0..1 by roughness
    // 0..1) under the test lights: their highlights become arcs, alike on both.
    GLASS_REQUIRE_SHARED();
    const std::string file = "AnisotropyStrengthTest/glTF-Binary/AnisotropyStrengthTest.glb";
    const auto [followed, ignored] =
        againstReference(withTestLights(sharedWorld(file)),
                         withTestLights(sharedWorld(file,
                                                    [](scene::Model& m) {
                                                        for (scene::Material& x : m.materials)
                                                            x.hasAnisotropy = false;
                                                    })),
                         256, true);
    std::printf("AnisotropyStrengthTest against the reference, where anisotropy changes the "
                "frame: %.2f dB, %.2f dB without it\n",
                followed, ignored);
    EXPECT_GE(followed, kAnisotropyFloor);
    EXPECT_GT(followed, ignored + 3.0);
}

TEST_F(Materials, PunctualLightsOfAFileLightItOnTheGpuAndInTheReference) {
    // LightsPunctualLamp's five point lights (KHR_lights_punctual, on its nodes) light its
    // metal on the GPU as in the reference (scored outside its glass shade, whose transmission
    // texture the GPU's glass does not read); without them the frame is far off.
    GLASS_REQUIRE_SHARED();
    const std::string file = "LightsPunctualLamp/glTF/LightsPunctualLamp.gltf";
    const auto [lit, unlit] =
        againstReference(sharedWorld(file, [](scene::Model& m) { EXPECT_EQ(m.lights.size(), 5u); }),
                         sharedWorld(file,
                                     [](scene::Model& m) {
                                         for (scene::Node& n : m.nodes)
                                             n.light = -1;
                                     }),
                         kSize, true, true);
    std::printf("LightsPunctualLamp against the reference, where the lights change the frame: "
                "%.2f dB, %.2f dB without them\n",
                lit, unlit);
    EXPECT_GE(lit, kLightsFloor);
    EXPECT_GT(lit, unlit + 3.0);
}

TEST_F(Materials, UnlitSurfacesTakeNoLightOnTheGpuAndInTheReference) {
    // UnlitTest (KHR_materials_unlit) under the test lights: its base colour is its colour on
    // both, the deferred lighting adding nothing to it; lit as metallic-roughness, it is not.
    GLASS_REQUIRE_SHARED();
    const std::string file = "UnlitTest/glTF-Binary/UnlitTest.glb";
    const auto [unlit, lit] = againstReference(
        withTestLights(sharedWorld(file,
                                   [](scene::Model& m) {
                                       EXPECT_TRUE(std::all_of(
                                           m.materials.begin(), m.materials.end(),
                                           [](const scene::Material& x) { return x.unlit; }));
                                   })),
        withTestLights(sharedWorld(file,
                                   [](scene::Model& m) {
                                       for (scene::Material& x : m.materials)
                                           x.unlit = false;
                                   })),
        kSize);
    std::printf("UnlitTest under lights against the reference: %.2f dB, %.2f dB lit\n", unlit, lit);
    EXPECT_GE(unlit, kUnlitFloor);
    EXPECT_GT(unlit, lit + 5.0);
}

TEST_F(Materials, LitOpaqueSurfacesAreShadedOncePerPixelAndLayeredOnesAsDrawn) {
    // With punctual lights, the opaque pass writes the materials without layers into the
    // surface targets and the lighting pass shades them; a material with layers is drawn and
    // shaded after it (opaque_layers), where the frame has such a surface. With the environment
    // alone, the opaque pass shades every surface as drawn. A sphere beside a layered one, the
    // two frames against the reference.
    auto spheres = [](int layered, bool lights) {
        scene::World world;
        for (int k = 0; k < 2; ++k) {
            auto loaded = asset::loadModel("builtin:sphere");
            EXPECT_TRUE(loaded.ok());
            scene::Model model = std::move(*loaded);
            model.materials.at(0).baseColorFactor = {0.8f, 0.3f, 0.2f, 1.0f};
            if (k < layered)
                test::matrix::addMaterialLayers(model.materials.at(0));
            scene::World one =
                scene::singleCharacterWorld(std::make_shared<const scene::Model>(std::move(model)));
            one.characters.at(0).placement.translation = {2.5 * k, 0.0, 0.0};
            one.characters.at(0).glass = scene::GlassMode::None;
            world.characters.push_back(one.characters.at(0));
        }
        return lights ? withTestLights(std::move(world)) : world;
    };
    const auto passes = [&](scene::World world) {
        WorldRig rig(std::move(world), context(), 64);
        std::vector<std::string> names;
        rig.render(0.0, &names);
        return names;
    };
    const auto has = [](const std::vector<std::string>& names, const char* name) {
        return std::find(names.begin(), names.end(), name) != names.end();
    };
    const auto mixed = passes(spheres(1, true));
    EXPECT_TRUE(has(mixed, "opaque") && has(mixed, "lighting") && has(mixed, "opaque_layers"));
    const auto plain = passes(spheres(0, true));
    EXPECT_TRUE(has(plain, "lighting") && !has(plain, "opaque_layers"));
    const auto layered = passes(spheres(2, true));
    EXPECT_TRUE(has(layered, "opaque") && !has(layered, "lighting"));
    const auto environment = passes(spheres(1, false));
    EXPECT_TRUE(has(environment, "opaque") && !has(environment, "lighting") &&
                !has(environment, "opaque_layers"));
    const auto [lit, dark] = againstReference(spheres(1, true), spheres(1, false), kSize, true);
    std::printf("a plain and a layered sphere under the test lights against the reference: "
                "%.2f dB, %.2f dB without the lights\n",
                lit, dark);
    EXPECT_GE(lit, kSphereLayerFloor);
    EXPECT_GT(lit, dark + 5.0);
}

// A glass texture is read only where some glass of the frame has one of its kind: a CPU
// rasteriser reads a texture that a branch skips, and the trace's read switches over every unit
// the variant has. The capture's and the trace's variants, for the textured sphere with its
// base colour alone and with its transmission and metallic-roughness textures too.
TEST_F(Materials, GlassTexturesAreReadOnlyWhereTheFrameHasThem) {
    const auto variants = [&](bool transmissionTextures) {
        scene::World world = test::matrix::texturedGlass();
        scene::Model model = *world.characters[0].model;
        if (!transmissionTextures)
            model.materials[0].transmissionTexture =
                model.materials[0].metallicRoughnessTexture = {};
        world.characters[0].model = std::make_shared<const scene::Model>(std::move(model));
        WorldRig rig(std::move(world), context(), 32);
        rig.set("method", "trace");
        rig.renderHdr();
        return rig.renderer().programVariantKeys();
    };
    // Whether the variant of `shader` has `define`.
    const auto has = [](const std::vector<std::string>& keys, const std::string& shader,
                        const std::string& define) {
        const auto key = std::find_if(keys.begin(), keys.end(), [&](const std::string& k) {
            return k.find(shader) != std::string::npos;
        });
        EXPECT_NE(key, keys.end()) << shader;
        return key != keys.end() && key->find("\n" + define + "\n") != std::string::npos;
    };
    const auto base = variants(false), all = variants(true);
    for (const char* shader : {"layer_capture.frag.glsl", "walk.frag.glsl"}) {
        EXPECT_TRUE(has(base, shader, "GLASS_BASE_COLOR_TEXTURES 1")) << shader;
        EXPECT_TRUE(has(base, shader, "GLASS_TRANSMISSION_TEXTURES 0")) << shader;
        EXPECT_TRUE(has(base, shader, "TRACED_TEXTURES_USED 1")) << shader;
        EXPECT_TRUE(has(all, shader, "GLASS_TRANSMISSION_TEXTURES 1")) << shader;
        EXPECT_TRUE(has(all, shader, "TRACED_TEXTURES_USED 3")) << shader;
    }
}

TEST_F(Materials, EmissiveStrengthBrightensTheEmissionOnTheGpuAndInTheReference) {
    // EmissiveStrengthTest's cubes (KHR_materials_emissive_strength 1 to 16).
    GLASS_REQUIRE_SHARED();
    const std::string file = "EmissiveStrengthTest/glTF-Binary/EmissiveStrengthTest.glb";
    const auto [followed, ignored] =
        againstReference(sharedWorld(file),
                         sharedWorld(file,
                                     [](scene::Model& m) {
                                         for (scene::Material& x : m.materials)
                                             x.emissiveStrength = 1.0f;
                                     }),
                         kSize, true);
    std::printf("EmissiveStrengthTest against the reference, where the strength changes the "
                "frame: %.2f dB, %.2f dB without it\n",
                followed, ignored);
    EXPECT_GE(followed, kEmissiveFloor);
    EXPECT_GT(followed, ignored + 3.0);
}

TEST_F(Materials, GlassReflectsThroughItsSpecularColourAndFilmOnTheGpuAndInTheReference) {
    // A glass sphere with KHR_materials_specular's colour and weight, an iridescent film, a
    // clear coat and a sheen, under the test lights (their highlights on the glass): the GPU's
    // glass and the reference's agree, and glass without the layers does not.
    auto glass = [](bool layers) {
        auto loaded = asset::loadModel("builtin:sphere");
        EXPECT_TRUE(loaded.ok());
        scene::Model model = std::move(*loaded);
        scene::Material& m = model.materials.at(0);
        m.hasTransmission = true;
        m.transmissionFactor = 1.0f;
        m.roughnessFactor = 0.15f;
        if (layers)
            test::matrix::addMaterialLayers(m);
        return withTestLights(
            scene::singleCharacterWorld(std::make_shared<const scene::Model>(std::move(model))));
    };
    const auto [followed, ignored] = againstReference(glass(true), glass(false), kSize, true);
    std::printf("a layered glass sphere against the reference, where the layers change the "
                "frame: %.2f dB, %.2f dB without them\n",
                followed, ignored);
    EXPECT_GE(followed, kGlassLayersFloor);
    EXPECT_GT(followed, ignored + 3.0);
}

} // namespace

namespace {

/** A world whose clip plays KHR_animation_pointer properties, beside the same world with their
 *  values at the time scored set; the floor its frame meets against the reference. */
struct AnimatedCase {
    const char* name;
    scene::World animated, fixed;
    double floor;
};

/** `make(animated)`'s world, its model's clip played where animated. */
scene::World played(const std::function<scene::World(bool)>& make, bool animated) {
    scene::World world = make(animated);
    if (animated)
        world.characters[0].play(0);
    return world;
}

/** The worlds of Materials.AnimatedPointersPlayOnTheGpuAndInTheReference at time `t`: an opaque
 *  sphere's factors, a glass's, a glass's texture transform and a light of the model, built in
 *  memory as the loader makes them; then all but the first together, through a glTF file. */
std::vector<AnimatedCase> animatedCases(double t) {
    using P = scene::PointerProperty;
    using test::matrix::animatePointers;
    const auto mix = [t](glm::vec4 a, glm::vec4 b) { return a + (b - a) * float(t); };
    const glm::vec4 grey(0.6f, 0.6f, 0.6f, 1.0f), blue(0.1f, 0.5f, 0.9f, 1.0f);
    const glm::vec4 rough0(0.3f), rough1(0.8f), ior0(1.2f), ior1(1.8f), tr0(1.0f), tr1(0.6f);
    const glm::vec4 offset0(0.1f, 0.0f, 0.0f, 0.0f), offset1(0.35f, 0.2f, 0.0f, 0.0f);
    const glm::vec4 turn0(0.0f), turn1(0.6f), power0(8.0f), power1(30.0f), cone0(0.45f),
        cone1(0.8f), white(1.0f), amber(1.0f, 0.55f, 0.2f, 1.0f);
    const auto opaque = [&](bool animated) {
        return withTestLights(sphereWorld([&](scene::Model& model) {
            if (animated) {
                animatePointers(model,
                                {{P::BaseColor, grey, blue}, {P::Roughness, rough0, rough1}});
                return;
            }
            model.materials[0].baseColorFactor = mix(grey, blue);
            model.materials[0].roughnessFactor = mix(rough0, rough1).x;
        }));
    };
    const auto glass = [&](bool animated) {
        scene::Material m = test::matrix::glassMaterial();
        if (!animated) {
            m.ior = mix(ior0, ior1).x;
            m.transmissionFactor = mix(tr0, tr1).x;
        }
        scene::World world = test::matrix::glassSphere(std::move(m));
        scene::Model model = *world.characters[0].model;
        if (animated)
            animatePointers(model, {{P::Ior, ior0, ior1}, {P::Transmission, tr0, tr1}});
        world.characters[0].model = std::make_shared<const scene::Model>(std::move(model));
        return world;
    };
    const auto textured = [&](bool animated) { // the base colour's transform slides and turns
        scene::World world = test::matrix::texturedGlass();
        scene::Model model = *world.characters[0].model;
        scene::TextureRef& base = model.materials[0].baseColorTexture;
        if (animated)
            animatePointers(model, {{P::TextureOffset, offset0, offset1, 0, 0},
                                    {P::TextureRotation, turn0, turn1, 0, 0}});
        else
            base.setUv({glm::vec2(mix(offset0, offset1)), mix(turn0, turn1).x, base.uv.scale});
        world.characters[0].model = std::make_shared<const scene::Model>(std::move(model));
        return world;
    };
    const auto lamp = [&](bool animated) { // a spot of the model's brightens, warms and widens
        test::matrix::Composer c;
        c.part(true, c.material(test::matrix::opaqueMaterial(glm::vec3(0.7f), 0.0f, 0.4f)),
               glm::dvec3(0.0));
        scene::Light spot;
        spot.type = scene::Light::Type::Spot;
        spot.innerConeAngle = 0.25f;
        spot.intensity = animated ? power0.x : mix(power0, power1).x;
        spot.color = animated ? glm::vec3(white) : glm::vec3(mix(white, amber));
        spot.outerConeAngle = animated ? cone0.x : mix(cone0, cone1).x;
        c.light(spot, glm::dvec3(0.6, 0.8, 2.5));
        if (animated)
            animatePointers(c.model, {{P::LightIntensity, power0, power1},
                                      {P::LightColor, white, amber},
                                      {P::LightOuterCone, cone0, cone1}});
        return c.world();
    };
    const auto file = [&](bool animated) { // the same channels, through a file and the loader
        test::TempDir dir;
        auto loaded = asset::loadGltf(test::pointerGlassSphereModel().save(dir.path(), "sphere"));
        EXPECT_TRUE(loaded.ok()) << (loaded.ok() ? "" : loaded.error().message);
        scene::Model model = std::move(*loaded);
        if (!animated) {
            model.animations.clear();
            scene::Material& m = model.materials.at(0);
            m.ior = mix(ior0, ior1).x;
            m.transmissionFactor = mix(tr0, tr1).x;
            m.baseColorTexture.setUv(
                {glm::vec2(mix(offset0, offset1)), 0.0f, m.baseColorTexture.uv.scale});
            model.lights.at(0).intensity = mix(power0, power1).x;
            model.lights.at(0).color = glm::vec3(mix(white, amber));
        }
        return scene::singleCharacterWorld(std::make_shared<const scene::Model>(std::move(model)));
    };
    std::vector<AnimatedCase> cases;
    const auto add = [&](const char* name, const std::function<scene::World(bool)>& make,
                         double floor) {
        cases.push_back({name, played(make, true), played(make, false), floor});
    };
    add("an opaque sphere's base colour and roughness", opaque, 60.0); // measured 64.2 dB
    add("a glass sphere's IOR and transmission", glass, 43.0);         // measured 44.9 dB
    add("a glass sphere's texture transform", textured, 33.0);         // measured 35.2 dB
    add("a spot light of the model", lamp, 60.0);                      // measured 64.0 dB
    add("a glTF file's glass, texture transform and spot light", file, 30.0);
    return cases;
}

} // namespace

TEST_F(Materials, AnimatedPointersPlayOnTheGpuAndInTheReference) {
    // Each case played by its clip to 0.7 s: the frame is the frame of the same world with the
    // values set (within 1/255), agrees with the reference at 0.7 s, and differs from the frame
    // at 0.
    const double t = 0.7;
    for (AnimatedCase& c : animatedCases(t)) {
        SCOPED_TRACE(c.name);
        WorldRig rig(c.animated, context(), kSize), fixed(c.fixed, context(), kSize);
        fixed.setCamera(rig.camera());
        const capture::Image played = rig.render(t), set = fixed.render(t);
        int most = 0;
        for (std::size_t i = 0; i < played.rgba.size(); ++i)
            most = std::max(most, std::abs(int(played.rgba[i]) - int(set.rgba[i])));
        EXPECT_LE(most, 1) << "the played values against the same values set";
        const auto reference = rig.reference(t, WorldRig::Evaluation::Deterministic);
        // An opaque sphere over the whole frame; the glass over its mask.
        const bool masked =
            std::find(reference.mask.begin(), reference.mask.end(), true) != reference.mask.end();
        const double agreed =
            capture::score(played, reference.image, masked ? &reference.mask : nullptr).psnr;
        const capture::Image start = rig.render(0.0);
        std::printf("%s played to %.1f s: %.2f dB against the reference; the frame at 0 differs "
                    "by %.2f dB\n",
                    c.name, t, agreed, capture::score(start, played).psnr);
        EXPECT_GE(agreed, c.floor);
        EXPECT_LT(capture::score(start, played).psnr, 40.0) << "the values changed the frame";
    }
}
