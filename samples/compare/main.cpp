// glass-compare: PSNR and SSIM between two images (over a mask if given) and an error heatmap.
#include "../common/Cli.h"
#include "../common/ToolMain.h"
#include "engine/capture/Image.h"
#include "engine/capture/Metrics.h"
#include "engine/core/Result.h"

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

/** The command line's values. */
struct Arguments {
    std::vector<std::string> images;
    std::optional<std::string> maskPath, heatmapPath, sheetPath;
    int columns = 2, cell = 256;
    bool json = false;
};

void addOptions(CLI::App& app, Arguments& a) {
    app.add_option("images", a.images, "A.png B.png, or the contact sheet's images")
        ->type_name("IMAGE");
    app.add_option("--mask", a.maskPath, "score only where this image is not black")
        ->type_name("M.png");
    app.add_option("--heatmap", a.heatmapPath, "write the per-pixel error as a colour ramp")
        ->type_name("OUT.png");
    app.add_flag("--json", a.json, "print the scores as JSON");
    app.add_option("--contact-sheet", a.sheetPath, "write the images side by side into OUT.png")
        ->type_name("OUT.png");
    app.add_option("--columns", a.columns, "the contact sheet's columns (default 2)")
        ->check(tool::range(1, 4096))
        ->type_name("N");
    app.add_option("--cell", a.cell, "the contact sheet's cell width in pixels (default 256)")
        ->check(tool::range(1, 4096))
        ->type_name("W");
}

/** Prints `message` as the tool's error; the exit status 1. */
int failed(const std::string& message) {
    std::fprintf(stderr, "glass-compare: %s\n", message.c_str());
    return 1;
}

int writeContactSheet(const Arguments& a) {
    std::vector<capture::Image> read;
    for (const std::string& path : a.images) {
        auto image = capture::readPng(path);
        if (!image)
            return failed(image.error().message);
        read.push_back(std::move(*image));
    }
    if (auto written =
            capture::writePng(*a.sheetPath, capture::contactSheet(read, a.columns, a.cell));
        !written)
        return failed(written.error().message);
    std::printf("%s (%zu images)\n", a.sheetPath->c_str(), a.images.size());
    return 0;
}

/** The mask image at `path` as a pixel mask (not black), of `width` x `height`. */
core::Result<std::vector<bool>> readMask(const std::string& path, int width, int height) {
    auto m = capture::readPng(path);
    if (!m || m->width != width || m->height != height)
        return core::Error{"mask " + path + ": " +
                           (m ? "size differs from the images" : m.error().message)};
    std::vector<bool> mask(std::size_t(m->width) * std::size_t(m->height));
    for (std::size_t i = 0; i < mask.size(); ++i)
        mask[i] = m->rgba[i * 4] + m->rgba[i * 4 + 1] + m->rgba[i * 4 + 2] > 0;
    return mask;
}

/** The scores over the whole image and, where given, over the mask. */
void printScores(const capture::Scores& full, const capture::Scores* masked, bool json) {
    if (json) {
        nlohmann::json j = {
            {"image", {{"psnr", full.psnr}, {"ssim", full.ssim}, {"pixels", full.pixels}}}};
        if (masked)
            j["mask"] = {
                {"psnr", masked->psnr}, {"ssim", masked->ssim}, {"pixels", masked->pixels}};
        std::printf("%s\n", j.dump(2).c_str());
        return;
    }
    std::printf("image: PSNR %.2f dB, SSIM %.4f over %zu pixels\n", full.psnr, full.ssim,
                full.pixels);
    if (masked)
        std::printf("mask:  PSNR %.2f dB, SSIM %.4f over %zu pixels\n", masked->psnr, masked->ssim,
                    masked->pixels);
}

int compareTwo(const Arguments& args) {
    auto a = capture::readPng(args.images[0]);
    auto b = capture::readPng(args.images[1]);
    for (const auto* image : {&a, &b})
        if (!*image)
            return failed(image->error().message);
    if (a->width != b->width || a->height != b->height)
        return failed(args.images[0] + " is " + std::to_string(a->width) + "x" +
                      std::to_string(a->height) + " but " + args.images[1] + " is " +
                      std::to_string(b->width) + "x" + std::to_string(b->height));
    std::optional<std::vector<bool>> mask;
    if (args.maskPath) {
        auto read = readMask(*args.maskPath, a->width, a->height);
        if (!read)
            return failed(read.error().message);
        mask = std::move(*read);
    }
    const capture::Scores full = capture::score(*a, *b);
    const capture::Scores masked = mask ? capture::score(*a, *b, &*mask) : capture::Scores{};
    if (args.heatmapPath)
        if (auto written = capture::writePng(*args.heatmapPath,
                                             capture::heatmap(*a, *b, 64, mask ? &*mask : nullptr));
            !written)
            return failed(written.error().message);
    printScores(full, mask ? &masked : nullptr, args.json);
    return 0;
}

} // namespace

int run(int argc, char** argv) {
    Arguments args;
    CLI::App app{"", "glass-compare"};
    tool::configure(app, kDescription, kExitStatus);
    addOptions(app, args);
    if (const auto code = tool::parseArguments(app, argc, argv))
        return *code;
    if (args.sheetPath)
        return args.images.empty() ? tool::usageError(app, "--contact-sheet needs images")
                                   : writeContactSheet(args);
    if (args.images.size() != 2)
        return tool::usageError(app, "needs exactly two images");
    return compareTwo(args);
}

int main(int argc, char** argv) {
    return tool::guardedMain("glass-compare", run, argc, argv);
}
