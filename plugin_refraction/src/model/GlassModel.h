// Private to the plugin: the optical model of glass (docs/methods.md, "The optical model") in
// C++, as the Embree reference traces it: the twin of optics.glsl, which the walk and the trace
// share on the GPU (as the engine keeps render/CpuShading beside common/brdf.glsl). One function
// per rule: the reflectance of an interface, the media a path is in, the crossing of an
// interface, the microfacet normals of rough glass.
#pragma once

#include "Optics.h"
#include "Settings.h"

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace refraction::model {

using glm::dvec3;

/** Entries of a path's media stack (optics.glsl's four bytes): a fifth nested glass is not
 *  entered, its crossings pass straight. */
inline constexpr int kMaxMedia = 4;
/** A path splits into its reflection and its refraction at an interface into glass while it
 *  has split less than this many times and the reflection carries at least kSplitWeight of
 *  the light; past that, the reflection sees the environment (deterministic) or one branch is
 *  chosen by Fresnel (sampled). */
inline constexpr int kSplitDepth = 2;
inline constexpr double kSplitWeight = 0.01;
/** The sampled reference, the ground truth, splits at every interface into glass this many
 *  times, however little the reflection carries, before it chooses by chance: any depth
 *  converges to the same light, a deeper one with less noise at a given number of samples. */
inline constexpr int kSampledSplitDepth = 3;
/** Roughness up to this is smooth where paths are sampled: no microfacet is picked. GGX's lobe
 *  at 0.05 (alpha 0.0025) is a few tenths of a degree wide, finer than a pixel resolves, yet
 *  sampling it made the figures' glass (roughness 0.04) noisy where rays reflect totally many
 *  times over: the two glass figures' 64 samples scored 35.14 dB against the reference, 35.43
 *  with it smooth. Lookups still blur by it where they blur. */
inline constexpr double kSmooth = 0.05;
/** A photon of the caustics (docs/materials.md, "Caustics") follows its refracted path only,
 *  totally reflected where it must, across at most this many surfaces: one still in glass
 *  after them is dropped. */
inline constexpr int kMaxPhotonCrossings = 16;

/** A glass surface at one point: its material's factors times its textures there (forced
 *  glass: base colour only, clear and not metallic). */
struct GlassSurface {
    dvec3 baseColor{1.0};
    double transmission = 1.0, roughness = 0.0, metallic = 0.0;
};

/** Unpolarised dielectric reflectance by `mode` at cosI (> 0) for eta = n_incident /
 *  n_transmitted: 1 past the critical angle. */
double fresnel(Settings::Fresnel mode, double cosI, double eta);
/** Refracts unit `i` at a surface whose unit normal `n` faces against it; false under total
 *  internal reflection. */
bool refract(const dvec3& i, const dvec3& n, double eta, dvec3& t);
/** The reflectance of an interface of glass `o` (its surface `s` there) in channel `c`, from
 *  a medium of index n1 into one of n2 (n1 / n2 = eta), at cosI: the Fresnel mode's, its F0
 *  coloured and weighted by KHR_materials_specular (the rise toward grazing kept), through
 *  the iridescent film, toward the base colour by metallic. */
double reflectance(Settings::Fresnel mode, const Optics& o, const GlassSurface& s, double cosI,
                   double eta, int c);

/** The media around a path: the glasses it entered (newest on top) with the solid (character)
 *  of each. Crossing a surface against its outward normal enters its glass; crossing one along
 *  it leaves the most recent entry of the same solid, if any. */
class Media {
public:
    /** The glass the path is in (null: air). */
    const Optics* top() const { return mCount ? mGlass[std::size_t(mCount - 1)] : nullptr; }
    bool contains(int solid) const;
    void enter(const Optics* glass, int solid);
    void leave(int solid);

private:
    std::array<const Optics*, kMaxMedia> mGlass{};
    std::array<int, kMaxMedia> mSolid{};
    int mCount = 0;
};

/** One path through the glass in one channel: where it is, where it goes, the light it carries
 *  and what it is in. */
struct Path {
    dvec3 origin{0.0}, dir{0.0};
    double weight = 1.0;
    Media media;
    double ior = 1.0, sigma = 0.0; ///< the medium's index and absorption (air: 1, 0)
    double roughness = 0.0;        ///< the roughest interface crossed (a lookup's blur)
    int interfaces = 0;            ///< interfaces crossed or reflected at after the entry
    int crossings = 0;             ///< surfaces crossed in all (passes included)
    int splits = 0;                ///< times it split (kSplitDepth)
};

/** What crossing a surface did to a path. */
enum class Crossed {
    Passed,    ///< the index did not change (overlapping parts of one solid): straight on
    Refracted, ///< into the new medium; `reflected` the share an interface into glass reflects
    Reflected  ///< totally internally reflected, still in its medium
};

/** The glass whose surface a path meets: its optics, solid and surface there, and whether the
 *  path enters it (against the outward face). */
struct SurfaceMet {
    const Optics* optics = nullptr;
    int solid = 0;
    GlassSurface surface;
    bool enters = true;
};

/** Crosses the surface `met` at the path's origin with facet normal `m` (the shading normal,
 *  or a sampled microfacet's) in channel `c`: the media change, and where the index changes,
 *  refraction (or total internal reflection) about m; a path entering a solid it is not in
 *  takes its surface's tint (base colour x transmission x (1 - metallic)) as well as 1 - F
 *  at an interface into glass, F then the share `reflected` (the caller's to follow or look up
 *  along reflect(dir, m)). Absorption along the segment before is the caller's. */
Crossed crossInterface(Path& path, const SurfaceMet& met, dvec3 m, int c, Settings::Fresnel mode,
                       double& reflected);

/** Two unit vectors that make a right-handed frame (tx, ty, n) with unit `n`: the frame
 *  microfacets are sampled in, and the reference's photons are spread in about their axis. */
std::pair<dvec3, dvec3> tangentFrame(const dvec3& n);

/** A GGX microfacet normal around `n` (roughness `roughness`, alpha = roughness^2) as the
 *  view `i` (toward the viewer, on n's side) sees them, from two uniform numbers: the
 *  distribution of visible normals (Heitz 2018), pdf G1(i, m) |i.m| D(m) / |i.n|. */
dvec3 sampleMicrofacet(const dvec3& n, double roughness, const dvec3& i, double u1, double u2);
/** The weight of a path scattered to `o` about a facet `m` so sampled, Fresnel aside: the
 *  microfacet BSDF (Walter et al. 2007, Eq. 20-21, separable Smith G) over the pdf and the
 *  Jacobian, G1(o, m); 0 where o leaves on the wrong side of the macro surface. */
double microfacetWeight(const dvec3& o, const dvec3& m, const dvec3& n, double roughness,
                        bool transmitted);

/** Small deterministic random numbers (a PCG hash of a state that advances). */
double random01(std::uint32_t& state);

} // namespace refraction::model
