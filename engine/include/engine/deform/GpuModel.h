// A model's static GPU data, uploaded once and shared by every character that places it: per
// mesh primitive the rest vertices, skin influences, morph deltas, indices and UVs, and with a
// subdivision level the OpenSubdiv refinement and its stencil tables.
#pragma once

#include "engine/core/Result.h"
#include "engine/deform/Subdivision.h"
#include "engine/gl/Buffer.h"
#include "engine/scene/Model.h"

#include <memory>
#include <vector>

namespace deform {

class GpuModel {
public:
    /** Uploads every primitive of every mesh the default scene's nodes use; with
     *  `subdivisionLevel` > 0 also builds each primitive's Loop refinement once. `model` must
     *  outlive the result. Needs a current GL context. Fails naming the mesh and primitive
     *  OpenSubdiv cannot refine, or a level outside 0..kMaxSubdivisionLevel. */
    static core::Result<std::shared_ptr<const GpuModel>> create(const scene::Model& model,
                                                                int subdivisionLevel = 0);
    ~GpuModel();

    const scene::Model& model() const { return *mModel; }
    int subdivisionLevel() const { return mLevel; }

    /** One primitive's buffers (defined privately in src/deform/GpuModelData.h). */
    struct Primitive;
    const Primitive& primitive(int mesh, std::size_t p) const;
    /** Its triangles as drawn (uint32; the refined mesh's with subdivision). */
    const gl::Buffer& indices(int mesh, std::size_t p) const;
    /** Its refinement; null at level 0. */
    const Subdivision* subdivision(int mesh, std::size_t p) const;

private:
    GpuModel() = default;
    const scene::Model* mModel = nullptr;
    int mLevel = 0;
    std::vector<std::vector<std::unique_ptr<Primitive>>> mPrimitives; // [mesh][primitive]
};

} // namespace deform
