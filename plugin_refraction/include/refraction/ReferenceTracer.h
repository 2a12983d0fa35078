// The ground truth every method is scored against: Embree traces the same deformed triangles
// (CPU reference deformation), the same interpolated shading normals, the same camera and the
// same environment lookup as the GPU, with real refraction and total internal reflection.
#pragma once

#include "engine/anim/Pose.h"
#include "engine/asset/HdrImage.h"
#include "engine/core/Result.h"
#include "engine/plugin/ParameterSet.h"
#include "engine/render/Camera.h"
#include "engine/render/FrameInfo.h"
#include "engine/scene/Model.h"

#include <vector>

namespace refraction {

struct ReferenceOptions {
    int samplesPerPixel = 16; ///< jittered in a stratified grid when a square
    int maxBounces = 8;       ///< total internal reflections followed inside the glass
    /** Follow only the entry and one exit (no further surfaces after leaving the glass): the
     *  closed-form two-interface model, for checking the tracer itself. */
    bool twoInterfaces = false;
    unsigned threads = 0;     ///< 0: all cores
    bool progress = false;    ///< a progress bar on stderr
};

struct ReferenceImage {
    glm::ivec2 size{0};
    std::vector<float> rgba;         ///< HDR, rows top to bottom; alpha: glass coverage (0..1)
    std::size_t trappedSamples = 0;  ///< paths still inside after maxBounces reflections (black)
};

/** Traces `model` in `pose` like the GPU frame of `settings` (size, environment rotation and
 *  intensity) with the glass configured by `glass` (the refraction plugin's parameters:
 *  ior, dispersion, tint, absorption, Fresnel at the entry, glass auto|all). Shading matches the
 *  GPU's: Fresnel-weighted environment reflection at the first entry, transmission tinted by the
 *  base colour, Beer-Lambert over the in-glass path, per-channel paths with dispersion; later
 *  entries into glass choose reflection or refraction by Fresnel. Fails on scene content it does
 *  not trace (opaque primitives, the ground plane), naming it. */
core::Result<ReferenceImage> traceReference(const scene::Model& model, const anim::Pose& pose,
                                            const render::Camera& camera, const asset::HdrImage& environment,
                                            const render::RenderSettings& settings,
                                            const plugin::ParameterSet& glass, const ReferenceOptions& options);

/** The environment radiance along world direction `d` exactly as the GPU samples it at mip
 *  level 0 (equirectangular, bilinear, u wrapping, rotation about +y, intensity). */
glm::dvec3 sampleEnvironment(const asset::HdrImage& image, float rotation, float intensity, glm::dvec3 d);

/** The display image of an HDR image, exactly as render/tonemap.frag.glsl makes it. */
std::vector<std::uint8_t> tonemap(const std::vector<float>& rgba, float exposure);

} // namespace refraction
