// Private to deform: the GPU layouts shared by the upload of a model (GpuModel) and the
// placement that deforms it (GpuDeformer).
#pragma once

#include "engine/deform/GpuModel.h"
#include "engine/gl/Buffer.h"

#include <glm/glm.hpp>

#include <span>

namespace deform {

/** std430 layout of common/vertex.glsl's DeformedVertex. */
struct VertexGpu {
    glm::vec4 position, normal, tangent;
};

/** std430 layout of deform.comp.glsl's Influence. */
struct InfluenceGpu {
    glm::uvec4 joints0{0}, joints1{0};
    glm::vec4 weights0{0.0f}, weights1{0.0f};
};

/** Stencils on the GPU, in the layout Osd::GLComputeEvaluator reads. */
struct GpuStencils {
    gl::Buffer sizes, offsets, indices, weights, duWeights, dvWeights;
    int count = 0;
    explicit GpuStencils(const Stencils& s)
        : sizes(std::span<const int>(s.sizes)), offsets(std::span<const int>(s.offsets)),
          indices(std::span<const int>(s.indices)), weights(std::span<const float>(s.weights)),
          count(int(s.count())) {
        if (!s.duWeights.empty()) {
            duWeights = gl::Buffer(std::span<const float>(s.duWeights));
            dvWeights = gl::Buffer(std::span<const float>(s.dvWeights));
        }
    }
};

struct GpuModel::Primitive {
    gl::Buffer rest, influences, deltas, indices, uvs;
    gl::Buffer cageIndices; // with subdivision: the file's triangles (indices: the refined)
    std::uint32_t targetCount = 0;
    bool closed = false; // scene::isClosed: its refinement is too
    // With subdivision: the tables, the drawn mesh's static buffers (indices and uvs above are
    // then the refined ones) and the corners the pack pass reads.
    std::unique_ptr<Subdivision> subdivision;
    std::unique_ptr<GpuStencils> refine, limit, faceVarying;
    gl::Buffer corners;
};

} // namespace deform
