// glass-soak: renders many frames headless while the clip loops, the glass method switches and
// the viewport resizes, and reports the process's resident memory and the context's live GL
// objects along the way; fails when either still grows after the warm-up.
#include "../common/Cli.h"
#include "../common/HeadlessScene.h"
#include "../common/ToolMain.h"
#include "engine/anim/Pose.h"
#include "engine/asset/ModelLoader.h"
#include "engine/gl/Buffer.h"
#include "engine/gl/Debug.h"
#include "engine/render/Renderer.h"
#include "refraction/RefractionPlugin.h"

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace {

constexpr const char* kDescription =
    R"(glass-soak [MODEL|SCENE [MODEL...]] [OPTIONS]: renders MODEL (default: builtin:sphere; a
scene file, or several models side by side) headless for --frames frames: the clips loop; every
--switch-every frames the glass method moves on (opaque, sir, isr, dir, dir with TIR reflect and
temporal accumulation, trace with it, hybrid); every --resize-every frames the viewport takes
the next of 4 sizes (around 128x128) and the world gains or loses a character (a copy of the
first, beside it: the renderer places and releases its deformer, the glass plugin its caches).
Every --report-every frames it prints the frame, resident memory (RSS, from /proc/self/statm)
and the live GL objects (counted by asking the driver about every name).
Warm-up: two full cycles of every pairing of method and size (the least common multiple of 7
switches and 4 resizes; every lazily created object exists by then).)";

constexpr const char* kExitStatus =
    R"(Exit status: 0; 1 when a report after the warm-up counts more live GL objects than any
report during it, when RSS at the end is more than 8 MiB over its warm-up maximum, or on any GL
error; 2 bad arguments, or a run too short to have a report after the warm-up.)";

long residentKiB() {
    std::ifstream statm("/proc/self/statm");
    long pages = 0, resident = 0;
    statm >> pages >> resident;
    return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

struct Report {
    int frame = 0;
    long rssKiB = 0;
    gl::LiveObjects live;
    std::string method;
    glm::ivec2 size{0};
};

struct Options {
    std::vector<std::string> paths;
    int frames = 10000, switchEvery = 100, resizeEvery = 175, reportEvery = 220;
    bool json = false, injectLeak = false;
};

std::optional<int> parse(int argc, char** argv, Options& o) {
    CLI::App app{"", "glass-soak"};
    tool::configure(app, kDescription, kExitStatus);
    app.add_option("models", o.paths, "glTF models or a scene file (.json)")
        ->type_name("MODEL|SCENE");
    for (auto [name, count, help] :
         {std::tuple{"--frames", &o.frames, "frames to render (default 10000)"},
          std::tuple{"--switch-every", &o.switchEvery,
                     "frames between method switches (default 100)"},
          std::tuple{"--resize-every", &o.resizeEvery,
                     "frames between resizes and world changes (default 175)"},
          std::tuple{"--report-every", &o.reportEvery, "frames between reports (default 220)"}})
        app.add_option(name, *count, help)->check(tool::range(1, 100000000))->type_name("N");
    app.add_flag("--json", o.json, "print the reports as JSON");
    app.add_flag("--inject-leak", o.injectLeak,
                 "keep one more GL buffer alive at every report (the test that shows the check "
                 "fails on a leak)");
    return tool::parseArguments(app, argc, argv);
}

/** The reports after the warm-up against those during it: 0 stable, 1 grown (or GL errors), 2
 *  no report after the warm-up. */
int judge(const std::vector<Report>& reports, const Options& o, int cycle) {
    // Warm-up: two full cycles of every pairing of method, size and world, so that every lazily
    // created object (a pass's timer query, ISR's BVH buffers, the pool's textures for each size,
    // the driver's code for each method at each size) exists: with only the longer of the two
    // cycles, the hybrid first ran at one size after the warm-up, and RSS rose by 3-15 MiB. After
    // it, neither the live GL objects nor RSS may pass their warm-up maximum (RSS: by 8 MiB).
    const int warmup = 2 * cycle;
    int warmObjects = 0, maxObjects = 0;
    long warmRss = 0, lastRss = 0;
    bool pastWarmup = false;
    for (const Report& r : reports) {
        if (r.frame <= warmup) {
            warmObjects = std::max(warmObjects, r.live.total());
            warmRss = std::max(warmRss, r.rssKiB);
        } else {
            pastWarmup = true;
            maxObjects = std::max(maxObjects, r.live.total());
            lastRss = r.rssKiB;
        }
    }
    const bool objectsStable = maxObjects <= warmObjects;
    const bool rssStable = lastRss - warmRss <= 8L * 1024L;
    const std::uint64_t errors = gl::errorCount();
    if (o.json) {
        nlohmann::json out = {
            {"model", o.paths.size() == 1 ? nlohmann::json(o.paths[0]) : nlohmann::json(o.paths)},
            {"frames", o.frames},
            {"cycle", cycle},
            {"gl_errors", errors},
            {"reports", nlohmann::json::array()}};
        for (const Report& r : reports)
            out["reports"].push_back({{"frame", r.frame},
                                      {"rss_kib", r.rssKiB},
                                      {"gl_objects", r.live.total()},
                                      {"method", r.method},
                                      {"size", {r.size.x, r.size.y}}});
        std::printf("%s\n", out.dump(2).c_str());
    }
    std::printf("glass-soak: %d frames; warm-up (first %d): max %d GL objects, max RSS %ld KiB; "
                "after: max %d GL objects, last RSS %ld KiB; %llu GL errors\n",
                o.frames, warmup, warmObjects, warmRss, maxObjects, lastRss,
                static_cast<unsigned long long>(errors));
    if (!pastWarmup) {
        std::fprintf(stderr, "glass-soak: no report after the warm-up of %d frames: run longer\n",
                     warmup);
        return 2;
    }
    if (!objectsStable || !rssStable || errors > 0) {
        std::fprintf(stderr, "glass-soak: %s\n",
                     !objectsStable ? "live GL objects grew after warm-up"
                     : !rssStable   ? "resident memory grew by more than 8 MiB after warm-up"
                                    : "GL errors");
        return 1;
    }
    return 0;
}

/** The world with one character more: a copy of the first, beside the others, a little later
 *  in its clips. */
scene::World grownWorld(const tool::HeadlessScene& headless) {
    scene::World grown = headless.world;
    scene::Character extra = grown.characters.front();
    extra.name += " (copy)";
    extra.placement.translation.x += 2.5 * double(headless.bounds.radius());
    extra.performance.shift(0.37);
    grown.characters.push_back(std::move(extra));
    return grown;
}

/** A method the soak cycles through: its TIR policy, and whether it accumulates over frames
 *  (the temporal history allocated, kept while off). */
struct Method {
    std::string name, tir;
    bool temporal;
};
const std::vector<Method> kMethods = {{"opaque", "clamp", false},  {"sir", "clamp", false},
                                      {"isr", "clamp", false},     {"dir", "clamp", false},
                                      {"dir", "reflect", true},    {"trace", "reflect", true},
                                      {"hybrid", "reflect", false}};
const std::vector<glm::ivec2> kSizes = {{128, 128}, {160, 96}, {96, 144}, {112, 112}};

/** The process's memory and live GL objects after `frame` frames, printed unless --json. */
Report report(int frame, const std::string& method, glm::ivec2 size, bool json) {
    gl::finish();
    Report r{frame, residentKiB(), gl::liveObjects(), method, size};
    if (!json)
        std::printf("frame %6d  rss %7ld KiB  GL objects %4d (buffers %d, textures %d, "
                    "framebuffers %d, vertex arrays %d, programs %d, queries %d)  %s %dx%d\n",
                    r.frame, r.rssKiB, r.live.total(), r.live.buffers, r.live.textures,
                    r.live.framebuffers, r.live.vertexArrays, r.live.programs, r.live.queries,
                    r.method.c_str(), size.x, size.y);
    std::fflush(stdout);
    return r;
}

} // namespace

int run(int argc, char** argv) {
    Options o;
    if (const auto code = parse(argc, argv, o))
        return *code;
    if (o.paths.empty())
        o.paths.push_back("builtin:sphere");
    auto opened = tool::openHeadlessScene(o.paths, 256);
    if (!opened) {
        std::fprintf(stderr, "glass-soak: %s\n", opened.error().message.c_str());
        return 1;
    }
    tool::HeadlessScene& headless = *opened;
    plugin::Plugin* const plugin = headless.glass.get();
    (void)plugin->parameters().set("glass", "all");
    // Every other size, one character more.
    const scene::World grown = grownWorld(headless);
    // The frames after which methods, sizes and worlds come round together (the world alternates
    // with every size, an even count of them): every pairing of a method with a size and world.
    const int cycle =
        std::lcm(o.switchEvery * int(kMethods.size()), o.resizeEvery * int(kSizes.size()));
    std::vector<Report> reports;
    std::vector<gl::Buffer> leaked; // --inject-leak: one more live buffer per report
    for (int frame = 0; frame < o.frames; ++frame) {
        const auto& [method, tir, temporal] =
            kMethods[std::size_t(frame / o.switchEvery) % kMethods.size()];
        const glm::ivec2 size = kSizes[std::size_t(frame / o.resizeEvery) % kSizes.size()];
        (void)plugin->parameters().set("method", method);
        (void)plugin->parameters().set("tir", tir);
        render::RenderSettings settings;
        settings.size = size;
        settings.ground = true;
        settings.temporal.enabled = temporal;
        const scene::World& world = (frame / o.resizeEvery) % 2 ? grown : headless.world;
        const double time = std::fmod(frame / 30.0, headless.duration);
        auto stats = headless.renderer->render(world, headless.camera(size, time), settings, time);
        if (!stats) {
            std::fprintf(stderr, "glass-soak: frame %d: %s\n", frame,
                         stats.error().message.c_str());
            return 1;
        }
        if ((frame + 1) % o.reportEvery == 0 || frame + 1 == o.frames) {
            if (o.injectLeak)
                leaked.emplace_back(std::size_t(1) << 16);
            reports.push_back(report(frame + 1, method + "/" + tir + (temporal ? "/temporal" : ""),
                                     size, o.json));
        }
    }
    gl::checkErrors("glass-soak");
    return judge(reports, o, cycle);
}

int main(int argc, char** argv) {
    return tool::guardedMain("glass-soak", run, argc, argv);
}
