// Engine-owned glTF camera.
#pragma once

namespace scene {

/** A perspective (yfov radians, aspect 0 = use the viewport's, zfar 0 = infinite) or
 *  orthographic (xmag, ymag half-extents) camera looking down -z of its node. */
struct Camera {
    enum class Type { Perspective, Orthographic } type = Type::Perspective;
    double yfov = 0.8, aspectRatio = 0.0, znear = 0.01, zfar = 0.0;
    double xmag = 1.0, ymag = 1.0;
};

} // namespace scene
