// The CPU reference deformation against hand-computed results, and on real characters.
#include "support/TestSupport.h"

#include "engine/anim/Pose.h"
#include "engine/asset/GltfLoader.h"
#include "engine/deform/CpuDeformer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace {

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double eps = 1e-6) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

scene::Model loadTwoJoint() {
    test::TempDir dir;
    auto model = asset::loadGltf(test::twoJointModel().save(dir.path(), "twojoint"));
    EXPECT_TRUE(model.ok()) << model.error().message;
    return std::move(model).value();
}

TEST(CpuDeformer, TwoJointSkinMatchesHandComputedPositions) {
    // t = 1: joint 1 (at x=1) turned 90 degrees about +z, morph weight 1 (+1 in z).
    // Joint 1's skin matrix is T(1,0,0) R90 T(-1,0,0): (x,y,z) -> (1-y, x-1, z).
    const scene::Model model = loadTwoJoint();
    const auto instances = deform::deformScene(model, anim::evaluate(model, 0, 1.0));
    ASSERT_EQ(instances.size(), 1u);
    const auto& p = instances[0].primitives[0].positions;
    expectNear(p[0], {0, 0, 1});     // joint 0 only
    expectNear(p[1], {1, 0, 1});     // half/half: (1,0,1) and (1,0,1)
    expectNear(p[2], {1, 1, 1});     // joint 1 only: (2,0,1) -> (1,1,1)
    expectNear(p[3], {0, 1, 1});     // joint 0 only
    expectNear(p[4], {0.5, 0.5, 1}); // half of (1,1,1) and (0,0,1)
    expectNear(p[5], {0, 1, 1});     // (2,1,1) -> (0,1,1)
    for (const glm::dvec3& n : instances[0].primitives[0].normals)
        expectNear(n, {0, 0, 1});
}

TEST(CpuDeformer, IdentitySkinReproducesBindPose) {
    const scene::Model model = loadTwoJoint();
    const auto instances = deform::deformScene(model, anim::restPose(model));
    const scene::Primitive& rest = model.meshes[0].primitives[0];
    for (std::size_t v = 0; v < rest.vertexCount(); ++v) {
        expectNear(instances[0].primitives[0].positions[v], glm::dvec3(rest.positions[v]), 1e-12);
        expectNear(instances[0].primitives[0].normals[v], glm::dvec3(rest.normals[v]), 1e-12);
    }
}

TEST(CpuDeformer, NormalsUseInverseTransposeUnderNonUniformScale) {
    scene::Primitive p;
    p.positions = {{1, 1, 0}};
    p.normals = {glm::normalize(glm::vec3(1, 1, 0))};
    p.tangents = {{glm::normalize(glm::vec3(1, -1, 0)), -1.0f}};
    p.joints[0] = {{0, 0, 0, 0}};
    p.weights[0] = {{1, 0, 0, 0}};
    p.indices = {0, 0, 0};
    const glm::dmat4 stretch = glm::scale(glm::dmat4(1.0), glm::dvec3(2, 1, 1));
    const auto out = deform::deformPrimitive(p, {}, std::span(&stretch, 1));
    expectNear(out.positions[0], {2, 1, 0});
    // The surface x + y = const becomes x/2 + y = const: normal (1/2, 1, 0) normalised.
    expectNear(out.normals[0], glm::normalize(glm::dvec3(0.5, 1, 0)), 1e-7);
    expectNear(glm::dvec3(out.tangents[0]), glm::normalize(glm::dvec3(2, -1, 0)), 1e-7);
    EXPECT_EQ(out.tangents[0].w, -1.0);
    EXPECT_NEAR(glm::dot(out.normals[0], glm::dvec3(out.tangents[0])), 0.0, 1e-7);
}

TEST(CpuDeformer, FlatNormalsFollowTheDeformedTriangle) {
    scene::Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    p.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    p.flatNormals = true;
    p.indices = {0, 1, 2};
    scene::MorphTarget lift;
    lift.positions = {{0, 0, 0}, {0, 0, 1}, {0, 0, 0}}; // tilt the triangle about y
    p.targets = {lift};
    const double w = 1.0;
    const auto out = deform::deformPrimitive(p, std::span(&w, 1), {});
    for (const glm::dvec3& n : out.normals)
        expectNear(n, glm::normalize(glm::dvec3(-1, 0, 1)), 1e-12);
}

TEST(CpuDeformer, AnimatedMorphCubeTargetsAtKnownWeights) {
    GLASS_REQUIRE_SHARED();
    const auto model =
        asset::loadGltf(test::sharedDir() / "assets/gltf/AnimatedMorphCube/AnimatedMorphCube.glb");
    ASSERT_TRUE(model.ok()) << model.error().message;
    const scene::Primitive& p = model->meshes[0].primitives[0];
    ASSERT_EQ(p.targets.size(), 2u);
    for (const std::array<double, 2> w :
         {std::array{1.0, 0.0}, std::array{0.0, 1.0}, std::array{0.5, 0.25}}) {
        const auto out = deform::deformPrimitive(p, w, {});
        for (std::size_t v = 0; v < p.vertexCount(); ++v) {
            const glm::dvec3 expected = glm::dvec3(p.positions[v]) +
                                        w[0] * glm::dvec3(p.targets[0].positions[v]) +
                                        w[1] * glm::dvec3(p.targets[1].positions[v]);
            expectNear(out.positions[v], expected, 1e-12);
            const glm::dvec3 n = glm::normalize(glm::dvec3(p.normals[v]) +
                                                w[0] * glm::dvec3(p.targets[0].normals[v]) +
                                                w[1] * glm::dvec3(p.targets[1].normals[v]));
            expectNear(out.normals[v], n, 1e-9);
        }
    }
    // The clip drives both weights: the deformed cube must differ from rest somewhere in it.
    const auto atRest = deform::deformScene(*model, anim::restPose(*model));
    double moved = 0.0;
    for (double t = 0.0; t <= model->animations[0].duration; t += 0.25) {
        const auto frame = deform::deformScene(*model, anim::evaluate(*model, 0, t));
        for (std::size_t v = 0; v < p.vertexCount(); ++v)
            moved = std::max(moved, glm::length(frame[0].primitives[0].positions[v] -
                                                atRest[0].primitives[0].positions[v]));
    }
    EXPECT_GT(moved, 1e-3);
}

TEST(CpuDeformer, CesiumManAtOneSecondIsFiniteAndInsideTheJointBound) {
    GLASS_REQUIRE_SHARED();
    const auto model = asset::loadGltf(test::sharedDir() / "assets/gltf/CesiumMan/CesiumMan.glb");
    ASSERT_TRUE(model.ok()) << model.error().message;
    const anim::Pose pose = anim::evaluate(*model, 0, 1.0);
    const auto instances = deform::deformScene(*model, pose);
    ASSERT_EQ(instances.size(), 1u);
    const scene::Primitive& rest = model->meshes[0].primitives[0];

    // Bound: each skinned vertex is a convex combination of M_j p (weights >= 0, sum 1), so it
    // lies in the box spanned by every joint matrix applied to the 8 corners of the rest box.
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::vec3& v : rest.positions) {
        lo = glm::min(lo, glm::dvec3(v));
        hi = glm::max(hi, glm::dvec3(v));
    }
    glm::dvec3 boundLo(1e300), boundHi(-1e300);
    for (const glm::dmat4& m : anim::skinMatrices(*model, pose, instances[0].node))
        for (int corner = 0; corner < 8; ++corner) {
            const glm::dvec3 c((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                               (corner & 4) ? hi.z : lo.z);
            const glm::dvec3 q = glm::dvec3(m * glm::dvec4(c, 1.0));
            boundLo = glm::min(boundLo, q);
            boundHi = glm::max(boundHi, q);
        }
    const auto& deformed = instances[0].primitives[0];
    double maxNormalError = 0.0;
    bool moved = false;
    for (std::size_t v = 0; v < deformed.positions.size(); ++v) {
        const glm::dvec3& p = deformed.positions[v];
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << v;
        for (int c = 0; c < 3; ++c) {
            EXPECT_GE(p[c], boundLo[c] - 1e-9) << "vertex " << v;
            EXPECT_LE(p[c], boundHi[c] + 1e-9) << "vertex " << v;
        }
        maxNormalError = std::max(maxNormalError, std::abs(glm::length(deformed.normals[v]) - 1.0));
        moved = moved || glm::length(p - glm::dvec3(rest.positions[v])) > 1e-3;
    }
    EXPECT_LT(maxNormalError, 1e-12);
    EXPECT_TRUE(moved) << "the walk cycle should move the mesh away from its bind pose";
}

} // namespace
