// glass-generate-assets: writes the project's default character and environment into assets/.
#include "../common/Cli.h"
#include "../common/ToolMain.h"
#include "Figure.h"
#include "Sky.h"

#include "engine/core/Files.h"

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace {

constexpr const char* kDescription =
    R"(glass-generate-assets: writes the project's own default assets (nothing third party):
  DIR/models/glass_figure.glb  a glass figure: 19-joint skeleton, a breathing morph target,
                               clips walk, wave and idle; KHR_materials_transmission, _volume,
                               _ior and _dispersion
  DIR/models/glass_figure_parts.glb
                               the same figure with a glass per body part (clear torso, blue
                               arms, amber legs) and a hammered-glass head (a normal map)
  DIR/env/sunset_sky.hdr       a procedural sunset: sun, coloured skyline, tiled floor
The output is deterministic. Each file is written atomically (temporary file, then rename).)";

constexpr const char* kExitStatus =
    "Exit status: 0 written, 1 a write failed or a file exists without --force, 2 bad arguments.";

} // namespace

int run(int argc, char** argv) {
    std::filesystem::path out = "assets";
    bool force = false;
    CLI::App app{"", "glass-generate-assets"};
    tool::configure(app, kDescription, kExitStatus);
    app.add_option("--out", out, "where to write (default: assets)")->type_name("DIR");
    app.add_flag("--force", force,
                 "replace files that exist (otherwise an existing file is an error and nothing "
                 "is written)");
    if (const auto code = tool::parseArguments(app, argc, argv))
        return *code;
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
