// glass-compare: PSNR and SSIM between two images (over a mask if given) and an error heatmap.
#include "../common/ToolMain.h"
#include "engine/capture/Image.h"
#include "engine/capture/Metrics.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <optional>
#include <string>

namespace {

constexpr const char* kUsage =
    R"(usage: glass-compare A.png B.png [--mask M.png] [--heatmap OUT.png] [--json]
       glass-compare --contact-sheet OUT.png [--columns N] [--cell W] IMAGE...

Scores image A against image B (same size): PSNR over RGB and mean SSIM of luminance (8x8
windows), over every pixel and, with --mask, over the pixels where M is not black. --heatmap
writes the per-pixel error as a colour ramp (black, blue, yellow, red at 64/255 and over).

--contact-sheet lays the images (PNG or JPEG, any sizes) out in a grid of N columns (default
2) of cells W pixels wide (default 256), each image fitted to its cell, and writes it to OUT.

Exit status: 0 success, 1 an image could not be read or the sizes differ, 2 bad arguments.
)";

int usageError(const std::string& message) {
    std::fprintf(stderr, "glass-compare: %s\n\n%s", message.c_str(), kUsage);
    return 2;
}

} // namespace

int run(int argc, char** argv) {
    std::vector<std::string> images;
    std::optional<std::string> maskPath, heatmapPath, sheetPath;
    int columns = 2, cell = 256;
    bool json = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (arg == "--json") {
            json = true;
        } else if (arg == "--mask" || arg == "--heatmap" || arg == "--contact-sheet") {
            if (i + 1 >= argc)
                return usageError(arg + " needs a value");
            (arg == "--mask" ? maskPath : arg == "--heatmap" ? heatmapPath : sheetPath) = argv[++i];
        } else if (arg == "--columns" || arg == "--cell") {
            int n = 0;
            if (i + 1 >= argc || std::sscanf(argv[i + 1], "%d", &n) != 1 || n < 1 || n > 4096)
                return usageError(arg + " needs a whole number from 1 to 4096");
            (arg == "--columns" ? columns : cell) = n;
            ++i;
        } else if (!arg.empty() && arg[0] == '-') {
            return usageError("unknown option " + arg);
        } else {
            images.push_back(arg);
        }
    }
    if (sheetPath) {
        if (images.empty())
            return usageError("--contact-sheet needs images");
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
        return usageError("needs exactly two images");
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
