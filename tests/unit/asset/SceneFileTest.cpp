// Scene files: one test per error, each naming the file and the key; a valid scene with
// shared models; character clocks and transforms; the round trip through saveScene; the worlds
// the tools make of model paths (render::loadWorld).
#include "support/TestSupport.h"

#include "engine/anim/Pose.h"
#include "engine/asset/HdrImage.h"
#include "engine/asset/ModelLoader.h"
#include "engine/asset/SceneFile.h"
#include "engine/core/Limits.h"
#include "engine/render/Camera.h"
#include "engine/render/WorldLoader.h"

#include <fstream>

namespace {

using Json = nlohmann::json;

/** A folder with the two-joint model (one clip, "bend", 1 s) as models/twojoint.glb. */
class SceneDir {
public:
    SceneDir() {
        std::filesystem::create_directories(dir / "models");
        test::twoJointModel().save(dir.path() / "models", "twojoint", test::GltfFormat::Glb);
    }
    std::filesystem::path write(const std::string& name, const std::string& text) const {
        auto path = dir / name;
        std::ofstream(path) << text;
        return path;
    }
    test::TempDir dir;
};

Json character(const Json& extra = Json::object()) {
    Json c = {{"model", "models/twojoint.glb"}};
    c.update(extra);
    return c;
}

struct BadScene {
    const char* name;
    std::string text;     ///< the scene file
    std::string expected; ///< what follows "asset::loadScene(): <path>: "
};

std::vector<BadScene> badScenes() {
    auto scene = [](Json characters, const Json& extra = Json::object()) {
        Json root = {{"characters", std::move(characters)}};
        root.update(extra);
        return root.dump();
    };
    return {
        {"NotJson", "{\"characters\": [", "not valid JSON"},
        {"NotAnObject", "[1, 2]", "(root): expected an object with a \"characters\" array"},
        {"NoCharacters", "{}", "characters: missing (an array of characters)"},
        {"CharacterNotAnObject", scene({7}), "characters[0]: expected an object, got 7"},
        {"NoModel", scene({Json::object()}),
         "characters[0].model: missing (a model path relative to the scene file)"},
        {"MissingModel", scene({character(), character({{"model", "models/ghost.glb"}})}),
         "characters[1].model: cannot load \"models/ghost.glb\" ("},
        {"UnknownClip", scene({character(), character({{"clip", "Jump"}})}),
         "characters[1].clip: \"Jump\" not in twojoint.glb (clips: bend)"},
        {"ClipIndexOutOfRange", scene({character({{"clip", 3}})}),
         "characters[0].clip: clip 3 not in twojoint.glb (clips: bend)"},
        {"TranslationOfTwo", scene({character({{"translation", {1, 2}}})}),
         "characters[0].translation: expected an array of 3 numbers, got [1,2]"},
        {"TranslationNotNumbers", scene({character({{"translation", {1, "up", 3}}})}),
         "characters[0].translation[1]: expected a number, got \"up\""},
        {"RotationNotUnit", scene({character({{"rotation", {0, 0, 0, 2}}})}),
         "characters[0].rotation: expected a unit quaternion [x, y, z, w], its length is 2"},
        {"ZeroScale", scene({character({{"scale", {1, 0, 1}}})}),
         "characters[0].scale: a scale of 0 flattens the character"},
        {"SpeedNotANumber", scene({character({{"speed", "fast"}})}),
         "characters[0].speed: expected a number, got \"fast\""},
        {"LayersWithTheShortForm",
         scene({character({{"clip", "bend"}, {"layers", {{{"clip", "bend"}}}}})}),
         "characters[0].clip: give the clip and its timing in \"layers\" or as the short form, "
         "not both"},
        {"LayerWithoutClip", scene({character({{"layers", {{{"weight", 0.5}}}}})}),
         "characters[0].layers[0].clip: missing (a clip's name or index)"},
        {"LayerClipUnknown",
         scene({character({{"layers", {{{"clip", "bend"}}, {{"clip", "run"}}}}})}),
         "characters[0].layers[1].clip: \"run\" not in twojoint.glb (clips: bend)"},
        {"LayerNegativeWeight", scene({character({{"layers", {{{"clip", 0}, {"weight", -1}}}}})}),
         "characters[0].layers[0].weight: expected a weight in [0, 1000], got -1"},
        {"MaskUnknownJoint", scene({character({{"layers", {{{"clip", 0}, {"mask", "elbow"}}}}})}),
         "characters[0].layers[0].mask: no node \"elbow\" in twojoint.glb"},
        {"MaskWeightOutOfRange",
         scene({character({{"layers", {{{"clip", 0}, {"mask", {{"tip", 2}}}}}}})}),
         "characters[0].layers[0].mask.tip: expected a weight in [0, 1], got 2"},
        {"TransitionWithoutTarget", scene({character({{"transitions", {{{"at", 1}}}}})}),
         "characters[0].transitions[0].to: missing"},
        {"TransitionNegativeDuration",
         scene({character({{"transitions", {{{"at", 1}, {"to", "bend"}, {"duration", -1}}}}})}),
         "characters[0].transitions[0].duration: expected seconds >= 0, got -1"},
        {"RootMotionUnknown", scene({character({{"root_motion", "teleport"}})}),
         "characters[0].root_motion: expected \"baked\", \"in_place\" or \"accumulate\", got "
         "\"teleport\""},
        {"MorphTargetUnknown", scene({character({{"morph_weights", {{"smile", 1}}}})}),
         "characters[0].morph_weights.smile: no morph target \"smile\" in twojoint.glb"},
        {"MorphAddNotANumber", scene({character({{"morph_weights", {{"0", {{"add", "x"}}}}}})}),
         "characters[0].morph_weights.0.add: expected a number, got \"x\""},
        {"RepeatCountZero", scene({character({{"loop", 0}})}),
         "characters[0].loop: expected a count of repeats in [1, 1000000], got 0"},
        {"PausedAtNotANumber", scene({character({{"paused_at", "now"}})}),
         "characters[0].paused_at: expected a number, got \"now\""},
        {"LoopNotABool", scene({character({{"loop", "yes"}})}),
         "characters[0].loop: expected true, false, \"repeat\", \"clamp\", \"ping_pong\" or a "
         "count of repeats, got \"yes\""},
        {"UnknownGlassMode", scene({character({{"glass", "glassy"}})}),
         "characters[0].glass: expected auto, all or none, got \"glassy\""},
        {"IorBelowOne", scene({character({{"ior", 0.5}})}),
         "characters[0].ior: expected an index of refraction in [1, 4], got 0.5"},
        {"TintOutOfRange", scene({character({{"tint", {1, 2, 0}}})}),
         "characters[0].tint: expected components in [0, 1], got [1,2,0]"},
        {"DispersionNegative", scene({character({{"dispersion", -1}})}),
         "characters[0].dispersion: expected 20 / Abbe number in [0, 10], got -1"},
        {"CameraFovZero", scene({character()}, {{"camera", {{"yfov", 0}}}}),
         "camera.yfov: expected radians in (0, 3.1), got 0"},
        {"CameraOnItsTarget",
         scene({character()}, {{"camera", {{"position", {1, 1, 1}}, {"target", {1, 1, 1}}}}}),
         "camera: position and target coincide"},
        {"CameraThroughUnknownCharacter",
         scene({character()}, {{"camera", {{"through", {{"character", "nobody"}, {"node", 0}}}}}}),
         "camera.through.character: no character \"nobody\" in the scene"},
        {"CameraThroughANodeWithoutACamera",
         scene({character()}, {{"camera", {{"through", {{"character", 0}, {"node", "tip"}}}}}}),
         "camera.through.node: no perspective camera on node \"tip\" of twojoint.glb"},
        {"GroundNotABool", scene({character()}, {{"ground", 1}}),
         "ground: expected true or false, got 1"},
        {"UnknownVariant", scene({character({{"variant", "blue"}})}),
         "characters[0].variant: \"blue\" not in twojoint.glb (variants: none)"},
        {"MissingEnvironment", scene({character()}, {{"environment", "env/none.hdr"}}),
         "environment: asset::loadHdr(): none.hdr: core::readFile(): "},
        {"EnvironmentNotAnImage", scene({character()}, {{"environment", "models/twojoint.glb"}}),
         "environment: asset::loadHdr(): twojoint.glb: not a Radiance HDR, PNG or JPEG image"},
        {"NumberOverflows",
         "{\"characters\": [\n  {\"model\": \"models/twojoint.glb\", \"speed\": 1e999}\n]}",
         "not valid JSON at line 2, column 49 (after the key \"speed\"): number overflow "
         "parsing '1e999'"},
        {"SyntaxErrorHasItsLine", "{\"characters\": [\n  {\"model\": \"a.glb\",}\n]}",
         "not valid JSON at line 2, column 21 (after the key \"model\"): syntax error"},
        {"LightsNotAnArray", scene({character()}, {{"lights", 3}}),
         "lights: expected an array of lights, got 3"},
        {"LightOfAnUnknownType", scene({character()}, {{"lights", {{{"type", "area"}}}}}),
         "lights[0].type: expected directional, point or spot, got \"area\""},
        {"PointLightWithoutPosition", scene({character()}, {{"lights", {{{"type", "point"}}}}}),
         "lights[0].position: missing (a point light's position in the world)"},
        {"SpotLightPointingNowhere",
         scene(
             {character()},
             {{"lights", {{{"type", "spot"}, {"position", {0, 1, 0}}, {"direction", {0, 0, 0}}}}}}),
         "lights[0].direction: a zero vector points nowhere"},
        {"SpotConeInsideOut",
         scene({character()}, {{"lights",
                                {{{"type", "spot"},
                                  {"position", {0, 1, 0}},
                                  {"direction", {0, -1, 0}},
                                  {"inner_cone_angle", 0.6},
                                  {"outer_cone_angle", 0.3}}}}}),
         "lights[0]: a spot light needs inner_cone_angle < outer_cone_angle <= pi/2"},
        {"NegativeIntensity",
         scene({character()},
               {{"lights",
                 {{{"type", "directional"}, {"direction", {0, -1, 0}}, {"intensity", -2}}}}}),
         "lights[0].intensity: expected a number of at least 0, got -2"},
        {"TooManyLights",
         scene({character()},
               {{"lights", Json(std::vector<Json>(
                               core::limits::kMaxLights + 1,
                               Json{{"type", "directional"}, {"direction", {0, -1, 0}}}))}}),
         "lights: 257 lights, the limit is 256"},
        {"TooManyCharacters",
         scene(Json(std::vector<Json>(core::limits::kMaxCharacters + 1, character()))),
         "characters: 4097 characters, the limit is 4096"},
        {"TooManyVertices",
         scene(
             Json(std::vector<Json>(200, character({{"model", "builtin:sphere?segments=1024"}})))),
         "vertices with this character, the limit is 67108864"},
    };
}

void PrintTo(const BadScene& c, std::ostream* os) {
    *os << c.name;
}

class BadSceneFile : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadSceneFile, FailsNamingFileAndKey) {
    SceneDir dir;
    const auto path = dir.write("bad.json", GetParam().text);
    const auto world = asset::loadScene(path);
    ASSERT_FALSE(world.ok());
    const std::string prefix = "asset::loadScene(): " + path.string() + ": ";
    EXPECT_EQ(world.error().message.rfind(prefix, 0), 0u) << world.error().message;
    EXPECT_NE(world.error().message.find(GetParam().expected), std::string::npos)
        << world.error().message;
}

INSTANTIATE_TEST_SUITE_P(Scene, BadSceneFile, ::testing::ValuesIn(badScenes()),
                         [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(SceneFile, TheExampleSceneLoads) {
    const auto world =
        asset::loadScene(std::filesystem::path(GLASS_SOURCE_DIR) / "assets/scenes/walk_past.json");
    ASSERT_TRUE(world.ok()) << world.error().message;
    ASSERT_EQ(world->characters.size(), 3u);
    EXPECT_EQ(world->characters[0].model, world->characters[2].model);
    EXPECT_NE(world->characters[0].mainClip(), world->characters[2].mainClip()); // walk, wave
    EXPECT_TRUE(world->environment && std::filesystem::exists(*world->environment));
    // The sun of its sky, low, casting the characters' shadows (and the glass's caustics).
    ASSERT_EQ(world->lights.size(), 1u);
    EXPECT_EQ(world->lights[0].light.type, scene::Light::Type::Directional);
    EXPECT_TRUE(world->lights[0].light.shadow.enabled);
}

TEST(SceneFile, MissingFileFailsNamingIt) {
    const auto world = asset::loadScene("/nonexistent/crowd.json");
    ASSERT_FALSE(world.ok());
    EXPECT_EQ(world.error().message,
              "asset::loadScene(): /nonexistent/crowd.json: cannot open the scene file");
}

TEST(SceneFile, ValidSceneSharesModelsAndKeepsEveryKey) {
    SceneDir dir;
    const Json root = {
        {"environment", "env/sky.hdr"},
        {"ground", true},
        {"camera", {{"position", {0, 1, 5}}, {"target", {0, 1, 0}}, {"yfov", 0.6}}},
        {"characters",
         {character({{"name", "walker"},
                     {"translation", {1, 0, 0}},
                     {"rotation", {0, 0.7071068, 0, 0.7071068}},
                     {"scale", {2, 2, 2}},
                     {"clip", "bend"},
                     {"time_offset", 0.25},
                     {"speed", 0.5},
                     {"glass", "all"},
                     {"ior", 1.33},
                     {"tint", {1, 0.5, 0.25}},
                     {"dispersion", 0.4},
                     {"written_by", "another tool"}}), // unknown: a warning, not an error
          character({{"clip", 0}, {"loop", false}, {"glass", "none"}}),
          {{"model", "builtin:sphere?segments=16"}}}}};
    std::filesystem::create_directories(dir.dir / "env");
    const auto sky = asset::encodeHdr({4, 2, std::vector<float>(24, 0.5f)});
    std::ofstream(dir.dir / "env/sky.hdr", std::ios::binary)
        .write(reinterpret_cast<const char*>(sky.data()), std::streamsize(sky.size()));
    const auto path = dir.write("crowd.json", root.dump());
    const auto world = asset::loadScene(path);
    ASSERT_TRUE(world.ok()) << world.error().message;
    ASSERT_EQ(world->characters.size(), 3u);
    const scene::Character& a = world->characters[0];
    const scene::Character& b = world->characters[1];
    const scene::Character& sphere = world->characters[2];
    EXPECT_EQ(a.model, b.model); // one model, loaded once, placed twice
    EXPECT_NE(a.model, sphere.model);
    EXPECT_EQ(a.name, "walker");
    EXPECT_EQ(b.name, "characters[1]");
    EXPECT_EQ(a.modelPath, (dir.dir / "models/twojoint.glb").string());
    EXPECT_EQ(sphere.modelPath, "builtin:sphere?segments=16");
    EXPECT_EQ(*world->environment, (dir.dir / "env/sky.hdr").string());
    EXPECT_TRUE(world->ground);
    ASSERT_TRUE(world->camera);
    EXPECT_FLOAT_EQ(world->camera->yfov, 0.6f);
    EXPECT_EQ(a.mainClip(), 0);
    EXPECT_EQ(a.glass, scene::GlassMode::All);
    EXPECT_EQ(b.glass, scene::GlassMode::None);
    EXPECT_EQ(sphere.glass, scene::GlassMode::Auto);
    EXPECT_FLOAT_EQ(*a.overrides.ior, 1.33f);
    EXPECT_EQ(*a.overrides.tint, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_FALSE(b.overrides.ior);
    EXPECT_EQ(sphere.mainClip(), -1); // no clips: the rest pose
    // Transform: scale 2, a quarter turn about +y, then the translation.
    const glm::dvec4 x = a.transform() * glm::dvec4(1, 0, 0, 1);
    EXPECT_NEAR(x.x, 1.0, 1e-6);
    EXPECT_NEAR(x.z, -2.0, 1e-6);
    // Clocks: (t + offset) * speed, wrapped when looping, clamped otherwise.
    const auto clipTime = [](const scene::Character& c, double t) {
        return c.performance.layers.front().clipTime(
            t, c.model->animations.empty() ? 0.0 : c.model->animations[0].duration);
    };
    EXPECT_NEAR(clipTime(a, 1.65), 0.95, 1e-12); // (1.65 + 0.25) * 0.5
    EXPECT_NEAR(clipTime(a, 2.15), 0.2, 1e-12);  // 1.2 wraps to 0.2
    EXPECT_NEAR(clipTime(b, -0.5), 0.0, 1e-12);  // clamped at the start
    EXPECT_NEAR(clipTime(b, 7.0), 1.0, 1e-12);   // and at the end
    EXPECT_EQ(clipTime(sphere, 3.0), 0.0);
}

TEST(SceneFile, TheExampleScenePlaysWithoutAJump) {
    // The walker strolls in, walking on across its clip's loop (accumulated root motion), and
    // crossfades into its idle where it stands: no character's root jumps on the scene clock.
    const auto world =
        asset::loadScene(std::filesystem::path(GLASS_SOURCE_DIR) / "assets/scenes/walk_past.json");
    ASSERT_TRUE(world.ok()) << world.error().message;
    EXPECT_FALSE(world->repeats()) << "a viewer's clock runs on rather than wrap";
    for (const scene::Character& c : world->characters) {
        SCOPED_TRACE(c.name);
        const int root = anim::motionNode(*c.model, c.mainClip());
        ASSERT_GE(root, 0);
        anim::Pose pose = anim::restPose(*c.model);
        const auto at = [&](double t) {
            anim::evaluate(*c.model, c.performance, t, pose);
            return glm::dvec3(c.transform() * pose.world[std::size_t(root)][3]);
        };
        glm::dvec3 previous = at(0.0);
        double largest = 0.0;
        for (int frame = 1; frame <= 12 * 60; ++frame) {
            const glm::dvec3 now = at(frame / 60.0);
            largest = std::max(largest, glm::length(now - previous));
            previous = now;
        }
        EXPECT_LT(largest, 0.02) << "the largest step in a frame at 60 Hz, metres";
    }
}

TEST(SceneFile, SavedSceneOpensAsTheSameWorld) {
    SceneDir dir;
    const Json root = {
        {"ground", true},
        {"lights",
         {{{"name", "key"},
           {"type", "spot"},
           {"position", {1, 2, 3}},
           {"direction", {0, -1, 0}},
           {"color", {1, 0.5, 0.25}},
           {"intensity", 40},
           {"range", 9},
           {"inner_cone_angle", 0.2},
           {"outer_cone_angle", 0.6}},
          {{"type", "directional"}, {"direction", {0, 0, -2}}}}},
        {"characters",
         {character({{"translation", {-1, 0, 0.5}},
                     {"rotation", {0, 0, 0.3826834, 0.9238795}},
                     {"clip", "bend"},
                     {"time_offset", 0.3},
                     {"speed", -1.5},
                     {"loop", false},
                     {"glass", "all"},
                     {"tint", {0.5, 0.5, 1}}}),
          {{"model", "builtin:sphere"}, {"scale", {0.5, 0.5, 0.5}}, {"dispersion", 1.0}}}}};
    const auto first = asset::loadScene(dir.write("a.json", root.dump()));
    ASSERT_TRUE(first.ok()) << first.error().message;
    std::filesystem::create_directories(dir.dir / "saved");
    const auto saved = dir.dir / "saved/b.json";
    ASSERT_TRUE(asset::saveScene(saved, *first).ok());
    // Paths are written relative to the new file's folder where they lie below it.
    std::ifstream in(saved);
    const Json written = Json::parse(in);
    EXPECT_EQ(written["characters"][0]["model"], (dir.dir / "models/twojoint.glb").string());
    EXPECT_EQ(written["characters"][0]["clip"], "bend");
    const auto second = asset::loadScene(saved);
    ASSERT_TRUE(second.ok()) << second.error().message;
    ASSERT_EQ(second->characters.size(), first->characters.size());
    EXPECT_EQ(second->ground, first->ground);
    ASSERT_EQ(first->lights.size(), 2u);
    ASSERT_EQ(second->lights.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        const scene::PlacedLight &a = first->lights[i], &b = second->lights[i];
        EXPECT_EQ(b.light.type, a.light.type);
        EXPECT_EQ(b.light.name, a.light.name);
        EXPECT_EQ(b.light.color, a.light.color);
        EXPECT_EQ(b.light.intensity, a.light.intensity);
        EXPECT_EQ(b.light.range, a.light.range);
        EXPECT_EQ(b.light.innerConeAngle, a.light.innerConeAngle);
        EXPECT_EQ(b.light.outerConeAngle, a.light.outerConeAngle);
        EXPECT_EQ(b.position, a.position);
        EXPECT_EQ(b.direction, a.direction);
    }
    EXPECT_EQ(first->lights[0].light.type, scene::Light::Type::Spot);
    EXPECT_FLOAT_EQ(first->lights[0].light.outerConeAngle, 0.6f);
    EXPECT_EQ(first->lights[1].direction, glm::vec3(0.0f, 0.0f, -1.0f)); // normalised
    EXPECT_EQ(first->lights[1].light.name, "lights[1]");
    for (std::size_t i = 0; i < first->characters.size(); ++i) {
        const scene::Character& a = first->characters[i];
        const scene::Character& b = second->characters[i];
        SCOPED_TRACE(a.name);
        EXPECT_EQ(b.modelPath, a.modelPath);
        EXPECT_EQ(b.placement.translation, a.placement.translation);
        EXPECT_NEAR(glm::length(glm::dvec4(b.placement.rotation.x, b.placement.rotation.y,
                                           b.placement.rotation.z, b.placement.rotation.w) -
                                glm::dvec4(a.placement.rotation.x, a.placement.rotation.y,
                                           a.placement.rotation.z, a.placement.rotation.w)),
                    0.0, 1e-6);
        EXPECT_EQ(b.placement.scale, a.placement.scale);
        EXPECT_EQ(b.performance, a.performance);
        EXPECT_EQ(b.glass, a.glass);
        EXPECT_EQ(b.overrides, a.overrides);
    }
    // A save below the models' folder writes them relative to it.
    ASSERT_TRUE(asset::saveScene(dir.dir / "c.json", *first).ok());
    std::ifstream inC(dir.dir / "c.json");
    EXPECT_EQ(Json::parse(inC)["characters"][0]["model"], "models/twojoint.glb");
}

TEST(SceneFile, ACameraLookedThroughRoundTripsAndMovesWithItsCharacter) {
    // A scene looking through the camera of a character's file (its yfov played by the clip,
    // 0.6 -> 1 rad over a second): by the character's name and the node's; saved, it opens the
    // same; at 0.75 s its camera is the file's there.
    SceneDir dir;
    test::pointerTwoJointModel().save(dir.dir / "models", "eye", test::GltfFormat::Glb);
    const Json root = {{"camera",
                        {{"position", {0, 1, 5}},
                         {"target", {0, 0, 0}},
                         {"through", {{"character", "watcher"}, {"node", "eye"}}}}},
                       {"characters",
                        {character(), character({{"model", "models/eye.glb"},
                                                 {"name", "watcher"},
                                                 {"translation", {3, 0, 0}}})}}};
    const auto first = asset::loadScene(dir.write("a.json", root.dump()));
    ASSERT_TRUE(first.ok()) << first.error().message;
    ASSERT_TRUE(first->camera && first->camera->through);
    EXPECT_EQ(first->camera->through->character, 1u);
    const scene::Model& model = *first->characters[1].model;
    EXPECT_EQ(model.nodes[std::size_t(first->camera->through->node)].name, "eye");
    ASSERT_TRUE(asset::saveScene(dir.dir / "b.json", *first).ok());
    const auto second = asset::loadScene(dir.dir / "b.json");
    ASSERT_TRUE(second.ok()) << second.error().message;
    EXPECT_EQ(second->camera->through, first->camera->through);
    const render::Camera camera =
        render::sceneCamera(*second, 0.75, 1.0f, render::worldBounds(*second));
    EXPECT_NEAR(camera.yfov, 0.9f, 1e-5f);
    EXPECT_NEAR(camera.position.x, 3.0f, 1e-5f) << "the eye node, moved with its character";
    EXPECT_NEAR(camera.position.z, 4.0f, 1e-5f);
}

TEST(SceneFile, PerformancesRoundTrip) {
    SceneDir dir;
    const Json root = {
        {"characters",
         {character({{"layers",
                      {{{"clip", "bend"}, {"weight", 0.7}, {"loop", "ping_pong"}, {"speed", 0.5}},
                       {{"clip", 0},
                        {"weight", 0.4},
                        {"time_offset", 0.2},
                        {"loop", 3},
                        {"additive", true},
                        {"mask", {{"root", 1.0}, {"tip", 0.5}}}}}},
                     {"transitions",
                      {{{"at", 2.0}, {"to", "bend"}, {"duration", 0.5}},
                       {{"at", 1.0}, {"to", 0}, {"duration", 0.25}}}},
                     {"root_motion", "accumulate"},
                     {"morph_weights", {{"0", 0.25}}},
                     {"paused_at", 0.4}}),
          character(
              {{"clip", "bend"}, {"loop", "clamp"}, {"morph_weights", {{"0", {{"add", 0.5}}}}}}),
          character({{"layers", {{{"clip", "bend"}, {"mask", "tip"}}}}})}}};
    const auto first = asset::loadScene(dir.write("a.json", root.dump()));
    ASSERT_TRUE(first.ok()) << first.error().message;
    const scene::Performance& p = first->characters[0].performance;
    ASSERT_EQ(p.layers.size(), 2u);
    EXPECT_EQ(p.layers[0].loop, scene::Loop::PingPong);
    EXPECT_EQ(p.layers[0].speed, 0.5);
    EXPECT_EQ(p.layers[1].loop, scene::Loop::Repeat);
    EXPECT_EQ(p.layers[1].repetitions, 3);
    EXPECT_TRUE(p.layers[1].additive);
    EXPECT_EQ(p.layers[1].mask, (std::vector<scene::MaskEntry>{{1, 1.0}, {2, 0.5}})); // root, tip
    ASSERT_EQ(p.transitions.size(), 2u);
    EXPECT_EQ(p.transitions[0].at, 1.0) << "sorted by time";
    EXPECT_EQ(p.rootMotion, scene::RootMotion::Accumulate);
    EXPECT_EQ(p.morphs, (std::vector<scene::MorphSetting>{{-1, 0, 0.25, false}}));
    EXPECT_EQ(p.pausedAt, 0.4);
    EXPECT_EQ(first->characters[1].performance.layers[0].loop, scene::Loop::Clamp);
    EXPECT_TRUE(first->characters[1].performance.morphs[0].add);
    EXPECT_EQ(first->characters[2].performance.layers[0].mask,
              (std::vector<scene::MaskEntry>{{2, 1.0}}));
    ASSERT_TRUE(asset::saveScene(dir.dir / "b.json", *first).ok());
    const auto second = asset::loadScene(dir.dir / "b.json");
    ASSERT_TRUE(second.ok()) << second.error().message;
    for (std::size_t i = 0; i < first->characters.size(); ++i)
        EXPECT_EQ(second->characters[i].performance, first->characters[i].performance) << i;
}

TEST(LoadWorld, ModelsAreLoadedOnceAndPlacedSideBySide) {
    SceneDir dir;
    const std::string model = (dir.dir / "models/twojoint.glb").string();
    const std::vector<std::string> paths{model, "builtin:sphere?segments=16", model};
    const auto world = render::loadWorld(paths);
    ASSERT_TRUE(world.ok()) << world.error().message;
    ASSERT_EQ(world->characters.size(), 3u);
    EXPECT_EQ(world->characters[0].model, world->characters[2].model) << "one file, one model";
    EXPECT_EQ(world->characters[0].mainClip(), 0) << "a model plays its first clip";
    EXPECT_EQ(world->characters[1].mainClip(), -1) << "the sphere has none";
    // Left to right in the order given, their bounds apart.
    std::vector<render::Bounds> bounds;
    for (const scene::Character& c : world->characters) {
        scene::World one;
        one.characters.push_back(c);
        bounds.push_back(render::worldBounds(one));
    }
    for (std::size_t i = 0; i + 1 < bounds.size(); ++i)
        EXPECT_LT(bounds[i].max.x, bounds[i + 1].min.x) << i;
    const render::Bounds all = render::worldBounds(*world);
    EXPECT_NEAR(all.min.x, -all.max.x, 1e-3f) << "centred on the origin";
}

TEST(LoadWorld, OneModelStandsAtTheOriginAndAScenePassesThrough) {
    SceneDir dir;
    const auto one = render::loadWorld(std::vector<std::string>{"builtin:sphere"});
    ASSERT_TRUE(one.ok()) << one.error().message;
    ASSERT_EQ(one->characters.size(), 1u);
    EXPECT_EQ(one->characters[0].placement.translation, glm::dvec3(0.0));
    EXPECT_EQ(one->characters[0].modelPath, "builtin:sphere");
    const auto scene = render::loadWorld(std::vector<std::string>{
        (std::filesystem::path(GLASS_SOURCE_DIR) / "assets/scenes/walk_past.json").string()});
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->characters.size(), 3u);
    EXPECT_TRUE(scene->camera.has_value());
}

TEST(LoadWorld, BadListsFailClearly) {
    SceneDir dir;
    const auto scenePath = dir.write("s.json", Json{{"characters", {character()}}}.dump());
    struct Case {
        std::vector<std::string> paths;
        std::string expected;
    };
    for (const Case& c :
         {Case{{}, "render::loadWorld(): no model or scene file given"},
          Case{{scenePath.string(), "builtin:sphere"}, "cannot be mixed with other models"},
          Case{{"builtin:sphere", (dir.dir / "missing.glb").string()}, "missing.glb"},
          Case{std::vector<std::string>(core::limits::kMaxCharacters + 1, "builtin:sphere"),
               "4097 models, the limit is 4096 characters"}}) {
        const auto world = render::loadWorld(c.paths);
        ASSERT_FALSE(world.ok()) << c.expected;
        EXPECT_NE(world.error().message.find(c.expected), std::string::npos)
            << world.error().message;
    }
}

TEST(LoadWorld, LimitsHoldOnAnyWorld) {
    auto sphere = std::make_shared<const scene::Model>(asset::makeSphere(1024));
    scene::World world;
    for (int i = 0; i < 100; ++i) {
        scene::Character c;
        c.name = "sphere " + std::to_string(i);
        c.model = sphere;
        world.characters.push_back(std::move(c));
    }
    EXPECT_TRUE(asset::checkWorldLimits(world, "crowd").ok());
    // A 1024-segment sphere has about 2^19 vertices: 2^26 in all is reached past 128 of them.
    const std::size_t each = sphere->meshes[0].primitives[0].vertexCount();
    const std::size_t over = core::limits::kMaxSceneVertices / each;
    world.characters.resize(over + 1, world.characters[0]);
    const auto limits = asset::checkWorldLimits(world, "crowd");
    ASSERT_FALSE(limits.ok());
    EXPECT_NE(limits.error().message.find("crowd: characters[" + std::to_string(over) + "]"),
              std::string::npos)
        << limits.error().message;
}

} // namespace
