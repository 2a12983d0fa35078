// The CPU twin of the GPU's material model, in double precision: the environment as
// common/environment.glsl samples it, a material read as render/opaque.frag.glsl reads it, and
// shaded as common/brdf.glsl shades it (its layers and the punctual lights included), and the
// display image as render/tonemap.frag.glsl makes it. What the Embree reference shades its
// opaque surfaces and its glass's layers with.
#pragma once

#include "engine/asset/HdrImage.h"
#include "engine/scene/Light.h"
#include "engine/scene/Model.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace render {

class Environment;

/** The environment as the GPU samples it: the prefiltered equirectangular levels (level 0 is
 *  the source; roughness r reads level r * (levels - 1), trilinear, both axes wrapping), the
 *  diffuse irradiance map, rotation about +y and intensity. */
class EnvironmentSampler {
public:
    /** One level from an image (no prefiltered levels: any roughness reads level 0; irradiance
     *  unavailable, black). */
    EnvironmentSampler(const asset::HdrImage& image, float rotation, float intensity);
    /** Reads the renderer's environment textures back (needs its GL context current). */
    static EnvironmentSampler fromGpu(const Environment& environment, float rotation,
                                      float intensity);

    glm::dvec3 radiance(glm::dvec3 direction, double roughness) const;
    glm::dvec3 irradiance(glm::dvec3 normal) const;

private:
    EnvironmentSampler() = default;
    struct Level {
        int width = 0, height = 0;
        std::vector<float> rgba;
    };
    static glm::dvec3 bilinear(const Level& level, glm::dvec2 uv);
    glm::dvec3 rotate(glm::dvec3 d) const;
    std::vector<Level> mLevels;
    Level mIrradiance;
    float mRotation = 0.0f, mIntensity = 1.0f;
};

namespace cpu {

using glm::dvec2;
using glm::dvec3;
using glm::dvec4;

/** common/brdf.glsl's SurfaceMaterial: the core model's defaults, no layer. */
struct Surface {
    dvec3 baseColor{1.0};
    double metallic = 1.0, roughness = 1.0, occlusion = 1.0;
    dvec3 dielectricF0{0.04};
    double specularWeight = 1.0;
    double clearcoat = 0.0, clearcoatRoughness = 0.0;
    dvec3 clearcoatNormal{0.0, 0.0, 1.0};
    dvec3 sheenColor{0.0};
    double sheenRoughness = 0.0;
    double iridescence = 0.0, iridescenceIor = 1.3, iridescenceThickness = 0.0;
    double anisotropy = 0.0;
    dvec3 anisotropyDirection{0.0};
};

/** What reaches P (normal N, unit L toward the light) of light `light` past what lies between:
 *  1 unshadowed, 0 behind an opaque caster, the colour glass lets through. */
using LightVisibility = std::function<dvec3(std::size_t light, dvec3 P, dvec3 N, dvec3 L)>;

/** What lights a surface: the environment and the punctual lights in world space, and, where
 *  the lights cast shadows, what reaches each point of them (common/shadows.glsl's twin). */
struct Lighting {
    const EnvironmentSampler& environment;
    std::span<const scene::PlacedLight> lights;
    LightVisibility visibility = {};
};

/** A point of a mesh as the fragment shader sees it: world position, its interpolated normal
 *  and the normal-mapped one (both facing the viewer), tangent (w: handedness; zero without
 *  one) and both texture coordinate sets (TEXCOORD_0 in xy, TEXCOORD_1 in zw). */
struct Point {
    dvec3 position, interpolatedNormal, normal;
    dvec4 tangent{0.0};
    dvec4 uv{0.0};
};

/** Bilinear RGBA of a glTF image at uv with wrapping (level 0: the GPU's mip filtering of
 *  distant texels is not reproduced); colour images decoded from sRGB. */
dvec4 sampleImage(const scene::Image& image, dvec2 uv, bool srgb);
/** The image a material's texture reads, or null. */
const scene::Image* textureImage(const scene::Model& model, const scene::TextureRef& t);
/** The texture coordinates `t` reads of `uvs`, through its KHR_texture_transform. */
dvec2 textureUv(const scene::TextureRef& t, dvec4 uvs);
/** The normal texture `map` (`image`) at uv around N and the tangent, as
 *  common/normal_map.glsl perturbs it. */
dvec3 perturbNormal(const scene::TextureRef& map, const scene::Image& image, dvec3 N, dvec4 tangent,
                    dvec4 uv);

dvec2 environmentBrdf(double NoV, double roughness);
/** Reflectance of a thin film over a substrate, per channel (common/brdf.glsl). */
dvec3 thinFilmReflectance(double cosI, double film, double nm, dvec3 substrate);
/** GGX's distribution times the height-correlated Smith visibility, roughness alpha `a`. */
double ggxLobe(double NoL, double NoV, double NoH, double a);
/** A light's radiance arriving at P and the unit direction L toward it. */
dvec3 lightArriving(const scene::PlacedLight& light, dvec3 P, dvec3& L);
/** A spot's cone falloff toward -L (L: unit, toward the light), common/lighting.glsl's. */
double spotFalloff(const scene::PlacedLight& light, dvec3 L);
/** Light `i` of `lighting` arriving at P (normal N) past its shadows, as common/lighting.glsl's
 *  lightArriving. */
dvec3 lightArriving(const Lighting& lighting, std::size_t i, dvec3 P, dvec3 N, dvec3& L);

/** Material `m` of `model` at `p` as render/opaque.frag.glsl reads it (the normal map already in
 *  p.normal); its emission in `emissive`. */
Surface readSurface(const scene::Model& model, const scene::Material& m, const Point& p,
                    dvec3& emissive);
/** `under` seen through the surface's sheen and clear coat (common/brdf.glsl layersOver). */
dvec3 layersOver(dvec3 under, const Surface& s, const Lighting& lighting, dvec3 P, dvec3 N,
                 dvec3 V);
/** The light the surface sends toward V (common/brdf.glsl shadeSurface). */
dvec3 shadeSurface(const Surface& s, const Lighting& lighting, dvec3 P, dvec3 N, dvec3 V);

/** The display image (RGBA8, alpha 255) of an HDR RGBA image, exactly as
 *  render/tonemap.frag.glsl makes it: exposure, the ACES fit, sRGB. */
std::vector<std::uint8_t> tonemap(std::span<const float> rgba, float exposure);

} // namespace cpu
} // namespace render
