// Loop refinement of a triangle primitive with OpenSubdiv: weld, refine uniformly, stencil
// tables for the refined vertices, their limit and the face-varying values; the rest mesh.
#include "engine/deform/Subdivision.h"

#include "engine/core/Limits.h"

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/osd/cpuEvaluator.h>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstring>
#include <memory>
#include <unordered_map>

namespace deform {
namespace {

using namespace OpenSubdiv;

// OpenSubdiv reports through global callbacks that print by default; keep this thread's last
// error for the message we return. Its warnings (e.g. a non-manifold edge, which it refines
// anyway) are not errors of ours and are dropped.
thread_local std::string tLastOsdMessage;

void recordError(Far::ErrorType, const char* message) {
    tLastOsdMessage = message;
}
void ignoreWarning(const char*) {}

/** A sparse combination of source vertices: the primvar PrimvarRefiner::Limit() accumulates
 *  when asked for the limit masks themselves rather than limit values. */
struct Combination {
    std::vector<std::pair<int, float>> terms;
    void Clear() { terms.clear(); }
    void AddWithWeight(const Combination& source, float weight) {
        for (const auto& [index, w] : source.terms)
            terms.emplace_back(index, w * weight);
    }
};

/** TEXCOORD_0 (xy) and TEXCOORD_1 (zw) of a face-varying value. */
struct Uv {
    glm::vec4 value{0.0f};
    void Clear() { value = glm::vec4(0.0f); }
    void AddWithWeight(const Uv& source, float weight) { value += weight * source.value; }
};

/** Far::StencilTable's arrays as our Stencils, source indices mapped through `sourceIndex`
 *  (empty: unchanged). */
Stencils copyTable(const Far::StencilTableReal<float>& table,
                   const std::vector<std::uint32_t>& sourceIndex) {
    Stencils s;
    s.sizes = table.GetSizes();
    s.offsets = table.GetOffsets();
    s.indices = table.GetControlIndices();
    s.weights = table.GetWeights();
    if (!sourceIndex.empty())
        for (int& i : s.indices)
            i = int(sourceIndex[std::size_t(i)]);
    return s;
}

struct Vec3Key {
    std::uint32_t x, y, z;
    bool operator==(const Vec3Key&) const = default;
};
struct Vec3KeyHash {
    std::size_t operator()(const Vec3Key& k) const {
        return std::size_t(k.x) * 73856093u ^ std::size_t(k.y) * 19349663u ^
               std::size_t(k.z) * 83492791u;
    }
};

Vec3Key keyOf(glm::vec3 p) {
    p += glm::vec3(0.0f); // -0 and +0 weld
    Vec3Key k;
    std::memcpy(&k.x, &p.x, 4);
    std::memcpy(&k.y, &p.y, 4);
    std::memcpy(&k.z, &p.z, 4);
    return k;
}

/** The cage OpenSubdiv refines: the triangles over the vertices welded by position (their
 *  representatives kept in `sub`), each corner's face-varying value its own vertex. A triangle
 *  with two corners welded together is counted in `sub` and left out. */
struct Cage {
    std::vector<int> faceVertices, faceValues;
};

Cage weldedCage(const scene::Primitive& primitive, Subdivision& sub) {
    std::vector<int> welded(primitive.vertexCount());
    std::unordered_map<Vec3Key, int, Vec3KeyHash> index;
    for (std::size_t v = 0; v < primitive.vertexCount(); ++v) {
        const auto [it, added] =
            index.emplace(keyOf(primitive.positions[v]), int(sub.representative.size()));
        if (added)
            sub.representative.push_back(std::uint32_t(v));
        welded[v] = it->second;
    }
    Cage cage;
    for (std::size_t t = 0; t < primitive.triangleCount(); ++t) {
        const std::uint32_t* c = &primitive.indices[3 * t];
        const int a = welded[c[0]], b = welded[c[1]], d = welded[c[2]];
        if (a == b || b == d || a == d) {
            ++sub.degenerateTriangles;
            continue;
        }
        cage.faceVertices.insert(cage.faceVertices.end(), {a, b, d});
        cage.faceValues.insert(cage.faceValues.end(), {int(c[0]), int(c[1]), int(c[2])});
    }
    return cage;
}

std::string osdDetail() {
    return tLastOsdMessage.empty() ? "" : ": " + tLastOsdMessage;
}

/** The cage refined uniformly to `level` by Loop's scheme (boundaries sharp at the edges only,
 *  face-varying values linear at the corners only), the last level's full topology kept for
 *  the limit masks. */
core::Result<std::unique_ptr<Far::TopologyRefiner>>
refineTopology(Cage& cage, int values, int vertices, int level, const std::string& where) {
    const int faceCount = int(cage.faceVertices.size() / 3);
    std::vector<int> verticesPerFace(std::size_t(faceCount), 3);
    Far::TopologyDescriptor::FVarChannel channel;
    channel.numValues = values;
    channel.valueIndices = cage.faceValues.data();
    Far::TopologyDescriptor descriptor;
    descriptor.numVertices = vertices;
    descriptor.numFaces = faceCount;
    descriptor.numVertsPerFace = verticesPerFace.data();
    descriptor.vertIndicesPerFace = cage.faceVertices.data();
    descriptor.numFVarChannels = 1;
    descriptor.fvarChannels = &channel;

    Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    sdc.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_CORNERS_ONLY);
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    Far::SetErrorCallback(recordError);
    Far::SetWarningCallback(ignoreWarning);
    tLastOsdMessage.clear();
    std::unique_ptr<Far::TopologyRefiner> refiner(
        Factory::Create(descriptor, Factory::Options(Sdc::SCHEME_LOOP, sdc)));
    if (!refiner)
        return core::Error{where + "OpenSubdiv rejects the topology" + osdDetail()};
    Far::TopologyRefiner::UniformOptions uniform(level);
    uniform.fullTopologyInLastLevel = true; // the limit masks need the last level's neighbours
    refiner->RefineUniform(uniform);
    return refiner;
}

/** The stencils from the cage to the last level's vertices and face-varying values. */
core::Status stencilTables(const Far::TopologyRefiner& refiner, Subdivision& sub,
                           const std::string& where) {
    // The float factory template itself: Far::StencilTableFactory::Create() downcasts what it
    // returns to a StencilTable it never constructed (undefined behaviour UBSan reports).
    using TableFactory = Far::StencilTableFactoryReal<float>;
    TableFactory::Options options;
    options.generateIntermediateLevels = false;
    options.generateOffsets = true;
    std::unique_ptr<const Far::StencilTableReal<float>> vertexTable(
        TableFactory::Create(refiner, options));
    options.interpolationMode = TableFactory::INTERPOLATE_FACE_VARYING;
    std::unique_ptr<const Far::StencilTableReal<float>> valueTable(
        TableFactory::Create(refiner, options));
    if (!vertexTable || !valueTable)
        return core::Error{where + "OpenSubdiv built no stencil table" + osdDetail()};
    sub.refine = copyTable(*vertexTable, sub.representative);
    sub.faceVarying = copyTable(*valueTable, {});
    return {};
}

/** The limit masks of the last level's `count` vertices (PrimvarRefiner::Limit() over unit
 *  combinations): per vertex, the position's, du's and dv's merged into one stencil over the
 *  union of their vertices. */
Stencils limitStencils(const Far::PrimvarRefiner& primvars, int count) {
    const std::size_t n = std::size_t(count);
    std::vector<Combination> unit(n), position(n), du(n), dv(n);
    for (int v = 0; v < count; ++v)
        unit[std::size_t(v)].terms = {{v, 1.0f}};
    primvars.Limit(unit, position, du, dv);
    Stencils s;
    std::vector<int> order;
    for (std::size_t v = 0; v < n; ++v) {
        order.clear();
        for (const Combination* c : {&position[v], &du[v], &dv[v]})
            for (const auto& term : c->terms)
                order.push_back(term.first);
        std::sort(order.begin(), order.end());
        order.erase(std::unique(order.begin(), order.end()), order.end());
        s.offsets.push_back(int(s.indices.size()));
        s.sizes.push_back(int(order.size()));
        const std::size_t base = s.weights.size();
        s.indices.insert(s.indices.end(), order.begin(), order.end());
        s.weights.resize(base + order.size(), 0.0f);
        s.duWeights.resize(base + order.size(), 0.0f);
        s.dvWeights.resize(base + order.size(), 0.0f);
        auto accumulate = [&](const Combination& c, std::vector<float>& weights) {
            for (const auto& [index, w] : c.terms) {
                const auto at = std::lower_bound(order.begin(), order.end(), index);
                weights[base + std::size_t(at - order.begin())] += w;
            }
        };
        accumulate(position[v], s.weights);
        accumulate(du[v], s.duWeights);
        accumulate(dv[v], s.dvWeights);
    }
    return s;
}

/** The output vertices, one per (refined vertex, face-varying value) a refined face uses, into
 *  `sub.corners`; returns the refined faces' indices into them. */
std::vector<std::uint32_t> refinedCorners(const Far::TopologyLevel& last, Subdivision& sub) {
    std::unordered_map<std::uint64_t, std::uint32_t> cornerIndex;
    std::vector<std::uint32_t> indices;
    indices.reserve(std::size_t(last.GetNumFaces()) * 3);
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        const Far::ConstIndexArray vertices = last.GetFaceVertices(f);
        const Far::ConstIndexArray values = last.GetFaceFVarValues(f);
        for (int k = 0; k < 3; ++k) {
            const RefinedCorner corner{std::uint32_t(vertices[k]), std::uint32_t(values[k])};
            const std::uint64_t key = std::uint64_t(corner.vertex) << 32 | corner.faceVarying;
            const auto [it, added] = cornerIndex.emplace(key, std::uint32_t(sub.corners.size()));
            if (added)
                sub.corners.push_back(corner);
            indices.push_back(it->second);
        }
    }
    return indices;
}

glm::vec3 vec3At(const std::vector<float>& a, std::size_t i) {
    return glm::vec3(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
}

/** The limit face-varying values (TEXCOORD_0 in xy, TEXCOORD_1 in zw) of the last level. */
std::vector<Uv> limitUvs(const scene::Primitive& primitive, const Subdivision& sub,
                         const Far::PrimvarRefiner& primvars, int count) {
    std::vector<Uv> values(static_cast<std::size_t>(count));
    std::vector<float> uvs(primitive.vertexCount() * 4);
    for (std::size_t v = 0; v < primitive.vertexCount(); ++v)
        std::memcpy(&uvs[4 * v], glm::value_ptr(primitive.uvs(v)), 4 * sizeof(float));
    const Evaluated refinedUv = evaluateOnCpu(sub.faceVarying, uvs.data(), 0, 4, 4);
    std::vector<Uv> refinedValues(values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
        refinedValues[i].value = glm::make_vec4(&refinedUv.values[4 * i]);
    primvars.LimitFaceVarying(refinedValues, values);
    return values;
}

/** Per refined vertex, the sum of its refined faces' normals (by their winding, area
 *  weighted). */
std::vector<glm::vec3> faceNormalSums(const Far::TopologyLevel& last,
                                      const std::vector<float>& refined) {
    std::vector<glm::vec3> sums(std::size_t(last.GetNumVertices()), glm::vec3(0.0f));
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        const Far::ConstIndexArray v = last.GetFaceVertices(f);
        const glm::vec3 a = vec3At(refined, std::size_t(v[0])),
                        b = vec3At(refined, std::size_t(v[1])),
                        c = vec3At(refined, std::size_t(v[2]));
        const glm::vec3 n = glm::cross(b - a, c - a);
        for (int k = 0; k < 3; ++k)
            sums[std::size_t(v[k])] += n;
    }
    return sums;
}

/** The rest mesh: the stencils applied to the rest cage, as the GPU will apply them, with
 *  du x dv turned to agree with the refined faces' winding over the whole mesh. */
void restMesh(const scene::Primitive& primitive, const Far::TopologyRefiner& refiner, int level,
              std::vector<std::uint32_t> indices, Subdivision& sub) {
    const Far::TopologyLevel& last = refiner.GetLevel(level);
    std::vector<float> restCage(primitive.vertexCount() * 3);
    std::memcpy(restCage.data(), primitive.positions.data(), restCage.size() * sizeof(float));
    const Evaluated refined = evaluateOnCpu(sub.refine, restCage.data(), 0, 3, 3);
    const Evaluated limit = evaluateOnCpu(sub.limit, refined.values.data(), 0, 3, 3);
    const std::vector<Uv> values =
        limitUvs(primitive, sub, Far::PrimvarRefiner(refiner), last.GetNumFVarValues());
    const std::vector<glm::vec3> faceNormalSum = faceNormalSums(last, refined.values);
    double agreement = 0.0;
    for (std::size_t v = 0; v < faceNormalSum.size(); ++v)
        agreement +=
            glm::dot(glm::cross(vec3At(limit.du, v), vec3At(limit.dv, v)), faceNormalSum[v]) > 0.0f
                ? 1.0
                : -1.0;
    sub.flipNormals = agreement < 0.0;

    scene::Primitive& rest = sub.rest;
    rest.material = primitive.material;
    rest.variantMaterials = primitive.variantMaterials;
    rest.indices = std::move(indices);
    for (const RefinedCorner& c : sub.corners) {
        const glm::vec3 du = vec3At(limit.du, c.vertex), dv = vec3At(limit.dv, c.vertex);
        glm::vec3 n = sub.flipNormals ? glm::cross(dv, du) : glm::cross(du, dv);
        if (glm::length(n) <= 0.0f)
            n = faceNormalSum[c.vertex];
        rest.positions.push_back(vec3At(limit.values, c.vertex));
        rest.normals.push_back(glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 0, 1));
        rest.uv0.push_back(glm::vec2(values[c.faceVarying].value));
        if (!primitive.uv1.empty())
            rest.uv1.push_back(
                glm::vec2(values[c.faceVarying].value.z, values[c.faceVarying].value.w));
    }
}

} // namespace

core::Result<Subdivision> buildSubdivision(const scene::Primitive& primitive, int level,
                                           const std::string& what) {
    const std::string where = "deform::buildSubdivision(): " + what + ": ";
    if (level < 1 || level > core::limits::kMaxSubdivisionLevel)
        return core::Error{where + "level " + std::to_string(level) + " is outside 1.." +
                           std::to_string(core::limits::kMaxSubdivisionLevel)};
    const std::size_t refinedTriangles = primitive.triangleCount() << (2 * level);
    if (refinedTriangles > core::limits::kMaxRefinedTriangles)
        return core::Error{where + std::to_string(primitive.triangleCount()) +
                           " triangles refine to " + std::to_string(refinedTriangles) +
                           " at level " + std::to_string(level) + ", over the limit of " +
                           std::to_string(core::limits::kMaxRefinedTriangles)};
    Subdivision sub;
    Cage cage = weldedCage(primitive, sub);
    if (cage.faceVertices.empty())
        return core::Error{where + "no triangle with three distinct corners"};
    auto refiner = refineTopology(cage, int(primitive.vertexCount()),
                                  int(sub.representative.size()), level, where);
    if (!refiner)
        return refiner.error();
    if (auto tables = stencilTables(**refiner, sub, where); !tables)
        return tables.error();
    const Far::TopologyLevel& last = (*refiner)->GetLevel(level);
    sub.limit = limitStencils(Far::PrimvarRefiner(**refiner), last.GetNumVertices());
    if (!tLastOsdMessage.empty())
        return core::Error{where + "OpenSubdiv: " + tLastOsdMessage};
    restMesh(primitive, **refiner, level, refinedCorners(last, sub), sub);
    return sub;
}

RefinedSurface refineCage(const Subdivision& sub, std::span<const glm::dvec3> positions,
                          std::span<const glm::dvec4> tangents) {
    std::vector<float> cage(positions.size() * 3);
    for (std::size_t v = 0; v < positions.size(); ++v)
        for (int k = 0; k < 3; ++k)
            cage[3 * v + std::size_t(k)] = float(positions[v][k]);
    const Evaluated refined = evaluateOnCpu(sub.refine, cage.data(), 0, 3, 3);
    const Evaluated limit = evaluateOnCpu(sub.limit, refined.values.data(), 0, 3, 3);
    Evaluated tangentValues;
    if (!tangents.empty()) {
        std::vector<float> t(tangents.size() * 4);
        for (std::size_t v = 0; v < tangents.size(); ++v)
            for (int k = 0; k < 4; ++k)
                t[4 * v + std::size_t(k)] = float(tangents[v][k]);
        tangentValues = evaluateOnCpu(sub.faceVarying, t.data(), 0, 4, 4);
    }
    auto at3 = [](const std::vector<float>& a, std::size_t i) {
        return glm::dvec3(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
    };
    RefinedSurface out;
    for (const RefinedCorner& c : sub.corners) {
        const glm::dvec3 du = at3(limit.du, c.vertex), dv = at3(limit.dv, c.vertex);
        glm::dvec3 n = sub.flipNormals ? glm::cross(dv, du) : glm::cross(du, dv);
        n = glm::dot(n, n) > 1e-30 ? glm::normalize(n) : glm::dvec3(0.0, 0.0, 1.0);
        out.positions.push_back(at3(limit.values, c.vertex));
        out.normals.push_back(n);
        if (tangents.empty())
            continue;
        const float* t = &tangentValues.values[4 * std::size_t(c.faceVarying)];
        glm::dvec3 tangent = glm::dvec3(t[0], t[1], t[2]);
        tangent -= n * glm::dot(n, tangent);
        if (glm::dot(tangent, tangent) < 1e-20)
            tangent = std::abs(n.x) < 0.9 ? glm::cross(n, glm::dvec3(1, 0, 0))
                                          : glm::cross(n, glm::dvec3(0, 1, 0));
        out.tangents.emplace_back(glm::normalize(tangent), t[3] < 0.0f ? -1.0 : 1.0);
    }
    return out;
}

Evaluated evaluateOnCpu(const Stencils& stencils, const float* source, int offset, int width,
                        int stride) {
    Evaluated out;
    const int count = int(stencils.count());
    out.values.assign(std::size_t(count) * std::size_t(width), 0.0f);
    const Osd::BufferDescriptor sourceDesc(offset, width, stride), packed(0, width, width);
    if (stencils.duWeights.empty()) {
        Osd::CpuEvaluator::EvalStencils(source, sourceDesc, out.values.data(), packed,
                                        stencils.sizes.data(), stencils.offsets.data(),
                                        stencils.indices.data(), stencils.weights.data(), 0, count);
        return out;
    }
    out.du.assign(out.values.size(), 0.0f);
    out.dv.assign(out.values.size(), 0.0f);
    Osd::CpuEvaluator::EvalStencils(
        source, sourceDesc, out.values.data(), packed, out.du.data(), packed, out.dv.data(), packed,
        stencils.sizes.data(), stencils.offsets.data(), stencils.indices.data(),
        stencils.weights.data(), stencils.duWeights.data(), stencils.dvWeights.data(), 0, count);
    return out;
}

} // namespace deform
