// Image error metrics over display images: PSNR and SSIM, optionally over a mask, and an
// error heatmap.
#pragma once

#include "engine/capture/Image.h"

#include <optional>
#include <vector>

namespace capture {

struct Scores {
    double psnr = 0.0;      ///< dB over RGB; +inf for identical images (reported as 99)
    double ssim = 0.0;      ///< mean SSIM of luminance, 8x8 windows centred on each pixel
    std::size_t pixels = 0; ///< pixels scored
};

/** Scores `a` against `b` (same size) over every pixel, or over the pixels where `mask` is
 *  true (mask.size() == width * height). */
Scores score(const Image& a, const Image& b, const std::vector<bool>* mask = nullptr);

/** Temporal stability of a method between two consecutive frames: the mean over the pixels where
 *  `mask` is true and over RGB of |(method1 - method0) - (reference1 - reference0)|, in 1/255
 *  (0: the method changes from frame to frame exactly as the reference does; flicker the
 *  reference does not have adds to it). All four images the same size. */
struct Flicker {
    double meanAbsDifference = 0.0;
    std::size_t pixels = 0;
};
Flicker flicker(const Image& method0, const Image& method1, const Image& reference0,
                const Image& reference1, const std::vector<bool>& mask);

/** Per-pixel absolute error (max over RGB) as a colour ramp: black (0) -> blue -> yellow -> red
 *  (>= `fullScale` in 1/255); pixels outside `mask` dimmed. */
Image heatmap(const Image& a, const Image& b, int fullScale = 64,
              const std::vector<bool>* mask = nullptr);

} // namespace capture
