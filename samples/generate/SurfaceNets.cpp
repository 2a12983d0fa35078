// Surface nets: a vertex per grid cell an implicit surface crosses, a quad per crossed grid
// edge, the vertices pulled onto the surface.
#include "SurfaceNets.h"

#include <algorithm>
#include <array>

namespace generate {

using glm::dvec3;
namespace {

/** The field sampled on a grid of points `h` apart from `lo`. */
struct Grid {
    glm::ivec3 n; ///< points per axis
    dvec3 lo;
    double h;
    std::vector<double> value;
    std::size_t at(int x, int y, int z) const {
        return (std::size_t(z) * std::size_t(n.y) + std::size_t(y)) * std::size_t(n.x) +
               std::size_t(x);
    }
};

/** A vertex per cell the surface crosses, at the mean of its edges' crossings, into `s`;
 *  returns each cell's vertex (by its lowest corner), -1 where it has none. */
std::vector<int> cellVertices(const Grid& g, Surface& s) {
    std::vector<int> cellVertex(g.value.size(), -1);
    for (int z = 0; z + 1 < g.n.z; ++z)
        for (int y = 0; y + 1 < g.n.y; ++y)
            for (int x = 0; x + 1 < g.n.x; ++x) {
                std::array<double, 8> v{};
                int inside = 0;
                for (int c = 0; c < 8; ++c) {
                    v[std::size_t(c)] = g.value[g.at(x + (c & 1), y + (c >> 1 & 1), z + (c >> 2))];
                    inside += v[std::size_t(c)] < 0.0;
                }
                if (inside == 0 || inside == 8)
                    continue;
                dvec3 sum(0.0);
                int crossings = 0;
                for (int c = 0; c < 8; ++c)
                    for (int bit : {1, 2, 4}) {
                        if (c & bit)
                            continue;
                        const double v0 = v[std::size_t(c)], v1 = v[std::size_t(c | bit)];
                        if ((v0 < 0.0) == (v1 < 0.0))
                            continue;
                        const dvec3 c0(c & 1, c >> 1 & 1, c >> 2);
                        const dvec3 c1((c | bit) & 1, (c | bit) >> 1 & 1, (c | bit) >> 2);
                        sum += c0 + (c1 - c0) * (v0 / (v0 - v1));
                        ++crossings;
                    }
                cellVertex[g.at(x, y, z)] = int(s.positions.size());
                s.positions.push_back(g.lo + (dvec3(x, y, z) + sum / double(crossings)) * g.h);
            }
    return cellVertex;
}

/** A quad per grid edge the surface crosses, over the four cells around the edge. */
std::vector<std::array<std::uint32_t, 4>> crossedQuads(const Grid& g,
                                                       const std::vector<int>& cellVertex) {
    std::vector<std::array<std::uint32_t, 4>> quads;
    for (int z = 1; z + 1 < g.n.z; ++z)
        for (int y = 1; y + 1 < g.n.y; ++y)
            for (int x = 1; x + 1 < g.n.x; ++x)
                for (int axis = 0; axis < 3; ++axis) {
                    glm::ivec3 p(x, y, z), e(0);
                    e[axis] = 1;
                    const glm::ivec3 q = p + e;
                    if ((g.value[g.at(p.x, p.y, p.z)] < 0.0) ==
                        (g.value[g.at(q.x, q.y, q.z)] < 0.0))
                        continue;
                    glm::ivec3 u(0), w(0);
                    u[(axis + 1) % 3] = 1;
                    w[(axis + 2) % 3] = 1;
                    std::array<std::uint32_t, 4> quad{};
                    const std::array<glm::ivec3, 4> cells{p - u - w, p - w, p, p - u};
                    for (std::size_t i = 0; i < 4; ++i)
                        quad[i] =
                            std::uint32_t(cellVertex[g.at(cells[i].x, cells[i].y, cells[i].z)]);
                    quads.push_back(quad);
                }
    return quads;
}

/** Two triangles per quad over the shorter diagonal, wound counter-clockwise from outside. */
void triangulate(const std::vector<std::array<std::uint32_t, 4>>& quads, Surface& s) {
    for (const auto& q : quads) {
        const auto& P = s.positions;
        const bool diagonal02 = glm::distance(P[q[0]], P[q[2]]) <= glm::distance(P[q[1]], P[q[3]]);
        const std::array<std::array<std::uint32_t, 3>, 2> triangles =
            diagonal02 ? std::array<std::array<std::uint32_t, 3>, 2>{{{q[0], q[1], q[2]},
                                                                      {q[0], q[2], q[3]}}}
                       : std::array<std::array<std::uint32_t, 3>, 2>{
                             {{q[0], q[1], q[3]}, {q[1], q[2], q[3]}}};
        for (auto t : triangles) {
            const dvec3 normal = glm::cross(P[t[1]] - P[t[0]], P[t[2]] - P[t[0]]);
            if (glm::dot(normal, s.normals[t[0]] + s.normals[t[1]] + s.normals[t[2]]) < 0.0)
                std::swap(t[1], t[2]);
            s.indices.insert(s.indices.end(), t.begin(), t.end());
        }
    }
}

} // namespace

glm::dvec3 gradient(const std::function<double(const dvec3&)>& f, const dvec3& p) {
    constexpr double e = 1e-5;
    return dvec3(f(p + dvec3(e, 0, 0)) - f(p - dvec3(e, 0, 0)),
                 f(p + dvec3(0, e, 0)) - f(p - dvec3(0, e, 0)),
                 f(p + dvec3(0, 0, e)) - f(p - dvec3(0, 0, e))) /
           (2.0 * e);
}

Surface surfaceNets(const std::function<double(const glm::dvec3&)>& f, glm::dvec3 lo, glm::dvec3 hi,
                    double h) {
    Grid g{glm::ivec3(glm::ceil((hi - lo) / h)) + 1, lo, h, {}};
    g.value.resize(std::size_t(g.n.x) * std::size_t(g.n.y) * std::size_t(g.n.z));
    for (int z = 0; z < g.n.z; ++z)
        for (int y = 0; y < g.n.y; ++y)
            for (int x = 0; x < g.n.x; ++x)
                g.value[g.at(x, y, z)] = f(lo + dvec3(x, y, z) * h);
    Surface s;
    const std::vector<std::array<std::uint32_t, 4>> quads = crossedQuads(g, cellVertices(g, s));
    // Pull each vertex onto the surface (Newton steps along the gradient), then its normal.
    for (dvec3& p : s.positions)
        for (int i = 0; i < 4; ++i) {
            const dvec3 d = gradient(f, p);
            p -= f(p) * d / std::max(glm::dot(d, d), 1e-12);
        }
    for (const dvec3& p : s.positions)
        s.normals.push_back(glm::normalize(gradient(f, p)));
    triangulate(quads, s);
    return s;
}

} // namespace generate
