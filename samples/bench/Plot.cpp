// Chart drawing: pixels, lines, a 5x7 font, axes with ticks, series and a legend.
#include "Plot.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

namespace bench {
namespace {

using Color = std::array<std::uint8_t, 3>;
constexpr Color kBlack{0, 0, 0}, kGrid{225, 225, 225}, kAxis{90, 90, 90};
constexpr int kScale = 2; // font pixels per glyph pixel

/** 5x7 glyphs, one byte a row (bit 4 the leftmost column). Lowercase prints as uppercase. */
const std::map<char, std::array<std::uint8_t, 7>>& glyphs() {
    static const std::map<char, std::array<std::uint8_t, 7>> g = {
        {' ', {0, 0, 0, 0, 0, 0, 0}},
        {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
        {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
        {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
        {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
        {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
        {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
        {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
        {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
        {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
        {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
        {'A', {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
        {'B', {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}},
        {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}},
        {'D', {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C}},
        {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}},
        {'F', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}},
        {'G', {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}},
        {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
        {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}},
        {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}},
        {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}},
        {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}},
        {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}},
        {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
        {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
        {'P', {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}},
        {'Q', {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}},
        {'R', {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}},
        {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}},
        {'T', {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
        {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
        {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}},
        {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}},
        {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}},
        {'Y', {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}},
        {'Z', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}},
        {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
        {',', {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}},
        {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}},
        {'/', {0x01, 0x01, 0x02, 0x04, 0x08, 0x10, 0x10}},
        {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
        {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}},
        {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
        {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}},
        {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}},
        {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}},
        {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F}},
        {'?', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x00, 0x04}},
    };
    return g;
}

class Canvas {
public:
    Canvas(int width, int height) : mImage{width, height, {}} {
        mImage.rgba.assign(std::size_t(width) * std::size_t(height) * 4, 255);
    }
    void pixel(int x, int y, Color c) {
        if (x < 0 || y < 0 || x >= mImage.width || y >= mImage.height)
            return;
        std::uint8_t* p = &mImage.rgba[(std::size_t(y) * std::size_t(mImage.width) + std::size_t(x)) * 4];
        p[0] = c[0];
        p[1] = c[1];
        p[2] = c[2];
        p[3] = 255;
    }
    void rect(int x, int y, int w, int h, Color c) {
        for (int j = y; j < y + h; ++j)
            for (int i = x; i < x + w; ++i)
                pixel(i, j, c);
    }
    /** A line `thickness` pixels wide (square brush), by DDA. */
    void line(glm::dvec2 a, glm::dvec2 b, Color c, int thickness) {
        const int steps = std::max(1, int(std::ceil(std::max(std::abs(b.x - a.x), std::abs(b.y - a.y)))));
        for (int s = 0; s <= steps; ++s) {
            const glm::dvec2 p = a + (b - a) * (double(s) / steps);
            rect(int(std::lround(p.x)) - thickness / 2, int(std::lround(p.y)) - thickness / 2,
                 thickness, thickness, c);
        }
    }
    static int textWidth(const std::string& text) { return int(text.size()) * 6 * kScale; }
    /** Text with its top-left corner at (x, y). */
    void text(int x, int y, const std::string& text, Color c) {
        for (char ch : text) {
            const auto it = glyphs().find(char(std::toupper(static_cast<unsigned char>(ch))));
            if (it != glyphs().end())
                for (int row = 0; row < 7; ++row)
                    for (int col = 0; col < 5; ++col)
                        if (it->second[std::size_t(row)] & (0x10 >> col))
                            rect(x + col * kScale, y + row * kScale, kScale, kScale, c);
            x += 6 * kScale;
        }
    }
    capture::Image take() { return std::move(mImage); }

private:
    capture::Image mImage;
};

/** 4672 -> "4.7K", 74752 -> "75K", 1196032 -> "1.2M". */
std::string compact(double v) {
    char out[32];
    const char* suffix = "";
    if (v >= 1e6) {
        v /= 1e6;
        suffix = "M";
    } else if (v >= 1e3) {
        v /= 1e3;
        suffix = "K";
    }
    std::snprintf(out, sizeof out, v < 10.0 && *suffix ? "%.1f%s" : "%.0f%s", v, suffix);
    return out;
}

/** A tick step of 1, 2 or 5 times a power of ten giving at most about 8 ticks up to `top`. */
double tickStep(double top) {
    const double raw = top / 8.0;
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * power >= raw)
            return m * power;
    return 10.0 * power;
}

} // namespace

capture::Image drawChart(const Chart& chart, int width, int height) {
    Canvas canvas(width, height);
    const int left = 100, right = width - 30, top = 70, bottom = height - 80;
    double xMin = 1e300, xMax = -1e300, yMax = 0.0;
    std::set<double> xs;
    for (const Series& s : chart.series)
        for (const glm::dvec2& p : s.points) {
            xMin = std::min(xMin, p.x);
            xMax = std::max(xMax, p.x);
            yMax = std::max(yMax, p.y);
            xs.insert(p.x);
        }
    if (xs.empty())
        xMin = xMax = 1.0;
    auto xOf = [&](double x) {
        const double lo = chart.logX ? std::log2(xMin) - 0.3 : xMin, hi = chart.logX ? std::log2(xMax) + 0.3 : xMax;
        const double t = ((chart.logX ? std::log2(x) : x) - lo) / std::max(hi - lo, 1e-9);
        return left + t * (right - left);
    };
    const double step = tickStep(std::max(yMax, 1e-9) * 1.05);
    const double yTop = std::ceil(std::max(yMax, 1e-9) * 1.05 / step) * step;
    auto yOf = [&](double y) { return bottom - y / yTop * (bottom - top); };

    canvas.text((width - Canvas::textWidth(chart.title)) / 2, 18, chart.title, kBlack);
    for (double y = 0.0; y <= yTop + 1e-9; y += step) {
        const int py = int(std::lround(yOf(y)));
        canvas.rect(left, py, right - left, 1, kGrid);
        char label[32];
        std::snprintf(label, sizeof label, step < 1.0 ? "%.1f" : "%.0f", y);
        canvas.text(left - 10 - Canvas::textWidth(label), py - 7, label, kAxis);
    }
    for (double x : xs) {
        const int px = int(std::lround(xOf(x)));
        canvas.rect(px, top, 1, bottom - top, kGrid);
        const std::string label = compact(x);
        canvas.text(px - Canvas::textWidth(label) / 2, bottom + 10, label, kAxis);
    }
    canvas.rect(left, top, 2, bottom - top + 1, kAxis);
    canvas.rect(left, bottom, right - left, 2, kAxis);
    canvas.text((left + right - Canvas::textWidth(chart.xLabel)) / 2, bottom + 40, chart.xLabel,
                kBlack);
    canvas.text(left - 80, top - 30, chart.yLabel, kBlack);

    for (const Series& s : chart.series) {
        for (std::size_t i = 1; i < s.points.size(); ++i)
            canvas.line({xOf(s.points[i - 1].x), yOf(s.points[i - 1].y)},
                        {xOf(s.points[i].x), yOf(s.points[i].y)}, s.color, 3);
        for (const glm::dvec2& p : s.points)
            canvas.rect(int(std::lround(xOf(p.x))) - 4, int(std::lround(yOf(p.y))) - 4, 9, 9,
                        s.color);
    }
    int legendY = top + 12;
    for (const Series& s : chart.series) {
        canvas.rect(left + 16, legendY, 24, 14, s.color);
        canvas.text(left + 50, legendY, s.name, kBlack);
        legendY += 24;
    }
    return canvas.take();
}

} // namespace bench
