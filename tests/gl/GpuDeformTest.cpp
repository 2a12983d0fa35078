// The GPU deform pass against the CPU reference: every skinned or morphing model, several times.
#include "support/GlTest.h"
#include "support/TestSupport.h"

#include "engine/anim/Pose.h"
#include "engine/asset/GltfLoader.h"
#include "engine/deform/CpuDeformer.h"
#include "engine/deform/GpuDeformer.h"

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

TEST_F(GpuDeform, TwoJointModelMatchesCpu) {
    test::TempDir dir;
    auto model = asset::loadGltf(test::twoJointModel().save(dir.path(), "twojoint"));
    ASSERT_TRUE(model.ok());
    compare(*model, 0, {0.0, 0.3, 0.77, 1.0});
}

TEST_F(GpuDeform, FileWithTwoSkinsMatchesCpu) {
    // The two-joint model with a second mesh node and a second skin over the same joints in the
    // other order (its JOINTS_0 indices then name the other joint): two skins, two results.
    test::GltfBuilder builder = test::twoJointModel();
    const auto inverseBind = builder.doc["skins"][0]["inverseBindMatrices"];
    builder.doc["skins"].push_back({{"joints", {2, 1}}, {"inverseBindMatrices", inverseBind}});
    builder.doc["nodes"].push_back(
        {{"name", "second"}, {"mesh", 0}, {"skin", 1}, {"translation", {0.0, 2.0, 0.0}}});
    builder.doc["scenes"][0]["nodes"].push_back(3);
    test::TempDir dir;
    auto model = asset::loadGltf(builder.save(dir.path(), "twoskins"));
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
    EXPECT_EQ(a.uv0, b.uv0);
    EXPECT_NE(&a.deformed, &b.deformed);
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

} // namespace
