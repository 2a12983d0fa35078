// GPU deformation of one placement of an uploaded model (GpuModel): its deformed buffers and
// per-frame uploads, the deform dispatches, then OpenSubdiv's GL compute evaluator on the
// deformed cages.
#include "engine/deform/GpuDeformer.h"

#include "GpuModelData.h"

#include "engine/gl/Commands.h"

#include <opensubdiv/osd/glComputeEvaluator.h>

#include <atomic>
#include <cstring>

namespace deform {
namespace {

constexpr std::uint32_t kGroupSize = 64;

std::uint32_t groups(std::size_t n) {
    return std::uint32_t((n + kGroupSize - 1) / kGroupSize);
}

} // namespace

/** Per instance primitive with subdivision: the deformed cage and the evaluators' outputs. */
struct GpuDeformer::Refined {
    gl::Buffer cage;          // DeformedVertex per file vertex
    gl::Buffer refined;       // 3 floats per refined vertex
    gl::Buffer limit, du, dv; // 3 floats per refined vertex
    gl::Buffer tangents;      // 4 floats per refined face-varying value
};

struct GpuDeformer::Evaluators {
    using Evaluator = OpenSubdiv::Osd::GLComputeEvaluator;
    using Desc = OpenSubdiv::Osd::BufferDescriptor;
    static constexpr int kStride = int(sizeof(VertexGpu) / sizeof(float));
    // cage positions -> refined positions; refined -> limit + du + dv; cage tangents -> refined
    const Desc cagePosition{0, 3, kStride}, cageTangent{8, 4, kStride}, packed3{0, 3, 3},
        packed4{0, 4, 4};
    std::unique_ptr<Evaluator> refine, limit, faceVarying;
};

GpuDeformer::~GpuDeformer() = default;

core::Result<std::unique_ptr<GpuDeformer>> GpuDeformer::create(const scene::Model& model,
                                                               const gl::ShaderLibrary& shaders,
                                                               int subdivisionLevel) {
    auto uploaded = GpuModel::create(model, subdivisionLevel);
    if (!uploaded)
        return uploaded.error();
    return create(std::move(*uploaded), shaders);
}

core::Result<std::unique_ptr<GpuDeformer>>
GpuDeformer::create(std::shared_ptr<const GpuModel> uploaded, const gl::ShaderLibrary& shaders) {
    static std::atomic<std::uint64_t> serials{0};
    std::unique_ptr<GpuDeformer> d(new GpuDeformer());
    const scene::Model& model = uploaded->model();
    const int subdivisionLevel = uploaded->subdivisionLevel();
    d->mUpload = std::move(uploaded);
    d->mSerial = ++serials;
    auto deformProgram = gl::Program::compute(shaders, "deform/deform.comp.glsl");
    if (!deformProgram)
        return core::Error{"deform::GpuDeformer::create(): " + deformProgram.error().message};
    auto flatProgram = gl::Program::compute(shaders, "deform/flat_normals.comp.glsl");
    if (!flatProgram)
        return core::Error{"deform::GpuDeformer::create(): " + flatProgram.error().message};
    d->mDeform = std::move(*deformProgram);
    d->mFlatNormals = std::move(*flatProgram);
    if (subdivisionLevel > 0) {
        auto packProgram = gl::Program::compute(shaders, "deform/subdivision_pack.comp.glsl");
        if (!packProgram)
            return core::Error{"deform::GpuDeformer::create(): " + packProgram.error().message};
        d->mPack = std::move(*packProgram);
        auto e = std::make_unique<Evaluators>();
        const OpenSubdiv::Osd::BufferDescriptor none;
        e->refine.reset(Evaluators::Evaluator::Create(e->cagePosition, e->packed3, none, none));
        e->limit.reset(
            Evaluators::Evaluator::Create(e->packed3, e->packed3, e->packed3, e->packed3));
        e->faceVarying.reset(Evaluators::Evaluator::Create(e->cageTangent, e->packed4, none, none));
        if (!e->refine || !e->limit || !e->faceVarying)
            return core::Error{"deform::GpuDeformer::create(): OpenSubdiv's GL compute "
                               "evaluator did not compile"};
        d->mEvaluators = std::move(e);
    }

    // The placement: per mesh node, deformed buffers and the per-frame uploads'; a node's later
    // instances (EXT_mesh_gpu_instancing) draw its first one's buffers from their own place.
    for (int node : model.meshNodes()) {
        const scene::Node& n = model.nodes[std::size_t(node)];
        const scene::Mesh& mesh = model.meshes[std::size_t(n.mesh)];
        GpuInstance instance;
        instance.node = node;
        instance.mesh = n.mesh;
        instance.deformation = d->mInstances.size();
        std::vector<Refined> refined;
        for (std::size_t i = 0; i < mesh.primitives.size(); ++i) {
            const scene::Primitive& p = mesh.primitives[i];
            const GpuModel::Primitive& s = d->mUpload->primitive(n.mesh, i);
            GpuPrimitive gp;
            gp.source = &p;
            gp.topology = s.subdivision ? &s.subdivision->rest : &p;
            gp.vertexCount = std::uint32_t(gp.topology->vertexCount());
            gp.indexCount = std::uint32_t(gp.topology->indices.size());
            gp.closed = s.closed;
            gp.deformed = std::make_shared<gl::Buffer>(gp.vertexCount * sizeof(VertexGpu));
            gp.uvs = &s.uvs;
            gp.indices = &s.indices;
            instance.primitives.push_back(std::move(gp));
            if (s.subdivision) {
                const std::size_t vertices = std::size_t(s.refine->count),
                                  values = std::size_t(s.faceVarying->count);
                Refined r;
                r.cage = gl::Buffer(p.vertexCount() * sizeof(VertexGpu));
                r.refined = gl::Buffer(vertices * 3 * sizeof(float));
                r.limit = gl::Buffer(vertices * 3 * sizeof(float));
                r.du = gl::Buffer(vertices * 3 * sizeof(float));
                r.dv = gl::Buffer(vertices * 3 * sizeof(float));
                r.tangents = gl::Buffer(values * 4 * sizeof(float));
                refined.push_back(std::move(r));
            }
        }
        if (subdivisionLevel > 0)
            d->mRefined.push_back(std::move(refined));
        for (std::size_t k = 0; k < n.drawCount(); ++k) {
            instance.instance = n.instance(k);
            d->mInstances.push_back(instance); // copies share the deformed buffers
            if (subdivisionLevel > 0 && k > 0)
                d->mRefined.emplace_back(); // unused: the first instance's refine
        }
    }
    d->mStaged.resize(d->mInstances.size());
    return d;
}

void PoseUpload::clear() {
    mMatrixValues.clear();
    mWeightValues.clear();
}

std::uint32_t PoseUpload::addMatrices(std::span<const glm::mat4> matrices) {
    const auto first = std::uint32_t(mMatrixValues.size());
    mMatrixValues.insert(mMatrixValues.end(), matrices.begin(), matrices.end());
    return first;
}

std::uint32_t PoseUpload::addWeights(std::span<const double> weights) {
    const auto first = std::uint32_t(mWeightValues.size());
    for (double w : weights)
        mWeightValues.push_back(float(w));
    return first;
}

void PoseUpload::upload() {
    // Buffers of at least one element, so that they can be bound when nothing is staged.
    auto put = [](gl::Buffer& buffer, const auto& values) {
        const std::size_t bytes = std::max<std::size_t>(values.size(), 1) * sizeof(values[0]);
        if (buffer.size() < bytes)
            buffer = gl::Buffer(std::max(bytes, 2 * buffer.size()));
        buffer.update(std::span(values));
    };
    put(mMatrices, mMatrixValues);
    put(mWeights, mWeightValues);
}

void GpuDeformer::stage(const anim::Pose& pose, const glm::dmat4& placement, PoseUpload& upload) {
    const scene::Model& model = mUpload->model();
    for (std::size_t i = 0; i < mInstances.size(); ++i) {
        GpuInstance& instance = mInstances[i];
        const auto node = std::size_t(instance.node);
        const glm::mat4 meshToWorld(placement * pose.world[node] * instance.instance);
        instance.previousMeshToWorld = mStagedBefore ? instance.meshToWorld : meshToWorld;
        instance.meshToWorld = meshToWorld;
        if (instance.deformation != i)
            continue; // draws another's deformation
        Staged& staged = mStaged[i];
        if (model.nodes[node].skin >= 0) {
            anim::skinMatrices(model, pose, instance.node, mScratchMatrices);
            staged.matrices = upload.addMatrices(mScratchMatrices);
        }
        const auto& weights = pose.weights[node];
        staged.weights = upload.addWeights(weights);
        staged.weightCount = std::uint32_t(weights.size());
    }
    mStagedBefore = true;
}

void GpuDeformer::keepPrevious(bool keep) {
    if (keep == mKeepPrevious)
        return;
    mKeepPrevious = keep;
    mPreviousValid = false;
    for (std::size_t i = 0; i < mInstances.size(); ++i)
        for (GpuPrimitive& gp : mInstances[i].primitives)
            gp.previous = !keep ? nullptr
                          : mInstances[i].deformation == i
                              ? std::make_shared<gl::Buffer>(gp.deformed->size())
                              : nullptr;
    for (GpuInstance& instance : mInstances) // later instances draw the first one's
        for (std::size_t p = 0; p < instance.primitives.size(); ++p)
            instance.primitives[p].previous =
                mInstances[instance.deformation].primitives[p].previous;
}

void GpuDeformer::keepResult(bool before) {
    if (!mKeepPrevious || before != mPreviousValid)
        return;
    gl::memoryBarrier(gl::BarrierBufferUpdate); // the deform's writes before the copy reads
    for (std::size_t i = 0; i < mInstances.size(); ++i)
        for (GpuPrimitive& gp : mInstances[i].primitives)
            if (mInstances[i].deformation == i)
                gp.previous->copyFrom(*gp.deformed);
    mPreviousValid = true;
}

void GpuDeformer::update(const anim::Pose& pose, const glm::dmat4& placement) {
    if (!mOwnUpload)
        mOwnUpload = std::make_unique<PoseUpload>();
    mOwnUpload->clear();
    stage(pose, placement, *mOwnUpload);
    mOwnUpload->upload();
    dispatch(*mOwnUpload);
}

void GpuDeformer::dispatch(const PoseUpload& upload) {
    keepResult(true); // the last dispatch's result, before this one rewrites it
    dispatchDeform(upload);
    keepResult(false);
}

void GpuDeformer::dispatchDeform(const PoseUpload& upload) {
    const scene::Model& model = mUpload->model();
    mDeform.use();
    gl::bindStorage(gl::slot::kMorphWeights, upload.weights());
    gl::bindStorage(gl::slot::kSkinMatrices, upload.matrices());
    for (std::size_t i = 0; i < mInstances.size(); ++i) {
        GpuInstance& instance = mInstances[i];
        if (instance.deformation != i)
            continue;
        const Staged& staged = mStaged[i];
        const bool skinned = model.nodes[std::size_t(instance.node)].skin >= 0;
        mDeform.set("uSkinBase", int(staged.matrices));
        mDeform.set("uWeightBase", int(staged.weights));
        for (std::size_t p = 0; p < instance.primitives.size(); ++p) {
            GpuPrimitive& gp = instance.primitives[p];
            const GpuModel::Primitive& s = mUpload->primitive(instance.mesh, p);
            gl::bindStorage(gl::slot::kRest, s.rest);
            gl::bindStorage(gl::slot::kInfluences, s.influences);
            gl::bindStorage(gl::slot::kMorphDeltas, s.deltas);
            gl::bindStorage(gl::slot::kVertices,
                            subdivisionLevel() > 0 ? mRefined[i][p].cage : *gp.deformed);
            mDeform.set("uVertexCount", int(gp.source->vertexCount()));
            mDeform.set("uTargetCount", int(std::min(s.targetCount, staged.weightCount)));
            mDeform.set("uSkinned", skinned && gp.source->isSkinned() ? 1 : 0);
            gl::dispatch(groups(gp.source->vertexCount()));
        }
    }
    if (subdivisionLevel() > 0) {
        refine();
        return;
    }
    bool anyFlat = false;
    for (const GpuInstance& instance : mInstances)
        for (const GpuPrimitive& gp : instance.primitives)
            anyFlat = anyFlat || gp.source->flatNormals;
    if (anyFlat) {
        gl::memoryBarrier(gl::BarrierStorage);
        mFlatNormals.use();
        for (std::size_t i = 0; i < mInstances.size(); ++i)
            for (GpuPrimitive& gp : mInstances[i].primitives) {
                if (!gp.source->flatNormals || mInstances[i].deformation != i)
                    continue;
                gl::bindStorage(gl::slot::kVertices, *gp.deformed);
                gl::bindStorage(gl::slot::kIndices, *gp.indices);
                mFlatNormals.set("uTriangleCount", int(gp.indexCount / 3));
                gl::dispatch(groups(gp.indexCount / 3));
            }
    }
    gl::memoryBarrier(gl::BarrierStorage | gl::BarrierVertex);
}

void GpuDeformer::refine() {
    // Limit normals replace the cage's (flat or not), so no flat-normal pass here.
    gl::memoryBarrier(gl::BarrierStorage);
    const Evaluators& e = *mEvaluators;
    auto each = [this](auto&& f) {
        for (std::size_t i = 0; i < mInstances.size(); ++i)
            for (std::size_t p = 0;
                 i == mInstances[i].deformation && p < mInstances[i].primitives.size(); ++p)
                f(mUpload->primitive(mInstances[i].mesh, p), mRefined[i][p],
                  mInstances[i].primitives[p]);
    };
    const OpenSubdiv::Osd::BufferDescriptor none;
    each([&](const GpuModel::Primitive& s, Refined& r, GpuPrimitive&) {
        const GpuStencils& t = *s.refine;
        e.refine->EvalStencils(r.cage.id(), e.cagePosition, r.refined.id(), e.packed3, 0, none, 0,
                               none, t.sizes.id(), t.offsets.id(), t.indices.id(), t.weights.id(),
                               0, 0, 0, t.count);
        const GpuStencils& fv = *s.faceVarying;
        e.faceVarying->EvalStencils(r.cage.id(), e.cageTangent, r.tangents.id(), e.packed4, 0, none,
                                    0, none, fv.sizes.id(), fv.offsets.id(), fv.indices.id(),
                                    fv.weights.id(), 0, 0, 0, fv.count);
    });
    gl::memoryBarrier(gl::BarrierStorage);
    each([&](const GpuModel::Primitive& s, Refined& r, GpuPrimitive&) {
        const GpuStencils& t = *s.limit;
        e.limit->EvalStencils(r.refined.id(), e.packed3, r.limit.id(), e.packed3, r.du.id(),
                              e.packed3, r.dv.id(), e.packed3, t.sizes.id(), t.offsets.id(),
                              t.indices.id(), t.weights.id(), t.duWeights.id(), t.dvWeights.id(), 0,
                              t.count);
    });
    gl::memoryBarrier(gl::BarrierStorage);
    mPack.use();
    each([&](const GpuModel::Primitive& s, Refined& r, GpuPrimitive& gp) {
        gl::bindStorage(gl::slot::kCorners, s.corners);
        gl::bindStorage(gl::slot::kLimit, r.limit);
        gl::bindStorage(gl::slot::kLimitDu, r.du);
        gl::bindStorage(gl::slot::kLimitDv, r.dv);
        gl::bindStorage(gl::slot::kRefinedTangents, r.tangents);
        gl::bindStorage(gl::slot::kVertices, *gp.deformed);
        mPack.set("uCornerCount", int(gp.vertexCount));
        mPack.set("uFlipNormals", s.subdivision->flipNormals ? 1 : 0);
        gl::dispatch(groups(gp.vertexCount));
    });
    gl::memoryBarrier(gl::BarrierStorage | gl::BarrierVertex);
}

GpuDeformer::Cage GpuDeformer::cage(std::size_t i, std::size_t p) const {
    const GpuPrimitive& gp = mInstances.at(i).primitives.at(p);
    if (subdivisionLevel() == 0)
        return {*gp.deformed, *gp.indices};
    return {mRefined.at(mInstances.at(i).deformation).at(p).cage,
            mUpload->primitive(mInstances.at(i).mesh, p).cageIndices};
}

const Subdivision* GpuDeformer::subdivision(std::size_t i, std::size_t p) const {
    return mUpload->subdivision(mInstances.at(i).mesh, p);
}

namespace {

DeformedPrimitive unpack(const gl::Buffer& buffer, std::size_t count) {
    const std::vector<std::uint8_t> bytes = buffer.download();
    std::vector<VertexGpu> vertices(count);
    std::memcpy(vertices.data(), bytes.data(), vertices.size() * sizeof(VertexGpu));
    DeformedPrimitive out;
    for (const VertexGpu& v : vertices) {
        out.positions.emplace_back(glm::vec3(v.position));
        out.normals.emplace_back(glm::vec3(v.normal));
        out.tangents.emplace_back(glm::vec4(v.tangent));
    }
    return out;
}

} // namespace

DeformedPrimitive GpuDeformer::download(std::size_t i, std::size_t p) const {
    const GpuPrimitive& gp = mInstances.at(i).primitives.at(p);
    return unpack(*gp.deformed, gp.vertexCount);
}

DeformedPrimitive GpuDeformer::downloadCage(std::size_t i, std::size_t p) const {
    const GpuPrimitive& gp = mInstances.at(i).primitives.at(p);
    return unpack(subdivisionLevel() > 0 ? mRefined.at(mInstances.at(i).deformation).at(p).cage
                                         : *gp.deformed,
                  gp.source->vertexCount());
}

} // namespace deform
