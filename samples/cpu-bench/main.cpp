// glass-cpu-bench: load time of models, the time to sample + deform one frame on the CPU
// reference path, and to pose many characters playing one clip or two layers (medians of many
// runs). A benchmark, not a test: it asserts nothing.
#include "../common/Cli.h"
#include "../common/ToolMain.h"
#include "engine/anim/Pose.h"
#include "engine/asset/ModelLoader.h"
#include "engine/deform/CpuDeformer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

/** The median time to pose `characters` characters (each its performance, a hundredth of a
 *  second apart) and compute every skin's matrices: the CPU side of a frame's animation. */
double animateMs(const scene::Model& model, const scene::Performance& performance, int characters,
                 int runs, double duration) {
    std::vector<anim::Pose> poses(std::size_t(characters), anim::restPose(model));
    std::vector<int> skinned;
    for (int node : model.meshNodes())
        if (model.nodes[std::size_t(node)].skin >= 0)
            skinned.push_back(node);
    std::vector<glm::mat4> skin;
    std::vector<double> frames;
    for (int r = 0; r < runs; ++r) {
        const double time = duration * double(r) / double(runs);
        const auto start = Clock::now();
        for (int k = 0; k < characters; ++k) {
            anim::Pose& pose = poses[std::size_t(k)];
            anim::evaluate(model, performance, time + 0.01 * k, pose);
            for (int node : skinned)
                anim::skinMatrices(model, pose, node, skin);
        }
        frames.push_back(millisecondsSince(start));
    }
    return median(frames);
}

} // namespace

int run(int argc, char** argv) {
    int runs = 200, characters = 64;
    std::vector<std::string> models;
    CLI::App app{"", "glass-cpu-bench"};
    tool::configure(app,
                    "glass-cpu-bench MODEL... [--runs N]: prints, per model, the median load time "
                    "(with and without image decoding), the median time to sample the first "
                    "clip and deform every mesh node (the CPU reference), and the median time to "
                    "pose N characters and their skins playing one clip, then two layers, as "
                    "one JSON line per model. A benchmark: it asserts nothing.",
                    "Exit status: 0, 1 a model could not be loaded, 2 bad arguments.");
    app.add_option("models", models, "glTF models")->type_name("MODEL");
    app.add_option("--runs", runs,
                   "runs of the sample and deform, a twentieth (at least 5) of "
                   "the loads (default 200)")
        ->check(tool::range(1, 1000000))
        ->type_name("N");
    app.add_option("--characters", characters,
                   "characters posed for the animate times (default 64)")
        ->check(tool::range(1, 100000))
        ->type_name("N");
    if (const auto code = tool::parseArguments(app, argc, argv))
        return *code;
    if (models.empty())
        return tool::usageError(app, "no model given");
    for (const std::string& path : models) {
        std::vector<double> loads, geometryLoads;
        for (int r = 0; r < std::max(5, runs / 20); ++r) {
            for (bool decodeImages : {true, false}) {
                const auto start = Clock::now();
                auto model = asset::loadModel(path, {.decodeImages = decodeImages});
                (decodeImages ? loads : geometryLoads).push_back(millisecondsSince(start));
                if (!model) {
                    std::fprintf(stderr, "glass-cpu-bench: %s\n", model.error().message.c_str());
                    return 1;
                }
            }
        }
        const scene::Model model = std::move(asset::loadModel(path).value());
        const int clip = model.animations.empty() ? -1 : 0;
        const double duration = clip < 0 ? 1.0 : model.animations[0].duration;
        std::vector<double> frames;
        std::size_t vertices = 0;
        anim::Pose pose = anim::restPose(model);
        for (int r = 0; r < runs; ++r) {
            const double time = duration * double(r) / double(runs);
            const auto start = Clock::now();
            anim::applyClip(model, clip, time, pose);
            anim::updateWorld(model, pose);
            const auto deformed = deform::deformScene(model, pose);
            frames.push_back(millisecondsSince(start));
            vertices = 0;
            for (const auto& instance : deformed)
                for (const auto& primitive : instance.primitives)
                    vertices += primitive.positions.size();
        }
        // 64 characters' poses: one clip each, then two layers each: the same clip at 0.6 and
        // a third of a run later at 0.4, so that both arms sample the same keys.
        scene::Performance two = scene::Performance::single(clip);
        two.layers[0].weight = 0.6;
        two.layers.push_back(two.layers[0]);
        two.layers[1].weight = 0.4;
        two.layers[1].timeOffset = duration / 3.0;
        const double single =
            animateMs(model, scene::Performance::single(clip), characters, runs, duration);
        const double layered = animateMs(model, two, characters, runs, duration);
        std::printf("{\"model\": \"%s\", \"load_ms_median\": %.3f, "
                    "\"load_without_images_ms_median\": %.3f, \"sample_deform_ms_median\": %.4f, "
                    "\"vertices\": %zu, \"animate_characters\": %d, "
                    "\"animate_one_clip_ms_median\": %.4f, \"animate_two_layers_ms_median\": %.4f, "
                    "\"runs\": %d}\n",
                    model.sourceName.c_str(), median(loads), median(geometryLoads), median(frames),
                    vertices, characters, single, layered, runs);
    }
    return 0;
}

int main(int argc, char** argv) {
    return tool::guardedMain("glass-cpu-bench", run, argc, argv);
}
