// GPU deformation: static per-primitive buffers, per-instance per-frame uploads, dispatches;
// then OpenSubdiv's GL compute evaluator on the deformed cages.
#include "engine/deform/GpuDeformer.h"

#include "engine/core/Limits.h"
#include "engine/gl/Commands.h"

#include <opensubdiv/osd/glComputeEvaluator.h>

#include <atomic>
#include <cstring>

namespace deform {
namespace {

/** std430 layout of common/vertex.glsl's DeformedVertex. */
struct VertexGpu {
    glm::vec4 position, normal, tangent;
};

/** std430 layout of deform.comp.glsl's Influence. */
struct InfluenceGpu {
    glm::uvec4 joints0{0}, joints1{0};
    glm::vec4 weights0{0.0f}, weights1{0.0f};
};

constexpr std::uint32_t kGroupSize = 64;

std::uint32_t groups(std::size_t n) {
    return std::uint32_t((n + kGroupSize - 1) / kGroupSize);
}

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

} // namespace

struct GpuDeformer::Static {
    gl::Buffer rest, influences, deltas, indices, uv0;
    gl::Buffer cageIndices; // with subdivision: the file's triangles (indices: the refined)
    std::uint32_t targetCount = 0;
    // With subdivision: the tables, the drawn mesh's static buffers (indices and uv0 above are
    // then the refined ones) and the corners the pack pass reads.
    std::unique_ptr<Subdivision> subdivision;
    std::unique_ptr<GpuStencils> refine, limit, faceVarying;
    gl::Buffer corners;
};

/** Per instance primitive with subdivision: the deformed cage and the evaluators' outputs. */
struct GpuDeformer::Refined {
    gl::Buffer cage;           // DeformedVertex per file vertex
    gl::Buffer refined;        // 3 floats per refined vertex
    gl::Buffer limit, du, dv;  // 3 floats per refined vertex
    gl::Buffer tangents;       // 4 floats per refined face-varying value
    gl::Buffer scalarRefined, scalarLimit; // refineScalar(): 1 float per refined vertex
};

struct GpuDeformer::Evaluators {
    using Evaluator = OpenSubdiv::Osd::GLComputeEvaluator;
    using Desc = OpenSubdiv::Osd::BufferDescriptor;
    static constexpr int kStride = int(sizeof(VertexGpu) / sizeof(float));
    // cage positions -> refined positions; refined -> limit + du + dv; cage tangents -> refined
    const Desc cagePosition{0, 3, kStride}, cageTangent{8, 4, kStride}, packed3{0, 3, 3},
        packed4{0, 4, 4}, packed1{0, 1, 1};
    std::unique_ptr<Evaluator> refine, limit, faceVarying, scalar;
};

GpuDeformer::~GpuDeformer() = default;

core::Result<std::unique_ptr<GpuDeformer>>
GpuDeformer::create(const scene::Model& model, const gl::ShaderLibrary& shaders,
                    int subdivisionLevel) {
    static std::atomic<std::uint64_t> serials{0};
    std::unique_ptr<GpuDeformer> d(new GpuDeformer());
    d->mModel = &model;
    d->mSerial = ++serials;
    d->mLevel = subdivisionLevel;
    if (subdivisionLevel < 0 || subdivisionLevel > core::limits::kMaxSubdivisionLevel)
        return core::Error{"deform::GpuDeformer::create(): subdivision level " +
                           std::to_string(subdivisionLevel) + " is outside 0.." +
                           std::to_string(core::limits::kMaxSubdivisionLevel)};
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
        auto gatherProgram = gl::Program::compute(shaders, "deform/corner_gather.comp.glsl");
        if (!gatherProgram)
            return core::Error{"deform::GpuDeformer::create(): " + gatherProgram.error().message};
        d->mGather = std::move(*gatherProgram);
        auto e = std::make_unique<Evaluators>();
        const OpenSubdiv::Osd::BufferDescriptor none;
        e->refine.reset(Evaluators::Evaluator::Create(e->cagePosition, e->packed3, none, none));
        e->limit.reset(
            Evaluators::Evaluator::Create(e->packed3, e->packed3, e->packed3, e->packed3));
        e->faceVarying.reset(Evaluators::Evaluator::Create(e->cageTangent, e->packed4, none, none));
        e->scalar.reset(Evaluators::Evaluator::Create(e->packed1, e->packed1, none, none));
        if (!e->refine || !e->limit || !e->faceVarying || !e->scalar)
            return core::Error{"deform::GpuDeformer::create(): OpenSubdiv's GL compute "
                               "evaluator did not compile"};
        d->mEvaluators = std::move(e);
    }

    d->mStatic.resize(model.meshes.size());
    for (int node : model.meshNodes()) {
        const scene::Node& n = model.nodes[std::size_t(node)];
        auto& statics = d->mStatic[std::size_t(n.mesh)];
        const scene::Mesh& mesh = model.meshes[std::size_t(n.mesh)];
        if (statics.empty()) {
            for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
                const scene::Primitive& p = mesh.primitives[pi];
                auto s = std::make_shared<Static>();
                const std::size_t count = p.vertexCount();
                std::vector<VertexGpu> rest(count);
                for (std::size_t v = 0; v < count; ++v)
                    rest[v] = {glm::vec4(p.positions[v], 1.0f), glm::vec4(p.normals[v], 0.0f),
                               p.tangents.empty() ? glm::vec4(1, 0, 0, 1) : p.tangents[v]};
                s->rest = gl::Buffer(std::span<const VertexGpu>(rest));
                std::vector<InfluenceGpu> influences(p.isSkinned() ? count : 1);
                for (std::size_t v = 0; p.isSkinned() && v < count; ++v) {
                    influences[v].joints0 = p.joints[0][v];
                    influences[v].weights0 = p.weights[0][v];
                    if (p.influenceSets() > 1) {
                        influences[v].joints1 = p.joints[1][v];
                        influences[v].weights1 = p.weights[1][v];
                    }
                }
                s->influences = gl::Buffer(std::span<const InfluenceGpu>(influences));
                s->targetCount = std::uint32_t(p.targets.size());
                std::vector<glm::vec4> deltas(
                    std::max<std::size_t>(1, p.targets.size() * count * 3), glm::vec4(0.0f));
                for (std::size_t t = 0; t < p.targets.size(); ++t) {
                    const scene::MorphTarget& target = p.targets[t];
                    for (std::size_t v = 0; v < count; ++v) {
                        glm::vec4* out = &deltas[(t * count + v) * 3];
                        if (!target.positions.empty())
                            out[0] = glm::vec4(target.positions[v], 0.0f);
                        if (!target.normals.empty())
                            out[1] = glm::vec4(target.normals[v], 0.0f);
                        if (!target.tangents.empty())
                            out[2] = glm::vec4(target.tangents[v], 0.0f);
                    }
                }
                s->deltas = gl::Buffer(std::span<const glm::vec4>(deltas));
                s->indices = gl::Buffer(std::span<const std::uint32_t>(p.indices));
                std::vector<glm::vec2> uv =
                    p.uv0.empty() ? std::vector<glm::vec2>(count, glm::vec2(0.0f)) : p.uv0;
                s->uv0 = gl::Buffer(std::span<const glm::vec2>(uv));
                if (subdivisionLevel > 0) {
                    auto sub = buildSubdivision(
                        p, subdivisionLevel,
                        "mesh " + std::to_string(n.mesh) + " '" + mesh.name + "' primitive " +
                            std::to_string(pi));
                    if (!sub)
                        return sub.error();
                    s->subdivision = std::make_unique<Subdivision>(std::move(*sub));
                    const Subdivision& sd = *s->subdivision;
                    s->refine = std::make_unique<GpuStencils>(sd.refine);
                    s->limit = std::make_unique<GpuStencils>(sd.limit);
                    s->faceVarying = std::make_unique<GpuStencils>(sd.faceVarying);
                    s->corners = gl::Buffer(std::span<const RefinedCorner>(sd.corners));
                    s->cageIndices = std::move(s->indices);
                    s->indices = gl::Buffer(std::span<const std::uint32_t>(sd.rest.indices));
                    s->uv0 = gl::Buffer(std::span<const glm::vec2>(sd.rest.uv0));
                }
                statics.push_back(std::move(s));
            }
        }
        GpuInstance instance;
        instance.node = node;
        instance.mesh = n.mesh;
        std::vector<Refined> refined;
        for (std::size_t i = 0; i < mesh.primitives.size(); ++i) {
            const scene::Primitive& p = mesh.primitives[i];
            const Static& s = *statics[i];
            GpuPrimitive gp;
            gp.source = &p;
            gp.topology = s.subdivision ? &s.subdivision->rest : &p;
            gp.vertexCount = std::uint32_t(gp.topology->vertexCount());
            gp.indexCount = std::uint32_t(gp.topology->indices.size());
            gp.deformed = gl::Buffer(gp.vertexCount * sizeof(VertexGpu));
            gp.uv0 = &s.uv0;
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
                r.scalarRefined = gl::Buffer(vertices * sizeof(float));
                r.scalarLimit = gl::Buffer(vertices * sizeof(float));
                refined.push_back(std::move(r));
            }
        }
        if (subdivisionLevel > 0)
            d->mRefined.push_back(std::move(refined));
        const std::size_t joints = n.skin >= 0 ? model.skins[std::size_t(n.skin)].joints.size() : 1;
        d->mSkinMatrices.emplace_back(joints * sizeof(glm::mat4));
        d->mMorphWeights.emplace_back(std::max<std::size_t>(1, mesh.morphTargetCount()) *
                                      sizeof(float));
        d->mInstances.push_back(std::move(instance));
    }
    return d;
}

void GpuDeformer::update(const anim::Pose& pose) {
    const scene::Model& model = *mModel;
    mDeform.use();
    for (std::size_t i = 0; i < mInstances.size(); ++i) {
        GpuInstance& instance = mInstances[i];
        const scene::Node& node = model.nodes[std::size_t(instance.node)];
        instance.meshToWorld = glm::mat4(pose.world[std::size_t(instance.node)]);
        const bool skinned = node.skin >= 0;
        if (skinned) {
            anim::skinMatrices(model, pose, instance.node, mScratchMatrices);
            mSkinMatrices[i].update(std::span<const glm::mat4>(mScratchMatrices));
        }
        const auto& weights = pose.weights[std::size_t(instance.node)];
        if (!weights.empty()) {
            mScratchWeights.assign(weights.begin(), weights.end());
            mMorphWeights[i].update(std::span<const float>(mScratchWeights));
        }
        gl::bindStorage(3, mMorphWeights[i]);
        gl::bindStorage(4, mSkinMatrices[i]);
        for (std::size_t p = 0; p < instance.primitives.size(); ++p) {
            GpuPrimitive& gp = instance.primitives[p];
            const Static& s = *mStatic[std::size_t(instance.mesh)][p];
            gl::bindStorage(0, s.rest);
            gl::bindStorage(1, s.influences);
            gl::bindStorage(2, s.deltas);
            gl::bindStorage(5, mLevel > 0 ? mRefined[i][p].cage : gp.deformed);
            mDeform.set("uVertexCount", int(gp.source->vertexCount()));
            mDeform.set("uTargetCount", int(std::min<std::size_t>(s.targetCount, weights.size())));
            mDeform.set("uSkinned", skinned && gp.source->isSkinned() ? 1 : 0);
            gl::dispatch(groups(gp.source->vertexCount()));
        }
    }
    if (mLevel > 0) {
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
        for (GpuInstance& instance : mInstances)
            for (GpuPrimitive& gp : instance.primitives) {
                if (!gp.source->flatNormals)
                    continue;
                gl::bindStorage(5, gp.deformed);
                gl::bindStorage(6, *gp.indices);
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
            for (std::size_t p = 0; p < mInstances[i].primitives.size(); ++p)
                f(*mStatic[std::size_t(mInstances[i].mesh)][p], mRefined[i][p],
                  mInstances[i].primitives[p]);
    };
    const OpenSubdiv::Osd::BufferDescriptor none;
    each([&](const Static& s, Refined& r, GpuPrimitive&) {
        const GpuStencils& t = *s.refine;
        e.refine->EvalStencils(r.cage.id(), e.cagePosition, r.refined.id(), e.packed3, 0, none, 0,
                               none, t.sizes.id(), t.offsets.id(), t.indices.id(),
                               t.weights.id(), 0, 0, 0, t.count);
        const GpuStencils& fv = *s.faceVarying;
        e.faceVarying->EvalStencils(r.cage.id(), e.cageTangent, r.tangents.id(), e.packed4, 0,
                                    none, 0, none, fv.sizes.id(), fv.offsets.id(),
                                    fv.indices.id(), fv.weights.id(), 0, 0, 0, fv.count);
    });
    gl::memoryBarrier(gl::BarrierStorage);
    each([&](const Static& s, Refined& r, GpuPrimitive&) {
        const GpuStencils& t = *s.limit;
        e.limit->EvalStencils(r.refined.id(), e.packed3, r.limit.id(), e.packed3, r.du.id(),
                              e.packed3, r.dv.id(), e.packed3, t.sizes.id(), t.offsets.id(),
                              t.indices.id(), t.weights.id(), t.duWeights.id(),
                              t.dvWeights.id(), 0, t.count);
    });
    gl::memoryBarrier(gl::BarrierStorage);
    mPack.use();
    each([&](const Static& s, Refined& r, GpuPrimitive& gp) {
        gl::bindStorage(0, s.corners);
        gl::bindStorage(1, r.limit);
        gl::bindStorage(2, r.du);
        gl::bindStorage(3, r.dv);
        gl::bindStorage(4, r.tangents);
        gl::bindStorage(5, gp.deformed);
        mPack.set("uCornerCount", int(gp.vertexCount));
        mPack.set("uFlipNormals", s.subdivision->flipNormals ? 1 : 0);
        gl::dispatch(groups(gp.vertexCount));
    });
    gl::memoryBarrier(gl::BarrierStorage | gl::BarrierVertex);
}

GpuDeformer::Cage GpuDeformer::cage(std::size_t i, std::size_t p) const {
    const GpuPrimitive& gp = mInstances.at(i).primitives.at(p);
    if (mLevel == 0)
        return {gp.deformed, *gp.indices};
    return {mRefined.at(i).at(p).cage,
            mStatic.at(std::size_t(mInstances[i].mesh)).at(p)->cageIndices};
}

void GpuDeformer::refineScalar(std::size_t i, std::size_t p, const gl::Buffer& cageValues,
                               const gl::Buffer& drawnValues) const {
    ENGINE_CHECK(mLevel > 0, "GpuDeformer::refineScalar() needs a subdivision level");
    const GpuPrimitive& gp = mInstances.at(i).primitives.at(p);
    const Static& s = *mStatic.at(std::size_t(mInstances[i].mesh)).at(p);
    const Refined& r = mRefined.at(i).at(p);
    const Evaluators& e = *mEvaluators;
    const OpenSubdiv::Osd::BufferDescriptor none;
    const GpuStencils& t = *s.refine;
    e.scalar->EvalStencils(cageValues.id(), e.packed1, r.scalarRefined.id(), e.packed1, 0, none, 0,
                           none, t.sizes.id(), t.offsets.id(), t.indices.id(), t.weights.id(), 0,
                           0, 0, t.count);
    gl::memoryBarrier(gl::BarrierStorage);
    const GpuStencils& l = *s.limit;
    e.scalar->EvalStencils(r.scalarRefined.id(), e.packed1, r.scalarLimit.id(), e.packed1, 0, none,
                           0, none, l.sizes.id(), l.offsets.id(), l.indices.id(), l.weights.id(),
                           0, 0, 0, l.count);
    gl::memoryBarrier(gl::BarrierStorage);
    mGather.use();
    gl::bindStorage(0, s.corners);
    gl::bindStorage(1, r.scalarLimit);
    gl::bindStorage(2, drawnValues);
    mGather.set("uCornerCount", int(gp.vertexCount));
    gl::dispatch(groups(gp.vertexCount));
    gl::memoryBarrier(gl::BarrierStorage | gl::BarrierVertex);
}

const Subdivision* GpuDeformer::subdivision(std::size_t i, std::size_t p) const {
    return mStatic.at(std::size_t(mInstances.at(i).mesh)).at(p)->subdivision.get();
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
    return unpack(gp.deformed, gp.vertexCount);
}

DeformedPrimitive GpuDeformer::downloadCage(std::size_t i, std::size_t p) const {
    const GpuPrimitive& gp = mInstances.at(i).primitives.at(p);
    return unpack(mLevel > 0 ? mRefined.at(i).at(p).cage : gp.deformed,
                  gp.source->vertexCount());
}

} // namespace deform
