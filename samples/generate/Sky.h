// The project's default environment: a procedural sky with a sun, a coloured skyline at the
// horizon and a tiled floor below it, so that refraction through glass reads clearly.
#pragma once

#include "engine/asset/HdrImage.h"

namespace generate {

/** An equirectangular image `width` x width/2 (linear RGB). Deterministic. */
asset::HdrImage buildSky(int width = 1024);

} // namespace generate
