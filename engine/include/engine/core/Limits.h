// Every hard limit of the engine, with the reason beside it. Loaders check these and report an
// error naming the element; nothing is silently truncated.
#pragma once

#include <cstddef>
#include <cstdint>

namespace core::limits {

/** Skin influences per vertex: JOINTS_0/1 + WEIGHTS_0/1, two vec4 sets, as the GPU deform
 *  pass reads them. A third set (JOINTS_2) is rejected rather than dropped. */
inline constexpr int kMaxInfluences = 8;

/** Joints per skin. Skin matrices live in an SSBO, so the GPU has no small cap; this bound
 *  only stops absurd files (each joint costs a 64-byte matrix per frame). */
inline constexpr std::size_t kMaxJointsPerSkin = 65536;

/** Morph targets per primitive. Deltas live in SSBOs; the bound stops absurd files whose
 *  per-frame weight loop would dominate (the glTF ecosystem rarely exceeds a few hundred). */
inline constexpr std::size_t kMaxMorphTargets = 4096;

/** Nodes in a file: the hierarchy walk and per-node pose arrays are sized by it. */
inline constexpr std::size_t kMaxNodes = 1u << 20;

/** Vertices per primitive: indices are 32-bit and the GPU deform pass dispatches per vertex. */
inline constexpr std::size_t kMaxVerticesPerPrimitive = std::size_t(1) << 28;

/** Texture width or height accepted by the loader; the GL layer re-checks against
 *  GL_MAX_TEXTURE_SIZE of the actual context. */
inline constexpr int kMaxTextureSize = 16384;

/** Decoded bytes a whole model may expand to (vertex data after conversion, images): a guard
 *  against counts that no file of this size could justify. */
inline constexpr std::uint64_t kMaxModelBytes = std::uint64_t(8) << 30;

/** Subdivision levels (OpenSubdiv uniform refinement): each level multiplies the triangles by
 *  four, so level 4 turns a 10k-triangle character into 2.6M triangles. */
inline constexpr int kMaxSubdivisionLevel = 4;

/** Triangles one primitive may have after refinement: the stencil tables grow with them
 *  (about 100 bytes a refined vertex at level 4) and are built on the CPU. */
inline constexpr std::size_t kMaxRefinedTriangles = std::size_t(1) << 23;

/** Characters in one scene: each costs a deform dispatch per primitive and a draw per glass
 *  or opaque primitive every frame; a crowd larger than this is not real time anywhere. */
inline constexpr std::size_t kMaxCharacters = 4096;

/** Punctual lights in one frame (a scene file's and its characters' KHR_lights_punctual lights):
 *  every shaded pixel evaluates each of them. */
inline constexpr std::size_t kMaxLights = 256;
/** Lights that cast shadows in one frame (each a map, a point light six): the first this many
 *  in the frame's order cast, the others light unshadowed, with a warning. */
inline constexpr std::size_t kMaxShadowedLights = 4;
/** A shadow map's texels per side. */
inline constexpr int kMinShadowResolution = 64, kMaxShadowResolution = 4096;

/** Bytes of a scene file: 4096 characters at a few hundred bytes each need about 2 MB; a file
 *  far larger is not a scene, and is refused before it is parsed. */
inline constexpr std::uint64_t kMaxSceneFileBytes = std::uint64_t(64) << 20;

/** EXT_mesh_gpu_instancing instances of one mesh node: each is drawn (and shaded, and traced by
 *  the reference) as a placement of its own, so its vertices count against kMaxSceneVertices
 *  too, though the GPU deforms the node once. */
inline constexpr std::size_t kMaxInstancesPerNode = 65536;

/** Deformed vertices of a whole scene (every character's, counted at level 0): the GPU holds
 *  a 48-byte deformed vertex for each, so 2^26 of them is 3 GiB before any refinement. */
inline constexpr std::size_t kMaxSceneVertices = std::size_t(1) << 26;

} // namespace core::limits
