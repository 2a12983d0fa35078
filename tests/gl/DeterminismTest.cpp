// Same inputs, same bytes: the default scene (a sun with shadows and caustics, characters walking)
// rendered three times by fresh renderers, every method with temporal accumulation, while two
// threads keep the CPU busy. In one process (three renderers alive at once, as the tests make
// them) and in three glass-capture processes. docs/hardening.md, "Deterministic frames".
#include "WorldRig.h"

#include "support/GlTest.h"
#include "support/TestSupport.h"

#include <atomic>
#include <fstream>
#include <iterator>
#include <thread>

namespace {

using test::WorldRig;

/** One test a method (ctest runs them side by side). */
class Determinism : public test::GlTest, public ::testing::WithParamInterface<const char*> {};
class DeterminismTool : public ::testing::TestWithParam<const char*> {};

const char* const kMethods[] = {"opaque", "sir", "isr", "dir", "trace", "hybrid"};
constexpr int kSize = 64;
// Three frames a thirtieth of a second apart: the history accumulates while the walkers move.
const double kTimes[] = {1.0, 1.0 + 1.0 / 30.0, 1.0 + 2.0 / 30.0};

/** Two threads spinning until destroyed: the frames render on a loaded machine. */
class BusyCpu {
public:
    BusyCpu() {
        for (auto& thread : mThreads)
            thread = std::thread([this] {
                std::uint64_t x = 1;
                while (!mStop.load(std::memory_order_relaxed))
                    x = x * 6364136223846793005ull + 1442695040888963407ull;
                mSink.store(x, std::memory_order_relaxed);
            });
    }
    ~BusyCpu() {
        mStop = true;
        for (auto& thread : mThreads)
            thread.join();
    }

private:
    std::atomic<bool> mStop{false};
    std::atomic<std::uint64_t> mSink{0};
    std::thread mThreads[2];
};

/** Every frame of `rig` at kTimes, their HDR floats one after another. */
std::vector<float> frames(WorldRig& rig) {
    std::vector<float> all;
    for (double time : kTimes) {
        const std::vector<float> frame = rig.renderHdr(time);
        all.insert(all.end(), frame.begin(), frame.end());
    }
    return all;
}

/** How many floats differ, and by at most how much. */
std::string difference(const std::vector<float>& a, const std::vector<float>& b) {
    if (a.size() != b.size())
        return "sizes " + std::to_string(a.size()) + " and " + std::to_string(b.size());
    std::size_t count = 0;
    float most = 0.0f;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::memcmp(&a[i], &b[i], sizeof(float)) != 0) {
            ++count;
            most = std::max(most, std::abs(a[i] - b[i]));
        }
    return std::to_string(count) + " floats differ, by up to " + std::to_string(most);
}

TEST_P(Determinism, FreshRenderersInOneProcessMakeTheSameBytes) {
    const char* method = GetParam();
    const BusyCpu busy;
    std::vector<std::unique_ptr<WorldRig>> rigs;
    for (int copy = 0; copy < 3; ++copy) {
        rigs.push_back(
            std::make_unique<WorldRig>(test::projectScene("walk_past.json"), context(), kSize));
        rigs.back()->useSceneCamera();
        rigs.back()->set("method", method);
        rigs.back()->temporal.enabled = true;
    }
    const std::vector<float> first = frames(*rigs[0]);
    ASSERT_FALSE(first.empty());
    for (int copy = 1; copy < 3; ++copy) {
        const std::vector<float> again = frames(*rigs[std::size_t(copy)]);
        EXPECT_TRUE(again == first)
            << method << ", renderer " << copy + 1 << ": " << difference(first, again);
    }
}

TEST_P(DeterminismTool, SeparateProcessesMakeTheSameBytes) {
    const char* method = GetParam();
    const BusyCpu busy;
    test::TempDir dir;
    const std::string capture = std::string(GLASS_BIN_DIR) + "/glass-capture";
    const std::string scene = std::string(GLASS_SOURCE_DIR) + "/assets/scenes/walk_past.json";
    std::vector<std::string> bytes;
    for (int copy = 0; copy < 3; ++copy) {
        const auto out = dir / std::to_string(copy);
        std::string log;
        const int status = test::runCommand(capture + " " + scene + " --size 64x64 --method " +
                                                method + " --temporal on --warmup 2 --time 1.1 " +
                                                "--force --out " + out.string() + " 2>&1",
                                            &log);
        if (log.find("no headless OpenGL") != std::string::npos)
            GTEST_SKIP() << log;
        ASSERT_EQ(status, 0) << log;
        std::ifstream png(out / "walk_past_scene_t1.100.png", std::ios::binary);
        ASSERT_TRUE(png.good()) << log;
        bytes.emplace_back(std::istreambuf_iterator<char>(png), std::istreambuf_iterator<char>());
    }
    EXPECT_EQ(bytes[1], bytes[0]) << method << ": the second process's frame";
    EXPECT_EQ(bytes[2], bytes[0]) << method << ": the third process's frame";
}

TEST_F(Determinism, ABlendedPoseIsAFunctionOfTime) {
    // The figure blending a weighted layer, an additive one and two crossfades: a frame at t is
    // the same bytes whether the renderer played every frame from 0 or starts at t.
    scene::World world = test::generatedWorld("glass_figure.glb");
    const scene::Model& model = *world.characters[0].model;
    scene::Performance& p = world.characters[0].performance;
    p.layers[0].weight = 0.8;
    scene::Layer& wave = p.layers.emplace_back();
    wave.clip = *model.findAnimation("wave");
    wave.weight = 0.5;
    wave.additive = true;
    p.transitions = {{0.2, *model.findAnimation("idle"), 0.3}, {0.4, 0, 0.2}};
    p.rootMotion = scene::RootMotion::Accumulate;
    WorldRig played(world, context(), 48), started(world, context(), 48);
    std::vector<float> last;
    for (int k = 0; k <= 15; ++k)
        last = played.renderHdr(k / 30.0);
    const std::vector<float> fresh = started.renderHdr(15 / 30.0);
    EXPECT_TRUE(last == fresh) << difference(last, fresh);
}

TEST_F(Determinism, EnvironmentsMadeUnderLoadAreTheSame) {
    // The timing-dependent frame's cause, caught where it happens: the environment's mip levels,
    // which llvmpipe's rasteriser generates on its own threads, read by the prefilter's compute
    // right after. Without the finish between them (Environment::create) some of these copies
    // differ in nearly every run; the frames above catch it in a few.
    const BusyCpu busy;
    const asset::HdrImage sky = render::Environment::proceduralSky(128);
    std::vector<std::vector<float>> first;
    for (int copy = 0; copy < 40; ++copy) {
        auto renderer = render::Renderer::create(sky, context());
        ASSERT_TRUE(renderer.ok()) << renderer.error().message;
        const render::Environment& environment = (*renderer)->environment();
        std::vector<std::vector<float>> levels{environment.irradiance().downloadFloat()};
        for (int level = 1; level < int(environment.levels()); ++level)
            levels.push_back(environment.prefiltered().downloadFloat(level));
        if (copy == 0)
            first = std::move(levels);
        for (std::size_t level = 0; level < levels.size(); ++level)
            ASSERT_TRUE(levels[level] == first[level])
                << "copy " << copy + 1 << (level ? ", prefiltered level " : ", irradiance ")
                << (level ? std::to_string(level) : "") << ": "
                << difference(first[level], levels[level]);
    }
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, Determinism, ::testing::ValuesIn(kMethods));
INSTANTIATE_TEST_SUITE_P(EveryMethod, DeterminismTool, ::testing::ValuesIn(kMethods));

} // namespace
