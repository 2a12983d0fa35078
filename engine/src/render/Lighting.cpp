// Punctual lights placed for a frame and the sheen albedo table (engine/render/Lighting.h).
#include "engine/render/Lighting.h"

#include "engine/anim/Pose.h"
#include "engine/core/Check.h"
#include "engine/core/Limits.h"
#include "engine/gl/Commands.h"
#include "engine/scene/World.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace render {
namespace {

/** One light as common/lighting.glsl's PunctualLight lays it out (std430). */
struct PunctualLightGpu {
    glm::vec4 position;  // w: type
    glm::vec4 direction; // w: range
    glm::vec4 radiance;  // w: cos outer
    glm::vec4 cone;      // x: cos inner, y: first shadow view (-1: none), z: filter radius
};
/** One shadow view as common/shadows.glsl's ShadowView lays it out (std430). */
struct ShadowViewGpu {
    glm::mat4 viewProjection;
    glm::vec4 tile;  // the tile's corner (xy) and sides (zw) in atlas uv
    glm::vec4 axis;  // perspective: the light's position; else the view's row -z (the distance)
    glm::vec4 texel; // x: ShadowView::texelSize, y: 1 for a perspective view, z: its near,
                     // w: the tile's side in texels
};
constexpr std::size_t kTableBytes = sizeof(float) * kSheenTableSize * kSheenTableSize;
constexpr std::size_t kViewsBytes = sizeof(ShadowViewGpu) * kMaxShadowViews;
// The table, the counts (a uvec4), the views, then the lights.
constexpr std::size_t kHeaderBytes = kTableBytes + 16 + kViewsBytes;

ShadowViewGpu packView(const ShadowView& v, glm::ivec2 atlas) {
    const glm::vec2 scale = 1.0f / glm::vec2(atlas);
    ShadowViewGpu g;
    g.viewProjection = v.viewProjection();
    // An atlas of several tiles need not be square: a tile's sides in uv differ.
    g.tile = glm::vec4(glm::vec2(v.tile.x, v.tile.y) * scale, float(v.tile.z) * scale);
    // What the shadows' distances along the light's rays are measured from: the light's
    // position, or the plane of its view (-z = dot(axis.xyz, p) + axis.w); less the near plane's.
    g.axis = v.perspective ? glm::vec4(glm::vec3(glm::inverse(v.view)[3]), 0.0f)
                           : -glm::transpose(v.view)[2];
    g.texel = glm::vec4(v.texelSize, v.perspective ? 1.0f : 0.0f, v.near, float(v.tile.z));
    return g;
}

/** The sheen lobe's albedo at NoV and roughness, integrated over half vectors (the lobe is
 *  narrow around half vectors in the tangent plane, which a dense grid in theta resolves). */
double integrateSheenAlbedo(double NoV, double roughness) {
    const double r = std::max(roughness, 0.07), alpha = r * r; // as common/brdf.glsl
    const glm::dvec3 V(std::sqrt(std::max(1.0 - NoV * NoV, 0.0)), 0.0, NoV);
    constexpr int kTheta = 256, kPhi = 64;
    double sum = 0.0;
    for (int i = 0; i < kTheta; ++i) {
        const double theta = (i + 0.5) * (M_PI / 2.0) / kTheta;
        const double sinH = std::sin(theta), cosH = std::cos(theta);
        const double D = (2.0 + 1.0 / alpha) * std::pow(sinH, 1.0 / alpha) / (2.0 * M_PI);
        for (int j = 0; j < kPhi; ++j) {
            const double phi = (j + 0.5) * (2.0 * M_PI) / kPhi;
            const glm::dvec3 H(sinH * std::cos(phi), sinH * std::sin(phi), cosH);
            const double VoH = glm::dot(V, H);
            const glm::dvec3 L = 2.0 * VoH * H - V;
            if (VoH <= 0.0 || L.z <= 0.0)
                continue;
            const double visibility = 1.0 / (4.0 * (L.z + NoV - L.z * NoV));
            // dL = 4 VoH dH, dH = sin(theta) dtheta dphi
            sum += D * visibility * L.z * 4.0 * VoH * sinH;
        }
    }
    return std::clamp(sum * (M_PI / 2.0 / kTheta) * (2.0 * M_PI / kPhi), 0.0, 1.0);
}

} // namespace

const std::array<float, kSheenTableSize * kSheenTableSize>& sheenAlbedoTable() {
    static const auto table = [] {
        std::array<float, kSheenTableSize * kSheenTableSize> t{};
        for (int row = 0; row < kSheenTableSize; ++row)
            for (int col = 0; col < kSheenTableSize; ++col)
                t[std::size_t(row * kSheenTableSize + col)] =
                    float(integrateSheenAlbedo(std::max(double(col) / (kSheenTableSize - 1), 1e-3),
                                               double(row) / (kSheenTableSize - 1)));
        return t;
    }();
    return table;
}

double sheenAlbedo(double NoV, double roughness) {
    const auto& t = sheenAlbedoTable();
    const double x = std::clamp(NoV, 0.0, 1.0) * (kSheenTableSize - 1),
                 y = std::clamp(roughness, 0.0, 1.0) * (kSheenTableSize - 1);
    const int i = std::min(int(x), kSheenTableSize - 2), j = std::min(int(y), kSheenTableSize - 2);
    const double fx = x - i, fy = y - j;
    auto at = [&](int c, int r) { return double(t[std::size_t(r * kSheenTableSize + c)]); };
    const double lo = at(i, j) + (at(i + 1, j) - at(i, j)) * fx;
    const double hi = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * fx;
    return lo + (hi - lo) * fy;
}

std::vector<int> lightNodes(const scene::Model& model) {
    std::vector<int> nodes;
    if (!model.lights.empty())
        for (int node : model.sceneNodes())
            if (model.nodes[std::size_t(node)].light >= 0)
                nodes.push_back(node);
    return nodes;
}

void placeLights(const scene::Model& model, std::span<const int> nodes, const anim::Pose& pose,
                 const glm::dmat4& placement, std::vector<scene::PlacedLight>& out) {
    for (int node : nodes) {
        const int light = model.nodes[std::size_t(node)].light;
        const glm::dmat4 world = placement * pose.world[std::size_t(node)];
        const glm::dvec3 axis(world * glm::dvec4(0.0, 0.0, -1.0, 0.0)); // scale does not count
        out.push_back({anim::lightOf(model, pose, light), glm::vec3(world[3]),
                       glm::length(axis) > 0.0 ? glm::vec3(glm::normalize(axis))
                                               : glm::vec3(0.0f, 0.0f, -1.0f)});
    }
}

std::vector<scene::PlacedLight> worldLights(const scene::World& world, double time) {
    std::vector<scene::PlacedLight> lights;
    for (const scene::Character& character : world.characters)
        if (!character.model->lights.empty())
            placeLights(*character.model, lightNodes(*character.model),
                        anim::evaluate(*character.model, character.performance, time),
                        character.transform(), lights);
    lights.insert(lights.end(), world.lights.begin(), world.lights.end());
    return lights;
}

void LightingBuffer::upload(const std::vector<scene::PlacedLight>& lights,
                            const ShadowPlan& shadows) {
    if (!mBuffer || lights.size() > mCapacity) {
        mCapacity = std::max<std::size_t>(lights.size(), 8);
        mBuffer = gl::Buffer(kHeaderBytes + mCapacity * sizeof(PunctualLightGpu));
        mBuffer.update(0, kTableBytes, sheenAlbedoTable().data());
    }
    // The counts (a uvec4), the views, then the lights, written at once from storage kept
    // across frames.
    ENGINE_CHECK(shadows.views.size() <= kMaxShadowViews, "too many shadow views");
    constexpr std::size_t kLights = 16 + kViewsBytes;
    mStaging.assign(kLights + lights.size() * sizeof(PunctualLightGpu), 0);
    const std::uint32_t count[4] = {std::uint32_t(lights.size()), 0, 0, 0};
    std::memcpy(mStaging.data(), count, sizeof(count));
    for (std::size_t v = 0; v < shadows.views.size(); ++v) {
        const ShadowViewGpu packed = packView(shadows.views[v], shadows.atlasSize);
        std::memcpy(mStaging.data() + 16 + v * sizeof(ShadowViewGpu), &packed, sizeof(packed));
    }
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const scene::PlacedLight& l = lights[i];
        const PunctualLightGpu packed{
            glm::vec4(l.position, float(int(l.light.type))), // w: LIGHT_* (render/Shared.h)
            glm::vec4(l.direction, l.light.range),
            glm::vec4(l.light.color * l.light.intensity, std::cos(l.light.outerConeAngle)),
            glm::vec4(std::cos(l.light.innerConeAngle),
                      i < shadows.firstView.size() ? float(shadows.firstView[i]) : -1.0f,
                      l.light.shadow.softness, 0.0f)};
        std::memcpy(mStaging.data() + kLights + i * sizeof(PunctualLightGpu), &packed,
                    sizeof(packed));
    }
    mBuffer.update(kTableBytes, mStaging.size(), mStaging.data());
    gl::bindStorage(gl::slot::kLighting, mBuffer);
}

} // namespace render
