// Any model path the tools accept: a glTF file, or a built-in analytic test model.
#pragma once

#include "engine/asset/GltfLoader.h"

namespace asset {

/** "builtin:sphere" or "builtin:sphere?segments=N" (8 <= N <= 1024, default 128): a unit sphere
 *  at the origin, N longitudes by N/2 latitudes, smooth normals; "builtin:box": the cube
 *  [-1, 1]^3, flat faces (scaled flat by a character's scale, a pane); each one glass material
 *  (transmission 1, ior 1.5). Anything else is loaded with loadGltf(). */
core::Result<scene::Model> loadModel(const std::string& pathOrBuiltin,
                                     const LoadOptions& options = {});

/** The built-in unit sphere (see loadModel). */
scene::Model makeSphere(int segments);
/** The built-in cube (see loadModel). */
scene::Model makeBox();

} // namespace asset
