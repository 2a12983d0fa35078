// Frame-capture test cases: a JSON case file (model, clip, times, camera, size, plugins and their
// parameters, tolerance) next to its golden PNGs, rendered and compared, or regenerated.
#pragma once

#include "CaptureSession.h"

#include <filesystem>

namespace capture {

struct CaseFile {
    std::filesystem::path path;
    SessionOptions session;
    std::vector<double> times;
    Tolerance tolerance;
    bool skipIfModelMissing = false;
};

/** Parses a case file. Paths inside it (model, env, plugins) are relative to its folder.
 *  Fails naming the file and the key on a missing or mistyped entry. */
core::Result<CaseFile> readCaseFile(const std::filesystem::path& path);

/** Golden of `time`: "<case stem>.t<seconds, 3 decimals>.png" beside the case file. */
std::filesystem::path goldenPath(const CaseFile& c, double time);

/** Exit codes of glass-capture --case. */
inline constexpr int kCaseMatch = 0, kCaseMismatch = 1, kCaseSkipped = 77;

/** Renders every time of the case and compares with its golden, or (update) rewrites the
 *  goldens. On a mismatch writes "<stem>.t<time>.actual.png", ".diff.png" and "<stem>.report.txt"
 *  into `outDir`. Prints one line per frame. Returns kCaseMatch, kCaseMismatch, or an Error. */
core::Result<int> runCase(const CaseFile& c, bool update, const std::filesystem::path& outDir);

} // namespace capture
