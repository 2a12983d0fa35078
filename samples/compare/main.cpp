// glass-compare: PSNR and SSIM between two images (over a mask if given) and an error heatmap.
#include "../common/Cli.h"
#include "../common/ToolMain.h"
#include "engine/capture/Image.h"
#include "engine/capture/Metrics.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <optional>
#include <string>

namespace {

constexpr const char* kDescription =
    R"(glass-compare A.png B.png: scores image A against image B (same size): PSNR over RGB and
mean SSIM of luminance (8x8 windows), over every pixel and, with --mask, over the pixels where M
is not black. --heatmap writes the per-pixel error as a colour ramp (black, blue, yellow, red at
64/255 and over).
glass-compare --contact-sheet OUT.png IMAGE...: lays the images (PNG or JPEG, any sizes) out in
a grid of --columns columns of cells --cell pixels wide, each image fitted to its cell.)";

constexpr const char* kExitStatus =
    "Exit status: 0 success, 1 an image could not be read or the sizes differ, 2 bad arguments.";

} // namespace

int run(int argc, char** argv) {
    std::vector<std::string> images;
    std::optional<std::string> maskPath, heatmapPath, sheetPath;
    int columns = 2, cell = 256;
    bool json = false;
    CLI::App app{"", "glass-compare"};
    tool::configure(app, kDescription, kExitStatus);
    app.add_option("images", images, "A.png B.png, or the contact sheet's images")
        ->type_name("IMAGE");
    app.add_option("--mask", maskPath, "score only where this image is not black")
        ->type_name("M.png");
    app.add_option("--heatmap", heatmapPath, "write the per-pixel error as a colour ramp")
        ->type_name("OUT.png");
    app.add_flag("--json", json, "print the scores as JSON");
    app.add_option("--contact-sheet", sheetPath, "write the images side by side into OUT.png")
        ->type_name("OUT.png");
    app.add_option("--columns", columns, "the contact sheet's columns (default 2)")
        ->check(tool::range(1, 4096))
        ->type_name("N");
    app.add_option("--cell", cell, "the contact sheet's cell width in pixels (default 256)")
        ->check(tool::range(1, 4096))
        ->type_name("W");
    if (const auto code = tool::parseArguments(app, argc, argv))
        return *code;
    if (sheetPath) {
        if (images.empty())
            return tool::usageError(app, "--contact-sheet needs images");
        std::vector<capture::Image> read;
        for (const std::string& path : images) {
            auto image = capture::readPng(path);
            if (!image) {
                std::fprintf(stderr, "glass-compare: %s\n", image.error().message.c_str());
                return 1;
            }
            read.push_back(std::move(*image));
        }
        if (auto written =
                capture::writePng(*sheetPath, capture::contactSheet(read, columns, cell));
            !written) {
            std::fprintf(stderr, "glass-compare: %s\n", written.error().message.c_str());
            return 1;
        }
        std::printf("%s (%zu images)\n", sheetPath->c_str(), images.size());
        return 0;
    }
    if (images.size() != 2)
        return tool::usageError(app, "needs exactly two images");
    auto a = capture::readPng(images[0]);
    auto b = capture::readPng(images[1]);
    for (const auto* image : {&a, &b})
        if (!*image) {
            std::fprintf(stderr, "glass-compare: %s\n", image->error().message.c_str());
            return 1;
        }
    if (a->width != b->width || a->height != b->height) {
        std::fprintf(stderr, "glass-compare: %s is %dx%d but %s is %dx%d\n", images[0].c_str(),
                     a->width, a->height, images[1].c_str(), b->width, b->height);
        return 1;
    }
    std::optional<std::vector<bool>> mask;
    if (maskPath) {
        auto m = capture::readPng(*maskPath);
        if (!m || m->width != a->width || m->height != a->height) {
            std::fprintf(stderr, "glass-compare: mask %s: %s\n", maskPath->c_str(),
                         m ? "size differs from the images" : m.error().message.c_str());
            return 1;
        }
        mask.emplace(std::size_t(m->width) * std::size_t(m->height));
        for (std::size_t i = 0; i < mask->size(); ++i)
            (*mask)[i] = m->rgba[i * 4] + m->rgba[i * 4 + 1] + m->rgba[i * 4 + 2] > 0;
    }
    const auto full = capture::score(*a, *b);
    const capture::Scores masked = mask ? capture::score(*a, *b, &*mask) : capture::Scores{};
    if (heatmapPath) {
        auto written =
            capture::writePng(*heatmapPath, capture::heatmap(*a, *b, 64, mask ? &*mask : nullptr));
        if (!written) {
            std::fprintf(stderr, "glass-compare: %s\n", written.error().message.c_str());
            return 1;
        }
    }
    if (json) {
        nlohmann::json j = {
            {"image", {{"psnr", full.psnr}, {"ssim", full.ssim}, {"pixels", full.pixels}}}};
        if (mask)
            j["mask"] = {{"psnr", masked.psnr}, {"ssim", masked.ssim}, {"pixels", masked.pixels}};
        std::printf("%s\n", j.dump(2).c_str());
    } else {
        std::printf("image: PSNR %.2f dB, SSIM %.4f over %zu pixels\n", full.psnr, full.ssim,
                    full.pixels);
        if (mask)
            std::printf("mask:  PSNR %.2f dB, SSIM %.4f over %zu pixels\n", masked.psnr,
                        masked.ssim, masked.pixels);
    }
    return 0;
}

int main(int argc, char** argv) {
    return tool::guardedMain("glass-compare", run, argc, argv);
}
