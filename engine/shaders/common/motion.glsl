// The frame's motion (temporal accumulation, docs/methods.md "Temporal accumulation"): per
// pixel, what it tracks, where that was on the previous frame, and what the resolve checks
// before it reuses the history there. One RGBA32UI texel:
//   x  identity: the kind of what the pixel tracks (bits 24-31, MOTION_*) and which one
//      (bits 0-23: a draw item, a glass id; a path through glass: the glass id it entered);
//      the history must show the same (motionSubject)
//   y  the motion in pixels, this frame's position minus the previous one (two halves)
//   z  the view depth of the tracked point now and on the previous frame (two halves; 0: none,
//      the environment and glass); for a path through glass (MOTION_THROUGH_GLASS) instead the
//      motion of the glass surface it entered (two halves), the resolve's first candidate
//   w  where a path through glass left it: its world direction (octahedral, 16 + 16 bits; 0:
//      none); a jump rejects the history
// The environment seen directly is all zeros (the frame's motion target is cleared to it, and
// the background writes none): its motion is the camera's turn at the pixel (motionAt).
// Positions are measured without the frame's jitter: uMotionViewProjection is this frame's
// unjittered world -> clip, uPreviousViewProjection the previous frame's.
#ifndef COMMON_MOTION_GLSL
#define COMMON_MOTION_GLSL
#include "common/math.glsl"

uniform mat4 uMotionViewProjection;
uniform mat4 uPreviousViewProjection;
uniform mat4 uMotionInverseViewProjection; // this frame's unjittered clip -> world
uniform vec2 uMotionSize; // the frame in pixels
uniform int uWriteMotion;  // the frame accumulates: passes write their pixels' motion

// WRITE_MOTION 0: a program for frames that do not accumulate, every motion write left out (a
// CPU rasteriser runs a branch the uniform turns off); where not given, the uniform decides.
#ifndef WRITE_MOTION
#define WRITE_MOTION 1
#endif
bool writesMotion() {
    return WRITE_MOTION != 0 && uWriteMotion != 0;
}

vec2 clipToPixel(vec4 clip) {
    return (clip.xy / clip.w * 0.5 + 0.5) * uMotionSize;
}

// The motion of a world point that moved from `previous` to `now`.
vec2 pointMotion(vec3 now, vec3 previous) {
    return clipToPixel(uMotionViewProjection * vec4(now, 1.0)) -
           clipToPixel(uPreviousViewProjection * vec4(previous, 1.0));
}

// The motion of what lies infinitely far along a world direction: the camera's turn alone.
vec2 directionMotion(vec3 direction) {
    return clipToPixel(uMotionViewProjection * vec4(direction, 0.0)) -
           clipToPixel(uPreviousViewProjection * vec4(direction, 0.0));
}

uint motionIdentity(uint kind, uint object) {
    return (kind << MOTION_KIND_SHIFT) | (object & MOTION_OBJECT_MASK);
}

uint motionDirection(vec3 direction) {
    return max(packUnorm2x16(octEncode(normalize(direction))), 1u);
}

uvec4 packMotion(uint identity, vec2 motion, float depth, float previousDepth, uint direction) {
    return uvec4(identity, packHalf2x16(clamp(motion, vec2(-8192.0), vec2(8192.0))),
                 packHalf2x16(vec2(depth, previousDepth)), direction);
}

uint motionKind(uvec4 m) {
    return m.x >> MOTION_KIND_SHIFT;
}

// The world direction through `pixel` (a position in pixels) of the unjittered frame.
vec3 pixelDirection(vec2 pixel) {
    vec2 ndc = pixel / uMotionSize * 2.0 - 1.0;
    vec4 far = uMotionInverseViewProjection * vec4(ndc, 1.0, 1.0);
    vec4 near = uMotionInverseViewProjection * vec4(ndc, -1.0, 1.0);
    return normalize(far.xyz / far.w - near.xyz / near.w);
}

vec2 motionPixels(uvec4 m) {
    return unpackHalf2x16(m.y);
}

vec2 motionDepths(uvec4 m) {
    return motionKind(m) == MOTION_THROUGH_GLASS ? vec2(0.0) : unpackHalf2x16(m.z);
}

// The motion of the pixel at `pixel` (its centre, in pixels) whose texel is m.
vec2 motionAt(uvec4 m, vec2 pixel) {
    return m.x == motionIdentity(MOTION_ENVIRONMENT, 0u) ? directionMotion(pixelDirection(pixel))
                                                        : motionPixels(m);
}

// Where the pixel at `pixel` (texel m) may find its history, in the order the resolve tries
// them: by its motion; for a path through glass first by the motion of the glass it entered
// (a moving body carries what it refracts with it: a glass sphere crossing the ground
// accumulated to 36.8 dB, 32.3 by the path's end first, both with the whole pixel's jitter;
// Temporal.AGlassBodyCarriesWhatItRefractsWithIt), then by its end's.
int motionCandidates(uvec4 m, vec2 pixel, out vec2 candidates[2]) {
    bool glass = motionKind(m) == MOTION_THROUGH_GLASS;
    candidates[1] = motionAt(m, pixel);
    candidates[0] = glass ? unpackHalf2x16(m.z) : candidates[1];
    return glass ? 2 : 1;
}

// What the history must show for the resolve to reuse it: the relative depth change that
// counts as a disocclusion, and the turn of a path's exit that counts as a jump: more than a
// right angle, a path that now leaves the glass another way. A bending limb turns the exit of
// its paths by tens of degrees between frames and the clip bounds what that changes; rejecting
// at 15 degrees threw away the history of a tenth of a walking figure's glass (2% at 90) and
// cost every method and scene up to 0.5 dB (docs/accuracy.md;
// Temporal.TheHistoryIsRejectedWhereThePathNowLeavesTheGlassAnotherWay).
const float kDepthTolerance = 0.05;
const float kExitTurn = 0.0;

// What the history must show for a pixel tracking `m`: the same thing, and for a glass pixel
// the same glass, whether its light is reflected or comes through it. What a path through glass
// ends on is no part of it: a bending limb refracts the ground on one frame and the sky on the
// next, and the clip bounds what such a history brings; rejected there too, the history of the
// walking figures' glass was thrown away where it was worth keeping (every playing row scored
// 0.01-0.22 dB less, docs/accuracy.md).
uint motionSubject(uvec4 m) {
    return motionKind(m) == MOTION_THROUGH_GLASS
               ? motionIdentity(MOTION_GLASS, m.x & MOTION_OBJECT_MASK)
               : m.x;
}

// Whether a history texel `h` (the previous frame's motion) shows what a pixel tracking `m`
// tracks: the same subject, no depth jump, no jump in the direction a path through glass left
// it.
bool showsSame(uvec4 m, uvec4 h) {
    if (motionSubject(m) != motionSubject(h))
        return false;
    vec2 d = motionDepths(m), hd = motionDepths(h);
    if (d.y > 0.0 && hd.x > 0.0 && abs(d.y - hd.x) > kDepthTolerance * max(d.y, hd.x))
        return false;
    if (m.w != 0u && h.w != 0u &&
        dot(octDecode(unpackUnorm2x16(m.w)), octDecode(unpackUnorm2x16(h.w))) < kExitTurn)
        return false;
    return true;
}

#endif
