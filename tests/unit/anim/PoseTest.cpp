// Pose evaluation on the two-joint model: world transforms, skin matrices, morph weights.
#include "support/TestSupport.h"

#include "engine/anim/Pose.h"
#include "engine/asset/GltfLoader.h"
#include "engine/render/Camera.h"
#include "engine/render/Lighting.h"

#include <glm/gtc/matrix_transform.hpp>

namespace {

scene::Model loadTwoJoint(const test::GltfBuilder& builder = test::twoJointModel()) {
    test::TempDir dir;
    auto model = asset::loadGltf(builder.save(dir.path(), "twojoint"));
    EXPECT_TRUE(model.ok()) << model.error().message;
    return std::move(model).value();
}

void expectMatrixNear(const glm::dmat4& a, const glm::dmat4& b, double eps = 1e-12) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            EXPECT_NEAR(a[c][r], b[c][r], eps) << "column " << c << " row " << r;
}

TEST(Pose, WorldTransformsFollowTheHierarchy) {
    const scene::Model model = loadTwoJoint();
    const anim::Pose pose = anim::evaluate(model, 0, 0.5);
    const glm::dmat4 expected = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(1, 0, 0)),
                                            glm::radians(45.0), glm::dvec3(0, 0, 1));
    expectMatrixNear(pose.world[2], expected, 1e-7);
    ASSERT_EQ(pose.weights[0].size(), 1u);
    EXPECT_NEAR(pose.weights[0][0], 0.5, 1e-12);
}

TEST(Pose, RestSkinMatricesAreIdentity) {
    const scene::Model model = loadTwoJoint();
    const anim::Pose pose = anim::restPose(model);
    for (const glm::dmat4& m : anim::skinMatrices(model, pose, 0))
        expectMatrixNear(m, glm::dmat4(1.0));
}

TEST(Pose, SkinMatricesCancelTheMeshNodeTransform) {
    test::GltfBuilder builder = test::twoJointModel();
    builder.doc["nodes"][0]["translation"] = {5.0, 0.0, 0.0};
    const scene::Model model = loadTwoJoint(builder);
    const anim::Pose pose = anim::evaluate(model, 0, 1.0);
    const auto skin = anim::skinMatrices(model, pose, 0);
    // world(mesh) * skinMatrix == world(joint) * inverseBind, whatever the mesh node's transform.
    expectMatrixNear(pose.world[0] * skin[1], pose.world[2] * model.skins[0].inverseBind[1]);
    expectMatrixNear(skin[0], glm::translate(glm::dmat4(1.0), glm::dvec3(-5, 0, 0)));
}

TEST(Pose, ClipByNameOrIndex) {
    const scene::Model model = loadTwoJoint();
    EXPECT_EQ(model.findAnimation("bend"), 0);
    EXPECT_EQ(model.findAnimation("0"), 0);
    EXPECT_FALSE(model.findAnimation("1").has_value());
    EXPECT_FALSE(model.findAnimation("walk").has_value());
}

TEST(Pose, ChangingClipResetsUntargetedState) {
    const scene::Model model = loadTwoJoint();
    anim::Pose pose = anim::evaluate(model, 0, 1.0);
    anim::applyClip(model, -1, 0.0, pose);
    anim::updateWorld(model, pose);
    EXPECT_EQ(pose.weights[0][0], 0.0);
    expectMatrixNear(pose.world[2], glm::translate(glm::dmat4(1.0), glm::dvec3(1, 0, 0)));
}

TEST(Pose, PointerChannelsPlayNodesAndSkipWhatTheEngineDoesNotPlay) {
    const scene::Model model = loadTwoJoint(test::pointerTwoJointModel());
    const scene::Model plain = loadTwoJoint();
    const anim::Pose a = anim::evaluate(model, 0, 0.5), b = anim::evaluate(plain, 0, 0.5);
    for (std::size_t i = 0; i < b.world.size(); ++i) { // the pointer model adds a lamp, a camera
        EXPECT_EQ(a.world[i], b.world[i]) << "node pointers play as the node's channels";
        EXPECT_EQ(a.weights[i], b.weights[i]);
    }
    const auto& pointers = model.animations[0].pointers;
    ASSERT_EQ(pointers.size(), 9u);
    for (std::size_t i = 0; i < pointers.size(); ++i)
        EXPECT_EQ(pointers[i].played, i != 3) << pointers[i].pointer;
    EXPECT_EQ(pointers[3].pointer, "/materials/0/alphaCutoff");
    // The metallic factor plays as the weight does (0 to 1 over the second), on a copy.
    const anim::Pose half = anim::evaluate(model, scene::Performance::single(0), 0.5);
    ASSERT_EQ(half.materials.size(), 1u);
    EXPECT_NEAR(half.materials[0].metallicFactor, 0.5f, 1e-6f);
    EXPECT_EQ(model.materials[0].metallicFactor, 0.0f);
    EXPECT_EQ(anim::materialOf(model, half, 0), &half.materials[0]);
    EXPECT_TRUE(anim::evaluate(plain, scene::Performance::single(0), 0.5).materials.empty());
    std::size_t warned = 0;
    for (const std::string& w : model.warnings) {
        warned += w == "animation 0 channel 3 ('bend'): KHR_animation_pointer "
                       "\"/materials/0/alphaCutoff\" is not played by this engine: skipped";
        EXPECT_EQ(w.find("extensionsUsed"), std::string::npos) << w;
    }
    EXPECT_EQ(warned, 1u);
}

TEST(Pose, PointerChannelsPlayTextureTransformsLightsAndCameras) {
    const scene::Model model = loadTwoJoint(test::pointerTwoJointModel());
    scene::Performance performance = scene::Performance::single(0);
    performance.layers[0].weight = 0.5; // the rest fills the other half
    const anim::Pose pose = anim::evaluate(model, performance, 0.5);
    const scene::TextureRef& base = pose.materials.at(0).baseColorTexture;
    EXPECT_NEAR(base.uv.offset.x, 0.125f, 1e-6f);
    EXPECT_NEAR(base.uv.offset.y, 0.0625f, 1e-6f);
    EXPECT_EQ(base.transform, base.uv.matrix()) << "the matrix follows the offset";
    EXPECT_EQ(model.materials[0].baseColorTexture.uv.offset, glm::vec2(0.0f));
    const scene::Light& light = anim::lightOf(model, pose, 0);
    EXPECT_EQ(&light, &pose.lights.at(0));
    EXPECT_NEAR(light.intensity, 0.5 * 0.5 + 0.5 * 4.0, 1e-6);
    EXPECT_NEAR(light.color.r, 0.75f, 1e-6f);
    EXPECT_NEAR(light.color.b, 0.875f, 1e-6f);
    EXPECT_NEAR(light.outerConeAngle, 0.5 * 0.8 + 0.5 * 0.5, 1e-6);
    EXPECT_NEAR(anim::cameraOf(model, pose, 0).yfov, 0.5 * 0.8 + 0.5 * 0.8, 1e-6);
    // What reads them: the placed light and the file's camera.
    std::vector<scene::PlacedLight> placed;
    render::placeLights(model, render::lightNodes(model), pose, glm::dmat4(1.0), placed);
    ASSERT_EQ(placed.size(), 1u);
    EXPECT_EQ(placed[0].light.intensity, light.intensity);
    const auto camera = render::gltfCamera(model, anim::evaluate(model, 0, 0.0), 1.0f);
    ASSERT_TRUE(camera.has_value());
    const anim::Pose full = anim::evaluate(model, scene::Performance::single(0), 0.75);
    EXPECT_NEAR(render::gltfCamera(model, full, 1.0f)->yfov, 0.9f, 1e-6f);
    EXPECT_TRUE(anim::evaluate(model, 0, 0.5).lights.empty()) << "one clip's nodes alone";
}

TEST(Pose, AMalformedPointerChannelIsRefusedNamingIt) {
    test::TempDir dir;
    const auto outOfRange =
        asset::loadGltf(test::pointerTwoJointModel("/nodes/9/rotation").save(dir.path(), "a"));
    ASSERT_FALSE(outOfRange.ok());
    EXPECT_NE(outOfRange.error().message.find("animation 0 channel 0 target"), std::string::npos)
        << outOfRange.error().message;
    test::GltfBuilder none = test::pointerTwoJointModel();
    none.doc["animations"][0]["channels"][1]["target"]["extensions"]["KHR_animation_pointer"].erase(
        "pointer");
    const auto missing = asset::loadGltf(none.save(dir.path(), "b"));
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find(
                  "animation 0 channel 1 has KHR_animation_pointer without a pointer string"),
              std::string::npos)
        << missing.error().message;
    for (const auto& [pointer, expected] : std::vector<std::pair<std::string, std::string>>{
             {"/extensions/KHR_lights_punctual/lights/3/intensity",
              "names light 3, file has 1 light"},
             {"/cameras/2/perspective/yfov", "names camera 2, file has 1 camera"},
             {"/materials/1/normalTexture/extensions/KHR_texture_transform/rotation",
              "names material 1, file has 1 material"}}) {
        test::GltfBuilder far = test::pointerTwoJointModel();
        far.doc["animations"][0]["channels"][2]["target"]["extensions"]["KHR_animation_pointer"]
               ["pointer"] = pointer;
        const auto refused = asset::loadGltf(far.save(dir.path(), "c"));
        ASSERT_FALSE(refused.ok()) << pointer;
        EXPECT_NE(refused.error().message.find("animation 0 channel 2 KHR_animation_pointer " +
                                               pointer + " " + expected),
                  std::string::npos)
            << refused.error().message;
    }
}

} // namespace
