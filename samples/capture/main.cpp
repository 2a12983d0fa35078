// glass-capture: renders a glTF character headless (EGL) at given times to PNG, with per-pass
// CPU/GPU timings; or runs a frame-capture test case against its goldens.
#include "../common/Cli.h"
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

constexpr const char* kDescription =
    R"(glass-capture MODEL|SCENE [MODEL...] [OPTIONS]: renders MODEL headless (EGL: a GPU device,
else Mesa llvmpipe) and writes one PNG per time to --out named MODEL_CLIP_tSECONDS.png (seconds
with 3 decimals). A scene file (.json, README "Scene files") renders its world
(SCENE_scene_tSECONDS.png with several characters; the time is the scene's); several MODELs are
placed side by side.
glass-capture --case FILE.json [--update] [--out DIR] [--plugin PATH [--set K=V]...]...: renders
a frame-capture case and compares it with its goldens.)";

constexpr const char* kExitStatus =
    R"(Exit status: 0 success, 1 the model or environment could not be loaded (nothing written) or
a case mismatched, 2 bad arguments, 77 a case whose model is missing and marked
skip_if_missing.)";

struct Options {
    capture::SessionOptions session;
    std::vector<double> times{0.0};
    std::string out = "out/capture";
    bool outGiven = false, json = false, dumpGraph = false, update = false;
    bool reference = false, compare = false;
    refraction::ReferenceOptions referenceOptions;
    std::string caseFile;
    std::string contactSheet;
    std::string dumpShaders;
    bool force = false;
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

/** The options that say what to render and where: the models, times, size, environment, the
 *  output, plugins. */
/** --time and --frames: the scene times captured. */
void addTimeOptions(CLI::App& app, Options& o) {
    app.add_option_function<double>(
           "--time", [&o](double t) { o.times = {t}; }, "one time in seconds (default 0)")
        ->check(CLI::NonNegativeNumber.description(""))
        ->type_name("T");
    app.add_option_function<std::string>(
           "--frames",
           [&o](const std::string& v) {
               double s = 0, e = 0, step = 0;
               const auto a = v.find(':'), b = v.find(':', a == std::string::npos ? a : a + 1);
               if (a == std::string::npos || b == std::string::npos ||
                   !tool::parseNumber(v.substr(0, a), s) ||
                   !tool::parseNumber(v.substr(a + 1, b - a - 1), e) ||
                   !tool::parseNumber(v.substr(b + 1), step) || s < 0 || e < s || step <= 0 ||
                   (e - s) / step > 10000)
                   throw CLI::ValidationError("--frames", "needs START:END:STEP with 0 <= START "
                                                          "<= END, STEP > 0 and at most 10000 "
                                                          "frames, got '" +
                                                              v + "'");
               o.times.clear();
               for (int k = 0; s + k * step <= e + 1e-9; ++k)
                   o.times.push_back(s + k * step);
               if (o.times.size() > 1) // the warm-up frames' spacing
                   o.session.warmupStep = o.times[1] - o.times[0];
           },
           "times S, S+STEP, ... up to E inclusive (at most 10000 frames)")
        ->type_name("S:E:STEP");
}

/** What the frame shows besides the characters: size, environment, ground, shadows, exposure,
 *  refinement. */
void addLookOptions(CLI::App& app, Options& o) {
    tool::addSize(app, "--size", o.session.size, 1, 8192,
                  "output size in pixels (default 256x256)");
    app.add_option("--env", o.session.environment,
                   "equirectangular environment (default: a procedural sky)")
        ->type_name("HDR");
    app.add_flag("--ground", o.session.ground, "draw a ground plane under the character");
    tool::addOnOff(
        app, "--shadows", o.session.shadows,
        "the lights cast shadows, each as its scene file's \"shadow\" says (default on)");
    app.add_option_function<std::string>(
           "--shadow-map",
           [&o](const std::string& v) {
               using View = render::RenderSettings::ShadowMapView;
               o.session.shadowMapView = v == "depth"      ? View::Depth
                                         : v == "glass"    ? View::Glass
                                         : v == "caustics" ? View::Caustics
                                                           : View::Off;
           },
           "a debug view in place of the scene: the lights' shadow atlas fitted into the frame, "
           "the casters' depth, the glass's transmittance or the caustics (default off)")
        ->check(tool::oneOf({"off", "depth", "glass", "caustics"}))
        ->type_name("off|depth|glass|caustics");
    app.add_option("--exposure", o.session.exposure,
                   "exposure multiplier before tonemapping (default 1)")
        ->check(CLI::PositiveNumber.description(""))
        ->type_name("E");
    app.add_option("--subdiv", o.session.subdivision,
                   "OpenSubdiv refinement level of every mesh, refined each frame from the "
                   "deformed mesh on the GPU, and as the reference traces it (default 0: the "
                   "file's triangles)")
        ->check(tool::range(0, core::limits::kMaxSubdivisionLevel))
        ->type_name("0.." + std::to_string(core::limits::kMaxSubdivisionLevel));
}

/** --plugin and the --set after it. */
void addPluginOptions(CLI::App& app, Options& o) {
    app.add_option_function<std::string>(
           "--plugin",
           [&o](const std::string& path) {
               o.session.plugins.push_back({path, {}});
           },
           "load a plugin module; --set KEY=VALUE after it sets its parameters")
        ->type_name("PATH")
        ->trigger_on_parse()
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_option_function<std::string>(
           "--set",
           [&o](const std::string& v) {
               const auto eq = v.find('=');
               if (o.session.plugins.empty() || eq == std::string::npos || eq == 0)
                   throw CLI::ValidationError("--set",
                                              "KEY=VALUE must follow a --plugin, got '" + v + "'");
               o.session.plugins.back().parameters.emplace_back(v.substr(0, eq), v.substr(eq + 1));
           },
           "a parameter of the plugin loaded last")
        ->type_name("KEY=VALUE")
        ->trigger_on_parse()
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

/** Where and how the frames are written, and the frame-capture cases. */
void addOutputOptions(CLI::App& app, Options& o) {
    app.add_option("--out", o.out,
                   "the folder to write to (default out/capture; with --case the "
                   "case's folder)")
        ->type_name("DIR");
    app.add_flag("--json", o.json,
                 "print files written, times and per-pass CPU/GPU timings as JSON, with the median "
                 "of each over all frames after the first (warm-up)");
    app.add_flag("--force", o.force,
                 "replace output files that exist (without it, an existing file is an error and "
                 "nothing is written); a run that fails removes what it wrote");
    app.add_option("--contact-sheet", o.contactSheet,
                   "also write the frames side by side in one picture (4 per row)")
        ->type_name("PNG");
    app.add_flag("--dump-graph", o.dumpGraph,
                 "print the compiled frame graph of the first frame to stderr");
    app.add_option("--dump-shaders", o.dumpShaders,
                   "write every program the run compiles to DIR, each stage as the final source "
                   "given to GL (the registry's and the variant's defines, includes expanded): "
                   "DIR/<program>-<hash>.<vert|frag|comp>; variants already there are kept")
        ->type_name("DIR");
    app.add_option("--case", o.caseFile,
                   "render a frame-capture case and compare with its goldens (exit 0 match, 1 "
                   "mismatch; .actual.png, .diff.png and a report go to --out, default the "
                   "case's folder); --plugin modules given here load after the case's own "
                   "\"plugins\"")
        ->type_name("FILE.json");
    app.add_flag("--update", o.update, "with --case: regenerate the goldens instead");
}

void addSceneOptions(CLI::App& app, Options& o) {
    app.add_option("models", o.session.models,
                   "glTF models (.glb, .gltf, builtin:NAME) or a scene "
                   "file (.json)")
        ->type_name("MODEL|SCENE");
    app.add_option("--clip", o.session.clip,
                   "clip index or name, for every character (default: the first clip, or the "
                   "scene file's; the rest pose if none)")
        ->type_name("N|NAME");
    app.add_option("--variant", o.session.variant,
                   "a KHR_materials_variants variant (name or index) for every character whose "
                   "model has it (glass-inspect lists a file's variants)")
        ->type_name("NAME");
    addTimeOptions(app, o);
    addLookOptions(app, o);
    addPluginOptions(app, o);
    addOutputOptions(app, o);
}

/** Temporal accumulation's options (docs/methods.md, "Temporal accumulation"). */
void addTemporalOptions(CLI::App& app, Options& o) {
    const std::string group = "Temporal accumulation (docs/methods.md)";
    render::TemporalSettings& t = o.session.temporal;
    tool::addOnOff(app, "--temporal", t.enabled,
                   "on: every frame's projection jittered and blended into a history that "
                   "carries across the frames written (--frames), each pixel reprojected by its "
                   "motion; the trace's and the hybrid's samples one a frame (default off)")
        ->group(group);
    app.add_option("--warmup", o.session.warmup,
                   "with --temporal on: N frames before the first one written, at the times "
                   "before it (--frames' STEP apart, else 1/30 s), as a playing viewer's history "
                   "holds them (default 10)")
        ->check(tool::range(0, 4096))
        ->type_name("N")
        ->group(group);
    tool::addHistoryOptions(app, t, group);
    app.add_option_function<std::string>(
           "--temporal-view",
           [&t](const std::string& v) {
               t.view = v == "rejected" ? render::TemporalSettings::View::Rejected
                                        : render::TemporalSettings::View::Motion;
           },
           "rejected: red where the history was rejected, green where it was clipped; motion: "
           "each pixel's motion (hue its direction, brightness its length up to 8 pixels)")
        ->check(tool::oneOf({"rejected", "motion"}))
        ->type_name("rejected|motion")
        ->group(group);
    app.add_option("--accumulate", o.session.accumulate,
                   "every frame written is N frames at its one time from a fresh history, "
                   "accumulated (still frames converge: N frames equal N samples a pixel)")
        ->check(tool::range(1, 4096))
        ->type_name("N")
        ->group(group);
}

/** The reference's options (Embree, on the CPU, all cores). */
void addReferenceOptions(CLI::App& app, Options& o) {
    const std::string group = "Reference (Embree, on the CPU; --method reference traces it alone)";
    app.add_flag("--compare-reference", o.compare,
                 "render --method and the reference, report PSNR and SSIM over the glass mask, "
                 "PSNR outside it and over the whole image, write MODEL_..._tT.reference.png and "
                 ".heatmap.png beside "
                 "the frame")
        ->group(group);
    app.add_option("--spp", o.referenceOptions.samplesPerPixel,
                   "reference samples per pixel, jittered (default 16)")
        ->check(tool::range(1, 4096))
        ->type_name("K")
        ->group(group);
    app.add_flag("--pixel-centres", o.referenceOptions.pixelCentres,
                 "the reference traces one ray through each pixel centre, where the GPU samples "
                 "(instead of --spp jittered rays)")
        ->group(group);
    app.add_flag("--deterministic", o.referenceOptions.deterministic,
                 "the reference's deterministic evaluation (docs/methods.md): pixel centres, "
                 "every reflection into glass followed to a stated depth and then looked up, "
                 "rough glass by its normals, paths ending after --interfaces as the trace's do; "
                 "what the trace at one sample a pixel computes")
        ->group(group);
    app.add_option("--max-bounces", o.referenceOptions.maxBounces,
                   "interfaces (refractions and reflections) a reference path follows after its "
                   "entry before it counts as trapped (default 1024)")
        ->check(tool::range(0, 4096))
        ->type_name("N")
        ->group(group);
    app.add_option("--photons", o.referenceOptions.photons,
                   "the reference's caustics: photons sent from each light that casts (default "
                   "262144)")
        ->check(tool::range(1, 1 << 26))
        ->type_name("N")
        ->group(group);
    app.add_option("--caustic-radius", o.referenceOptions.causticRadius,
                   "the reference's caustics: the radius their photons are gathered over, world "
                   "units (default 0: a twentieth of the glass's bounding radius)")
        ->check(CLI::NonNegativeNumber.description(""))
        ->type_name("R")
        ->group(group);
}

/** The combinations the options cannot say alone. */
std::optional<int> checkCombinations(const CLI::App& app, Options& o) {
    const auto given = [&](const char* name) { return app.count(name) > 0; };
    const bool warmupGiven = given("--warmup"), accumulateGiven = given("--accumulate");
    const bool weightGiven = given("--history-weight") || given("--history-rejection") ||
                             given("--converge-still") || given("--temporal-view");
    o.outGiven = given("--out");
    if (given("--time") && given("--frames"))
        return tool::usageError(app, "--time and --frames are exclusive");
    if (o.reference && o.compare)
        return tool::usageError(app, "--method reference and --compare-reference are exclusive");
    o.referenceOptions.subdivision = o.session.subdivision; // the reference traces it too
    if ((warmupGiven && !o.session.temporal.enabled) ||
        (weightGiven && !o.session.temporal.enabled && !accumulateGiven))
        return tool::usageError(app, "--warmup goes with --temporal on; --history-weight, "
                                     "--history-rejection, --converge-still and --temporal-view "
                                     "with --temporal on or --accumulate");
    if (accumulateGiven && o.session.temporal.enabled)
        return tool::usageError(app, "--accumulate and --temporal on are exclusive (accumulate "
                                     "converges each frame from a fresh history)");
    if (o.session.temporal.enabled && !warmupGiven)
        o.session.warmup = 10;
    if (o.caseFile.empty() && o.session.models.empty())
        return tool::usageError(app, "no model given");
    if (!o.caseFile.empty() && !o.session.models.empty())
        return tool::usageError(app, "--case takes its model from the case file");
    if (o.update && o.caseFile.empty())
        return tool::usageError(app, "--update goes with --case");
    return std::nullopt;
}

std::optional<int> parse(int argc, char** argv, Options& o) {
    CLI::App app{"", "glass-capture"};
    tool::configure(app, kDescription, kExitStatus);
    addSceneOptions(app, o);
    addTemporalOptions(app, o);
    // The built-in refraction plugin's parameters (materials with KHR_materials_transmission
    // are glass), and --method reference.
    const plugin::ParameterSet glass = refraction::createPlugin()->parameters();
    tool::addParameterOptions(
        app, glass, o.session.refraction,
        "Glass (the built-in refraction plugin; --method reference: the reference instead)",
        [&o](const std::string& name, const std::string& value) {
            return name == "method" && value == "reference" && (o.reference = true);
        });
    addReferenceOptions(app, o);
    if (const auto code = tool::parseArguments(app, argc, argv))
        return code;
    return checkCombinations(app, o);
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

std::filesystem::path sibling(std::filesystem::path path, const char* suffix) {
    return path.replace_extension(std::string(suffix) + ".png");
}

/** What --compare-reference keeps from frame to frame: the last frame and its reference, and
 *  the flicker summed over consecutive pairs (capture::flicker). */
struct Comparison {
    std::optional<capture::RenderedFrame> previous, previousReference;
    double flickerSum = 0.0;
    std::size_t flickerPairs = 0;
};

void addReferenceFacts(nlohmann::json& entry, const capture::RenderedFrame& traced) {
    entry["reference_ms"] = traced.milliseconds;
    entry["trapped_samples"] = traced.trappedSamples;
    entry["glass_surfaces_per_pixel"] = traced.surfaceHistogram;
}

/** The frame at `path` scored against the reference at its time, which is written beside it
 *  with the heatmap; the scores into `entry` and `scoreText`, the flicker into `comparison`. */
core::Status compareWithReference(capture::CaptureSession& session, const Options& o,
                                  const capture::RenderedFrame& frame,
                                  const std::filesystem::path& path, Outputs& outputs,
                                  nlohmann::json& entry, std::string& scoreText,
                                  Comparison& comparison) {
    auto reference = session.renderReference(frame.time, o.referenceOptions);
    if (!reference)
        return reference.error();
    const auto masked = capture::score(frame.image, reference->image, &reference->glassMask);
    const auto full = capture::score(frame.image, reference->image);
    // Outside the glass: what receives the lights' shadows and caustics (and the sky).
    std::vector<bool> outside(reference->glassMask.size());
    for (std::size_t p = 0; p < outside.size(); ++p)
        outside[p] = !reference->glassMask[p];
    const auto around = capture::score(frame.image, reference->image, &outside);
    for (const auto& [file, image] :
         {std::pair{sibling(path, ".reference"), reference->image},
          std::pair{sibling(path, ".heatmap"),
                    capture::heatmap(frame.image, reference->image, 64, &reference->glassMask)}})
        if (auto written = outputs.write(file, image); !written)
            return written;
    entry["reference_file"] = sibling(path, ".reference").string();
    entry["heatmap_file"] = sibling(path, ".heatmap").string();
    addReferenceFacts(entry, *reference);
    entry["scores"] = {
        {"mask", {{"psnr", masked.psnr}, {"ssim", masked.ssim}, {"pixels", masked.pixels}}},
        {"outside", {{"psnr", around.psnr}, {"ssim", around.ssim}, {"pixels", around.pixels}}},
        {"image", {{"psnr", full.psnr}, {"ssim", full.ssim}, {"pixels", full.pixels}}}};
    char text[200];
    std::snprintf(text, sizeof text,
                  ", glass mask %zu px: PSNR %.2f dB, SSIM %.4f; outside it %.2f dB; image PSNR "
                  "%.2f dB",
                  masked.pixels, masked.psnr, masked.ssim, around.psnr, full.psnr);
    scoreText = text;
    if (comparison.previous) {
        std::vector<bool> both(reference->glassMask.size());
        for (std::size_t p = 0; p < both.size(); ++p)
            both[p] = reference->glassMask[p] && comparison.previousReference->glassMask[p];
        const capture::Flicker f =
            capture::flicker(comparison.previous->image, frame.image,
                             comparison.previousReference->image, reference->image, both);
        entry["flicker"] = f.meanAbsDifference;
        comparison.flickerSum += f.meanAbsDifference;
        ++comparison.flickerPairs;
    }
    comparison.previous = frame;
    comparison.previousReference = *reference;
    return {};
}

/** The report's header: the model, clip, size and how the frames accumulate. */
nlohmann::json reportHeader(const Options& o, const capture::CaptureSession& session) {
    nlohmann::json report = {{"model", o.session.models.size() == 1
                                           ? nlohmann::json(o.session.models[0])
                                           : nlohmann::json(o.session.models)},
                             {"clip", session.clipLabel()},
                             {"size", {o.session.size.x, o.session.size.y}},
                             {"frames", nlohmann::json::array()}};
    if (o.session.temporal.enabled)
        report["temporal"] = {{"warmup_frames", o.session.warmup},
                              {"warmup_step", o.session.warmupStep},
                              {"history_weight", o.session.temporal.historyWeight},
                              {"moving_jitter", o.session.temporal.movingJitter}};
    if (o.session.accumulate > 0)
        report["accumulate"] = o.session.accumulate;
    return report;
}

/** Renders, writes (and compares) every frame, then the contact sheet; the report filled. */
core::Status captureFrames(capture::CaptureSession& session, const Options& o, Outputs& outputs,
                           nlohmann::json& report) {
    auto frameFile = [&](double time) {
        return std::filesystem::path(o.out) /
               capture::frameFileName(session.stem(), session.clipLabel(), time);
    };
    std::vector<std::filesystem::path> planned;
    for (double time : o.times) {
        planned.push_back(frameFile(time));
        if (o.compare)
            for (const char* suffix : {".reference", ".heatmap"})
                planned.push_back(sibling(frameFile(time), suffix));
    }
    if (!o.contactSheet.empty())
        planned.emplace_back(o.contactSheet);
    if (auto free = outputs.check(planned); !free)
        return free;
    std::vector<capture::Image> sheetFrames;
    Comparison comparison;
    for (std::size_t i = 0; i < o.times.size(); ++i) {
        auto frame = o.reference ? session.renderReference(o.times[i], o.referenceOptions)
                                 : session.render(o.times[i]);
        if (!frame)
            return frame.error();
        if (i == 0 && o.dumpGraph)
            std::fprintf(stderr, "%s", frame->stats.graph.c_str());
        const auto path = frameFile(frame->time);
        if (auto written = outputs.write(path, frame->image); !written)
            return written;
        nlohmann::json entry = capture::statsJson(frame->stats);
        entry["time"] = frame->time;
        entry["file"] = path.string();
        if (o.reference)
            addReferenceFacts(entry, *frame);
        std::string scoreText;
        if (o.compare)
            if (auto compared = compareWithReference(session, o, *frame, path, outputs, entry,
                                                     scoreText, comparison);
                !compared)
                return compared;
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
        if (auto written = outputs.write(o.contactSheet, sheet); !written)
            return written;
        report["contact_sheet"] = o.contactSheet;
        if (!o.json)
            std::printf("%s (contact sheet, %d frames)\n", o.contactSheet.c_str(),
                        int(sheetFrames.size()));
    }
    if (comparison.flickerPairs > 0) {
        const double mean = comparison.flickerSum / double(comparison.flickerPairs);
        report["flicker"] = {{"mean_abs_difference", mean}, {"pairs", comparison.flickerPairs}};
        if (!o.json)
            std::printf("flicker against the reference: %.3f (mean |frame change - reference "
                        "change| over the glass, 1/255, %zu frame pairs)\n",
                        mean, comparison.flickerPairs);
    }
    return {};
}

int fail(const std::string& message) {
    std::fprintf(stderr, "%s\n", message.c_str());
    return 1;
}

} // namespace

int run(int argc, char** argv) {
    Options o;
    if (const auto code = parse(argc, argv, o))
        return *code;
    // every shader library the run makes (gl::ShaderLibrary) dumps where this names
    if (!o.dumpShaders.empty())
        setenv("GLASS_DUMP_SHADERS", o.dumpShaders.c_str(), 1);
    if (!o.caseFile.empty())
        return runCase(o);
    auto session = capture::CaptureSession::create(o.session);
    if (!session)
        return fail(session.error().message);
    nlohmann::json report = reportHeader(o, **session);
    if (o.session.temporal.enabled && !o.json)
        std::printf("temporal accumulation: %d warm-up frames %.4f s apart before the first\n",
                    o.session.warmup, o.session.warmupStep);
    std::error_code ec;
    std::filesystem::create_directories(o.out, ec);
    if (ec)
        return fail("glass-capture: cannot create " + o.out + ": " + ec.message());
    o.referenceOptions.progress = !o.json;
    Outputs outputs(o.force);
    if (auto captured = captureFrames(**session, o, outputs, report); !captured)
        return fail(captured.error().message);
    outputs.commit();
    if (o.json) {
        report["median"] = capture::medianStats(report["frames"]);
        std::printf("%s\n", report.dump(2).c_str());
    }
    return 0;
}

int main(int argc, char** argv) {
    return tool::guardedMain("glass-capture", run, argc, argv);
}
