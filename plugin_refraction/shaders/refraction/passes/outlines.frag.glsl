// After the walk, over the glass rectangle and one pixel around it: the outlines of smooth glass
// anti-aliased. A pixel's colour is what its centre sees; where a glass surface's outline
// crosses the pixel, part of it sees the surface and part what lies behind. Near an outline of a
// smooth surface the part of its normal across the line of sight grows about linearly on screen
// and reaches length 1 at the outline: extrapolated from the nearest layer's normals of two
// pixels it places the outline to a fraction of a pixel, and the surface's share of each pixel
// it crosses follows (a straight edge through a pixel box). The rest of the pixel takes the
// colour of the neighbour across the outline. Creases (a pane's edge) are left as they are.
// What it reads of each pixel's nearest layer the shading pass wrote (outSurface); a pixel
// whose colour's alpha is negative took the fresh samples, which anti-alias it already.
layout(binding = SCENE_COLOR_UNIT) uniform sampler2D uColor; // the shaded frame
// per pixel, packed: the nearest layer's depth, glass, part across
layout(binding = OUTLINE_SURFACE_UNIT) uniform usampler2D uSurface;
uniform vec2 uViewportSize;
out vec4 outColor;

const float kSameSurface = 0.05; // neighbours on one surface: depths within 5%
const float kNone = NO_DEPTH;

// Pixel p's nearest layer (walk.frag.glsl): x its depth (kNone: none), y its glass id,
// z the part across.
vec3 nearestSurface(ivec2 p) {
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, ivec2(uViewportSize))))
        return vec3(kNone, -1.0, 0.0);
    uint s = texelFetch(uSurface, p, 0).x;
    if (s == 0u)
        return vec3(kNone, -1.0, 0.0);
    float along = float(s >> 24) / 255.0;
    return vec3(unpackHalf2x16(s & 0xFFFFu).x, float((s >> 16) & 255u), sqrt(1.0 - along * along));
}

bool sameSurface(vec3 a, vec3 b) {
    return a.x < kNone && b.x < kNone && a.y == b.y &&
           abs(a.x - b.x) <= kSameSurface * min(a.x, b.x);
}

const ivec2 kSteps[4] = ivec2[](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));

// The outline of surface s (on pixel p), its neighbours nb (along kSteps), as a line on
// screen: the unit direction toward it and its distance from p's centre in pixels. False where
// no smooth outline is near.
bool outlineNear(vec3 s, vec3 nb[4], out vec2 toward, out float distance) {
    vec2 gradient = vec2(0.0);
    for (int axis = 0; axis < 2; ++axis) {
        // One-sided difference toward the side that is still on the surface.
        int after = 2 * axis, before = after + 1;
        if (sameSurface(s, nb[before]))
            gradient[axis] = s.z - nb[before].z;
        else if (sameSurface(s, nb[after]))
            gradient[axis] = nb[after].z - s.z;
    }
    float slope = length(gradient);
    toward = slope > 0.0 ? gradient / slope : vec2(0.0);
    distance = slope > 0.0 ? (1.0 - s.z) / slope : 1.0e9;
    return s.z > 0.6 && slope > 0.01 && distance < 1.5;
}

// The share of a pixel box whose centre lies `distance` (signed, inside positive) from a
// straight edge with normal `toward`.
float coverage(float distance, vec2 toward) {
    return clamp(0.5 + distance / max(abs(toward.x) + abs(toward.y), 1.0), 0.0, 1.0);
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 color = texelFetch(uColor, p, 0);
    outColor = vec4(color.rgb, 1.0);
    if (color.a < 0.0) { // a pixel that took the fresh samples (walk_motion.glsl): anti-aliased
        outColor.a = color.a; // by them; the resolve reads how many
        return;
    }
    vec3 s = nearestSurface(p), nb[4];
    // Most pixels: the four neighbours' nearest depths agree with the pixel's.
    int nearer = -1; // the neighbour on the nearest surface in front of the pixel's
    float nearest = s.x;
    bool outline = false;
    for (int i = 0; i < 4; ++i) {
        nb[i] = nearestSurface(p + kSteps[i]);
        float z = s.x, zq = nb[i].x;
        bool apart = min(z, zq) < kNone && abs(zq - z) > kSameSurface * min(z, zq);
        outline = outline || apart;
        if (apart && zq < nearest) {
            nearest = zq;
            nearer = i;
        }
    }
    if (!outline)
        return;
    // On a surface whose outline crosses the pixel: the colour behind it is the neighbours'
    // across the outline (off the surface, behind it).
    vec2 toward;
    float distance;
    if (s.x < kNone && outlineNear(s, nb, toward, distance)) {
        vec3 behind = vec3(0.0);
        float weight = 0.0;
        for (int i = 0; i < 4; ++i) {
            float share = max(dot(vec2(kSteps[i]), toward), 0.0);
            if (share > 0.0 && !sameSurface(s, nb[i]) && nb[i].x > s.x) {
                behind += share * texelFetch(uColor, p + kSteps[i], 0).rgb;
                weight += share;
            }
        }
        if (weight > 0.0)
            outColor.rgb = mix(behind / weight, color.rgb, coverage(distance, toward));
        return;
    }
    // Off it, next to a nearer surface whose outline crosses the pixel: that surface's share.
    if (nearer < 0)
        return;
    ivec2 q = p + kSteps[nearer];
    vec3 qb[4];
    for (int i = 0; i < 4; ++i)
        qb[i] = i == (nearer ^ 1) ? s : nearestSurface(q + kSteps[i]);
    if (outlineNear(nb[nearer], qb, toward, distance)) {
        float share = coverage(distance + dot(vec2(kSteps[nearer]), toward), toward);
        outColor.rgb = mix(color.rgb, texelFetch(uColor, q, 0).rgb, share);
    }
}
