// The plugin's parameters as data, and their decoding into Settings.
#include "Settings.h"

namespace refraction {

using Type = plugin::Parameter::Type;

// Each Enum's choices in the order of its Settings enum, which decode() reads by index.
const std::vector<plugin::Parameter>& Settings::parameterTable() {
    static const std::vector<plugin::Parameter> kTable = {
        {.name = "method",
         .label = "Method",
         .type = Type::Enum,
         .defaultValue = 3,
         .choices = {"opaque", "sir", "isr", "dir", "trace", "hybrid"},
         .help = "opaque: no glass; sir: one interface; isr: Wyman's estimate with per-frame d_N; "
                 "dir: depth-map search, no preprocessing; trace: the refracted path traced "
                 "through the glass BVH from the first layer; hybrid: dir, and the trace for the "
                 "pixels the layers may not represent (hybrid-criteria)"},
        {.name = "glass",
         .label = "Glass",
         .type = Type::Enum,
         .choices = {"auto", "all"},
         .help = "auto: materials with transmission; all: every mesh"},
        {.name = "ior",
         .label = "IOR",
         .max = 4.0,
         .help = "index of refraction; 0: the material's"},
        {.name = "dispersion",
         .label = "Dispersion",
         .min = -1.0,
         .max = 10.0,
         .defaultValue = -1.0,
         .help = "20 / Abbe number (KHR_materials_dispersion); -1: the material's"},
        {.name = "dispersion-search",
         .label = "Dispersion search",
         .type = Type::Enum,
         .choices = {"shared", "per-channel"},
         .help = "shared: one exit search, red and blue bent from green's exit point by their own "
                 "indices; per-channel: red, green and blue each search their exit (three "
                 "searches and lookups)"},
        {.name = "tint",
         .label = "Tint",
         .type = Type::Color,
         .defaultValue = 1.0,
         .help = "multiplies the attenuation colour"},
        {.name = "absorption-distance",
         .label = "Absorption distance",
         .max = 1e6,
         .help = "distance at which light takes the attenuation colour; 0: the material's"},
        {.name = "fresnel",
         .label = "Fresnel",
         .type = Type::Enum,
         .choices = {"exact", "schlick", "off"}},
        {.name = "search-steps",
         .label = "Search steps",
         .type = Type::Int,
         .min = 1,
         .max = 16,
         .defaultValue = 5,
         .help = "DIR conservative binary search steps"},
        {.name = "tir",
         .label = "TIR",
         .type = Type::Enum,
         .defaultValue = 1,
         .choices = {"clamp", "reflect"},
         .help = "reflect (default): bounce inside and search again, as light does; clamp: exit "
                 "tangent (the papers)"},
        {.name = "tir-bounces",
         .label = "TIR bounces",
         .type = Type::Int,
         .min = 1,
         .max = 8,
         .defaultValue = 2,
         .help = "reflections followed with tir=reflect"},
        {.name = "back-surface",
         .label = "Back surface",
         .type = Type::Enum,
         .choices = {"farthest", "first"},
         .help = "which back face the depth map keeps (ISR paper §3.2)"},
        {.name = "surfaces",
         .label = "Surfaces",
         .type = Type::Enum,
         .choices = {"layers", "two-surface"},
         .help = "layers: every glass surface a ray crosses (up to layer-capacity per pixel), "
                 "captured in one geometry pass whatever the materials, and walked interface by "
                 "interface; two-surface: the papers' nearest front and one back surface"},
        {.name = "layer-capacity",
         .label = "Layers per pixel (K)",
         .type = Type::Int,
         .min = 1,
         .max = 8,
         .defaultValue = 4,
         .help = "glass fragments kept per pixel; a pixel with more keeps its nearest front and "
                 "farthest back (debug view overflow)"},
        {.name = "interfaces",
         .label = "Interfaces (N)",
         .type = Type::Int,
         .min = 1,
         .max = 32,
         .defaultValue = 8,
         .help = "interfaces a layered ray crosses at most, the entry included"},
        {.name = "march-steps",
         .label = "March steps",
         .type = Type::Int,
         .min = 1,
         .max = 64,
         .defaultValue = 12,
         .help = "layered search: coarse samples along the ray before search-steps halvings"},
        {.name = "geometry-passes",
         .label = "Geometry passes",
         .type = Type::Enum,
         .choices = {"one", "two"},
         .help = "how surfaces=two-surface captures its pair: one pass (MAX blending; a single "
                 "glass material without a normal map and back-surface=farthest, else two), or "
                 "the papers' back-face pass then front-face pass; layers always draw once"},
        {.name = "trace-samples",
         .label = "Trace samples",
         .type = Type::Int,
         .min = 1,
         .max = 64,
         .defaultValue = 1,
         .help = "trace and hybrid: rays per glass pixel, the first at its centre, the others "
                 "jittered (the hybrid's walk enters each where the layers around it place the "
                 "surface); one a frame where the frame accumulates, whose frames are the "
                 "samples"},
        {.name = "fresh-samples",
         .label = "Samples without history",
         .type = Type::Int,
         .min = 1,
         .max = 16,
         .defaultValue = 4,
         .help = "trace and hybrid, a frame that accumulates while anything moves: samples a "
                 "glass pixel takes where its history will be rejected (a surface it did not "
                 "show, a jump in its path's exit), the first jittered with the frame, the "
                 "others over the pixel; 1: one, as every other pixel"},
        {.name = "fresh-contrast",
         .label = "Fresh where the history differs",
         .min = 0.0,
         .max = 1.0,
         .defaultValue = 0.3,
         .help = "with fresh-samples: also where the first sample's luminance differs from the "
                 "history's by more than this share of the brighter; 0: only where the history "
                 "will be rejected"},
        {.name = "hybrid-criteria",
         .label = "Hybrid criteria",
         .type = Type::Int,
         .min = 1,
         .max = kHandAll,
         .defaultValue = kHandAll,
         .help = "hybrid: what hands a pixel to the trace, a sum of 1 more than K layers, 2 the "
                 "walk left the layers, 4 a total internal reflection it followed, 8 a crossing "
                 "near an outline"},
        {.name = "nearby",
         .label = "Nearby scene",
         .type = Type::Bool,
         .defaultValue = 1,
         .help = "exit rays see the opaque scene on screen before the environment"},
        {.name = "outline-aa",
         .label = "Outline anti-aliasing",
         .type = Type::Bool,
         .defaultValue = 1,
         .help = "layers: the outlines of smooth glass share each pixel with what is behind"},
        {.name = "glass-shadows",
         .label = "Glass shadows",
         .type = Type::Bool,
         .defaultValue = 1,
         .help = "the glass tints the light it lets through to what it shadows (Fresnel, tint, "
                 "transmission, absorption); off: it casts no shadow"},
        {.name = "caustics",
         .label = "Caustics",
         .type = Type::Bool,
         .defaultValue = 1,
         .help = "with glass shadows: the light the glass refracts lands where its path through "
                 "the glass takes it, focused or spread (photons from the lights); off: the "
                 "light through the glass goes straight"},
        {.name = "caustic-photons",
         .label = "Caustic photons (k)",
         .type = Type::Int,
         .min = 1,
         .max = 4096,
         .defaultValue = 8,
         .help = "thousands of photons a frame over all the lights' glass (more: finer and "
                 "smoother caustics, slower)"},
        {.name = "debug",
         .label = "Debug view",
         .type = Type::Enum,
         .choices = {"none", "back-depth", "back-normal", "dv", "dn", "exit-uv", "steps", "tir",
                     "exit-point", "exit-direction", "layer-count", "overflow", "hybrid"},
         .help = "hybrid: the pixels traced for overflow red, leaving the layers yellow, TIR blue, "
                 "an outline green"},
    };
    return kTable;
}

Settings Settings::decode(const plugin::ParameterSet& p) {
    auto index = [&](const char* name) { return int(p.number(name)); };
    Settings s;
    s.method = Method(index("method"));
    s.glass = Glass(index("glass"));
    s.ior = p.number("ior");
    s.dispersion = p.number("dispersion");
    const auto tint = p.color("tint");
    s.tint = {tint[0], tint[1], tint[2]};
    s.absorptionDistance = p.number("absorption-distance");
    s.fresnel = Fresnel(index("fresnel"));
    s.searchSteps = index("search-steps");
    s.tir = Tir(index("tir"));
    s.tirBounces = index("tir-bounces");
    s.backSurface = BackSurface(index("back-surface"));
    s.geometryPasses = GeometryPasses(index("geometry-passes"));
    s.dispersionSearch = DispersionSearch(index("dispersion-search"));
    s.surfaces = Surfaces(index("surfaces"));
    s.layerCapacity = index("layer-capacity");
    s.interfaces = index("interfaces");
    s.marchSteps = index("march-steps");
    s.traceSamples = index("trace-samples");
    s.freshSamples = index("fresh-samples");
    s.freshContrast = p.number("fresh-contrast");
    s.hybridCriteria = index("hybrid-criteria");
    s.nearby = p.flag("nearby");
    s.outlineAntialiasing = p.flag("outline-aa");
    s.glassShadows = p.flag("glass-shadows");
    s.caustics = p.flag("caustics");
    s.causticPhotons = int(p.number("caustic-photons")) * 1000;
    s.debug = index("debug");
    return s;
}

bool Settings::isGlass(const scene::Model& model, int material, scene::GlassMode mode) const {
    if (method == Method::Opaque || mode == scene::GlassMode::None)
        return false;
    if (glass == Glass::All || mode == scene::GlassMode::All)
        return true;
    return material >= 0 && model.materials[std::size_t(material)].isTransmissive();
}

} // namespace refraction
