// The ground truth every method is scored against: Embree traces the same deformed triangles
// (CPU reference deformation), the same interpolated shading normals and normal maps, the same
// camera and the same environment lookup as the GPU, with real refraction and total internal
// reflection.
#pragma once

#include "engine/anim/Pose.h"
#include "engine/asset/HdrImage.h"
#include "engine/core/Result.h"
#include "engine/plugin/ParameterSet.h"
#include "engine/render/Camera.h"
#include "engine/render/CpuShading.h"
#include "engine/render/FrameInfo.h"
#include "engine/scene/Model.h"
#include "engine/scene/World.h"

#include <vector>

namespace refraction {

/** The environment as the GPU samples it (the engine's CPU twin of its shading). */
using EnvironmentSampler = render::EnvironmentSampler;

struct ReferenceOptions {
    int samplesPerPixel = 16; ///< jittered in a stratified grid when a square
    /** One ray through each pixel's centre, as the GPU rasterises (samplesPerPixel unused):
     *  the two then see the same point of every surface, outlines included. */
    bool pixelCentres = false;
    /** The deterministic evaluation (docs/methods.md, "The optical model"), for checks of
     *  exactness: one ray through each pixel's centre; every reflection into glass followed
     *  as a branch while the path has splits left and it carries enough light, else looked up
     *  in its direction (no choice by chance); rough surfaces by their normals, the lookups
     *  blurred by the roughest interface crossed; a path ends as the GPU trace's does, after
     *  the `interfaces` parameter's interfaces, seeing the ground or the environment along it.
     *  The trace at one sample a pixel runs the same model. */
    bool deterministic = false;
    /** OpenSubdiv level the characters are refined to, as Renderer::setSubdivisionLevel
     *  refines them (0: the files' triangles). */
    int subdivision = 0;
    /** Interfaces a path crosses or reflects at after the entry before it is given up (black,
     *  counted as trapped when in glass); paths whose throughput falls under 1e-4 end first. */
    int maxBounces = 1024;
    /** Follow only the entry and one exit (no further surfaces after leaving the glass): the
     *  closed-form two-interface model, for checking the tracer itself. */
    bool twoInterfaces = false;
    /** The caustics (with the plugin's caustics and glass shadows, and shadows on): photons
     *  sent toward the glass from each casting light, and the radius their density is
     *  estimated over around a receiver (0: a twentieth of the glass's bounding radius). The
     *  estimate's noise falls as 1 / sqrt(photons in the radius), its blur grows with the
     *  radius (docs/materials.md, "Caustics"). */
    int photons = 1 << 18;
    double causticRadius = 0.0;
    unsigned threads = 0;  ///< 0: all cores
    bool progress = false; ///< a progress bar on stderr
};

struct ReferenceImage {
    glm::ivec2 size{0};
    std::vector<float> rgba;        ///< HDR, rows top to bottom; alpha: glass coverage (0..1)
    std::size_t trappedSamples = 0; ///< paths still in glass after maxBounces interfaces (black)
    /** Pixels whose primary ray (the pixel centre's first sample) first meets glass, by how many
     *  glass surfaces its straight line crosses before an opaque surface or the sky ([n]: n
     *  surfaces, 64 at most): what the layered capture must hold per pixel. */
    std::vector<std::size_t> surfaceHistogram;
};

/** Traces every character of `world` at scene time `time` (each deformed by the CPU reference
 *  in its clip's pose and placed by its transform) like the GPU frame of `settings` (size,
 *  ground plane) lit by `environment`, with the glass configured by `glass` (the refraction
 *  plugin's parameters: ior, dispersion, tint, absorption, Fresnel, glass auto|all) and each
 *  character's glass mode and overrides. Shading matches the GPU's: Fresnel-weighted
 *  environment reflection at the first entry, transmission tinted by the base colour of each
 *  glass entered, Beer-Lambert over every in-glass segment with its glass's attenuation,
 *  per-channel paths with dispersion. Every interface is followed with the media on both sides
 *  (a stack of entered solids, each character one solid: glass in glass, overlapping
 *  characters); interfaces into glass choose reflection or refraction by Fresnel, a ray
 *  leaving glass for air refracts unless totally reflected. Opaque primitives and the
 *  ground plane are traced and shaded like the GPU's opaque pass (metallic-roughness with the
 *  split-sum environment lighting; base colour, metallic-roughness and emissive textures at
 *  level 0; no occlusion maps), so exit rays meet the real nearby scene. Normal maps (level 0)
 *  perturb the normals of glass and opaque surfaces alike, as on the GPU. */
core::Result<ReferenceImage>
traceReference(const scene::World& world, double time, const render::Camera& camera,
               const EnvironmentSampler& environment, const render::RenderSettings& settings,
               const render::GroundPlane& ground, const plugin::ParameterSet& glass,
               const ReferenceOptions& options);

} // namespace refraction
