// The reference's scene (ReferenceTracer.cpp): every character's surfaces at one scene time,
// deformed and refined as the GPU draws them, in world space, with what the tracer reads of
// their materials; and their bounds.
#pragma once

#include "Settings.h"
#include "model/Optics.h"

#include "engine/core/Result.h"
#include "engine/scene/World.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace refraction::reference {

using glm::dvec3;
using glm::dvec4;

/** One primitive of one character as the tracer meets it. */
struct Surface {
    std::vector<dvec3> positions, normals;     // world
    std::vector<dvec4> tangents;               // world, where a map or anisotropy needs them
    std::vector<dvec4> uv;                     // TEXCOORD_0 in xy, TEXCOORD_1 in zw
    const scene::Image* normalImage = nullptr; // the material's normal texture, if it has one
    std::vector<std::uint32_t> indices;
    bool glass = true;
    bool authored = false;                     // glass by its material (its textures all count)
    bool mirrored = false;                     // placed mirrored: its winding reversed (glTF)
    int solid = 0;                             // the character: one closed solid (media rule)
    const scene::Model* model = nullptr;       // whose material and textures
    const scene::Material* material = nullptr; // opaque surfaces
    /** The character's materials with their animated factors played (anim::Pose::materials),
     *  which `material` points into; null where none plays. */
    std::shared_ptr<const std::vector<scene::Material>> animated;
    Optics optics; // glass surfaces
};

/** Every character's surfaces at scene time `time`, deformed by the CPU reference, refined to
 *  `subdivision` as the GPU refines them, in world space; `decoded` says which are glass and
 *  with what optics. */
core::Result<std::vector<Surface>> worldSurfaces(const scene::World& world, double time,
                                                 const Settings& decoded, int subdivision);

/** The box (lo, hi) around the surfaces' positions, the glass's alone with `glassOnly`; lo > hi
 *  where there are none. */
std::pair<dvec3, dvec3> surfaceBounds(const std::vector<Surface>& surfaces, bool glassOnly);

/** The tracer's epsilon: a hundred-thousandth of the surfaces' extent. */
double sceneEpsilon(const std::vector<Surface>& surfaces);

} // namespace refraction::reference
