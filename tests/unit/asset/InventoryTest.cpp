// Every third-party sample in ../shared/assets/gltf loads, and its counts equal INVENTORY.json
// (same counting rules: vertices are POSITION accessor counts per primitive, meshes once each).
#include "support/TestSupport.h"

#include "engine/asset/GltfLoader.h"

#include <fstream>
#include <set>

namespace {

nlohmann::json inventory() {
    const auto shared = test::sharedDir();
    if (shared.empty())
        return nlohmann::json::object();
    std::ifstream in(shared / "assets" / "INVENTORY.json");
    return nlohmann::json::parse(in);
}

std::vector<std::string> inventoryModels() {
    std::vector<std::string> names;
    const nlohmann::json inv = inventory();
    if (inv.contains("models"))
        for (const auto& m : inv["models"])
            names.push_back(m["name"].get<std::string>());
    if (names.empty())
        names.emplace_back("NoSharedAssets");
    return names;
}

class InventoryModel : public ::testing::TestWithParam<std::string> {};

TEST_P(InventoryModel, LoadsWithInventoryCounts) {
    GLASS_REQUIRE_SHARED();
    const nlohmann::json inv = inventory();
    nlohmann::json expected;
    for (const auto& m : inv["models"])
        if (m["name"] == GetParam())
            expected = m;
    ASSERT_FALSE(expected.is_null());
    const auto path = test::sharedDir() / "assets" / expected["file"].get<std::string>();
    const auto model = asset::loadGltf(path);
    ASSERT_TRUE(model.ok()) << model.error().message;

    std::size_t primitives = 0, triangles = 0, vertices = 0, maxTargets = 0;
    for (const scene::Mesh& mesh : model->meshes)
        for (const scene::Primitive& p : mesh.primitives) {
            ++primitives;
            triangles += p.triangleCount();
            vertices += p.sourceVertexCount;
            maxTargets = std::max(maxTargets, p.targets.size());
        }
    EXPECT_EQ(model->meshes.size(), expected["meshes"].get<std::size_t>());
    EXPECT_EQ(primitives, expected["primitives"].get<std::size_t>());
    EXPECT_EQ(triangles, expected["triangles"].get<std::size_t>());
    EXPECT_EQ(vertices, expected["vertices"].get<std::size_t>());
    EXPECT_EQ(model->skins.size(), expected["skins"].get<std::size_t>());
    std::vector<std::size_t> joints;
    for (const scene::Skin& skin : model->skins)
        joints.push_back(skin.joints.size());
    EXPECT_EQ(joints, expected["joints_per_skin"].get<std::vector<std::size_t>>());
    EXPECT_EQ(maxTargets, expected["max_morph_targets"].get<std::size_t>());
    ASSERT_EQ(model->animations.size(), expected["animations"].get<std::size_t>());
    for (std::size_t a = 0; a < model->animations.size(); ++a) {
        const auto& clip = expected["animation_list"][a];
        EXPECT_EQ(model->animations[a].name, clip["name"].get<std::string>());
        EXPECT_EQ(model->animations[a].channels.size(), clip["channels"].get<std::size_t>());
        EXPECT_NEAR(model->animations[a].duration, clip["duration_s"].get<double>(), 5e-4);
    }
    std::size_t glass = 0;
    for (const scene::Material& m : model->materials)
        glass += m.isTransmissive() ? 1 : 0;
    EXPECT_EQ(glass, expected["transmissive_materials"].size());
}

INSTANTIATE_TEST_SUITE_P(SharedAssets, InventoryModel, ::testing::ValuesIn(inventoryModels()),
                         [](const auto& testInfo) { return testInfo.param; });

TEST(Inventory, EverySharedModelFileIsListed) {
    GLASS_REQUIRE_SHARED();
    std::set<std::string> listed;
    const nlohmann::json inv = inventory();
    for (const auto& m : inv["models"])
        listed.insert(m["file"].get<std::string>());
    const auto root = test::sharedDir() / "assets";
    std::size_t found = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root / "gltf")) {
        const auto ext = entry.path().extension();
        if (ext != ".gltf" && ext != ".glb")
            continue;
        ++found;
        EXPECT_TRUE(listed.count(std::filesystem::relative(entry.path(), root).string()))
            << entry.path();
    }
    EXPECT_EQ(found, listed.size());
}

} // namespace
