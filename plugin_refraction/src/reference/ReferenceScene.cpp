// The reference's scene: the characters deformed on the CPU, refined by OpenSubdiv as the GPU
// refines them, placed in world space.
#include "ReferenceScene.h"

#include "engine/anim/Pose.h"
#include "engine/deform/CpuDeformer.h"
#include "engine/deform/Subdivision.h"
#include "engine/render/CpuShading.h"

#include <string>

namespace refraction::reference {

core::Result<std::vector<Surface>> worldSurfaces(const scene::World& world, double time,
                                                 const Settings& decoded, int subdivision) {
    std::vector<Surface> surfaces;
    for (std::size_t solid = 0; solid < world.characters.size(); ++solid) {
        const scene::Character& character = world.characters[solid];
        const scene::Model& model = *character.model;
        const double extent = glassExtent(restSides(model), character);
        // Its materials as its pose at `time` shows them (KHR_animation_pointer factors).
        anim::Pose pose = anim::evaluate(model, character.performance, time);
        const auto animated =
            pose.materials.empty()
                ? nullptr
                : std::make_shared<const std::vector<scene::Material>>(std::move(pose.materials));
        for (const auto& instance : deform::deformCharacter(character, time)) {
            const scene::Mesh& mesh = model.meshes[std::size_t(instance.mesh)];
            for (std::size_t p = 0; p < instance.primitives.size(); ++p) {
                const scene::Primitive& source = mesh.primitives[p];
                deform::DeformedPrimitive deformed = instance.primitives[p];
                const scene::Primitive* primitive = &source;
                deform::Subdivision refined;
                if (subdivision > 0) {
                    auto built = deform::buildSubdivision(source, subdivision,
                                                          "mesh " + std::to_string(instance.mesh) +
                                                              " primitive " + std::to_string(p));
                    if (!built)
                        return built.error();
                    refined = std::move(*built);
                    const deform::RefinedSurface surface =
                        deform::refineCage(refined, deformed.positions, deformed.tangents);
                    deformed = {surface.positions, surface.normals, surface.tangents};
                    primitive = &refined.rest;
                }
                const auto placed = deform::toWorld(deformed, instance.meshToWorld);
                Surface s;
                s.positions = placed.positions;
                s.normals = placed.normals;
                s.indices = primitive->indices;
                if (!primitive->uv0.empty() || !primitive->uv1.empty())
                    for (std::size_t v = 0; v < primitive->vertexCount(); ++v)
                        s.uv.emplace_back(primitive->uvs(v));
                const int material = source.materialFor(character.variant);
                s.animated = animated;
                s.material = material < 0 ? nullptr
                             : animated   ? &(*animated)[std::size_t(material)]
                                          : &model.materials[std::size_t(material)];
                if (s.material && !s.uv.empty() && !placed.tangents.empty()) {
                    s.normalImage = render::cpu::textureImage(model, s.material->normalTexture);
                    if (s.normalImage || s.material->hasAnisotropy ||
                        s.material->clearcoatNormalTexture.present())
                        s.tangents = placed.tangents;
                }
                s.model = &model;
                s.glass = decoded.isGlass(model, material, character.glass);
                s.authored = s.material && s.material->isTransmissive();
                s.mirrored = glm::determinant(glm::dmat3(instance.meshToWorld)) < 0.0;
                s.solid = int(solid);
                s.optics = opticsFor(decoded, s.material, character.overrides, extent);
                if (!s.optics.dispersion)
                    s.optics.ior = glm::vec3(s.optics.ior.g);
                surfaces.push_back(std::move(s));
            }
        }
    }
    return surfaces;
}

std::pair<dvec3, dvec3> surfaceBounds(const std::vector<Surface>& surfaces, bool glassOnly) {
    dvec3 lo(1e300), hi(-1e300);
    for (const Surface& s : surfaces)
        if (s.glass || !glassOnly)
            for (const dvec3& p : s.positions) {
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
    return {lo, hi};
}

double sceneEpsilon(const std::vector<Surface>& surfaces) {
    const auto [lo, hi] = surfaceBounds(surfaces, false);
    return lo.x > hi.x ? 1e-6 : 1e-5 * glm::length(hi - lo);
}

} // namespace refraction::reference
