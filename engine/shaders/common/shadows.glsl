// What a light's shadow maps say of a point: the opaque casters' depth atlas (compared, filtered
// over the light's radius in texels) and the glass's, which holds along each of the light's rays
// the glass's optical depth (RGB: -ln of what it lets through) and its nearest distance (A), so
// that light through glass arrives tinted; and the caustics a plugin focused, which hold the
// light the glass refracted onto the receiver each texel sees (RGB, a share of the light that
// would reach it unblocked; A under NO_GLASS where focused). A receiver behind glass takes only
// the focused light; one in the open takes it on top of the light's own (docs/materials.md,
// "Shadows" and "Caustics"). Included by common/lighting.glsl; the atlases are bound by
// render::bindShadowMaps (the caustics by the plugin that focuses them).
#ifndef COMMON_SHADOWS_GLSL
#define COMMON_SHADOWS_GLSL

layout(binding = SHADOW_DEPTH_UNIT) uniform sampler2DShadow uShadowDepth;
layout(binding = SHADOW_GLASS_UNIT) uniform sampler2D uShadowGlass;
layout(binding = SHADOW_CAUSTICS_UNIT) uniform sampler2D uShadowCaustics;
// Whether the point being shaded receives the caustics: true for opaque surfaces and the
// ground; glass shading clears it around its own lights (its highlights take the light
// straight through the glass, as the reference's do).
bool gCausticReceiver = true;

// The view of `light` that sees P: its first, or for a point light the cube face of P.
int shadowView(PunctualLight light, vec3 P) {
    int view = int(light.cone.y);
    if (int(light.position.w) != LIGHT_POINT)
        return view;
    vec3 d = P - light.position.xyz, a = abs(d);
    if (a.x >= a.y && a.x >= a.z)
        return view + (d.x >= 0.0 ? 0 : 1);
    if (a.y >= a.z)
        return view + (d.y >= 0.0 ? 2 : 3);
    return view + (d.z >= 0.0 ? 4 : 5);
}

// Distance from the light to P along its rays past the near plane (ShadowView::distance).
float shadowDistance(ShadowView view, vec3 P) {
    return (view.texel.y > 0.5 ? distance(P, view.axis.xyz) : dot(view.axis.xyz, P) + view.axis.w) -
           view.texel.z;
}

// One tap of both atlases at `uv` (clamped into the tile): the opaque casters' visibility times
// what the glass in front of P lets through (P farther than the glass's nearest surface by more
// than `texel`, a texel's size at P).
vec3 shadowTap(ShadowView view, vec2 uv, float depth, float distanceToLight, float texel) {
    vec2 halfTexel = 0.5 * view.tile.zw / view.texel.w;
    vec2 lo = view.tile.xy + halfTexel, hi = view.tile.xy + view.tile.zw - halfTexel;
    uv = clamp(uv, lo, hi);
    float lit = texture(uShadowDepth, vec3(uv, depth));
    if (lit <= 0.0)
        return vec3(0.0);
    vec4 glass = textureLod(uShadowGlass, uv, 0.0);
    // The glass in front of P (a receiver behind the glass's nearest surface along the ray).
    bool behindGlass = distanceToLight > glass.a + 2.0 * texel;
    // A receiver where a plugin focused caustics takes the focused light, and the light's own
    // where no glass is in front.
    vec4 caustic = textureLod(uShadowCaustics, uv, 0.0);
    if (gCausticReceiver && caustic.a < NO_GLASS)
        return lit * (caustic.rgb + (behindGlass ? 0.0 : 1.0));
    return behindGlass ? lit * exp(-max(glass.rgb, vec3(0.0))) : vec3(lit);
}

// What reaches P (normal N, unit L toward the light) of `light` past its casters: 1 unshadowed.
vec3 lightShadow(PunctualLight light, vec3 P, vec3 N, vec3 L) {
    if (light.cone.y < 0.0)
        return vec3(1.0);
    ShadowView view = shadowViews[shadowView(light, P)];
    float softness = light.cone.z;
    // Offset along the normal toward the light by a few texels at P: no acne on lit slopes.
    float distanceToLight = shadowDistance(view, P);
    float texel = view.texel.x * (view.texel.y > 0.5 ? distanceToLight + view.texel.z : 1.0);
    vec3 Nl = dot(N, L) < 0.0 ? -N : N;
    vec3 offset = P + (Nl * (1.5 + softness) + L * 0.5) * texel;
    vec4 clip = view.viewProjection * vec4(offset, 1.0);
    if (clip.w <= 0.0)
        return vec3(1.0);
    vec3 ndc = clip.xyz / clip.w;
    if (any(greaterThan(abs(ndc.xy), vec2(1.0))))
        return vec3(1.0); // outside the map: no caster there
    vec2 uv = view.tile.xy + (ndc.xy * 0.5 + 0.5) * view.tile.zw;
    float depth = min(ndc.z * 0.5 + 0.5, 1.0); // receivers past the far plane meet its clear
    if (softness <= 0.0)
        return shadowTap(view, uv, depth, distanceToLight, texel);
    // A 3 x 3 grid of filtered taps over the radius: a tent of about 2 * softness texels.
    vec3 sum = vec3(0.0);
    vec2 step = softness * view.tile.zw / view.texel.w;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x)
            sum += shadowTap(view, uv + vec2(x, y) * step, depth, distanceToLight, texel);
    return sum / 9.0;
}

#endif
