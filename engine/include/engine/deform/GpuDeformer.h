// GPU deformation of one placement of an uploaded model (GpuModel, shared by every placement):
// per frame, per mesh node, one compute pass per primitive applies morph deltas and skinning and
// writes one deformed vertex buffer that every later pass reads. With a subdivision level,
// OpenSubdiv's GL compute evaluator then refines that deformed cage into the dense buffer the
// passes read instead.
#pragma once

#include "engine/anim/Pose.h"
#include "engine/core/Result.h"
#include "engine/deform/CpuDeformer.h"
#include "engine/deform/GpuModel.h"
#include "engine/deform/Subdivision.h"
#include "engine/gl/Buffer.h"
#include "engine/gl/Program.h"
#include "engine/scene/Model.h"

#include <glm/glm.hpp>

#include <memory>
#include <span>
#include <vector>

namespace deform {

/** GPU buffers of one primitive of one mesh node, as drawn. `deformed` holds vertexCount
 *  DeformedVertex (common/vertex.glsl: position, normal, tangent as vec4, mesh-node space),
 *  rewritten by every update(); `uvs` and `indices` are static, shared by the mesh's instances
 *  and by every placement of the model, owned by the GpuModel. With subdivision all of them are
 *  the refined mesh's. */
struct GpuPrimitive {
    const scene::Primitive* source = nullptr; ///< the file's primitive (material, skin)
    /** The mesh drawn, at rest: `source` itself, or the refined mesh (Subdivision::rest). */
    const scene::Primitive* topology = nullptr;
    std::uint32_t vertexCount = 0;
    std::uint32_t indexCount = 0;
    /** It bounds a solid in every pose (scene::isClosed; a refinement of a closed cage is too):
     *  from outside only its front faces show. */
    bool closed = false;
    /** Shared by the draws of one mesh node: EXT_mesh_gpu_instancing's instances draw one
     *  deformation. */
    std::shared_ptr<gl::Buffer> deformed;
    /** `deformed` as the previous dispatch left it (the same layout), where the deformer keeps
     *  it (GpuDeformer::keepPrevious: motion vectors); else null. */
    std::shared_ptr<gl::Buffer> previous;
    const gl::Buffer* uvs = nullptr;     ///< vec4 per vertex: TEXCOORD_0, TEXCOORD_1 (or zeros)
    const gl::Buffer* indices = nullptr; ///< uint32 triangle list
};

/** One draw of a mesh node of the default scene on the GPU (a node with EXT_mesh_gpu_instancing
 *  has one per instance: each placed on its own, all drawing the first one's deformation). */
struct GpuInstance {
    int node = -1;
    int mesh = -1;
    glm::dmat4 instance{1.0}; ///< the node's instance transform (scene::Node::instance)
    /** The index of the draw that deforms the buffers this one draws: itself, or the node's
     *  first instance. */
    std::size_t deformation = 0;
    /** placement * world(node) * instance: mesh space to world space, refreshed by stage() and
     *  update(). */
    glm::mat4 meshToWorld{1.0f};
    /** meshToWorld as the stage() before the last set it (the last's on the first). */
    glm::mat4 previousMeshToWorld{1.0f};
    std::vector<GpuPrimitive> primitives;
};

/** The per-frame uploads of any number of deformers: every skin matrix and morph weight of a
 *  frame staged on the CPU (GpuDeformer::stage), then one upload per buffer. The buffers grow
 *  (by doubling) only when a frame needs more than any before, so a steady scene allocates
 *  nothing per frame. */
class PoseUpload {
public:
    /** Starts a frame: forgets the staged values (keeps the storage). */
    void clear();
    /** Stages values; returns the index of the first in the buffer. */
    std::uint32_t addMatrices(std::span<const glm::mat4> matrices);
    std::uint32_t addWeights(std::span<const double> weights);
    /** Uploads what was staged: one buffer update each (a reallocation when it grew). */
    void upload();
    const gl::Buffer& matrices() const { return mMatrices; }
    const gl::Buffer& weights() const { return mWeights; }

private:
    std::vector<glm::mat4> mMatrixValues;
    std::vector<float> mWeightValues;
    gl::Buffer mMatrices, mWeights;
};

class GpuDeformer {
public:
    /** Places `model` once more: deformed buffers of every mesh node of the default scene over
     *  the shared static data, and the deform programs (its skin matrices and morph weights go
     *  through a PoseUpload each frame). Needs a current GL context. */
    static core::Result<std::unique_ptr<GpuDeformer>> create(std::shared_ptr<const GpuModel> model,
                                                             const gl::ShaderLibrary& shaders);
    /** Uploads `model` (GpuModel::create, failing as it does) and places it. */
    static core::Result<std::unique_ptr<GpuDeformer>>
    create(const scene::Model& model, const gl::ShaderLibrary& shaders, int subdivisionLevel = 0);
    ~GpuDeformer();

    /** Stages this pose's skin matrices and morph weights into `upload` and sets each
     *  instance's meshToWorld to placement * world(node). No GL call. */
    void stage(const anim::Pose& pose, const glm::dmat4& placement, PoseUpload& upload);
    /** Runs the deform passes on what stage() left in `upload` (uploaded since): one dispatch
     *  per primitive, plus one for flat normals where the file had none, then the refinement
     *  of each deformed cage (stencils to the refined vertices, to their limit positions and
     *  tangents, face-varying tangents, one pack dispatch). Issues a barrier so draws and later
     *  compute passes see the result. No allocation, no sync. */
    void dispatch(const PoseUpload& upload);
    /** stage(), upload and dispatch() with an upload of this deformer's own: for a deformer
     *  used alone (tests, tools); a renderer stages every character into one upload. */
    void update(const anim::Pose& pose, const glm::dmat4& placement = glm::dmat4(1.0));

    /** Keeps each deformed buffer as the previous dispatch left it (GpuPrimitive::previous), a
     *  copy on the GPU before each dispatch rewrites it: the motion of every vertex without a
     *  second deformation. The first dispatch after this call (or after any dispatch with it
     *  off) keeps its own result: no motion. Off frees the copies. */
    void keepPrevious(bool keep);
    bool keepsPrevious() const { return mKeepPrevious; }

    const std::vector<GpuInstance>& instances() const { return mInstances; }
    int subdivisionLevel() const { return mUpload->subdivisionLevel(); }
    /** The uploaded model this placement deforms. */
    const std::shared_ptr<const GpuModel>& model() const { return mUpload; }
    /** Differs between any two deformers of a process (plugins key their caches on it). */
    std::uint64_t serial() const { return mSerial; }

    /** Reads primitive `p` of instance `i` back as drawn (synchronises: tests and tools only). */
    DeformedPrimitive download(std::size_t i, std::size_t p) const;
    /** The deformed cage (the file's vertices) before refinement; download() at level 0. */
    DeformedPrimitive downloadCage(std::size_t i, std::size_t p) const;
    /** The deformed cage of instance `i`'s primitive `p`, as update() left it: the file's
     *  vertices (DeformedVertex) and triangles. The drawn buffers themselves at level 0. */
    struct Cage {
        const gl::Buffer& vertices;
        const gl::Buffer& indices;
    };
    Cage cage(std::size_t i, std::size_t p) const;
    /** The refinement of instance `i`'s primitive `p`; null at level 0. */
    const Subdivision* subdivision(std::size_t i, std::size_t p) const;

private:
    GpuDeformer() = default;
    void dispatchDeform(const PoseUpload& upload); // dispatch()'s passes
    /** With keepPrevious: before a dispatch, the last one's result into the previous buffers;
     *  after the first, its own (`before` says which call this is). */
    void keepResult(bool before);
    void refine();     // the subdivision passes of update()
    struct Refined;    // per instance primitive: the cage and the evaluators' outputs
    struct Evaluators; // OpenSubdiv's GL compute evaluators, one per buffer layout
    std::shared_ptr<const GpuModel> mUpload;
    std::uint64_t mSerial = 0;
    std::unique_ptr<Evaluators> mEvaluators;
    std::vector<std::vector<Refined>> mRefined; // [instance][primitive], empty at level 0
    std::vector<GpuInstance> mInstances;
    struct Staged {
        std::uint32_t matrices = 0, weights = 0, weightCount = 0; // into the PoseUpload
    };
    std::vector<Staged> mStaged; // per instance, by the last stage()
    std::vector<glm::mat4> mScratchMatrices;
    std::unique_ptr<PoseUpload> mOwnUpload; // update()'s
    bool mKeepPrevious = false;
    bool mPreviousValid = false; // the previous buffers hold an earlier dispatch's result
    bool mStagedBefore = false;  // stage() ran before: previousMeshToWorld has a value
    gl::Program mDeform, mFlatNormals, mPack;
};

} // namespace deform
