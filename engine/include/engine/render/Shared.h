// The render module's numbers its shaders share (gl/Registry.h): the lights' types and the sheen
// table's size (common/lighting.glsl), the material texture slots (common/material_uv.glsl), the
// material layers a shading variant compiles in (common/brdf.glsl), what a pixel's motion tracks
// (common/motion.glsl) and the temporal resolve's debug views. The renderer registers them in its
// shader library as "render".
#pragma once

#include "engine/gl/Registry.h"

#include <span>

#include <cstdint>

namespace render {

/** What a pixel's motion tracks (common/motion.glsl, the identity's high byte: MOTION_*). */
enum class MotionKind : std::uint32_t {
    Environment = 0, ///< the environment: the camera's turn alone
    Ground = 1,      ///< the ground plane (a still world point)
    Opaque = 2,      ///< a draw item (object: its index + 1)
    Glass = 3,       ///< a glass surface itself (a plugin's: its reflection)
    ThroughGlass = 4 ///< what a path through glass ends on (a plugin's)
};
inline constexpr std::uint32_t kMotionKindShift = 24;
inline constexpr std::uint32_t kMotionObjectMask = 0xFFFFFFu;

std::span<const gl::Shared> sharedTable();

} // namespace render
