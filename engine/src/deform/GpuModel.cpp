// The upload of a model: static per-primitive buffers and subdivision tables, once per model.
#include "GpuModelData.h"

#include "engine/core/Limits.h"

namespace deform {
namespace {

/** Both texture coordinate sets of every vertex (scene::Primitive::uvs). */
std::vector<glm::vec4> packUvs(const scene::Primitive& p) {
    std::vector<glm::vec4> uvs(p.vertexCount());
    for (std::size_t v = 0; v < uvs.size(); ++v)
        uvs[v] = p.uvs(v);
    return uvs;
}

std::unique_ptr<GpuModel::Primitive> upload(const scene::Primitive& p) {
    auto s = std::make_unique<GpuModel::Primitive>();
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
    s->closed = scene::isClosed(p);
    std::vector<glm::vec4> deltas(std::max<std::size_t>(1, p.targets.size() * count * 3),
                                  glm::vec4(0.0f));
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
    s->uvs = gl::Buffer(std::span<const glm::vec4>(packUvs(p)));
    return s;
}

/** Refines `s` (the upload of `p`) to `level`: tables, and the refined mesh's static buffers
 *  in place of the file's (which stay as the cage's indices). */
core::Status refine(GpuModel::Primitive& s, const scene::Primitive& p, int level,
                    const std::string& where) {
    auto sub = buildSubdivision(p, level, where);
    if (!sub)
        return sub.error();
    s.subdivision = std::make_unique<Subdivision>(std::move(*sub));
    const Subdivision& sd = *s.subdivision;
    s.refine = std::make_unique<GpuStencils>(sd.refine);
    s.limit = std::make_unique<GpuStencils>(sd.limit);
    s.faceVarying = std::make_unique<GpuStencils>(sd.faceVarying);
    s.corners = gl::Buffer(std::span<const RefinedCorner>(sd.corners));
    s.cageIndices = std::move(s.indices);
    s.indices = gl::Buffer(std::span<const std::uint32_t>(sd.rest.indices));
    s.uvs = gl::Buffer(std::span<const glm::vec4>(packUvs(sd.rest)));
    return {};
}

} // namespace

GpuModel::~GpuModel() = default;

core::Result<std::shared_ptr<const GpuModel>> GpuModel::create(const scene::Model& model,
                                                               int subdivisionLevel) {
    if (subdivisionLevel < 0 || subdivisionLevel > core::limits::kMaxSubdivisionLevel)
        return core::Error{"deform::GpuModel::create(): subdivision level " +
                           std::to_string(subdivisionLevel) + " is outside 0.." +
                           std::to_string(core::limits::kMaxSubdivisionLevel)};
    std::shared_ptr<GpuModel> m(new GpuModel());
    m->mModel = &model;
    m->mLevel = subdivisionLevel;
    m->mPrimitives.resize(model.meshes.size());
    for (int node : model.meshNodes()) {
        const int meshIndex = model.nodes[std::size_t(node)].mesh;
        auto& primitives = m->mPrimitives[std::size_t(meshIndex)];
        if (!primitives.empty())
            continue; // another node's mesh, uploaded already
        const scene::Mesh& mesh = model.meshes[std::size_t(meshIndex)];
        for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
            const scene::Primitive& p = mesh.primitives[pi];
            auto uploaded = upload(p);
            if (subdivisionLevel > 0)
                if (auto refined = refine(*uploaded, p, subdivisionLevel,
                                          "mesh " + std::to_string(meshIndex) + " '" + mesh.name +
                                              "' primitive " + std::to_string(pi));
                    !refined)
                    return refined.error();
            primitives.push_back(std::move(uploaded));
        }
    }
    return std::shared_ptr<const GpuModel>(std::move(m));
}

const GpuModel::Primitive& GpuModel::primitive(int mesh, std::size_t p) const {
    return *mPrimitives.at(std::size_t(mesh)).at(p);
}

const gl::Buffer& GpuModel::indices(int mesh, std::size_t p) const {
    return primitive(mesh, p).indices;
}

const Subdivision* GpuModel::subdivision(int mesh, std::size_t p) const {
    return primitive(mesh, p).subdivision.get();
}

} // namespace deform
