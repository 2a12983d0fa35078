// Shadow views and the atlas they share (engine/render/Shadows.h).
#include "engine/render/Shadows.h"

#include "engine/core/Limits.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace render {
namespace {

/** The eight corners of `b`. */
std::array<glm::vec3, 8> corners(const Bounds& b) {
    std::array<glm::vec3, 8> c;
    for (int i = 0; i < 8; ++i)
        c[std::size_t(i)] = glm::vec3(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y,
                                      i & 4 ? b.max.z : b.min.z);
    return c;
}

/** An up vector for a view along `forward` (not parallel to it). */
glm::vec3 upFor(const glm::vec3& forward) {
    return std::abs(forward.y) > 0.99f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
}

/** The near and far distances of a perspective view from `position` that hold `casters`. */
glm::vec2 depthRange(const glm::vec3& position, const Bounds& casters) {
    const glm::vec3 closest = glm::clamp(position, casters.min, casters.max);
    float farthest = 0.0f;
    for (const glm::vec3& c : corners(casters))
        farthest = std::max(farthest, glm::distance(position, c));
    const float radius = std::max(casters.radius(), 1e-3f);
    const float near = std::max(0.9f * glm::distance(position, closest), 1e-3f * radius);
    return {near, std::max(farthest * 1.05f, near * 2.0f)};
}

ShadowView perspectiveView(const glm::vec3& position, const glm::vec3& forward, float fov,
                           const Bounds& casters, int resolution) {
    const glm::vec2 range = depthRange(position, casters);
    ShadowView v;
    v.view = glm::lookAt(position, position + forward, upFor(forward));
    v.projection = glm::perspective(fov, 1.0f, range.x, range.y);
    v.near = range.x;
    v.perspective = true;
    v.texelSize = 2.0f * std::tan(0.5f * fov) / float(resolution);
    return v;
}

/** A directional light's box: its rays' cross-section around the casters, their depth range
 *  and some room behind them for the receivers. */
ShadowView directionalView(const glm::vec3& direction, const Bounds& casters, int resolution) {
    const float radius = std::max(casters.radius(), 1e-3f);
    const glm::vec3 eye = casters.center() - direction * (2.0f * radius);
    ShadowView v;
    v.view = glm::lookAt(eye, casters.center(), upFor(direction));
    Bounds box;
    for (const glm::vec3& c : corners(casters))
        box.add(glm::vec3(v.view * glm::vec4(c, 1.0f)));
    const float margin = 0.02f * radius;
    v.near = std::max(-box.max.z - margin, 1e-3f * radius);
    v.projection = glm::ortho(box.min.x - margin, box.max.x + margin, box.min.y - margin,
                              box.max.y + margin, v.near, -box.min.z + radius);
    v.perspective = false;
    v.texelSize = std::max(box.max.x - box.min.x, box.max.y - box.min.y) / float(resolution);
    return v;
}

/** A tile's side rounded up to a multiple of 4 texels, so that its corner and side stay whole
 *  in an atlas of the same tiles at a half or a quarter of the resolution (a plugin's). */
int wholeTile(int side) {
    return (side + 3) / 4 * 4;
}

/** Places the views' tiles on shelves, largest first, in an atlas at most `limit` wide. */
glm::ivec2 packTiles(std::vector<ShadowView>& views, int limit) {
    std::vector<std::size_t> order(views.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return views[a].tile.z > views[b].tile.z;
    });
    const int largest = views[order.front()].tile.z;
    const int columns = int(std::ceil(std::sqrt(double(views.size()))));
    const int width = std::min(largest * columns, std::max(limit, largest));
    glm::ivec2 cursor(0), size(0);
    int shelf = 0;
    for (std::size_t i : order) {
        glm::ivec3& t = views[i].tile;
        if (cursor.x + t.z > width) {
            cursor = {0, cursor.y + shelf};
            shelf = 0;
        }
        t.x = cursor.x;
        t.y = cursor.y;
        cursor.x += t.z;
        shelf = std::max(shelf, t.z);
        size = glm::max(size, glm::ivec2(cursor.x, cursor.y + shelf));
    }
    return size;
}

} // namespace

std::vector<bool> castingLights(std::span<const scene::PlacedLight> lights) {
    std::vector<bool> casts(lights.size(), false);
    std::size_t count = 0;
    for (std::size_t i = 0; i < lights.size(); ++i)
        if (lights[i].light.shadow.enabled && lights[i].light.intensity > 0.0f &&
            count < core::limits::kMaxShadowedLights) {
            casts[i] = true;
            ++count;
        }
    return casts;
}

ShadowPlan planShadows(std::span<const scene::PlacedLight> lights, const Bounds& casters,
                       int maxTextureSize) {
    ShadowPlan plan;
    plan.firstView.assign(lights.size(), -1);
    if (casters.empty())
        return plan;
    const std::vector<bool> casts = castingLights(lights);
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const scene::PlacedLight& placed = lights[i];
        const scene::Light& light = placed.light;
        if (!casts[i]) {
            plan.overLimit += light.shadow.enabled && light.intensity > 0.0f;
            continue;
        }
        plan.firstView[i] = int(plan.views.size());
        const int resolution =
            wholeTile(std::clamp(light.shadow.resolution, core::limits::kMinShadowResolution,
                                 core::limits::kMaxShadowResolution));
        std::vector<ShadowView> views;
        if (light.type == scene::Light::Type::Directional) {
            views.push_back(directionalView(placed.direction, casters, resolution));
        } else if (light.type == scene::Light::Type::Spot) {
            const float fov = std::min(2.0f * light.outerConeAngle + 0.02f, 2.97f);
            views.push_back(
                perspectiveView(placed.position, placed.direction, fov, casters, resolution));
        } else {
            // A little over 90 degrees, so that a face's filter finds texels past its edge.
            const float fov = 2.0f * std::atan(1.0f + 8.0f / float(resolution));
            // In the order common/shadows.glsl's shadowView() picks them: +x, -x, +y, -y, +z, -z.
            static const glm::vec3 kFaces[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                                {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
            for (const glm::vec3& face : kFaces)
                views.push_back(perspectiveView(placed.position, face, fov, casters, resolution));
        }
        for (ShadowView& v : views) {
            v.light = i;
            v.tile = {0, 0, resolution};
            plan.views.push_back(v);
        }
    }
    if (plan.views.empty())
        return plan;
    for (;;) {
        plan.atlasSize = packTiles(plan.views, maxTextureSize);
        if (plan.atlasSize.x <= maxTextureSize && plan.atlasSize.y <= maxTextureSize)
            break;
        ++plan.halved;
        for (ShadowView& v : plan.views) {
            const int side = std::max(wholeTile(v.tile.z / 2), 16);
            v.texelSize *= float(v.tile.z) / float(side);
            v.tile.z = side;
        }
    }
    return plan;
}

} // namespace render
