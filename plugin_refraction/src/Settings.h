// Private to the plugin: its parameters decoded into types once per frame (or per reference
// image), which the GPU passes and the reference tracer read, so that no frame compares strings.
#pragma once

#include "engine/plugin/ParameterSet.h"
#include "engine/scene/Model.h"
#include "engine/scene/World.h"

#include <glm/glm.hpp>

#include <vector>

namespace refraction {

struct Settings {
    // Each enum lists its parameter's choices in the order of parameterTable().
    enum class Method { Opaque, Sir, Isr, Dir, Trace, Hybrid };
    enum class Glass { Auto, All };
    enum class Fresnel { Exact, Schlick, Off };
    enum class Tir { Clamp, Reflect };
    enum class BackSurface { Farthest, First };
    enum class GeometryPasses { One, Two };
    enum class DispersionSearch { Shared, PerChannel };
    enum class Surfaces { Layers, TwoSurface };
    /** What hands a hybrid's pixel to the trace (hybrid-criteria: a sum of these; the shaders'
     *  HYBRID_*): a pixel, or one the walk crossed, holds more than K layers; the walk left the
     *  layers; it followed a total internal reflection the layers may not represent; it crossed
     *  a surface whose normal was filtered near an outline. */
    enum HybridCriterion : int {
        kHandOverflow = 1,
        kHandOffLayers = 2,
        kHandReflection = 4,
        kHandOutline = 8,
        kHandAll = 15
    };
    /** The walk's dispersion variant where the frame's glass has none (DISPERSION_NONE); else
     *  the dispersion search's (DISPERSION_SEARCH_*). */
    static constexpr int kNoDispersion = -1;

    Method method = Method::Dir;
    Glass glass = Glass::Auto;
    double ior = 0.0;                ///< 0: the material's
    double dispersion = -1.0;        ///< 20 / Abbe number; negative: the material's
    glm::dvec3 tint{1.0};            ///< multiplies the attenuation colour
    double absorptionDistance = 0.0; ///< 0: the material's
    Fresnel fresnel = Fresnel::Exact;
    int searchSteps = 5;
    Tir tir = Tir::Reflect;
    int tirBounces = 2;
    BackSurface backSurface = BackSurface::Farthest;
    GeometryPasses geometryPasses = GeometryPasses::One;
    DispersionSearch dispersionSearch = DispersionSearch::Shared;
    Surfaces surfaces = Surfaces::Layers;
    int layerCapacity = 4; ///< K: fragments kept per pixel by the layered capture
    int interfaces = 8;    ///< N: interfaces a layered walk crosses at most
    int marchSteps = 12;   ///< coarse samples of the layered search before the binary search
    int traceSamples = 1;  ///< trace and hybrid: rays per glass pixel
    /** Accumulating while anything moves: samples a glass pixel takes where the resolve will
     *  reject its history (FrameContext::freshSamples; DIR, the trace and the hybrid). */
    int freshSamples = 4;
    /** And where the first sample's luminance differs from its history's by this share. */
    double freshContrast = 0.3;
    int hybridCriteria = kHandAll; ///< hybrid: what hands a pixel to the trace (HybridCriterion)
    bool nearby = true;
    bool outlineAntialiasing = true; ///< the layered path's outline pass (layers_outline)
    /** The glass tints the light through it into the shadow maps (refraction.glass_shadow). */
    bool glassShadows = true;
    /** The glass focuses the light it refracts (refraction.caustic_*), with glass shadows. */
    bool caustics = true;
    int causticPhotons = 8000; ///< photons a frame over every light's glass, about
    int debug = 0; ///< index into the "debug" parameter's choices (the shaders' DEBUG_*)

    /** The plugin's parameters as data: name, label, type, range, default, choices, help. */
    static const std::vector<plugin::Parameter>& parameterTable();
    /** Reads every parameter of the refraction plugin's set (which must declare them all). */
    static Settings decode(const plugin::ParameterSet& parameters);

    /** Isr, Dir and Trace find an exit through a back surface; Sir refracts once. */
    bool twoInterfaces() const { return method != Method::Opaque && method != Method::Sir; }
    /** The layered path: every glass layer in one geometry pass (any materials, normal maps). */
    bool layered() const { return surfaces == Surfaces::Layers && method != Method::Opaque; }
    /** Isr measures d_N every frame and reads it. */
    bool usesNormalDistance() const { return method == Method::Isr; }
    /** Trace and Hybrid trace rays through the glass BVH. */
    bool traces() const { return method == Method::Trace || method == Method::Hybrid; }
    /** The walk adds several samples a pixel up: the trace's and the hybrid's. */
    bool addsSamples() const { return traces() && traceSamples > 1; }
    /** The methods that take fresh samples while a frame accumulates (freshSamples): those that
     *  trace. DIR's, walked, bought at most 0.27 dB for twice the frame and more flicker; SIR's
     *  and ISR's estimated exits change more from frame to frame than across a pixel, and their
     *  history averages that (ISR lost 1.3 dB with them on the two figures, SIR gained nothing:
     *  docs/accuracy.md). */
    bool freshSampled() const { return traces(); }
    /** The layers' outline pass runs: on, and the glass one sample a pixel (the trace's
     *  samples anti-alias its outlines themselves; the pass over them cost 0.5 dB). */
    bool outlinePass() const {
        return layered() && outlineAntialiasing && !(method == Method::Trace && traceSamples > 1);
    }
    /** Isr (its d_N) and the tracing methods need the glass BVH. */
    /** The lights' caustics are focused: on, with glass shadows. */
    bool focusesCaustics() const { return glassShadows && caustics; }
    bool usesGlassBvh() const { return method == Method::Isr || traces(); }
    /** Whether a primitive drawn with `material` (of `model`; -1 the default, as its
     *  character's variant picks it) in glass mode `mode` renders as glass: never with Opaque
     *  or GlassMode::None, always with GlassMode::All; with GlassMode::Auto every mesh under
     *  Glass::All, else materials with KHR_materials_transmission. */
    bool isGlass(const scene::Model& model, int material,
                 scene::GlassMode mode = scene::GlassMode::Auto) const;
};

} // namespace refraction
