// Case files, golden comparison and regeneration.
#include "CaptureCase.h"

#include "engine/core/Files.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>

namespace capture {
namespace {

/** Temporal accumulation: "accumulate": N frames at each time from a fresh history, or
 *  "temporal": {"warmup": W, "history_weight": H, "moving_jitter": J} to carry the history
 *  across the times. */
core::Status readTemporal(const nlohmann::json& j, CaseFile& c, const std::string& where) {
    c.session.accumulate = j.value("accumulate", 0);
    if (c.session.accumulate < 0 || c.session.accumulate > 4096)
        return core::Error{where + "\"accumulate\" must be 0..4096 frames"};
    if (j.contains("temporal")) {
        const auto& t = j["temporal"];
        if (!t.is_object())
            return core::Error{where + "\"temporal\" must be an object"};
        c.session.temporal.enabled = true;
        c.session.warmup = t.value("warmup", 10);
        c.session.temporal.historyWeight =
            t.value("history_weight", c.session.temporal.historyWeight);
        c.session.temporal.movingJitter = t.value("moving_jitter", c.session.temporal.movingJitter);
        if (c.session.warmup < 0 || c.session.warmup > 4096 ||
            !(c.session.temporal.historyWeight >= 0.0f &&
              c.session.temporal.historyWeight <= 0.99f) ||
            !(c.session.temporal.movingJitter >= 0.0f && c.session.temporal.movingJitter <= 1.0f))
            return core::Error{where + "\"temporal\": warmup 0..4096, history_weight 0..0.99, "
                                       "moving_jitter 0..1"};
        if (c.times.size() > 1)
            c.session.warmupStep = c.times[1] - c.times[0];
    }
    return {};
}

/** "camera": a position and target, or an orbit (azimuth, elevation), and the field of view. */
void readCamera(const nlohmann::json& j, CaseFile& c) {
    if (j.contains("camera") && j["camera"].is_object()) {
        const auto& cam = j["camera"];
        CameraOverride o;
        if (cam.contains("position")) {
            glm::vec3 position;
            for (int k = 0; k < 3; ++k) {
                position[k] = cam.at("position").at(std::size_t(k)).get<float>();
                o.target[k] = cam.at("target").at(std::size_t(k)).get<float>();
            }
            o.position = position;
        }
        o.yfov = cam.value("yfov", 0.7f);
        o.azimuth = cam.value("azimuth", 0.0f);
        o.elevation = cam.value("elevation", 0.15f);
        c.session.camera = o;
    }
}

/** "plugins": each module's path (relative to the case file) and parameters. */
void readPlugins(const nlohmann::json& j, CaseFile& c,
                 const std::function<std::string(const std::string&)>& resolve) {
    if (j.contains("plugins"))
        for (const auto& p : j["plugins"]) {
            SessionOptions::PluginSpec spec;
            spec.path = resolve(p.at("path").get<std::string>());
            if (p.contains("parameters"))
                for (const auto& [key, value] : p["parameters"].items())
                    spec.parameters.emplace_back(key, value.is_string() ? value.get<std::string>()
                                                                        : value.dump());
            c.session.plugins.push_back(spec);
        }
}

} // namespace

core::Result<CaseFile> readCaseFile(const std::filesystem::path& path) {
    const std::string where = "glass-capture: " + path.string() + ": ";
    std::ifstream in(path);
    if (!in)
        return core::Error{where + "cannot open the case file"};
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
        return core::Error{where + "not valid JSON (" + e.what() + ")"};
    }
    const std::filesystem::path dir = path.parent_path();
    auto resolve = [&](const std::string& p) { return (dir / p).lexically_normal().string(); };
    CaseFile c;
    c.path = path;
    try {
        const auto& models = j.contains("model") ? j["model"] : nlohmann::json();
        const bool list = models.is_array() && !models.empty() &&
                          std::all_of(models.begin(), models.end(),
                                      [](const nlohmann::json& m) { return m.is_string(); });
        if (!models.is_string() && !list)
            return core::Error{where + "\"model\" (a model or scene file path relative to the "
                                       "case file, or an array of model paths) is required"};
        for (const auto& m : list ? models : nlohmann::json::array({models})) {
            const std::string model = m.get<std::string>();
            c.session.models.push_back(model.rfind("builtin:", 0) == 0 ? model : resolve(model));
        }
        if (j.contains("clip"))
            c.session.clip = j["clip"].is_string() ? j["clip"].get<std::string>()
                                                   : std::to_string(j["clip"].get<int>());
        if (j.contains("variant"))
            c.session.variant = j["variant"].is_string() ? j["variant"].get<std::string>()
                                                         : std::to_string(j["variant"].get<int>());
        if (!j.contains("times") || !j["times"].is_array() || j["times"].empty())
            return core::Error{where + "\"times\" (a non-empty array of seconds) is required"};
        for (const auto& t : j["times"])
            c.times.push_back(t.get<double>());
        if (j.contains("size"))
            c.session.size = {j["size"].at(0).get<int>(), j["size"].at(1).get<int>()};
        if (c.session.size.x < 1 || c.session.size.y < 1 || c.session.size.x > 8192 ||
            c.session.size.y > 8192)
            return core::Error{where + "\"size\" must be [width, height] within 1..8192"};
        if (j.contains("env") && !j["env"].is_null())
            c.session.environment = resolve(j["env"].get<std::string>());
        c.session.ground = j.value("ground", false);
        c.session.shadows = j.value("shadows", true);
        if (j.contains("shadow_map")) {
            using View = render::RenderSettings::ShadowMapView;
            const std::string view = j["shadow_map"].get<std::string>();
            const std::array<std::pair<const char*, View>, 4> views{{{"off", View::Off},
                                                                     {"depth", View::Depth},
                                                                     {"glass", View::Glass},
                                                                     {"caustics", View::Caustics}}};
            const auto it = std::find_if(views.begin(), views.end(),
                                         [&](const auto& v) { return view == v.first; });
            if (it == views.end())
                return core::Error{where + "\"shadow_map\" must be off, depth, glass or caustics"};
            c.session.shadowMapView = it->second;
        }
        c.session.exposure = j.value("exposure", 1.0f);
        c.session.subdivision = j.value("subdiv", 0);
        if (auto read = readTemporal(j, c, where); !read)
            return read.error();
        readCamera(j, c);
        readPlugins(j, c, resolve);
        if (j.contains("refraction"))
            for (const auto& [key, value] : j["refraction"].items())
                c.session.refraction.emplace_back(key, value.is_string() ? value.get<std::string>()
                                                                         : value.dump());
        if (j.contains("tolerance")) {
            c.tolerance.maxAbsDiff = j["tolerance"].value("max_abs_diff", c.tolerance.maxAbsDiff);
            c.tolerance.maxFailingFraction =
                j["tolerance"].value("max_failing_fraction", c.tolerance.maxFailingFraction);
        }
        c.skipIfModelMissing = j.value("skip_if_missing", false);
    } catch (const std::exception& e) {
        return core::Error{where + "malformed entry (" + e.what() + ")"};
    }
    return c;
}

std::filesystem::path goldenPath(const CaseFile& c, double time) {
    return c.path.parent_path() / (c.path.stem().string() + ".t" + secondsText(time) + ".png");
}

core::Result<int> runCase(const CaseFile& c, bool update, const std::filesystem::path& outDir) {
    auto session = CaptureSession::create(c.session);
    if (!session)
        return session.error();
    std::ostringstream report;
    bool allMatch = true;
    for (double time : c.times) {
        auto frame = (*session)->render(time);
        if (!frame)
            return frame.error();
        const auto golden = goldenPath(c, time);
        if (update) {
            auto written = writePng(golden, frame->image);
            if (!written)
                return written.error();
            std::printf("updated %s\n", golden.string().c_str());
            continue;
        }
        auto expected = readPng(golden);
        if (!expected)
            return core::Error{"glass-capture: no golden for t=" + secondsText(time) + " (" +
                               expected.error().message + "); run with --update to create it"};
        const Comparison cmp = compare(frame->image, *expected, c.tolerance);
        char line[256];
        std::snprintf(line, sizeof line,
                      "%s t=%s: %s (max abs diff %d, failing pixels %zu = %.4f%%, allowed %.4f%%)",
                      c.path.stem().string().c_str(), secondsText(time).c_str(),
                      !cmp.sizeMatches ? "SIZE MISMATCH"
                      : cmp.passed     ? "match"
                                       : "MISMATCH",
                      cmp.maxAbsDiff, cmp.failingPixels, 100.0 * cmp.failingFraction,
                      100.0 * c.tolerance.maxFailingFraction);
        std::printf("%s\n", line);
        report << line << "\n";
        if (cmp.sizeMatches && cmp.passed)
            continue;
        allMatch = false;
        std::filesystem::create_directories(outDir);
        const std::string stem = c.path.stem().string() + ".t" + secondsText(time);
        auto a = writePng(outDir / (stem + ".actual.png"), frame->image);
        if (!a)
            return a.error();
        if (cmp.sizeMatches) {
            auto d = writePng(outDir / (stem + ".diff.png"), cmp.diff);
            if (!d)
                return d.error();
        }
        report << "  golden " << golden.string() << "\n  actual "
               << (outDir / (stem + ".actual.png")).string() << "\n  diff   "
               << (outDir / (stem + ".diff.png")).string() << "\n";
    }
    if (!update && !allMatch) {
        const auto reportPath = outDir / (c.path.stem().string() + ".report.txt");
        auto w = core::writeFileAtomic(reportPath, report.str());
        if (!w)
            return w.error();
        std::printf("report: %s\n", reportPath.string().c_str());
    }
    return allMatch || update ? kCaseMatch : kCaseMismatch;
}

} // namespace capture
