// The GPU deform pass against the CPU reference: every skinned or morphing model, several times.
#include "support/GlTest.h"
#include "support/TestSupport.h"

#include "engine/anim/Pose.h"
#include "engine/asset/GltfLoader.h"
#include "engine/deform/CpuDeformer.h"
#include "engine/deform/GpuDeformer.h"
#include "engine/render/Camera.h"
#include "engine/render/Environment.h"
#include "engine/render/Renderer.h"

#include <glm/gtc/quaternion.hpp>

#include <fstream>

namespace {

class GpuDeform : public test::GlTest {
protected:
    /** Max position error over the bounding-box diagonal and max normal angle error
     *  (1 - cos) at `clip`/`times`. */
    void compare(const scene::Model& model, int clip, const std::vector<double>& times) {
        auto deformer = deform::GpuDeformer::create(model, shaders());
        ASSERT_TRUE(deformer.ok()) << deformer.error().message;
        for (double time : times) {
            const anim::Pose pose = anim::evaluate(model, clip, time);
            (*deformer)->update(pose);
            expectMatchesCpu(**deformer, model, pose, time);
        }
    }

    /** `deformer`'s buffers as `pose` left them, against the CPU oracle. */
    void expectMatchesCpu(const deform::GpuDeformer& deformer, const scene::Model& model,
                          const anim::Pose& pose, double time) {
        const auto cpu = deform::deformScene(model, pose);
        ASSERT_EQ(cpu.size(), deformer.instances().size());
        for (std::size_t i = 0; i < cpu.size(); ++i)
            for (std::size_t p = 0; p < cpu[i].primitives.size(); ++p) {
                const auto gpu = deformer.download(i, p);
                const auto& ref = cpu[i].primitives[p];
                glm::dvec3 lo(1e300), hi(-1e300);
                for (const auto& v : ref.positions) {
                    lo = glm::min(lo, v);
                    hi = glm::max(hi, v);
                }
                const double diagonal = std::max(glm::length(hi - lo), 1e-12);
                double position = 0.0, normal = 0.0;
                for (std::size_t v = 0; v < ref.positions.size(); ++v) {
                    position = std::max(position, glm::length(gpu.positions[v] - ref.positions[v]));
                    normal = std::max(normal, glm::length(gpu.normals[v] - ref.normals[v]));
                }
                SCOPED_TRACE(model.sourceName + " t=" + std::to_string(time) + " instance " +
                             std::to_string(i) + " primitive " + std::to_string(p));
                EXPECT_LE(position / diagonal, 1e-4);
                EXPECT_LE(normal, 1e-3);
            }
    }
};

/** The two-joint model with a second mesh node and a second skin over the same joints in the
 *  other order, in `dir`. */
std::filesystem::path twoSkinsFile(const test::TempDir& dir) {
    test::GltfBuilder builder = test::twoJointModel();
    const auto inverseBind = builder.doc["skins"][0]["inverseBindMatrices"];
    builder.doc["skins"].push_back({{"joints", {2, 1}}, {"inverseBindMatrices", inverseBind}});
    builder.doc["nodes"].push_back(
        {{"name", "second"}, {"mesh", 0}, {"skin", 1}, {"translation", {0.0, 2.0, 0.0}}});
    builder.doc["scenes"][0]["nodes"].push_back(3);
    return builder.save(dir.path(), "twoskins");
}

TEST_F(GpuDeform, TwoJointModelMatchesCpu) {
    test::TempDir dir;
    auto model = asset::loadGltf(test::twoJointModel().save(dir.path(), "twojoint"));
    ASSERT_TRUE(model.ok());
    compare(*model, 0, {0.0, 0.3, 0.77, 1.0});
}

TEST_F(GpuDeform, FileWithTwoSkinsMatchesCpu) {
    // Its JOINTS_0 indices name the other joint under the second skin: two skins, two results.
    test::TempDir dir;
    auto model = asset::loadGltf(twoSkinsFile(dir));
    ASSERT_TRUE(model.ok()) << model.error().message;
    ASSERT_EQ(model->skins.size(), 2u);
    compare(*model, 0, {0.0, 0.4, 0.9});
    // Not vacuous: in the world (where one skin over the same joints would put both copies in
    // the same place, glTF skinning ignoring the mesh node's transform) the copies differ.
    const auto cpu = deform::deformScene(*model, anim::evaluate(*model, 0, 0.9));
    ASSERT_EQ(cpu.size(), 2u);
    const auto first = deform::toWorld(cpu[0].primitives[0], cpu[0].meshToWorld);
    const auto second = deform::toWorld(cpu[1].primitives[0], cpu[1].meshToWorld);
    double differs = 0.0;
    for (std::size_t v = 0; v < first.positions.size(); ++v)
        differs = std::max(differs, glm::length(first.positions[v] - second.positions[v]));
    EXPECT_GT(differs, 1e-3);
}

TEST_F(GpuDeform, PlacementsOfOneUploadDeformIndependently) {
    test::TempDir dir;
    auto model = asset::loadGltf(test::twoJointModel().save(dir.path(), "twojoint"));
    ASSERT_TRUE(model.ok());
    auto uploaded = deform::GpuModel::create(*model);
    ASSERT_TRUE(uploaded.ok()) << uploaded.error().message;
    auto first = deform::GpuDeformer::create(*uploaded, shaders());
    auto second = deform::GpuDeformer::create(*uploaded, shaders());
    ASSERT_TRUE(first.ok() && second.ok());
    // The static buffers are the upload's, once; the deformed ones each placement's own.
    const auto& a = (*first)->instances()[0].primitives[0];
    const auto& b = (*second)->instances()[0].primitives[0];
    EXPECT_EQ(a.indices, b.indices);
    EXPECT_EQ(a.uvs, b.uvs);
    EXPECT_NE(a.deformed, b.deformed);
    const anim::Pose early = anim::evaluate(*model, 0, 0.2), late = anim::evaluate(*model, 0, 0.9);
    (*first)->update(early);
    (*second)->update(late);
    expectMatchesCpu(**first, *model, early, 0.2);
    expectMatchesCpu(**second, *model, late, 0.9);
    // Not vacuous: the two poses differ where the oracle says they do.
    const auto cpuEarly = deform::deformScene(*model, early);
    const auto cpuLate = deform::deformScene(*model, late);
    double moved = 0.0;
    for (std::size_t v = 0; v < cpuEarly[0].primitives[0].positions.size(); ++v)
        moved = std::max(moved, glm::length(cpuEarly[0].primitives[0].positions[v] -
                                            cpuLate[0].primitives[0].positions[v]));
    EXPECT_GT(moved, 1e-3);
}

TEST_F(GpuDeform, WorldOfCharactersMatchesCpuThroughOneUpload) {
    // Two characters of one model at other phases, speeds and transforms, one of a file with
    // two skins, and one blending layers through a crossfade: the renderer stages all their skin
    // matrices into one upload and deforms each; every character's vertices in the world equal the
    // CPU oracle's.
    test::TempDir dir;
    auto oneSkin = asset::loadGltf(test::twoJointModel().save(dir.path(), "twojoint"));
    auto twoSkins = asset::loadGltf(twoSkinsFile(dir));
    ASSERT_TRUE(oneSkin.ok() && twoSkins.ok());
    const auto shared = std::make_shared<const scene::Model>(std::move(*oneSkin));
    scene::World world;
    for (int k = 0; k < 3; ++k) {
        scene::Character c;
        c.name = "character " + std::to_string(k);
        c.model = k < 2 ? shared : std::make_shared<const scene::Model>(std::move(*twoSkins));
        c.play(0);
        c.performance.layers[0].timeOffset = 0.31 * k;
        c.performance.layers[0].speed = k == 1 ? -0.7 : 1.0;
        c.placement.translation = glm::dvec3(1.5 * k, 0.2 * k, -0.5 * k);
        c.placement.rotation = glm::angleAxis(0.4 * k + 0.1, glm::normalize(glm::dvec3(0.2, 1, 0)));
        c.placement.scale = glm::dvec3(1.0 + 0.25 * k);
        world.characters.push_back(std::move(c));
    }
    // A fourth blends: a weighted layer, an additive one, a crossfade and a morph weight added.
    scene::Character blended = world.characters[0];
    blended.name = "blended";
    blended.placement.translation.x -= 1.5;
    scene::Performance& blend = blended.performance;
    blend.layers[0].weight = 0.6;
    blend.layers.push_back(blend.layers[0]);
    blend.layers[1].additive = true;
    blend.layers[1].weight = 0.5;
    blend.layers[1].timeOffset = 0.2;
    blend.transitions = {{0.3, 0, 0.5}};
    blend.morphs = {{-1, 0, 0.2, true}};
    world.characters.push_back(std::move(blended));
    auto renderer = render::Renderer::create(render::Environment::proceduralSky(16), context());
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    render::RenderSettings settings;
    settings.size = {16, 16};
    for (double time : {0.0, 0.45, 1.3}) {
        auto frame = (*renderer)->render(
            world, render::frameBounds(render::worldBounds(world), 1.0f), settings, time);
        ASSERT_TRUE(frame.ok()) << frame.error().message;
        ASSERT_EQ((*renderer)->characterCount(), world.characters.size());
        std::vector<std::vector<glm::dvec3>> placed;
        for (std::size_t c = 0; c < world.characters.size(); ++c) {
            const deform::GpuDeformer& gpu = (*renderer)->geometry(c);
            const auto cpu = deform::deformCharacter(world.characters[c], time);
            ASSERT_EQ(cpu.size(), gpu.instances().size());
            std::vector<glm::dvec3> positions;
            for (std::size_t i = 0; i < cpu.size(); ++i) {
                const auto ref = deform::toWorld(cpu[i].primitives[0], cpu[i].meshToWorld);
                const auto got = gpu.download(i, 0);
                const glm::dmat4 meshToWorld(gpu.instances()[i].meshToWorld);
                double error = 0.0;
                for (std::size_t v = 0; v < ref.positions.size(); ++v) {
                    const glm::dvec3 p(meshToWorld * glm::dvec4(got.positions[v], 1.0));
                    error = std::max(error, glm::length(p - ref.positions[v]));
                    positions.push_back(p);
                }
                SCOPED_TRACE("character " + std::to_string(c) + " instance " + std::to_string(i) +
                             " t=" + std::to_string(time));
                EXPECT_LE(error, 1e-4);
            }
            placed.push_back(std::move(positions));
        }
        // Not vacuous: the two characters of one model are posed and placed apart.
        double apart = 0.0;
        for (std::size_t v = 0; v < placed[0].size(); ++v)
            apart = std::max(apart, glm::length(placed[0][v] - placed[1][v]));
        EXPECT_GT(apart, 0.5);
    }
}

TEST_F(GpuDeform, EverySharedSkinnedOrMorphingModelMatchesCpu) {
    GLASS_REQUIRE_SHARED();
    std::ifstream in(test::sharedDir() / "assets/INVENTORY.json");
    const auto inventory = nlohmann::json::parse(in);
    int compared = 0;
    for (const auto& entry : inventory["models"]) {
        if (entry["skins"] == 0 && entry["morph_primitives"] == 0)
            continue;
        auto model =
            asset::loadGltf(test::sharedDir() / "assets" / entry["file"].get<std::string>());
        ASSERT_TRUE(model.ok()) << model.error().message;
        const int clip = model->animations.empty() ? -1 : 0;
        const double duration = clip < 0 ? 0.0 : model->animations[0].duration;
        compare(*model, clip, {0.0, 0.37 * duration, 0.81 * duration, duration});
        ++compared;
    }
    EXPECT_GE(compared, 7);
}

TEST_F(GpuDeform, EveryGpuInstanceOfASkinnedNodeIsDeformedAndPlacedAsTheCpuDoes) {
    // EXT_mesh_gpu_instancing on a skinned node: one placement per instance, each deformed as
    // the oracle deforms it and moved by its instance transform.
    test::TempDir dir;
    auto model = asset::loadGltf(test::instancedTwoJointModel().save(dir.path(), "instanced"));
    ASSERT_TRUE(model.ok()) << model.error().message;
    auto deformer = deform::GpuDeformer::create(*model, shaders());
    ASSERT_TRUE(deformer.ok()) << deformer.error().message;
    ASSERT_EQ((*deformer)->instances().size(), 3u);
    const anim::Pose pose = anim::evaluate(*model, 0, 0.6);
    (*deformer)->update(pose);
    expectMatchesCpu(**deformer, *model, pose, 0.6);
    const auto cpu = deform::deformScene(*model, pose);
    for (std::size_t i = 0; i < cpu.size(); ++i)
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(glm::distance(glm::dvec4((*deformer)->instances()[i].meshToWorld[c]),
                                      cpu[i].meshToWorld[c]),
                        0.0, 1e-5)
                << "instance " << i;
}

} // namespace
