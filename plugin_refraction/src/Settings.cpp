// Decoding the plugin's parameters into Settings.
#include "Settings.h"

#include "engine/core/Check.h"

#include <initializer_list>
#include <string>

namespace refraction {
namespace {

/** The enum value of an Enum parameter's choice, by its position in `names`. */
template <class E>
E choose(const plugin::ParameterSet& p, const char* parameter,
         std::initializer_list<const char*> names) {
    const std::string& chosen = p.choice(parameter);
    int index = 0;
    for (const char* name : names) {
        if (chosen == name)
            return E(index);
        ++index;
    }
    ENGINE_CHECK(false,
                 std::string("refraction settings do not know ") + parameter + " '" + chosen + "'");
    return E(0);
}

} // namespace

Settings Settings::decode(const plugin::ParameterSet& p) {
    Settings s;
    s.method = choose<Method>(p, "method", {"opaque", "sir", "isr", "dir"});
    s.glass = choose<Glass>(p, "glass", {"auto", "all"});
    s.ior = p.number("ior");
    s.dispersion = p.number("dispersion");
    const auto tint = p.color("tint");
    s.tint = {tint[0], tint[1], tint[2]};
    s.absorptionDistance = p.number("absorption-distance");
    s.fresnel = choose<Fresnel>(p, "fresnel", {"exact", "schlick", "off"});
    s.searchSteps = int(p.number("search-steps"));
    s.tir = choose<Tir>(p, "tir", {"clamp", "reflect"});
    s.tirBounces = int(p.number("tir-bounces"));
    s.backSurface = choose<BackSurface>(p, "back-surface", {"farthest", "first"});
    s.geometryPasses = choose<GeometryPasses>(p, "geometry-passes", {"one", "two"});
    s.dispersionSearch =
        choose<DispersionSearch>(p, "dispersion-search", {"shared", "per-channel"});
    s.surfaces = choose<Surfaces>(p, "surfaces", {"layers", "two-surface"});
    s.layerCapacity = int(p.number("layer-capacity"));
    s.interfaces = int(p.number("interfaces"));
    s.marchSteps = int(p.number("march-steps"));
    s.nearby = p.flag("nearby");
    s.outlineAntialiasing = p.flag("outline-aa");
    s.debug = int(p.number("debug"));
    return s;
}

bool Settings::isGlass(const scene::Model& model, const scene::Primitive& primitive,
                       scene::GlassMode mode) const {
    if (method == Method::Opaque || mode == scene::GlassMode::None)
        return false;
    if (glass == Glass::All || mode == scene::GlassMode::All)
        return true;
    return primitive.material >= 0 &&
           model.materials[std::size_t(primitive.material)].isTransmissive();
}

} // namespace refraction
