// OpenSubdiv refinement of deforming meshes: the GPU (GL compute evaluator) against OpenSubdiv's
// CPU evaluator on the same deformed cage, the refined topology, UV seams, errors.
#include "support/GlTest.h"
#include "support/TestSupport.h"

#include "engine/anim/Pose.h"
#include "engine/asset/GltfLoader.h"
#include "engine/deform/GpuDeformer.h"
#include "engine/deform/Subdivision.h"

#include <map>

namespace {

const std::filesystem::path kFigure =
    std::filesystem::path(GLASS_SOURCE_DIR) / "assets/models/glass_figure.glb";

glm::vec3 at3(const std::vector<float>& a, std::size_t i) {
    return {a[3 * i], a[3 * i + 1], a[3 * i + 2]};
}

class Subdivision : public test::GlTest {
protected:
    /** Deforms `model` at `time` with refinement `level` and compares every primitive's
     *  refined positions and normals with OpenSubdiv's CPU evaluator run on the GPU's own
     *  deformed cage. Returns the number of refined vertices compared. */
    std::size_t compareWithCpu(const scene::Model& model, int level, double time) {
        auto deformer = deform::GpuDeformer::create(model, shaders(), level);
        EXPECT_TRUE(deformer.ok()) << deformer.error().message;
        if (!deformer)
            return 0;
        (*deformer)->update(anim::evaluate(model, model.animations.empty() ? -1 : 0, time));
        std::size_t compared = 0;
        for (std::size_t i = 0; i < (*deformer)->instances().size(); ++i)
            for (std::size_t p = 0; p < (*deformer)->instances()[i].primitives.size(); ++p) {
                SCOPED_TRACE(model.sourceName + " instance " + std::to_string(i) + " primitive " +
                             std::to_string(p));
                const deform::Subdivision* sub = (*deformer)->subdivision(i, p);
                EXPECT_NE(sub, nullptr);
                if (!sub)
                    continue;
                const auto cage = (*deformer)->downloadCage(i, p);
                std::vector<float> cagePositions;
                for (const glm::dvec3& v : cage.positions)
                    cagePositions.insert(cagePositions.end(),
                                         {float(v.x), float(v.y), float(v.z)});
                const auto refined =
                    deform::evaluateOnCpu(sub->refine, cagePositions.data(), 0, 3, 3);
                const auto limit = deform::evaluateOnCpu(sub->limit, refined.values.data(), 0, 3, 3);
                const auto gpu = (*deformer)->download(i, p);
                EXPECT_EQ(gpu.positions.size(), sub->corners.size());
                glm::dvec3 lo(1e30), hi(-1e30);
                for (const glm::dvec3& v : cage.positions) {
                    lo = glm::min(lo, v);
                    hi = glm::max(hi, v);
                }
                const double diagonal = glm::length(hi - lo);
                double position = 0.0, normal = 0.0;
                for (std::size_t c = 0; c < sub->corners.size(); ++c) {
                    const std::size_t v = sub->corners[c].vertex;
                    position = std::max<double>(
                        position, glm::length(glm::dvec3(at3(limit.values, v)) - gpu.positions[c]) / diagonal);
                    glm::vec3 n = glm::cross(at3(limit.du, v), at3(limit.dv, v));
                    n = glm::normalize(sub->flipNormals ? -n : n);
                    normal = std::max<double>(normal, glm::length(glm::dvec3(n) - gpu.normals[c]));
                }
                EXPECT_LE(position, 1e-5);
                EXPECT_LE(normal, 1e-3);
                compared += sub->corners.size();
            }
        return compared;
    }
};

TEST_F(Subdivision, Level2OnTheGpuMatchesOpenSubdivsCpuEvaluatorOnTheDeformedFigure) {
    auto model = asset::loadGltf(kFigure);
    ASSERT_TRUE(model.ok()) << model.error().message;
    ASSERT_FALSE(model->animations.empty());
    const double duration = model->animations[0].duration;
    for (double time : {0.0, 0.4 * duration, 0.9 * duration})
        EXPECT_GT(compareWithCpu(*model, 2, time), 100000u);
}

TEST_F(Subdivision, Level2MatchesOnCesiumMan) {
    GLASS_REQUIRE_SHARED();
    auto model = asset::loadGltf(test::sharedDir() / "assets/gltf/CesiumMan/CesiumMan.glb");
    ASSERT_TRUE(model.ok()) << model.error().message;
    EXPECT_GT(compareWithCpu(*model, 2, 0.7), 30000u);
}

TEST_F(Subdivision, RefinedFigureIsWatertightWithOutwardNormalsAtEveryLevel) {
    auto model = asset::loadGltf(kFigure);
    ASSERT_TRUE(model.ok());
    const scene::Primitive& body = model->meshes[0].primitives[0];
    for (int level = 1; level <= 2; ++level) {
        SCOPED_TRACE("level " + std::to_string(level));
        auto sub = deform::buildSubdivision(body, level, "figure body");
        ASSERT_TRUE(sub.ok()) << sub.error().message;
        EXPECT_EQ(sub->rest.triangleCount(),
                  (body.triangleCount() - sub->degenerateTriangles) << (2 * level));
        // Every edge between refined vertices (not corners: seams split those) has two faces.
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
        const auto& idx = sub->rest.indices;
        for (std::size_t t = 0; t < idx.size(); t += 3)
            for (int k = 0; k < 3; ++k) {
                std::uint32_t a = sub->corners[idx[t + k]].vertex,
                              b = sub->corners[idx[t + (k + 1) % 3]].vertex;
                ++edges[{std::min(a, b), std::max(a, b)}];
            }
        for (const auto& [edge, faces] : edges)
            ASSERT_EQ(faces, 2) << "edge " << edge.first << "-" << edge.second;
        // Limit normals agree with the refined faces' winding.
        std::vector<glm::vec3> faceSum(sub->rest.vertexCount(), glm::vec3(0.0f));
        for (std::size_t t = 0; t < idx.size(); t += 3) {
            const glm::vec3 a = sub->rest.positions[idx[t]], b = sub->rest.positions[idx[t + 1]],
                            c = sub->rest.positions[idx[t + 2]];
            for (int k = 0; k < 3; ++k)
                faceSum[idx[t + k]] += glm::cross(b - a, c - a);
        }
        std::size_t agree = 0;
        for (std::size_t v = 0; v < faceSum.size(); ++v)
            agree += glm::dot(faceSum[v], sub->rest.normals[v]) > 0.0f;
        EXPECT_EQ(agree, faceSum.size());
    }
}

TEST_F(Subdivision, UvSeamsSplitCornersButNotPositions) {
    GLASS_REQUIRE_SHARED();
    auto model = asset::loadGltf(test::sharedDir() / "assets/gltf/CesiumMan/CesiumMan.glb");
    ASSERT_TRUE(model.ok());
    const scene::Primitive& p = model->meshes[0].primitives[0];
    auto sub = deform::buildSubdivision(p, 2, "CesiumMan");
    ASSERT_TRUE(sub.ok()) << sub.error().message;
    // The file splits vertices at seams: welding finds fewer cage vertices than it has.
    EXPECT_LT(sub->representative.size(), p.vertexCount());
    std::size_t refinedVertices = 0;
    for (const auto& c : sub->corners)
        refinedVertices = std::max<std::size_t>(refinedVertices, c.vertex + 1);
    EXPECT_GT(sub->corners.size(), refinedVertices); // seam corners: one per side
    // Corners of one refined vertex share its position; their UVs differ only across a seam,
    // and every UV stays within the file's UV range.
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const glm::vec2& uv : p.uv0) {
        lo = glm::min(lo, uv);
        hi = glm::max(hi, uv);
    }
    std::map<std::uint32_t, glm::vec3> positionOf;
    for (std::size_t c = 0; c < sub->corners.size(); ++c) {
        const auto [it, added] = positionOf.emplace(sub->corners[c].vertex, sub->rest.positions[c]);
        EXPECT_EQ(it->second, sub->rest.positions[c]);
        const glm::vec2 uv = sub->rest.uv0[c];
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(uv, lo - 1e-4f)) &&
                    glm::all(glm::lessThanEqual(uv, hi + 1e-4f)))
            << "corner " << c;
    }
}

TEST_F(Subdivision, BadLevelsAndDegenerateMeshesAreErrorsNamingThePrimitive) {
    auto model = asset::loadGltf(kFigure);
    ASSERT_TRUE(model.ok());
    auto tooDeep = deform::GpuDeformer::create(*model, shaders(), 5);
    ASSERT_FALSE(tooDeep.ok());
    EXPECT_NE(tooDeep.error().message.find("subdivision level 5 is outside 0..4"),
              std::string::npos);
    scene::Primitive flat;
    flat.positions = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f)};
    flat.normals.assign(3, glm::vec3(0, 0, 1));
    flat.indices = {0, 1, 2};
    auto degenerate = deform::buildSubdivision(flat, 1, "mesh 3 'sliver' primitive 1");
    ASSERT_FALSE(degenerate.ok());
    EXPECT_NE(degenerate.error().message.find("mesh 3 'sliver' primitive 1: no triangle"),
              std::string::npos)
        << degenerate.error().message;
}

} // namespace
