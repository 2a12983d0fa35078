// The second oracle: three.js's AnimationMixer (tests/mixer/mixer.mjs, three pinned by its lock
// file) poses the same files with the same layers and crossfades; every node's world position
// must agree within 1e-5 of the skeleton's bounding diagonal, and morph weights within 1e-5.
#include "support/TestSupport.h"

#include "engine/anim/Pose.h"
#include "engine/asset/ModelLoader.h"

#include <fstream>

namespace {

using Json = nlohmann::json;

struct OracleCase {
    const char* name;
    const char* model; ///< under ../shared/assets/gltf
    Json layers;       ///< [{"clip", "weight", "additive"}]
    Json transitions;  ///< [{"at", "to", "duration"}]
};

std::vector<OracleCase> cases() {
    return {
        {"FoxCrossfades",
         "Fox/Fox.glb",
         {{{"clip", "Survey"}}},
         {{{"at", 0.5}, {"to", "Walk"}, {"duration", 0.4}},
          {{"at", 1.3}, {"to", "Run"}, {"duration", 0.4}}}},
        {"FoxWeights",
         "Fox/Fox.glb",
         {{{"clip", "Walk"}, {"weight", 0.45}}, {{"clip", "Run"}, {"weight", 0.3}}},
         Json::array()},
        {"FoxAdditive",
         "Fox/Fox.glb",
         {{{"clip", "Survey"}}, {{"clip", "Walk"}, {"weight", 0.6}, {"additive", true}}},
         Json::array()},
        {"CesiumManHalfWeightAndAdditive",
         "CesiumMan/CesiumMan.glb",
         {{{"clip", ""}, {"weight", 0.5}}, {{"clip", ""}, {"weight", 0.8}, {"additive", true}}},
         Json::array()},
        {"CesiumManCrossfadeToItself",
         "CesiumMan/CesiumMan.glb",
         {{{"clip", ""}}},
         {{{"at", 0.7}, {"to", ""}, {"duration", 0.5}}}},
        {"MorphCubeWeightsAndAdditive",
         "AnimatedMorphCube/AnimatedMorphCube.glb",
         {{{"clip", "Square"}, {"weight", 0.6}},
          {{"clip", "Square"}, {"weight", 0.5}, {"additive", true}}},
         Json::array()},
    };
}

void PrintTo(const OracleCase& c, std::ostream* os) {
    *os << c.name;
}

class MixerOracle : public ::testing::TestWithParam<OracleCase> {};

TEST_P(MixerOracle, PosesMatchThreeJs) {
    GLASS_REQUIRE_SHARED();
    const std::filesystem::path modules =
        std::filesystem::path(GLASS_BIN_DIR) / "../mixer/node_modules";
    if (!std::filesystem::exists(modules / "three"))
        GTEST_SKIP() << "three.js is not installed (scripts/npm-deps installs it into build/mixer)";
    const OracleCase& c = GetParam();
    const std::filesystem::path modelPath = test::sharedDir() / "assets/gltf" / c.model;
    auto loaded = asset::loadModel(modelPath.string());
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    const scene::Model& model = *loaded;
    ASSERT_FALSE(model.animations.empty());
    // Clips by name ("" for the first, CesiumMan's has none), to both by index.
    const auto clipIndex = [&](const Json& j) {
        const std::string name = j.get<std::string>();
        return name.empty() ? 0 : *model.findAnimation(name);
    };
    Json spec = {{"model", modelPath.string()},
                 {"layers", Json::array()},
                 {"transitions", Json::array()},
                 {"times", Json::array()}};
    scene::Performance performance;
    for (const Json& l : c.layers) {
        scene::Layer& layer = performance.layers.emplace_back();
        layer.clip = clipIndex(l["clip"]);
        layer.weight = l.value("weight", 1.0);
        layer.additive = l.value("additive", false);
        spec["layers"].push_back(
            {{"clip", layer.clip}, {"weight", layer.weight}, {"additive", layer.additive}});
    }
    for (const Json& t : c.transitions) {
        performance.transitions.push_back(
            {t["at"].get<double>(), clipIndex(t["to"]), t["duration"].get<double>()});
        spec["transitions"].push_back({{"at", t["at"]},
                                       {"to", performance.transitions.back().to},
                                       {"duration", t["duration"]}});
    }
    for (int i = 0; i < 20; ++i)
        spec["times"].push_back(0.105 * i);
    test::TempDir dir;
    std::ofstream(dir / "spec.json") << spec.dump();
    std::string out;
    ASSERT_EQ(test::runCommand("node " + std::string(GLASS_SOURCE_DIR) + "/tests/mixer/mixer.mjs " +
                                   modules.string() + " " + (dir / "spec.json").string() + " 2>&1",
                               &out),
              0)
        << out;
    const Json oracle = Json::parse(out);
    // The skeleton's bounding diagonal: every node three places, over every frame.
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const Json& frame : oracle["frames"])
        for (const auto& [index, p] : frame["positions"].items()) {
            const glm::dvec3 v(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
    const double diagonal = std::max(glm::length(hi - lo), 1e-12); // a lone node: none
    const double tolerance = 1e-5 * diagonal;
    anim::Pose pose = anim::restPose(model);
    double worst = 0.0, worstWeight = 0.0;
    for (const Json& frame : oracle["frames"]) {
        anim::evaluate(model, performance, frame["time"].get<double>(), pose);
        for (const auto& [index, p] : frame["positions"].items()) {
            const glm::dvec3 theirs(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
            const glm::dvec3 ours(pose.world[std::size_t(std::stoi(index))][3]);
            worst = std::max(worst, glm::length(ours - theirs));
        }
        for (const auto& [index, w] : frame["weights"].items()) {
            const std::vector<double>& ours = pose.weights[std::size_t(std::stoi(index))];
            ASSERT_EQ(ours.size(), w.size()) << "node " << index;
            for (std::size_t k = 0; k < ours.size(); ++k)
                worstWeight = std::max(worstWeight, std::abs(ours[k] - w[k].get<double>()));
        }
    }
    std::printf("%s against three.js r%s: %.3g of the diagonal, morph weights %.3g\n", c.name,
                oracle["three"].get<std::string>().c_str(), worst / diagonal, worstWeight);
    EXPECT_LE(worst, tolerance) << "three.js r" << oracle["three"].get<std::string>()
                                << ": the largest distance is " << worst / diagonal
                                << " of the diagonal";
    EXPECT_LE(worstWeight, 1e-5);
}

INSTANTIATE_TEST_SUITE_P(Anim, MixerOracle, ::testing::ValuesIn(cases()),
                         [](const auto& testInfo) { return std::string(testInfo.param.name); });

} // namespace
