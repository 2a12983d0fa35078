// Private to the asset module: attributes a file may omit and the engine needs (flat normals,
// tangents), and the unwelding that flat normals require.
#pragma once

#include "engine/scene/Mesh.h"

namespace asset::detail {

/** Gives every triangle its own three vertices (all attributes and morph deltas follow), so
 *  each vertex belongs to one face; indices become 0..n-1. */
void unweld(scene::Primitive& primitive);

/** Sets each vertex normal to its triangle's face normal; the primitive must be unwelded.
 *  Degenerate triangles get +z. */
void computeFlatNormals(scene::Primitive& primitive);

/** Per-vertex tangents from the UV set `texCoord` (0 or 1): per-triangle dP/du accumulated,
 *  Gram-Schmidt orthogonalised against the normal, handedness in w from dP/dv. Vertices with no
 *  usable UV gradient get any unit vector perpendicular to the normal. */
void generateTangents(scene::Primitive& primitive, int texCoord);

} // namespace asset::detail
