// PSNR, SSIM and heatmaps.
#include "engine/capture/Metrics.h"

#include "engine/core/Check.h"

#include <algorithm>
#include <cmath>

namespace capture {
namespace {

std::vector<double> luminance(const Image& image) {
    std::vector<double> y(std::size_t(image.width) * std::size_t(image.height));
    for (std::size_t i = 0; i < y.size(); ++i)
        y[i] = 0.2126 * image.rgba[i * 4] + 0.7152 * image.rgba[i * 4 + 1] +
               0.0722 * image.rgba[i * 4 + 2];
    return y;
}

} // namespace

Scores score(const Image& a, const Image& b, const std::vector<bool>* mask) {
    ENGINE_CHECK(a.width == b.width && a.height == b.height,
                 "score() of images of different sizes");
    const std::size_t n = std::size_t(a.width) * std::size_t(a.height);
    ENGINE_CHECK(!mask || mask->size() == n, "mask size differs from the image");
    Scores s;
    double squared = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        if (mask && !(*mask)[i])
            continue;
        ++s.pixels;
        for (int c = 0; c < 3; ++c) {
            const double d =
                double(a.rgba[i * 4 + std::size_t(c)]) - double(b.rgba[i * 4 + std::size_t(c)]);
            squared += d * d;
        }
    }
    if (s.pixels == 0)
        return s;
    const double mse = squared / double(s.pixels * 3);
    s.psnr = mse > 0.0 ? std::min(99.0, 10.0 * std::log10(255.0 * 255.0 / mse)) : 99.0;

    // SSIM (Wang et al. 2004) on luminance with 8x8 windows, constants for 8-bit data.
    const std::vector<double> ya = luminance(a), yb = luminance(b);
    const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
    double sum = 0.0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(a.width) + std::size_t(x);
            if (mask && !(*mask)[i])
                continue;
            double ma = 0, mb = 0, vaa = 0, vbb = 0, vab = 0;
            int count = 0;
            for (int dy = -4; dy < 4; ++dy)
                for (int dx = -4; dx < 4; ++dx) {
                    const int xx = std::clamp(x + dx, 0, a.width - 1),
                              yy = std::clamp(y + dy, 0, a.height - 1);
                    const std::size_t j = std::size_t(yy) * std::size_t(a.width) + std::size_t(xx);
                    ma += ya[j];
                    mb += yb[j];
                    vaa += ya[j] * ya[j];
                    vbb += yb[j] * yb[j];
                    vab += ya[j] * yb[j];
                    ++count;
                }
            ma /= count;
            mb /= count;
            vaa = vaa / count - ma * ma;
            vbb = vbb / count - mb * mb;
            vab = vab / count - ma * mb;
            sum += ((2 * ma * mb + c1) * (2 * vab + c2)) /
                   ((ma * ma + mb * mb + c1) * (vaa + vbb + c2));
        }
    s.ssim = sum / double(s.pixels);
    return s;
}

Image heatmap(const Image& a, const Image& b, int fullScale, const std::vector<bool>* mask) {
    ENGINE_CHECK(a.width == b.width && a.height == b.height,
                 "heatmap() of images of different sizes");
    Image out{a.width, a.height, std::vector<std::uint8_t>(a.rgba.size())};
    for (std::size_t i = 0; i < a.rgba.size() / 4; ++i) {
        int worst = 0;
        for (int c = 0; c < 3; ++c)
            worst = std::max(worst, std::abs(int(a.rgba[i * 4 + std::size_t(c)]) -
                                             int(b.rgba[i * 4 + std::size_t(c)])));
        const double t = std::min(1.0, double(worst) / double(fullScale));
        // black -> blue -> yellow -> red
        double r, g, bl;
        if (t < 1.0 / 3.0) {
            r = 0;
            g = 0;
            bl = 3 * t;
        } else if (t < 2.0 / 3.0) {
            const double u = 3 * t - 1;
            r = u;
            g = u;
            bl = 1 - u;
        } else {
            const double u = 3 * t - 2;
            r = 1;
            g = 1 - u;
            bl = 0;
        }
        const double dim = mask && !(*mask)[i] ? 0.25 : 1.0;
        out.rgba[i * 4] = std::uint8_t(255 * r * dim);
        out.rgba[i * 4 + 1] = std::uint8_t(255 * g * dim);
        out.rgba[i * 4 + 2] = std::uint8_t(255 * bl * dim);
        out.rgba[i * 4 + 3] = 255;
    }
    return out;
}

Flicker flicker(const Image& method0, const Image& method1, const Image& reference0,
                const Image& reference1, const std::vector<bool>& mask) {
    Flicker f;
    double sum = 0.0;
    for (std::size_t p = 0; p < mask.size() && p * 4 + 3 < method0.rgba.size(); ++p) {
        if (!mask[p])
            continue;
        for (std::size_t c = 0; c < 3; ++c) {
            const std::size_t i = p * 4 + c;
            const int method = int(method1.rgba[i]) - int(method0.rgba[i]);
            const int reference = int(reference1.rgba[i]) - int(reference0.rgba[i]);
            sum += std::abs(method - reference);
        }
        ++f.pixels;
    }
    f.meanAbsDifference = f.pixels ? sum / double(3 * f.pixels) : 0.0;
    return f;
}

} // namespace capture
