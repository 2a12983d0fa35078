// Built-in analytic models and the loader front door.
#include "engine/asset/ModelLoader.h"

#include <charconv>
#include <cmath>

namespace asset {

namespace {

/** A one-node model of `primitive` in the built-in clear glass (IOR 1.5). */
scene::Model glassModel(const std::string& name, scene::Primitive primitive) {
    primitive.sourceVertexCount = primitive.positions.size();
    primitive.material = 0;
    scene::Model model;
    model.sourceName = "builtin:" + name;
    scene::Material glass;
    glass.name = name + " glass";
    glass.baseColorFactor = glm::vec4(1.0f);
    glass.metallicFactor = 0.0f;
    glass.roughnessFactor = 0.0f;
    glass.hasTransmission = true;
    glass.transmissionFactor = 1.0f;
    glass.hasIor = true;
    glass.ior = 1.5f;
    glass.hasVolume = true;
    model.materials.push_back(glass);
    scene::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(std::move(primitive));
    model.meshes.push_back(std::move(mesh));
    scene::Node node;
    node.name = name;
    node.mesh = 0;
    model.nodes.push_back(node);
    model.scenes.push_back({0});
    model.defaultScene = 0;
    return model;
}

} // namespace

scene::Model makeSphere(int segments) {
    const int longitudes = segments, latitudes = segments / 2;
    scene::Primitive p;
    // The seam's column (lon = longitudes) and each pole's row repeat a point exactly, so that
    // the surface reads as closed (scene::isClosed): sin(pi) and sin(2 pi) are not 0 in doubles.
    for (int lat = 0; lat <= latitudes; ++lat) {
        const double theta = M_PI * double(lat) / double(latitudes);
        const double sinTheta = lat == 0 || lat == latitudes ? 0.0 : std::sin(theta);
        for (int lon = 0; lon <= longitudes; ++lon) {
            const double phi = 2.0 * M_PI * double(lon % longitudes) / double(longitudes);
            const glm::vec3 n(float(sinTheta * std::cos(phi)), float(std::cos(theta)),
                              float(-sinTheta * std::sin(phi)));
            p.positions.push_back(n);
            p.normals.push_back(n);
            p.tangents.emplace_back(float(-std::sin(phi)), 0.0f, float(-std::cos(phi)), 1.0f);
            p.uv0.emplace_back(float(lon) / float(longitudes), float(lat) / float(latitudes));
        }
    }
    const auto index = [&](int lat, int lon) {
        return std::uint32_t(lat * (longitudes + 1) + lon);
    };
    for (int lat = 0; lat < latitudes; ++lat)
        for (int lon = 0; lon < longitudes; ++lon) {
            const std::uint32_t a = index(lat, lon), b = index(lat + 1, lon),
                                c = index(lat + 1, lon + 1), d = index(lat, lon + 1);
            if (lat > 0)
                p.indices.insert(p.indices.end(), {a, b, d});
            if (lat + 1 < latitudes)
                p.indices.insert(p.indices.end(), {d, b, c});
        }
    return glassModel("sphere", std::move(p));
}

scene::Model makeBox() {
    scene::Primitive p;
    // Per face: its normal and two in-face axes u, v (u x v = normal: counter-clockwise outside).
    const glm::vec3 normals[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                  {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    for (const glm::vec3& n : normals) {
        const glm::vec3 u =
            std::abs(n.y) > 0.5f ? glm::vec3(1, 0, 0) * n.y : glm::vec3(-n.z, 0.0f, n.x);
        const glm::vec3 v = glm::cross(n, u);
        const auto first = std::uint32_t(p.positions.size());
        for (const glm::vec2 corner :
             {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
            p.positions.push_back(n + corner.x * u + corner.y * v);
            p.normals.push_back(n);
            p.tangents.emplace_back(u, 1.0f);
            p.uv0.push_back(corner * 0.5f + 0.5f);
        }
        p.indices.insert(p.indices.end(),
                         {first, first + 1, first + 2, first, first + 2, first + 3});
    }
    return glassModel("box", std::move(p));
}

core::Result<scene::Model> loadModel(const std::string& path, const LoadOptions& options) {
    const std::string prefix = "builtin:sphere";
    if (path.rfind("builtin:", 0) != 0)
        return loadGltf(path, options);
    int segments = 128;
    if (path == "builtin:box")
        return makeBox();
    if (path == prefix)
        return makeSphere(segments);
    const std::string query = prefix + "?segments=";
    if (path.rfind(query, 0) == 0) {
        const char* begin = path.data() + query.size();
        const char* end = path.data() + path.size();
        const auto [ptr, ec] = std::from_chars(begin, end, segments);
        if (ec == std::errc() && ptr == end && segments >= 8 && segments <= 1024)
            return makeSphere(segments);
        return core::Error{"asset::loadModel(): " + path +
                           ": segments must be an integer in 8..1024"};
    }
    return core::Error{"asset::loadModel(): unknown built-in model '" + path +
                       "' (known: builtin:sphere, builtin:sphere?segments=N, builtin:box)"};
}

} // namespace asset
