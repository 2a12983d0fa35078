// GPU deformation: per frame, per mesh node, one compute pass per primitive applies morph
// deltas and skinning and writes one deformed vertex buffer that every later pass reads.
#pragma once

#include "engine/anim/Pose.h"
#include "engine/core/Result.h"
#include "engine/deform/CpuDeformer.h"
#include "engine/gl/Buffer.h"
#include "engine/gl/Program.h"
#include "engine/scene/Model.h"

#include <glm/glm.hpp>

#include <memory>
#include <vector>

namespace deform {

/** GPU buffers of one primitive of one mesh node. `deformed` holds vertexCount DeformedVertex
 *  (common/vertex.glsl: position, normal, tangent as vec4, mesh-node space), rewritten by
 *  every update(); `uv0` and `indices` are static, shared by the mesh's instances and owned by
 *  the deformer. */
struct GpuPrimitive {
    const scene::Primitive* source = nullptr;
    std::uint32_t vertexCount = 0;
    std::uint32_t indexCount = 0;
    gl::Buffer deformed;
    const gl::Buffer* uv0 = nullptr;     ///< vec2 per vertex (zeros when the file has none)
    const gl::Buffer* indices = nullptr; ///< uint32 triangle list
};

/** One mesh node of the default scene on the GPU. */
struct GpuInstance {
    int node = -1;
    int mesh = -1;
    glm::mat4 meshToWorld{1.0f}; ///< world(node), refreshed by update()
    std::vector<GpuPrimitive> primitives;
};

class GpuDeformer {
public:
    /** Uploads rest attributes, influences and morph deltas of every mesh node of the default
     *  scene and compiles the deform programs. Needs a current GL context. */
    static core::Result<std::unique_ptr<GpuDeformer>> create(const scene::Model& model,
                                                             const gl::ShaderLibrary& shaders);

    /** Uploads this pose's skin matrices and morph weights and runs the deform passes (one
     *  dispatch per primitive, plus one for flat normals where the file had none). Issues a
     *  barrier so draws and later compute passes see the result. No allocation, no sync. */
    void update(const anim::Pose& pose);

    const std::vector<GpuInstance>& instances() const { return mInstances; }

    /** Reads primitive `p` of instance `i` back (synchronises: tests and tools only). */
    DeformedPrimitive download(std::size_t i, std::size_t p) const;

private:
    GpuDeformer() = default;
    struct Static; // per mesh primitive: rest, influences, morph deltas
    const scene::Model* mModel = nullptr;
    std::vector<GpuInstance> mInstances;
    std::vector<std::vector<std::shared_ptr<Static>>> mStatic; // [mesh][primitive]
    std::vector<gl::Buffer> mSkinMatrices;                     // per instance (empty: unskinned)
    std::vector<gl::Buffer> mMorphWeights;                     // per instance
    std::vector<glm::mat4> mScratchMatrices;
    std::vector<float> mScratchWeights;
    gl::Program mDeform, mFlatNormals;
};

} // namespace deform
