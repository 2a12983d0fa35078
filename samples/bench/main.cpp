// glass-bench: frame time of each glass method on a model or a scene (and on N copies of it on a
// grid), the methods interleaved frame by frame so that their ratios hold on a noisy machine.
#include "Plot.h"

#include "../common/Cli.h"
#include "../common/HeadlessScene.h"
#include "../common/ToolMain.h"
#include "engine/anim/Pose.h"
#include "engine/asset/ModelLoader.h"
#include "engine/capture/Image.h"
#include "engine/core/Files.h"
#include "engine/core/Limits.h"
#include "engine/deform/CpuDeformer.h"
#include "engine/gl/Commands.h"
#include "engine/gl/Debug.h"
#include "engine/render/Renderer.h"
#include "refraction/RefractionPlugin.h"

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace {

constexpr const char* kDescription =
    R"(glass-bench MODEL|SCENE [MODEL...] [OPTIONS]: renders MODEL (a scene file, or several models
side by side) headless (EGL) at each OpenSubdiv level of --subdiv with each method, interleaved
frame by frame (opaque, sir, isr, dir, opaque, ...) while the clips play (1/30 s per round),
after --warmup rounds, for --frames measured rounds. Per method, level and count: median and p95
frame time (render + finish, wall clock), the median CPU time of the frame on the render thread
(animate, upload, record, issue and, on a CPU rasteriser, execute; "cpu ms") and of the engine's
own work ("animate+record ms": pose every character, upload the skin matrices, list and claim
the draw items, record and compile the frame graph), each pass's median GPU and CPU time,
triangles drawn, pixels the world covers (CPU coverage of the deformed file triangles at the
middle of the clip) and the GPU memory of the frame graph's pooled textures and buffers (the
layer arrays among them). Without --instances every pass is timed alone, the wall clock between
a finish before it and one after it (exact per-pass GPU times; the CPU times then include those
waits); with it, frames pipeline as in an application and pass times come from the timer
queries. Prints a table (and a progress line on a terminal).)";

/** The steps glass-bench --skip can leave out of a frame, each a define SKIP_<STEP> that the
 *  shaders test (RenderSettings::skippedSteps; docs/performance.md, "Where the time goes"). */
const std::vector<std::pair<std::string, std::string>> kSkippableSteps = {
    {"entry", "the walk pass shades nothing (its rectangle and mask alone)"},
    {"walk", "the walk shades its entry's colour and stops"},
    {"search", "the walk's search: each crossing at the next layer of the start's own pixel"},
    {"normals", "the walk's filtered normals: the crossed layer's own"},
    {"surfaces", "the walk's textured surfaces per layer: the material's"},
    {"interface", "the interface model (Fresnel, specular, film): a constant reflectance"},
    {"scene", "the walk's marches through the nearby opaque scene"},
    {"scene_tiles", "the marches' test of the scene's depth tiles (the frame is the same)"},
    {"glass_color", "the light at the entry (reflection, highlights, clear coat, sheen)"},
    {"lights", "every punctual light's shading (and its shadow), everywhere"},
    {"shadows", "every shadow lookup, everywhere"},
    {"motion", "the walk's motion for the temporal resolve"},
    {"handover", "the hybrid hands no pixel to its trace"},
    {"textures", "the captures' and the glass shadow's texture reads"},
    {"fallback", "the capture's bids for the overflow fallback"},
    {"history_filter", "the resolve's Catmull-Rom history read: one bilinear read"},
    {"clip", "the resolve's variance clipping"},
    {"footprint", "the resolve's 3x3 footprint check: the pixel's own motion"}};

constexpr const char* kExitStatus = "Exit status: 0, 1 a load or render error, 2 bad arguments.";

double percentile(std::vector<double> values, double p) {
    if (values.empty())
        return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t i =
        std::min(values.size() - 1, std::size_t(std::lround(p * double(values.size() - 1))));
    return values[i];
}

/** Pixels covered by the deformed triangles at `size` (any facing), by edge functions at pixel
 *  centres: the share of the image the glass pass works on. */
std::size_t coveredPixels(const scene::World& world, double time, const render::Camera& camera,
                          glm::ivec2 size) {
    std::vector<std::uint8_t> covered(std::size_t(size.x) * std::size_t(size.y), 0);
    const glm::dmat4 viewProjection(camera.viewProjection());
    for (const scene::Character& character : world.characters)
        for (const deform::DeformedInstance& instance : deform::deformCharacter(character, time)) {
            const scene::Model& model = *character.model;
            const scene::Mesh& mesh = model.meshes[std::size_t(instance.mesh)];
            for (std::size_t p = 0; p < instance.primitives.size(); ++p) {
                std::vector<glm::dvec3> screen;
                bool behind = false;
                for (const glm::dvec3& v : instance.primitives[p].positions) {
                    const glm::dvec4 clip =
                        viewProjection * instance.meshToWorld * glm::dvec4(v, 1.0);
                    behind = behind || clip.w <= 0.0;
                    screen.emplace_back((clip.x / clip.w * 0.5 + 0.5) * size.x,
                                        (clip.y / clip.w * 0.5 + 0.5) * size.y, 0.0);
                }
                if (behind)
                    continue; // the benchmark frames the whole model; nothing is behind the camera
                const auto& indices = mesh.primitives[p].indices;
                for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
                    const glm::dvec3 a = screen[indices[t]], b = screen[indices[t + 1]],
                                     c = screen[indices[t + 2]];
                    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
                    if (area == 0.0)
                        continue;
                    const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
                    const int x1 = std::min(size.x - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
                    const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
                    const int y1 = std::min(size.y - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
                    for (int y = y0; y <= y1; ++y)
                        for (int x = x0; x <= x1; ++x) {
                            const double px = x + 0.5, py = y + 0.5;
                            const double w0 = (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
                            const double w1 = (c.x - b.x) * (py - b.y) - (c.y - b.y) * (px - b.x);
                            const double w2 = (a.x - c.x) * (py - c.y) - (a.y - c.y) * (px - c.x);
                            if ((w0 >= 0 && w1 >= 0 && w2 >= 0) || (w0 <= 0 && w1 <= 0 && w2 <= 0))
                                covered[std::size_t(y) * std::size_t(size.x) + std::size_t(x)] = 1;
                        }
                }
            }
        }
    return std::size_t(std::count(covered.begin(), covered.end(), std::uint8_t(1)));
}

struct MethodRun {
    std::string method;
    bool temporal = false;
    bool lit = true;                  ///< the frame's punctual lights on (RenderSettings::lights)
    std::vector<std::string> skipped; ///< RenderSettings::skippedSteps (--skip)
    /** A temporal run's own plugin and renderer, whose history carries across its frames as in
     *  an application (the other runs share the scene's, switching the method each frame). */
    std::unique_ptr<plugin::Plugin> glass;
    std::unique_ptr<render::Renderer> renderer;
    std::vector<double> frameMs, cpuMs, engineMs;
    std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> passes;
    std::vector<std::string> passOrder;
    std::size_t transientBytes = 0, historyBytes = 0;
    refraction::LayerStats layers; ///< after the last round (layered methods)
    std::string label() const {
        std::string skips;
        for (const std::string& step : skipped)
            skips += (skips.empty() ? " -" : "-") + step;
        return method + (lit ? "" : "+unlit") + (temporal ? "+temporal" : "") + skips;
    }
};

/** N characters from `base`: its characters in turn, on a square grid in the x-z plane (cells
 *  a fifth wider than the widest character), copy k at phase k/N of its clip. */
scene::World gridWorld(const scene::World& base, int count) {
    scene::World grid = base;
    grid.characters.clear();
    grid.camera.reset(); // the tool frames the whole grid
    float cell = 0.0f;
    for (const scene::Character& c : base.characters) {
        std::map<int, render::Bounds> perClip;
        const render::Bounds b = render::performanceBounds(*c.model, c.performance, perClip, 4);
        cell = std::max({cell, b.max.x - b.min.x, b.max.z - b.min.z});
    }
    cell *= 1.2f;
    const int columns = int(std::ceil(std::sqrt(double(count))));
    for (int k = 0; k < count; ++k) {
        scene::Character c = base.characters[std::size_t(k) % base.characters.size()];
        c.name += " #" + std::to_string(k + 1);
        const double centre = 0.5 * double(columns - 1);
        c.placement.translation = glm::dvec3(double(cell) * (double(k % columns) - centre), 0.0,
                                             double(cell) * (double(k / columns) - centre));
        c.performance.shift(c.period() * double(k) / double(count));
        grid.characters.push_back(std::move(c));
    }
    return grid;
}

/** With --skip: what leaving each step out saved, against the same method with every step
 *  (`whole`, by method, light and accumulation). */
void printSkipped(const std::vector<MethodRun>& runs,
                  const std::map<std::tuple<std::string, bool, bool>, double>& whole) {
    bool header = false;
    for (const MethodRun& r : runs) {
        const auto all = whole.find({r.method, r.lit, r.temporal});
        if (r.skipped.empty() || all == whole.end() || all->second <= 0.0)
            continue;
        if (!header)
            std::printf("\n| run | skipped | median ms | saved ms | saved, of the frame |\n"
                        "|---|---|---:|---:|---:|\n");
        header = true;
        std::string steps;
        for (const std::string& step : r.skipped)
            steps += (steps.empty() ? "" : ", ") + step;
        const double median = percentile(r.frameMs, 0.5);
        std::printf("| %s | %s | %.2f | %.2f | %.1f%% |\n", r.label().c_str(), steps.c_str(),
                    median, all->second - median, 100.0 * (all->second - median) / all->second);
    }
    if (header)
        std::printf("\n");
}

/** One run's figures, in the table's and the report's terms. */
struct RunFigures {
    double median = 0.0, p95 = 0.0, cpu = 0.0, engine = 0.0;
    double ratio = 0.0;         ///< to the opaque run with the same lights; 0: none ran
    double ratioUnlit = 0.0;    ///< a lit run's to the unlit opaque run; 0: none ran
    double saved = 0.0;         ///< what a run with --skip saves against the whole method
    double temporalRatio = 0.0; ///< to the same method without accumulation; 0: none ran
    double rays = 0.0, nodesPerRay = 0.0, raysPerSecond = 0.0;
    std::string slowest; ///< the three slowest passes
    nlohmann::json passes = nlohmann::json::array();
};

/** The medians of the runs with every step (no --skip), by method, lights and accumulation:
 *  what the ratios are to. */
using WholeMedians = std::map<std::tuple<std::string, bool, bool>, double>;

double wholeMedian(const WholeMedians& whole, const std::string& method, bool lit, bool temporal) {
    const auto found = whole.find({method, lit, temporal});
    return found == whole.end() ? 0.0 : found->second;
}

RunFigures figuresOf(const MethodRun& r, const WholeMedians& whole) {
    RunFigures f;
    f.median = percentile(r.frameMs, 0.5);
    f.p95 = percentile(r.frameMs, 0.95);
    f.cpu = percentile(r.cpuMs, 0.5);
    f.engine = percentile(r.engineMs, 0.5);
    std::vector<std::pair<double, std::string>> slowest;
    for (const std::string& name : r.passOrder) {
        const auto& [gpu, cpu] = r.passes.at(name);
        slowest.emplace_back(percentile(gpu, 0.5), name);
        f.passes.push_back(
            {{"name", name}, {"gpu_ms", percentile(gpu, 0.5)}, {"cpu_ms", percentile(cpu, 0.5)}});
    }
    std::sort(slowest.rbegin(), slowest.rend());
    for (std::size_t i = 0; i < std::min<std::size_t>(3, slowest.size()); ++i) {
        char item[96];
        std::snprintf(item, sizeof item, "%s%s %.1f", i ? ", " : "", slowest[i].second.c_str(),
                      slowest[i].first);
        f.slowest += item;
    }
    const double opaque = wholeMedian(whole, "opaque", r.lit, false);
    const double unlit = wholeMedian(whole, "opaque", false, false);
    f.ratio = opaque > 0.0 ? f.median / opaque : 0.0;
    f.ratioUnlit = r.lit && unlit > 0.0 ? f.median / unlit : 0.0;
    const double all = wholeMedian(whole, r.method, r.lit, r.temporal);
    f.saved = !r.skipped.empty() && all > 0.0 ? all - f.median : 0.0;
    const double off = wholeMedian(whole, r.method, r.lit, false);
    f.temporalRatio = r.temporal && off > 0.0 ? f.median / off : 0.0;
    // The trace's rays (a frame), BVH nodes a ray, and rays a second of the whole frame.
    f.rays = double(r.layers.traceRays);
    f.nodesPerRay = f.rays > 0.0 ? double(r.layers.traceSteps) / f.rays : 0.0;
    f.raysPerSecond = f.median > 0.0 ? f.rays / (f.median * 1e-3) : 0.0;
    return f;
}

/** The run's row of the printed table. */
void printRow(const MethodRun& r, const RunFigures& f, int level, std::size_t characters,
              std::size_t triangles) {
    char timesOpaque[40] = "-"; // without the opaque run: unknown
    if (f.ratio > 0.0)
        std::snprintf(timesOpaque, sizeof timesOpaque, "%.2f", f.ratio);
    if (f.ratioUnlit > 0.0) // a lit run beside an unlit opaque one: what the lights cost
        std::snprintf(timesOpaque + std::strlen(timesOpaque),
                      sizeof timesOpaque - std::strlen(timesOpaque), " (%.2f unlit)", f.ratioUnlit);
    const double walked = std::max(double(r.layers.walkedPixels), 1.0);
    char temporal[80] = "-";
    if (r.temporal) {
        char times[16] = "-"; // without the run without it (--temporal on alone): unknown
        if (f.temporalRatio > 0.0)
            std::snprintf(times, sizeof times, "%.3f", f.temporalRatio);
        std::snprintf(temporal, sizeof temporal, "%s, %.1f MiB, fresh %.1f%%", times,
                      double(r.historyBytes) / 1048576.0,
                      100.0 * double(r.layers.freshPixels) / walked);
    }
    char layers[48] = "-";
    if (r.layers.capacity > 0)
        std::snprintf(layers, sizeof layers, "K=%d: %zu B/px, %u px over", r.layers.capacity,
                      r.layers.bytesPerPixel, r.layers.overflowPixels);
    // The hybrid's share of the glass pixels it traced, in all and for each reason.
    auto share = [&](std::uint32_t pixels) { return 100.0 * double(pixels) / walked; };
    const auto& by = r.layers.hybridBy;
    char trace[192] = "-";
    if (f.rays > 0.0)
        std::snprintf(trace, sizeof trace, "%.0fk rays, %.0f nodes/ray, %.2f Mrays/s", f.rays / 1e3,
                      f.nodesPerRay, f.raysPerSecond / 1e6);
    if (r.method == "hybrid")
        std::snprintf(trace + std::strlen(trace), sizeof trace - std::strlen(trace),
                      "; traced %.1f%% of the glass (over K %.1f, off the layers %.1f, TIR "
                      "%.1f, outline %.1f)",
                      share(r.layers.hybridTraced), share(by[0]), share(by[1]), share(by[2]),
                      share(by[3]));
    std::printf("| %s | %d | %zu | %zu | %.2f | %.2f | %s | %.2f | %.2f | %.1f | %s | %s | %s "
                "| %s |\n",
                r.label().c_str(), level, characters, triangles, f.median, f.p95, timesOpaque,
                f.cpu, f.engine, double(r.transientBytes) / 1048576.0, temporal, layers, trace,
                f.slowest.c_str());
    std::fflush(stdout);
}

/** The run's row of the JSON report. */
nlohmann::json rowJson(const MethodRun& r, const RunFigures& f, int level, std::size_t characters,
                       std::size_t triangles) {
    const auto ratio = [](double v) { return v > 0.0 ? nlohmann::json(v) : nlohmann::json(); };
    const auto& by = r.layers.hybridBy;
    return {{"method", r.label()},
            {"temporal", r.temporal},
            {"ratio_to_without_temporal", ratio(f.temporalRatio)},
            {"history_bytes", r.historyBytes},
            {"level", level},
            {"characters", characters},
            {"triangles", triangles},
            {"median_ms", f.median},
            {"p95_ms", f.p95},
            {"cpu_ms", f.cpu},
            {"animate_record_ms", f.engine},
            {"ratio_to_opaque", ratio(f.ratio)},
            {"lights", r.lit},
            {"skipped", r.skipped},
            {"saved_ms", f.saved},
            {"ratio_to_unlit_opaque", ratio(f.ratioUnlit)},
            {"transient_bytes", r.transientBytes},
            {"layer_capacity", r.layers.capacity},
            {"layer_bytes_per_pixel", r.layers.bytesPerPixel},
            {"layer_bytes", r.layers.bytes},
            {"layer_overflow_pixels", r.layers.overflowPixels},
            {"trace_rays", r.layers.traceRays},
            {"trace_nodes_per_ray", f.nodesPerRay},
            {"trace_max_nodes_per_pixel_draw", r.layers.traceMaxSteps},
            {"trace_rays_per_second", f.raysPerSecond},
            {"walked_pixels", r.layers.walkedPixels},
            {"hybrid_traced_pixels", r.layers.hybridTraced},
            {"fresh_pixels", r.layers.freshPixels},
            {"hybrid_traced_by",
             {{"overflow", by[0]}, {"off_the_layers", by[1]}, {"tir", by[2]}, {"outline", by[3]}}},
            {"passes", f.passes}};
}

/** Prints one table row per run of `level` and `characters` and returns them as JSON; ratios
 *  are to the opaque run of the same configuration. */
std::vector<nlohmann::json> summarise(const std::vector<MethodRun>& runs, int level,
                                      std::size_t characters, std::size_t triangles) {
    WholeMedians whole;
    for (const MethodRun& r : runs)
        if (r.skipped.empty())
            whole[{r.method, r.lit, r.temporal}] = percentile(r.frameMs, 0.5);
    std::vector<nlohmann::json> rows;
    for (const MethodRun& r : runs) {
        const RunFigures f = figuresOf(r, whole);
        printRow(r, f, level, characters, triangles);
        rows.push_back(rowJson(r, f, level, characters, triangles));
    }
    printSkipped(runs, whole);
    return rows;
}

/** The chart of a report: one line per method through its (triangles, median ms) per level. */
capture::Image plot(const nlohmann::json& report) {
    static const std::map<std::string, std::array<std::uint8_t, 3>> colors = {
        {"opaque", {120, 120, 120}},
        {"sir", {52, 101, 164}},
        {"isr", {230, 126, 34}},
        {"dir", {46, 139, 87}},
        {"trace", {142, 68, 173}},
        {"hybrid", {196, 160, 0}},
        {"dir+temporal", {120, 200, 140}},
        {"hybrid+temporal", {240, 210, 90}},
        {"trace+temporal", {190, 140, 220}}};
    bench::Chart chart;
    const std::string name =
        std::filesystem::path(report["model"].get<std::string>()).filename().string();
    chart.title = name + " " + std::to_string(report["size"][0].get<int>()) + "x" +
                  std::to_string(report["size"][1].get<int>()) + ": median frame time";
    chart.xLabel = "triangles drawn (subdivision levels, characters)";
    chart.yLabel = "ms per frame";
    for (const nlohmann::json& row : report["results"]) {
        const std::string method = row["method"];
        auto it = std::find_if(chart.series.begin(), chart.series.end(),
                               [&](const bench::Series& s) { return s.name == method; });
        if (it == chart.series.end()) {
            const auto color = colors.find(method);
            chart.series.push_back(
                {method,
                 color != colors.end() ? color->second : std::array<std::uint8_t, 3>{0, 0, 0},
                 {}});
            it = std::prev(chart.series.end());
        }
        it->points.emplace_back(row["triangles"].get<double>(), row["median_ms"].get<double>());
    }
    return bench::drawChart(chart);
}

struct Options {
    std::string jsonPath, plotPath, glass = "all";
    std::vector<std::string> paths;
    std::vector<std::string> methods = {"opaque", "sir", "isr", "dir"};
    std::vector<int> levels = {0};
    std::vector<int> instances; // empty: the world as loaded
    glm::ivec2 size{512, 512};
    int frames = 60, warmup = 10;
    bool force = false, ground = false, shadows = true;
    std::vector<std::pair<std::string, std::string>> assignments;
    std::vector<bool> temporalModes = {false};
    std::vector<bool> lightModes = {true};
    std::vector<std::vector<std::string>> skips = {{}}; ///< --skip: each run's left-out steps
    render::TemporalSettings temporal;                  ///< a temporal run's (enabled per run)
    bool paused = false;
    plugin::ParameterSet parameters; ///< the glass's, with --glass and every --set applied
};

/** `text` as a whole number in lo..hi, or nothing. */
std::optional<int> wholeNumber(const std::string& text, long lo, long hi) {
    char* end = nullptr;
    const long n = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || n < lo || n > hi)
        return std::nullopt;
    return int(n);
}

/** "on" or "off" as a bool, or nothing. */
std::optional<bool> onOrOff(const std::string& mode) {
    if (mode != "on" && mode != "off")
        return std::nullopt;
    return mode == "on";
}

/** The frame measured: size, rounds, glass, ground, shadows and any refraction parameter. */
void addFrameOptions(CLI::App& app, Options& o) {
    tool::addSize(app, "--size", o.size, 16, 8192, "frame size (default 512x512)");
    app.add_option("--frames", o.frames, "measured rounds (default 60)")
        ->check(tool::range(1, 100000))
        ->type_name("N");
    app.add_option("--warmup", o.warmup, "warm-up rounds (default 10)")
        ->check(tool::range(0, 100000))
        ->type_name("W");
    app.add_option("--glass", o.glass,
                   "all (default): play every mesh as glass; auto: the "
                   "transmissive materials")
        ->check(tool::oneOf({"all", "auto"}))
        ->type_name("all|auto");
    app.add_flag("--ground", o.ground,
                 "draw the ground plane (opaque geometry the glass sees through its nearby-scene "
                 "walk; without opaque geometry the walk is skipped)");
    tool::addOnOff(
        app, "--shadows", o.shadows,
        "the lights cast shadows, each as its scene file's \"shadow\" says (default on)");
    app.add_option_function<std::string>(
           "--set",
           [&o](const std::string& v) {
               const std::size_t equals = v.find('=');
               if (equals == std::string::npos)
                   throw CLI::ValidationError("--set", "needs KEY=VALUE, got '" + v + "'");
               o.assignments.emplace_back(v.substr(0, equals), v.substr(equals + 1));
           },
           "sets any other refraction parameter for every method (e.g. --set nearby=off, --set "
           "search-steps=8)")
        ->type_name("KEY=VALUE")
        ->trigger_on_parse()
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

/** What the runs vary: lights on and off, accumulation, the steps skipped. */
void addVariedOptions(CLI::App& app, Options& o) {
    tool::addList<bool>(
        app, "--temporal", o.temporalModes, onOrOff, "off, on or off,on",
        "on: also runs each method with temporal accumulation (\"dir+temporal\": the jitter, the "
        "motion vectors, the glass pixels' reprojection and the temporal resolve, the trace's "
        "and the hybrid's samples one a frame), with its frame time as a ratio to the same "
        "method without it (\"x off\") and the history's GPU memory (each such run has a "
        "renderer of its own, whose history carries across its frames as an application's "
        "does)")
        ->type_name("off,on");
    tool::addList<bool>(
        app, "--lights", o.lightModes, onOrOff, "on, off or off,on",
        "off: also runs each method without the punctual lights (\"dir+unlit\", the environment "
        "alone); a lit run's x opaque then also gives its ratio to the unlit opaque run (default "
        "on)")
        ->type_name("off,on");
    std::string steps;
    for (const auto& [step, what] : kSkippableSteps)
        steps += "\n  " + step + ": " + what;
    tool::addList<std::vector<std::string>>(
        app, "--skip", o.skips,
        [](const std::string& item) -> std::optional<std::vector<std::string>> {
            std::vector<std::string> set;
            if (item == "none")
                return set;
            std::stringstream in(item);
            for (std::string step; std::getline(in, step, '+');) {
                if (std::none_of(kSkippableSteps.begin(), kSkippableSteps.end(),
                                 [&](const auto& known) { return known.first == step; }))
                    return std::nullopt;
                set.push_back(step);
            }
            return set.empty() ? std::nullopt : std::optional(set);
        },
        "none or steps joined by + (see --help)",
        "for measurement: also runs each method with each set of steps left out of its shaders "
        "(\"dir -search\"; none: every step), and prints what each set saved against the run "
        "with every step. The frames are wrong by design. The steps:" +
            steps)
        ->type_name("none,STEP[+STEP],...");
}

/** The accumulation's settings and a paused clock. */
void addTemporalOptions(CLI::App& app, Options& o) {
    tool::addHistoryOptions(app, o.temporal);
    app.add_flag("--paused", o.paused,
                 "every round at the middle of the clips, as in a paused viewer: a temporal run's "
                 "frames are still and converge (glass-capture --accumulate), the trace's paths "
                 "sampled");
}

/** The report's files. */
void addReportOptions(CLI::App& app, Options& o) {
    app.add_option("--json", o.jsonPath, "also write everything as JSON (atomically)")
        ->type_name("FILE");
    app.add_option("--plot", o.plotPath,
                   "also write a chart of each method's median frame time against the triangles "
                   "drawn (atomically)")
        ->type_name("PNG");
    app.add_flag("--force", o.force, "replace the --json and --plot files if they exist");
}

void addOptions(CLI::App& app, Options& o) {
    app.add_option("models", o.paths, "glTF models or a scene file (.json)")
        ->type_name("MODEL|SCENE");
    tool::addList<std::string>(
        app, "--methods", o.methods,
        [&o](const std::string& method) -> std::optional<std::string> {
            if (!plugin::ParameterSet(o.parameters).set("method", method))
                return std::nullopt;
            return method;
        },
        "methods of the refraction plugin", "the methods to run (default opaque,sir,isr,dir)")
        ->type_name("M,...");
    tool::addList<int>(
        app, "--subdiv", o.levels,
        [](const std::string& level) {
            return wholeNumber(level, 0, core::limits::kMaxSubdivisionLevel);
        },
        "levels 0.." + std::to_string(core::limits::kMaxSubdivisionLevel),
        "OpenSubdiv levels, each refined every frame on the GPU from the deformed mesh "
        "(default 0: the file's triangles)")
        ->type_name("L,...");
    tool::addList<int>(
        app, "--instances", o.instances,
        [](const std::string& count) {
            return wholeNumber(count, 1, long(core::limits::kMaxCharacters));
        },
        "counts 1.." + std::to_string(core::limits::kMaxCharacters),
        "also runs each count N of characters: copies of the scene's characters in turn, on a "
        "square grid in the x-z plane, copy k at phase k/N of its clip, the camera framing all")
        ->type_name("N,...");
    addFrameOptions(app, o);
    addVariedOptions(app, o);
    addTemporalOptions(app, o);
    addReportOptions(app, o);
}

std::optional<int> parse(int argc, char** argv, Options& o) {
    o.parameters = refraction::createPlugin()->parameters();
    CLI::App app{"", "glass-bench"};
    tool::configure(app, kDescription, kExitStatus);
    addOptions(app, o);
    if (const auto code = tool::parseArguments(app, argc, argv))
        return code;
    if (o.paths.empty())
        return tool::usageError(app, "no model given");
    // Checked on the parameters before any loading.
    o.assignments.insert(o.assignments.begin(), {"glass", o.glass});
    for (const auto& [key, value] : o.assignments)
        if (auto ok = o.parameters.set(key, value); !ok)
            return tool::usageError(app, "--" +
                                             std::string(key == "glass" ? "glass" : "set " + key) +
                                             ": " + ok.error().message);
    return std::nullopt;
}

/** The runs of one configuration: a method each, with and without accumulation; a temporal
 *  run gets its own plugin and renderer. */
core::Result<std::vector<MethodRun>> createRuns(const Options& o, tool::HeadlessScene& headless,
                                                const scene::World& world, int level,
                                                const render::Bounds& bounds) {
    std::vector<MethodRun> runs;
    for (const std::vector<std::string>& skipped : o.skips)
        for (bool lit : o.lightModes)
            for (bool temporal : o.temporalModes)
                for (const std::string& method : o.methods) {
                    MethodRun run;
                    run.method = method;
                    run.temporal = temporal;
                    run.lit = lit;
                    run.skipped = skipped;
                    if (temporal) {
                        auto created =
                            render::Renderer::create(headless.environment, *headless.context);
                        if (!created)
                            return created.error();
                        run.renderer = std::move(*created);
                        run.glass = refraction::createPlugin();
                        run.glass->parameters() = o.parameters;
                        (void)run.glass->parameters().set("method", method);
                        core::Status ready = run.renderer->addPlugin(run.glass.get());
                        if (ready)
                            ready = run.renderer->setSubdivisionLevel(level);
                        if (ready)
                            ready = run.renderer->prepare(world);
                        if (!ready)
                            return ready.error();
                        run.renderer->setGround(render::GroundPlane::under(bounds));
                    }
                    runs.push_back(std::move(run));
                }
    return runs;
}

/** One round's frame of run `r` at `time`, timed and recorded (after the warm-up). */
core::Status measureFrame(MethodRun& r, tool::HeadlessScene& headless, const scene::World& world,
                          const render::Camera& camera, render::RenderSettings& settings,
                          double time, bool measured, bool last, const Options& o) {
    plugin::Plugin* const plugin = headless.glass.get();
    if (!r.renderer)
        (void)plugin->parameters().set("method", r.method);
    settings.temporal = o.temporal;
    settings.temporal.enabled = r.temporal;
    settings.lights = r.lit;
    settings.skippedSteps = r.skipped;
    render::Renderer& renderer = r.renderer ? *r.renderer : *headless.renderer;
    const auto start = std::chrono::steady_clock::now();
    auto stats = renderer.render(world, camera, settings, time);
    gl::finish();
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!stats)
        return stats.error();
    if (!measured)
        return {};
    if (last && r.method != "opaque") // read back after timing
        if (const auto* refractionPlugin =
                dynamic_cast<const refraction::RefractionPlugin*>(r.glass ? r.glass.get() : plugin))
            r.layers = refractionPlugin->layerStats();
    r.frameMs.push_back(ms);
    r.cpuMs.push_back(stats->cpuMs);
    r.engineMs.push_back(stats->animateMs + stats->recordMs);
    r.transientBytes = std::max(r.transientBytes, stats->transientBytes);
    r.historyBytes = std::max(r.historyBytes, stats->historyBytes);
    for (const render::PassStats& p : stats->passes) {
        if (!r.passes.count(p.name))
            r.passOrder.push_back(p.name);
        r.passes[p.name].first.push_back(p.gpuMs);
        r.passes[p.name].second.push_back(p.cpuMs);
    }
    return {};
}

/** Every method's rounds on `world` at subdivision `level`, its rows added to `report`. */
core::Status benchWorld(const Options& o, tool::HeadlessScene& headless, const scene::World& world,
                        int level, render::RenderSettings& settings, nlohmann::json& report) {
    const render::Bounds bounds = render::worldBounds(world);
    headless.renderer->setGround(render::GroundPlane::under(bounds));
    // One camera for every round: a file's camera the scene looks through, where it is at 0.
    const render::Camera camera = tool::viewOf(world, bounds, o.size, 0.0);
    if (auto prepared = headless.renderer->prepare(world); !prepared)
        return prepared;
    std::size_t triangles = 0;
    for (std::size_t c = 0; c < headless.renderer->characterCount(); ++c)
        for (const auto& instance : headless.renderer->geometry(c).instances())
            for (const auto& primitive : instance.primitives)
                triangles += primitive.indexCount / 3;
    const double duration = tool::sweepPeriod(world);
    const std::size_t covered = coveredPixels(world, 0.5 * duration, camera, o.size);
    auto runs = createRuns(o, headless, world, level, bounds);
    if (!runs)
        return runs.error();
    const bool terminal = isatty(STDERR_FILENO) != 0;
    const int rounds = o.warmup + o.frames;
    for (int round = 0; round < rounds; ++round) {
        const double time = o.paused ? 0.5 * duration : std::fmod(round / 30.0, duration);
        for (MethodRun& r : *runs)
            if (auto measured = measureFrame(r, headless, world, camera, settings, time,
                                             round >= o.warmup, round + 1 == rounds, o);
                !measured)
                return measured;
        if (terminal)
            std::fprintf(stderr, "\rglass-bench: level %d, %zu characters, %s round %d/%d   ",
                         level, world.characters.size(), round < o.warmup ? "warm-up" : "measured",
                         round + 1, rounds);
    }
    if (terminal)
        std::fprintf(stderr, "\n");
    if (gl::checkErrors("glass-bench") > 0 || gl::errorCount() > 0)
        return core::Error{"GL errors (see the log)"};
    for (nlohmann::json& row : summarise(*runs, level, world.characters.size(), triangles)) {
        row["covered_pixels"] = covered;
        report["results"].push_back(std::move(row));
    }
    return {};
}

int fail(const std::string& message) {
    std::fprintf(stderr, "glass-bench: %s\n", message.c_str());
    return 1;
}

int run(int argc, char** argv) {
    Options o;
    if (const auto code = parse(argc, argv, o))
        return *code;
    const std::string model = o.paths.size() == 1 ? o.paths[0] : o.paths[0] + " ...";
    for (const std::string& path : {o.jsonPath, o.plotPath})
        if (!path.empty() && !o.force && std::filesystem::exists(path))
            return fail(path + " exists (use --force to replace it)");
    auto opened = tool::openHeadlessScene(o.paths);
    if (!opened)
        return fail(opened.error().message);
    tool::HeadlessScene& headless = *opened;
    headless.glass->parameters() = o.parameters;
    render::RenderSettings settings;
    settings.size = o.size;
    settings.exactPassTimes = o.instances.empty();
    settings.ground = o.ground || headless.world.ground;
    settings.shadows = o.shadows;

    std::printf("%s, %dx%d, %d rounds after %d warm-up%s (%s)\n", model.c_str(), o.size.x, o.size.y,
                o.frames, o.warmup, o.paused ? ", paused" : "", gl::rendererString());
    std::printf("| method | level | characters | triangles | median ms | p95 ms | x opaque | "
                "cpu ms | animate+record ms | transients MiB | temporal: x off, history | layers | "
                "trace | slowest passes (GPU ms) |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|---|\n");
    nlohmann::json report = {{"model", model},
                             {"paths", o.paths},
                             {"renderer", gl::rendererString()},
                             {"size", {o.size.x, o.size.y}},
                             {"frames", o.frames},
                             {"warmup", o.warmup},
                             {"paused", o.paused},
                             {"history_weight", o.temporal.historyWeight},
                             {"moving_jitter", o.temporal.movingJitter},
                             {"history_rejection", o.temporal.rejectHistory},
                             {"converge_still", o.temporal.convergeStill},
                             {"settings", o.assignments},
                             {"ground", settings.ground},
                             {"shadows", settings.shadows},
                             {"exact_pass_times", settings.exactPassTimes},
                             {"results", nlohmann::json::array()}};
    std::vector<scene::World> worlds;
    if (o.instances.empty())
        worlds.push_back(headless.world);
    for (int count : o.instances)
        worlds.push_back(gridWorld(headless.world, count));
    for (int level : o.levels) {
        if (auto refined = headless.renderer->setSubdivisionLevel(level); !refined)
            return fail(model + ": " + refined.error().message);
        for (const scene::World& world : worlds)
            if (auto benched = benchWorld(o, headless, world, level, settings, report); !benched)
                return fail(benched.error().message);
    }
    if (!o.jsonPath.empty())
        if (auto written = core::writeFileAtomic(o.jsonPath, report.dump(2) + "\n"); !written)
            return fail(written.error().message);
    if (!o.plotPath.empty())
        if (auto written = capture::writePng(o.plotPath, plot(report)); !written)
            return fail(written.error().message);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    return tool::guardedMain("glass-bench", run, argc, argv);
}
