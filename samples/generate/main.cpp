// glass-generate-assets: writes the project's default character and environment into assets/.
#include "../common/ToolMain.h"
#include "Figure.h"
#include "Sky.h"

#include "engine/core/Files.h"

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace {

const char* const kUsage = R"(usage: glass-generate-assets [--out DIR] [--force]

Writes the project's own default assets (nothing third party):
  DIR/models/glass_figure.glb  a glass figure: 19-joint skeleton, a breathing morph target,
                               clips walk, wave and idle; KHR_materials_transmission, _volume,
                               _ior and _dispersion
  DIR/models/glass_figure_parts.glb
                               the same figure with a glass per body part (clear torso, blue
                               arms, amber legs) and a hammered-glass head (a normal map)
  DIR/env/sunset_sky.hdr       a procedural sunset: sun, coloured skyline, tiled floor

  --out DIR   where to write (default: assets)
  --force     replace files that exist (otherwise an existing file is an error and nothing
              is written)

The output is deterministic. Each file is written atomically (temporary file, then rename).
Exit status: 0 written, 1 a write failed or a file exists without --force, 2 bad arguments.
)";

} // namespace

int run(int argc, char** argv) {
    std::filesystem::path out = "assets";
    bool force = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (arg == "--force") {
            force = true;
        } else if (arg == "--out" && i + 1 < argc) {
            out = argv[++i];
        } else {
            std::fprintf(stderr, "glass-generate-assets: unexpected '%s'\n\n%s", arg.c_str(),
                         kUsage);
            return 2;
        }
    }
    const std::filesystem::path figure = out / "models" / "glass_figure.glb";
    const std::filesystem::path parts = out / "models" / "glass_figure_parts.glb";
    const std::filesystem::path sky = out / "env" / "sunset_sky.hdr";
    for (const auto& path : {figure, parts, sky})
        if (!force && std::filesystem::exists(path)) {
            std::fprintf(stderr, "glass-generate-assets: %s exists (use --force to replace it)\n",
                         path.string().c_str());
            return 1;
        }
    const std::vector<std::uint8_t> glb = generate::buildFigureGlb();
    const std::vector<std::uint8_t> partsGlb = generate::buildFigureGlb({.parts = true});
    const std::vector<std::uint8_t> hdr = asset::encodeHdr(generate::buildSky());
    for (const auto& [path, bytes] :
         {std::pair{figure, &glb}, std::pair{parts, &partsGlb}, std::pair{sky, &hdr}}) {
        std::error_code ec;
        std::filesystem::create_directories(path.parent_path(), ec);
        if (auto written = core::writeFileAtomic(path, *bytes); !written) {
            std::fprintf(stderr, "glass-generate-assets: %s\n", written.error().message.c_str());
            return 1;
        }
        std::printf("%s (%zu bytes)\n", path.string().c_str(), bytes->size());
    }
    return 0;
}

int main(int argc, char** argv) {
    return tool::guardedMain("glass-generate-assets", run, argc, argv);
}
