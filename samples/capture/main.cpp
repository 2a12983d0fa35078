// glass-capture: renders a glTF character headless (EGL) at given times to PNG, with per-pass
// CPU/GPU timings; or runs a frame-capture test case against its goldens.
#include "../common/ToolMain.h"
#include "CaptureCase.h"
#include "CaptureSession.h"

#include "engine/capture/Metrics.h"
#include "engine/core/Limits.h"
#include "refraction/ReferenceTracer.h"
#include "refraction/RefractionPlugin.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

constexpr const char* kUsage =
    R"(usage: glass-capture MODEL|SCENE [MODEL...] [--clip N|NAME] [--variant NAME] [--time T | --frames START:END:STEP]
                     [--size WxH] [--env HDR] [--out DIR] [--json] [--ground] [--exposure E]
                     [--subdiv N]
                     [--plugin PATH [--set KEY=VALUE]...]... [--dump-graph] [--contact-sheet PNG] [--force]
                     [--method opaque|sir|isr|dir|trace|hybrid] [--glass auto|all] [--ior N] [--dispersion D]
                     [--tint R,G,B] [--absorption-distance D] [--fresnel exact|schlick|off]
                     [--search-steps N] [--tir clamp|reflect] [--tir-bounces B]
                     [--back-surface farthest|first] [--nearby on|off] [--debug VIEW]
                     [--geometry-passes one|two] [--dispersion-search shared|per-channel]
                     [--surfaces layers|two-surface] [--layer-capacity K] [--interfaces N]
                     [--outline-aa on|off] [--trace-samples S] [--hybrid-criteria C]
                     [--march-steps M]
                     [--temporal on|off [--warmup N] [--history-weight W]
                      [--temporal-view rejected|motion] [--history-rejection on|off]
                      [--converge-still on|off]]
                     [--accumulate N]
                     [--method reference] [--compare-reference] [--spp K | --pixel-centres] [--max-bounces N]
       glass-capture --case FILE.json [--update] [--out DIR] [--plugin PATH [--set K=V]...]...

Renders MODEL headless (EGL: a GPU device, else Mesa llvmpipe) and writes one PNG per time to
DIR (default out/capture) named MODEL_CLIP_tSECONDS.png (seconds with 3 decimals). A scene file
(.json, README "Scene files") renders its world (SCENE_scene_tSECONDS.png with several
characters; T is the scene time); several MODELs are placed side by side.

  --clip N|NAME       clip index or name, for every character (default: the first clip, or the
                      scene file's; the rest pose if none)
  --variant NAME      a KHR_materials_variants variant (name or index) for every character
                      whose model has it (glass-inspect lists a file's variants)
  --time T            one time in seconds (default 0)
  --frames S:E:STEP   times S, S+STEP, ... up to E inclusive (at most 10000 frames)
  --size WxH          output size in pixels (default 256x256)
  --env HDR           equirectangular environment (default: a procedural sky)
  --ground            draw a ground plane under the character
  --exposure E        exposure multiplier before tonemapping (default 1)
  --subdiv N          OpenSubdiv refinement level 0..4 of every mesh, refined each frame from
                      the deformed mesh on the GPU, and as the reference traces it (default 0:
                      the file's triangles)
  --plugin PATH       load a plugin module; --set KEY=VALUE after it sets its parameters
  Temporal accumulation (docs/methods.md, "Temporal accumulation"):
  --temporal on|off   on: every frame's projection jittered and blended into a history that
                      carries across the frames written (--frames), each pixel reprojected by
                      its motion; the trace's and the hybrid's samples one a frame (default off)
  --warmup N          with --temporal on: N frames before the first one written, at the
                      times before it (--frames' STEP apart, else 1/30 s), as a playing
                      viewer's history holds them (default 10)
  --history-weight W  the history's weight while anything moves, 0..0.99 (default 0.8)
  --history-rejection off  keep every reprojected history unclipped (to show what the
                      rejection and clipping are for; default on)
  --converge-still off  frames at one time blend as moving ones do (the history weight, the
                      neighbourhood's clip) instead of averaging every frame (default on)
  --temporal-view V   rejected: red where the history was rejected, green where it was
                      clipped; motion: each pixel's motion (hue its direction, brightness its
                      length up to 8 pixels)
  --accumulate N      every frame written is N frames at its one time from a fresh history,
                      accumulated (still frames converge: N frames equal N samples a pixel)
  Glass (the built-in refraction plugin; materials with KHR_materials_transmission are glass):
  --method M          opaque, sir (one interface), isr (Wyman, d_N per frame), dir (default:
                      depth-map search, no preprocessing), trace (the path traced exactly
                      through the glass BVH from the first layer), hybrid (dir, and the trace
                      where the layers may not hold the path)
  --glass auto|all    auto: transmissive materials (default); all: play every mesh as glass
  --ior N             index of refraction, 0 = the material's (default)
  --dispersion D      20/Abbe number, -1 = the material's (default)
  --dispersion-search shared (default): one exit search, red and blue refracted from green's
                      exit point; per-channel: each colour channel searches its own exit
  --tint R,G,B        multiplies the attenuation colour; --absorption-distance D sets where
                      light reaches it (0 = the material's)
  --fresnel M         exact (default), schlick or off
  --search-steps N    DIR binary search steps, 1..16 (default 5)
  --tir P             reflect (default: as light does) or clamp (the papers: leave tangent);
                      --tir-bounces B (default 2)
  --back-surface S    farthest (default) or first back face
  --nearby on|off     exit rays see the opaque scene before the environment (default on)
  --surfaces S        layers (default): every glass surface a ray crosses, captured in one
                      geometry pass (--layer-capacity K per pixel, default 4), walked over at
                      most --interfaces N (default 8), each crossing found by --march-steps M
                      coarse samples (default 12) then --search-steps halvings; two-surface:
                      the papers' nearest front and one back surface
  --outline-aa on|off layers: the outlines of smooth glass anti-aliased (default on)
  --trace-samples S   trace and hybrid: rays per glass pixel, the first at its centre, the
                      others jittered within it (1..64, default 1)
  --hybrid-criteria C hybrid: what hands a pixel to the trace, a sum of 1 (more than K layers),
                      2 (the walk left the layers), 4 (a total internal reflection it
                      followed), 8 (a crossing near an outline); default 15, all
  --geometry-passes G two-surface only: one (default): front and back surfaces gathered in one
                      geometry pass (MAX blending) and refracted in a full-screen pass; two: the
                      papers' back-face pass then front-face pass (also used where one cannot:
                      several glass materials, a normal map, --back-surface first)
  --debug VIEW        none, back-depth, back-normal, dv, dn, exit-uv, steps, tir, exit-point,
                      exit-direction, layer-count, overflow
  Reference (Embree, on the CPU, all cores; glass-only scenes without --ground):
  --method reference  trace the ground truth instead of rendering on the GPU
  --compare-reference render --method and the reference, report PSNR and SSIM over the glass
                      mask and the whole image, write MODEL_..._tT.reference.png and
                      .heatmap.png beside the frame
  --spp K             reference samples per pixel, jittered (default 16)
  --pixel-centres     the reference traces one ray through each pixel centre, where the GPU
                      samples (instead of --spp jittered rays)
  --deterministic     the reference's deterministic evaluation (docs/methods.md): pixel
                      centres, every reflection into glass followed to a stated depth and then
                      looked up, rough glass by its normals, paths ending after --interfaces as
                      the trace's do; what the trace at one sample a pixel computes
  --max-bounces N     interfaces (refractions and reflections) a reference path follows after
                      its entry before it counts as trapped (default 1024)
  --json              print files written, times and per-pass CPU/GPU timings as JSON, with
                      the median of each over all frames after the first (warm-up)
  --force             replace output files that exist (without it, an existing file is an
                      error and nothing is written); a run that fails removes what it wrote
  --contact-sheet PNG also write the frames side by side in one picture (4 per row)
  --dump-graph        print the compiled frame graph of the first frame to stderr
  --case FILE.json    render a frame-capture case and compare with its goldens (exit 0 match,
                      1 mismatch; .actual.png, .diff.png and a report go to --out, default the
                      case's folder); --update regenerates the goldens instead; --plugin
                      modules given here load after the case's own "plugins"

Exit status: 0 success, 1 the model or environment could not be loaded (nothing written) or a
case mismatched, 2 bad arguments, 77 a case whose model is missing and marked skip_if_missing.
)";

int usageError(const std::string& message) {
    std::fprintf(stderr, "glass-capture: %s\n\n%s", message.c_str(), kUsage);
    return 2;
}

bool parseDouble(const std::string& s, double& out) {
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return !s.empty() && *end == '\0' && std::isfinite(out);
}

struct Options {
    capture::SessionOptions session;
    std::vector<double> times{0.0};
    std::string out = "out/capture";
    bool outGiven = false, json = false, dumpGraph = false, update = false;
    bool reference = false, compare = false;
    refraction::ReferenceOptions referenceOptions;
    std::string caseFile;
    std::string contactSheet;
    bool force = false;
    bool warmupGiven = false, weightGiven = false, accumulateGiven = false;
};

/** The files one run writes: refuses existing ones without --force before anything is written,
 *  and removes what was written when the run fails (no partial output). */
class Outputs {
public:
    explicit Outputs(bool force) : mForce(force) {}
    ~Outputs() {
        if (!mCommitted)
            for (const auto& path : mWritten)
                std::filesystem::remove(path);
    }
    /** Fails naming the first planned file that exists (unless forced). */
    core::Status check(const std::vector<std::filesystem::path>& planned) const {
        if (!mForce)
            for (const auto& path : planned)
                if (std::filesystem::exists(path))
                    return core::Error{"glass-capture: " + path.string() +
                                       " exists (use --force to replace it); nothing written"};
        return {};
    }
    core::Status write(const std::filesystem::path& path, const capture::Image& image) {
        auto written = capture::writePng(path, image);
        if (written)
            mWritten.push_back(path);
        return written;
    }
    void commit() { mCommitted = true; }

private:
    bool mForce = false, mCommitted = false;
    std::vector<std::filesystem::path> mWritten;
};

std::optional<int> parse(int argc, char** argv, Options& o) {
    bool haveTime = false, haveFrames = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto next = [&]() -> std::optional<std::string> {
            if (i + 1 >= argc)
                return std::nullopt;
            return std::string(argv[++i]);
        };
        if (arg == "--help" || arg == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (arg == "--json") {
            o.json = true;
        } else if (arg == "--ground") {
            o.session.ground = true;
        } else if (arg == "--dump-graph") {
            o.dumpGraph = true;
        } else if (arg == "--update") {
            o.update = true;
        } else if (arg == "--force") {
            o.force = true;
        } else if (arg == "--compare-reference") {
            o.compare = true;
        } else if (arg == "--subdiv") {
            const auto v = next();
            double n = 0;
            if (!v || !parseDouble(*v, n) || n != std::floor(n) || n < 0 ||
                n > core::limits::kMaxSubdivisionLevel)
                return usageError("--subdiv needs a level 0.." +
                                  std::to_string(core::limits::kMaxSubdivisionLevel));
            o.session.subdivision = int(n);
        } else if (arg == "--temporal") {
            const auto v = next();
            if (!v || (*v != "on" && *v != "off"))
                return usageError("--temporal needs on or off");
            o.session.temporal.enabled = *v == "on";
        } else if (arg == "--history-rejection" || arg == "--converge-still") {
            const auto v = next();
            if (!v || (*v != "on" && *v != "off"))
                return usageError(arg + " needs on or off");
            (arg == "--converge-still" ? o.session.temporal.convergeStill
                                       : o.session.temporal.rejectHistory) = *v == "on";
            o.weightGiven = true; // goes with --temporal on
        } else if (arg == "--temporal-view") {
            const auto v = next();
            if (!v || (*v != "rejected" && *v != "motion"))
                return usageError("--temporal-view needs rejected or motion");
            o.session.temporal.view = *v == "rejected" ? render::TemporalSettings::View::Rejected
                                                       : render::TemporalSettings::View::Motion;
            o.weightGiven = true; // goes with --temporal on
        } else if (arg == "--warmup" || arg == "--accumulate" || arg == "--history-weight") {
            const auto v = next();
            double n = 0;
            const bool weight = arg == "--history-weight";
            if (!v || !parseDouble(*v, n) || n < (arg == "--accumulate" ? 1 : 0) ||
                n > (weight ? 0.99 : 4096) || (!weight && n != std::floor(n)))
                return usageError(
                    arg + (weight ? " needs a weight in 0..0.99" : " needs an integer up to 4096"));
            if (weight)
                o.session.temporal.historyWeight = float(n);
            else
                (arg == "--warmup" ? o.session.warmup : o.session.accumulate) = int(n);
            (weight ? o.weightGiven : arg == "--warmup" ? o.warmupGiven : o.accumulateGiven) = true;
        } else if (arg == "--pixel-centres") {
            o.referenceOptions.pixelCentres = true;
        } else if (arg == "--deterministic") {
            o.referenceOptions.deterministic = true;
        } else if (arg == "--spp" || arg == "--max-bounces") {
            const auto v = next();
            double n = 0;
            const double limit = 4096;
            if (!v || !parseDouble(*v, n) || n != std::floor(n) || n < (arg == "--spp" ? 1 : 0) ||
                n > limit)
                return usageError(arg + " needs an integer up to " + std::to_string(int(limit)));
            (arg == "--spp" ? o.referenceOptions.samplesPerPixel : o.referenceOptions.maxBounces) =
                int(n);
        } else if (arg == "--method" || arg == "--glass" || arg == "--ior" ||
                   arg == "--dispersion" || arg == "--tint" || arg == "--absorption-distance" ||
                   arg == "--fresnel" || arg == "--search-steps" || arg == "--tir" ||
                   arg == "--tir-bounces" || arg == "--back-surface" || arg == "--nearby" ||
                   arg == "--geometry-passes" || arg == "--dispersion-search" || arg == "--debug" ||
                   arg == "--surfaces" || arg == "--layer-capacity" || arg == "--interfaces" ||
                   arg == "--march-steps" || arg == "--outline-aa" || arg == "--trace-samples" ||
                   arg == "--hybrid-criteria") {
            const auto v = next();
            if (!v)
                return usageError(arg + " needs a value");
            if (arg == "--method" && *v == "reference") {
                o.reference = true;
                continue;
            }
            plugin::ParameterSet check = refraction::createPlugin()->parameters();
            if (auto status = check.set(arg.substr(2), *v); !status)
                return usageError(arg + ": " + status.error().message);
            o.session.refraction.emplace_back(arg.substr(2), *v);
        } else if (arg == "--clip" || arg == "--variant" || arg == "--time" || arg == "--frames" ||
                   arg == "--size" || arg == "--env" || arg == "--out" || arg == "--exposure" ||
                   arg == "--plugin" || arg == "--contact-sheet" || arg == "--set" ||
                   arg == "--case") {
            const auto v = next();
            if (!v)
                return usageError(arg + " needs a value");
            if (arg == "--clip") {
                o.session.clip = *v;
            } else if (arg == "--variant") {
                o.session.variant = *v;
            } else if (arg == "--time") {
                double t = 0;
                if (!parseDouble(*v, t) || t < 0)
                    return usageError("--time needs a non-negative number of seconds, got '" + *v +
                                      "'");
                o.times = {t};
                haveTime = true;
            } else if (arg == "--frames") {
                double s = 0, e = 0, step = 0;
                const auto a = v->find(':'), b = v->find(':', a == std::string::npos ? a : a + 1);
                if (a == std::string::npos || b == std::string::npos ||
                    !parseDouble(v->substr(0, a), s) ||
                    !parseDouble(v->substr(a + 1, b - a - 1), e) ||
                    !parseDouble(v->substr(b + 1), step) || s < 0 || e < s || step <= 0 ||
                    (e - s) / step > 10000)
                    return usageError("--frames needs START:END:STEP with 0 <= START <= END, STEP "
                                      "> 0 and at most "
                                      "10000 frames, got '" +
                                      *v + "'");
                o.times.clear();
                for (int k = 0; s + k * step <= e + 1e-9; ++k)
                    o.times.push_back(s + k * step);
                haveFrames = true;
            } else if (arg == "--size") {
                int w = 0, h = 0;
                char extra = 0;
                if (std::sscanf(v->c_str(), "%dx%d%c", &w, &h, &extra) != 2 || w < 1 || h < 1 ||
                    w > 8192 || h > 8192)
                    return usageError("--size needs WxH within 1..8192, got '" + *v + "'");
                o.session.size = {w, h};
            } else if (arg == "--env") {
                o.session.environment = *v;
            } else if (arg == "--contact-sheet") {
                o.contactSheet = *v;
            } else if (arg == "--out") {
                o.out = *v;
                o.outGiven = true;
            } else if (arg == "--exposure") {
                double e = 0;
                if (!parseDouble(*v, e) || e <= 0)
                    return usageError("--exposure needs a positive number, got '" + *v + "'");
                o.session.exposure = float(e);
            } else if (arg == "--plugin") {
                o.session.plugins.push_back({*v, {}});
            } else if (arg == "--set") {
                const auto eq = v->find('=');
                if (o.session.plugins.empty() || eq == std::string::npos || eq == 0)
                    return usageError("--set KEY=VALUE must follow a --plugin, got '" + *v + "'");
                o.session.plugins.back().parameters.emplace_back(v->substr(0, eq),
                                                                 v->substr(eq + 1));
            } else {
                o.caseFile = *v;
            }
        } else if (!arg.empty() && arg[0] == '-') {
            return usageError("unknown option " + arg);
        } else {
            o.session.models.push_back(arg);
        }
    }
    if (o.reference && o.compare)
        return usageError("--method reference and --compare-reference are exclusive");
    o.referenceOptions.subdivision = o.session.subdivision; // the reference traces it too
    if (haveTime && haveFrames)
        return usageError("--time and --frames are exclusive");
    if ((o.warmupGiven && !o.session.temporal.enabled) ||
        (o.weightGiven && !o.session.temporal.enabled && !o.accumulateGiven))
        return usageError("--warmup goes with --temporal on; --history-weight, "
                          "--history-rejection, --converge-still and --temporal-view with "
                          "--temporal on or --accumulate");
    if (o.accumulateGiven && o.session.temporal.enabled)
        return usageError("--accumulate and --temporal on are exclusive (accumulate converges "
                          "each frame from a fresh history)");
    if (o.session.temporal.enabled && !o.warmupGiven)
        o.session.warmup = 10;
    if (haveFrames && o.times.size() > 1)
        o.session.warmupStep = o.times[1] - o.times[0];
    if (o.caseFile.empty() && o.session.models.empty())
        return usageError("no model given");
    if (!o.caseFile.empty() && !o.session.models.empty())
        return usageError("--case takes its model from the case file");
    if (o.update && o.caseFile.empty())
        return usageError("--update goes with --case");
    return std::nullopt;
}

int runCase(const Options& o) {
    auto c = capture::readCaseFile(o.caseFile);
    if (!c) {
        std::fprintf(stderr, "%s\n", c.error().message.c_str());
        return 2;
    }
    for (const std::string& model : c->session.models)
        if (c->skipIfModelMissing && model.rfind("builtin:", 0) != 0 &&
            !std::filesystem::exists(model)) {
            std::printf(
                "skipped %s: model %s is not present (third-party samples live in ../shared)\n",
                o.caseFile.c_str(), model.c_str());
            return capture::kCaseSkipped;
        }
    // plugins named on the command line (build artefacts, say) come after the case's own
    c->session.plugins.insert(c->session.plugins.end(), o.session.plugins.begin(),
                              o.session.plugins.end());
    const std::filesystem::path outDir =
        o.outGiven ? std::filesystem::path(o.out) : c->path.parent_path();
    auto result = capture::runCase(*c, o.update, outDir);
    if (!result) {
        std::fprintf(stderr, "%s\n", result.error().message.c_str());
        return 1;
    }
    return *result;
}

} // namespace

int run(int argc, char** argv) {
    Options o;
    if (const auto code = parse(argc, argv, o))
        return *code;
    if (!o.caseFile.empty())
        return runCase(o);

    auto session = capture::CaptureSession::create(o.session);
    if (!session) {
        std::fprintf(stderr, "%s\n", session.error().message.c_str());
        return 1;
    }
    const std::string stem = (*session)->stem();
    nlohmann::json report = {{"model", o.session.models.size() == 1
                                           ? nlohmann::json(o.session.models[0])
                                           : nlohmann::json(o.session.models)},
                             {"clip", (*session)->clipLabel()},
                             {"size", {o.session.size.x, o.session.size.y}},
                             {"frames", nlohmann::json::array()}};
    if (o.session.temporal.enabled)
        report["temporal"] = {{"warmup_frames", o.session.warmup},
                              {"warmup_step", o.session.warmupStep},
                              {"history_weight", o.session.temporal.historyWeight}};
    if (o.session.accumulate > 0)
        report["accumulate"] = o.session.accumulate;
    if (o.session.temporal.enabled && !o.json)
        std::printf("temporal accumulation: %d warm-up frames %.4f s apart before the first\n",
                    o.session.warmup, o.session.warmupStep);
    std::error_code ec;
    std::filesystem::create_directories(o.out, ec);
    if (ec) {
        std::fprintf(stderr, "glass-capture: cannot create %s: %s\n", o.out.c_str(),
                     ec.message().c_str());
        return 1;
    }
    o.referenceOptions.progress = !o.json;
    auto frameFile = [&](double time) {
        return std::filesystem::path(o.out) /
               capture::frameFileName(stem, (*session)->clipLabel(), time);
    };
    auto sibling = [](std::filesystem::path path, const char* suffix) {
        return path.replace_extension(std::string(suffix) + ".png");
    };
    Outputs outputs(o.force);
    std::vector<std::filesystem::path> planned;
    for (double time : o.times) {
        planned.push_back(frameFile(time));
        if (o.compare)
            for (const char* suffix : {".reference", ".heatmap"})
                planned.push_back(sibling(frameFile(time), suffix));
    }
    if (!o.contactSheet.empty())
        planned.emplace_back(o.contactSheet);
    if (auto free = outputs.check(planned); !free) {
        std::fprintf(stderr, "%s\n", free.error().message.c_str());
        return 1;
    }
    std::vector<capture::Image> sheetFrames;
    // Temporal stability against the reference over consecutive frames (capture::flicker).
    std::optional<capture::RenderedFrame> previous, previousReference;
    double flickerSum = 0.0;
    std::size_t flickerPairs = 0;
    for (std::size_t i = 0; i < o.times.size(); ++i) {
        auto frame = o.reference ? (*session)->renderReference(o.times[i], o.referenceOptions)
                                 : (*session)->render(o.times[i]);
        if (!frame) {
            std::fprintf(stderr, "%s\n", frame.error().message.c_str());
            return 1;
        }
        if (i == 0 && o.dumpGraph)
            std::fprintf(stderr, "%s", frame->stats.graph.c_str());
        const auto path = frameFile(frame->time);
        if (auto written = outputs.write(path, frame->image); !written) {
            std::fprintf(stderr, "%s\n", written.error().message.c_str());
            return 1;
        }
        nlohmann::json entry = capture::statsJson(frame->stats);
        entry["time"] = frame->time;
        entry["file"] = path.string();
        auto referenceFacts = [&entry](const capture::RenderedFrame& traced) {
            entry["reference_ms"] = traced.milliseconds;
            entry["trapped_samples"] = traced.trappedSamples;
            entry["glass_surfaces_per_pixel"] = traced.surfaceHistogram;
        };
        if (o.reference)
            referenceFacts(*frame);
        std::string scoreText;
        if (o.compare) {
            auto reference = (*session)->renderReference(o.times[i], o.referenceOptions);
            if (!reference) {
                std::fprintf(stderr, "%s\n", reference.error().message.c_str());
                return 1;
            }
            const auto masked =
                capture::score(frame->image, reference->image, &reference->glassMask);
            const auto full = capture::score(frame->image, reference->image);
            for (const auto& [file, image] :
                 {std::pair{sibling(path, ".reference"), reference->image},
                  std::pair{
                      sibling(path, ".heatmap"),
                      capture::heatmap(frame->image, reference->image, 64, &reference->glassMask)}})
                if (auto written = outputs.write(file, image); !written) {
                    std::fprintf(stderr, "%s\n", written.error().message.c_str());
                    return 1;
                }
            entry["reference_file"] = sibling(path, ".reference").string();
            entry["heatmap_file"] = sibling(path, ".heatmap").string();
            referenceFacts(*reference);
            entry["scores"] = {
                {"mask", {{"psnr", masked.psnr}, {"ssim", masked.ssim}, {"pixels", masked.pixels}}},
                {"image", {{"psnr", full.psnr}, {"ssim", full.ssim}, {"pixels", full.pixels}}}};
            char text[160];
            std::snprintf(text, sizeof text,
                          ", glass mask %zu px: PSNR %.2f dB, SSIM %.4f; image PSNR %.2f dB",
                          masked.pixels, masked.psnr, masked.ssim, full.psnr);
            scoreText = text;
            if (previous) {
                std::vector<bool> both(reference->glassMask.size());
                for (std::size_t p = 0; p < both.size(); ++p)
                    both[p] = reference->glassMask[p] && previousReference->glassMask[p];
                const capture::Flicker f =
                    capture::flicker(previous->image, frame->image, previousReference->image,
                                     reference->image, both);
                entry["flicker"] = f.meanAbsDifference;
                flickerSum += f.meanAbsDifference;
                ++flickerPairs;
            }
            previous = *frame;
            previousReference = *reference;
        }
        report["frames"].push_back(entry);
        if (!o.contactSheet.empty())
            sheetFrames.push_back(frame->image);
        if (!o.json)
            std::printf("%s (cpu %.2f ms, gpu %.2f ms%s)\n", path.string().c_str(),
                        frame->stats.cpuMs, frame->stats.gpuMs, scoreText.c_str());
    }
    if (!o.contactSheet.empty()) {
        const int cell = std::min(o.session.size.x, 320);
        const capture::Image sheet = capture::contactSheet(sheetFrames, 4, cell);
        if (auto written = outputs.write(o.contactSheet, sheet); !written) {
            std::fprintf(stderr, "%s\n", written.error().message.c_str());
            return 1;
        }
        report["contact_sheet"] = o.contactSheet;
        if (!o.json)
            std::printf("%s (contact sheet, %d frames)\n", o.contactSheet.c_str(),
                        int(sheetFrames.size()));
    }
    outputs.commit();
    if (flickerPairs > 0) {
        const double mean = flickerSum / double(flickerPairs);
        report["flicker"] = {{"mean_abs_difference", mean}, {"pairs", flickerPairs}};
        if (!o.json)
            std::printf("flicker against the reference: %.3f (mean |frame change - reference "
                        "change| over the glass, 1/255, %zu frame pairs)\n",
                        mean, flickerPairs);
    }
    if (o.json) {
        report["median"] = capture::medianStats(report["frames"]);
        std::printf("%s\n", report.dump(2).c_str());
    }
    return 0;
}

int main(int argc, char** argv) {
    return tool::guardedMain("glass-capture", run, argc, argv);
}
