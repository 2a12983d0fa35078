// GPU deformation: static per-primitive buffers, per-instance per-frame uploads, dispatches.
#include "engine/deform/GpuDeformer.h"

#include "engine/gl/Commands.h"

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

} // namespace

struct GpuDeformer::Static {
    gl::Buffer rest, influences, deltas, indices, uv0;
    std::uint32_t targetCount = 0;
};

core::Result<std::unique_ptr<GpuDeformer>> GpuDeformer::create(const scene::Model& model,
                                                               const gl::ShaderLibrary& shaders) {
    std::unique_ptr<GpuDeformer> d(new GpuDeformer());
    d->mModel = &model;
    auto deformProgram = gl::Program::compute(shaders, "deform/deform.comp.glsl");
    if (!deformProgram)
        return core::Error{"deform::GpuDeformer::create(): " + deformProgram.error().message};
    auto flatProgram = gl::Program::compute(shaders, "deform/flat_normals.comp.glsl");
    if (!flatProgram)
        return core::Error{"deform::GpuDeformer::create(): " + flatProgram.error().message};
    d->mDeform = std::move(*deformProgram);
    d->mFlatNormals = std::move(*flatProgram);

    d->mStatic.resize(model.meshes.size());
    for (int node : model.meshNodes()) {
        const scene::Node& n = model.nodes[std::size_t(node)];
        auto& statics = d->mStatic[std::size_t(n.mesh)];
        const scene::Mesh& mesh = model.meshes[std::size_t(n.mesh)];
        if (statics.empty()) {
            for (const scene::Primitive& p : mesh.primitives) {
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
                statics.push_back(std::move(s));
            }
        }
        GpuInstance instance;
        instance.node = node;
        instance.mesh = n.mesh;
        for (std::size_t i = 0; i < mesh.primitives.size(); ++i) {
            const scene::Primitive& p = mesh.primitives[i];
            GpuPrimitive gp;
            gp.source = &p;
            gp.vertexCount = std::uint32_t(p.vertexCount());
            gp.indexCount = std::uint32_t(p.indices.size());
            gp.deformed = gl::Buffer(p.vertexCount() * sizeof(VertexGpu));
            gp.uv0 = &statics[i]->uv0;
            gp.indices = &statics[i]->indices;
            instance.primitives.push_back(std::move(gp));
        }
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
            gl::bindStorage(5, gp.deformed);
            mDeform.set("uVertexCount", int(gp.vertexCount));
            mDeform.set("uTargetCount", int(std::min<std::size_t>(s.targetCount, weights.size())));
            mDeform.set("uSkinned", skinned && gp.source->isSkinned() ? 1 : 0);
            gl::dispatch(groups(gp.vertexCount));
        }
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

DeformedPrimitive GpuDeformer::download(std::size_t i, std::size_t p) const {
    const GpuPrimitive& gp = mInstances.at(i).primitives.at(p);
    const std::vector<std::uint8_t> bytes = gp.deformed.download();
    std::vector<VertexGpu> vertices(gp.vertexCount);
    std::memcpy(vertices.data(), bytes.data(), vertices.size() * sizeof(VertexGpu));
    DeformedPrimitive out;
    for (const VertexGpu& v : vertices) {
        out.positions.emplace_back(glm::vec3(v.position));
        out.normals.emplace_back(glm::vec3(v.normal));
        out.tangents.emplace_back(glm::vec4(v.tangent));
    }
    return out;
}

} // namespace deform
