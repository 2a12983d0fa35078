// A line chart drawn into an RGBA image: the benchmark's frame time against triangle count, one
// line per method. Its own 5x7 bitmap font; no plotting or font library.
#pragma once

#include "engine/capture/Image.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace bench {

struct Series {
    std::string name;
    std::array<std::uint8_t, 3> color;
    std::vector<glm::dvec2> points; ///< (x, y), drawn in the order given
};

struct Chart {
    std::string title, xLabel, yLabel;
    bool logX = true; ///< x on a log2 scale (triangle counts grow 4x a level)
    std::vector<Series> series;
};

/** Draws `chart` at `width` x `height` (white background, axes with ticks and labels, one
 *  polyline with point markers per series, a legend). */
capture::Image drawChart(const Chart& chart, int width = 720, int height = 440);

} // namespace bench
