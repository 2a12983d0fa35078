// scene::isClosed: which primitives bound a solid in every pose.
#include "engine/scene/Mesh.h"

#include <gtest/gtest.h>

#include <array>

namespace {

/** A unit cube as a glTF exporter writes it: four vertices a face (split for their normals),
 *  two triangles a face, wound counter-clockwise seen from outside. */
scene::Primitive splitCube() {
    scene::Primitive p;
    // Each face: its outward axis, and two axes whose cross product is that normal.
    const std::array<std::array<glm::vec3, 3>, 6> faces{{
        {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)},
        {glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1), glm::vec3(0, 1, 0)},
        {glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0)},
        {glm::vec3(0, -1, 0), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1)},
        {glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)},
        {glm::vec3(0, 0, -1), glm::vec3(0, 1, 0), glm::vec3(1, 0, 0)},
    }};
    for (const auto& [n, u, v] : faces) {
        const auto base = std::uint32_t(p.positions.size());
        for (const glm::vec2 c :
             {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
            p.positions.push_back(0.5f * (n + c.x * u + c.y * v));
            p.normals.push_back(n);
        }
        for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u})
            p.indices.push_back(base + i);
    }
    return p;
}

TEST(Mesh, ASplitCubeIsClosedAndLosesItWithAHoleOrAFlippedTriangle) {
    scene::Primitive cube = splitCube();
    EXPECT_TRUE(scene::isClosed(cube));

    scene::Primitive holed = cube;
    holed.indices.resize(holed.indices.size() - 3);
    EXPECT_FALSE(scene::isClosed(holed));

    scene::Primitive flipped = cube;
    std::swap(flipped.indices[1], flipped.indices[2]);
    EXPECT_FALSE(scene::isClosed(flipped));

    // A degenerate triangle covers nothing: it neither opens nor closes the surface.
    scene::Primitive degenerate = cube;
    degenerate.indices.insert(degenerate.indices.end(), {0u, 0u, 1u});
    EXPECT_TRUE(scene::isClosed(degenerate));
    degenerate = holed;
    degenerate.indices.insert(degenerate.indices.end(), {0u, 0u, 1u});
    EXPECT_FALSE(scene::isClosed(degenerate));
}

TEST(Mesh, SeamCopiesCountAsOneOnlyWhereTheyDeformAlike) {
    scene::Primitive cube = splitCube();
    cube.joints[0].assign(cube.vertexCount(), glm::uvec4(0, 1, 0, 0));
    cube.weights[0].assign(cube.vertexCount(), glm::vec4(0.5f, 0.5f, 0.0f, 0.0f));
    EXPECT_TRUE(scene::isClosed(cube));
    // One copy of a corner follows another joint: the seam may open as it moves.
    scene::Primitive skinned = cube;
    skinned.weights[0][0] = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
    EXPECT_FALSE(scene::isClosed(skinned));
    // Or a morph target moves it alone.
    scene::Primitive morphed = cube;
    morphed.targets.push_back({});
    morphed.targets[0].positions.assign(morphed.vertexCount(), glm::vec3(0.0f));
    EXPECT_TRUE(scene::isClosed(morphed));
    morphed.targets[0].positions[0] = glm::vec3(0.1f, 0.0f, 0.0f);
    EXPECT_FALSE(scene::isClosed(morphed));
}

} // namespace
