// The viewer's camera: orbits a target (drag), pans it (shift- or right-drag), zooms (wheel),
// frames a character's bounds and returns to that framing.
#pragma once

#include "engine/render/Camera.h"
#include "engine/scene/World.h"

#include <glm/glm.hpp>

namespace viewer {

/** Where the camera is: on a sphere of `distance` around `target`, at `azimuth` about +y from
 *  +z and `elevation` above the horizon (radians). */
struct Orbit {
    glm::vec3 target{0.0f};
    float distance = 3.0f;
    float azimuth = 0.0f;
    float elevation = 0.15f;
};

class OrbitCamera {
public:
    /** Frames `bounds` (the whole clip's) and makes that framing the one reset() returns to. */
    void frame(const render::Bounds& bounds, float aspect);
    void reset() { mOrbit = mHome; }

    /** A drag of `pixels` in a viewport `viewportHeight` pixels high: a full-height drag turns
     *  the camera by pi about the target; elevation stays within +-89 degrees. */
    void orbit(glm::vec2 pixels, float viewportHeight);
    /** Moves the target with the cursor: the point under it stays under it at the target's depth.
     */
    void pan(glm::vec2 pixels, float viewportHeight);
    /** Wheel steps: each multiplies the distance by 0.9 (in) or 1/0.9 (out), within limits set
     *  by the framed radius. */
    void zoom(float steps);

    render::Camera camera(float aspect) const;

    const Orbit& orbitState() const { return mOrbit; }
    void setOrbit(const Orbit& orbit);
    float yfov() const { return mYfov; }

    /** Looks from `camera.position` at `camera.target` with its field of view (a scene file's
     *  camera, or a file's camera where it stands). */
    void look(const scene::WorldCamera& camera);
    /** Where the camera stands and looks, as a scene file keeps it. */
    scene::WorldCamera placement() const;

private:
    Orbit mOrbit, mHome;
    float mRadius = 1.0f;
    float mYfov = 0.7f;
};

} // namespace viewer
