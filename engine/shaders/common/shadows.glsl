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
#if POINT_LIGHTS
    if (int(light.position.w) == LIGHT_POINT) {
        vec3 d = P - light.position.xyz, a = abs(d);
        if (a.x >= a.y && a.x >= a.z)
            return view + (d.x >= 0.0 ? 0 : 1);
        if (a.y >= a.z)
            return view + (d.y >= 0.0 ? 2 : 3);
        return view + (d.z >= 0.0 ? 4 : 5);
    }
#endif
    return view;
}

// Whether `view` is a perspective one (a point light's or a spot's), as the frame's types of
// light allow.
bool perspective(ShadowView view) {
#if !LOCAL_LIGHTS
    return false;
#elif !DIRECTIONAL_LIGHTS
    return true;
#else
    return view.texel.y > 0.5;
#endif
}

// Distance from the light to P along its rays past the near plane (ShadowView::distance).
float shadowDistance(ShadowView view, vec3 P) {
    return (perspective(view) ? distance(P, view.axis.xyz) : dot(view.axis.xyz, P) + view.axis.w) -
           view.texel.z;
}

// Which parts of the lookup a program compiles (render::LightingFeatures::defines, from what
// the frame's lights and plugins use; a program built without them keeps every part): a
// CPU rasteriser runs every branch of a quad, so a part that is off must be out of the program.
// SHADOW_MAPS: some light casts; SHADOW_SOFT: some casting light filters over a radius;
// SHADOW_GLASS: a plugin drew glass into the glass atlas; SHADOW_CAUSTICS: a plugin focused
// caustics.
#ifndef SHADOW_MAPS
#define SHADOW_MAPS 1
#endif
#ifndef SHADOW_SOFT
#define SHADOW_SOFT 1
#endif
#ifndef SHADOW_GLASS
#define SHADOW_GLASS 1
#endif
#ifndef SHADOW_CAUSTICS
#define SHADOW_CAUSTICS 1
#endif

// The opaque casters' visibility at `uv` (clamped into the tile), a bilinear compared tap.
float shadowVisibility(ShadowView view, vec2 uv, float depth) {
    vec2 halfTexel = 0.5 * view.tile.zw / view.texel.w;
    return texture(uShadowDepth,
                   vec3(clamp(uv, view.tile.xy + halfTexel, view.tile.xy + view.tile.zw - halfTexel),
                        depth));
}

// What the glass and the caustics make of the light that reaches P past the opaque casters,
// read once at the filter's centre `uv`: what the glass in front of P lets through (P farther
// than the glass's nearest surface by more than `texel`, a texel's size at P), or where a
// plugin focused caustics, the focused light plus the light's own where no glass is in front.
vec3 shadowTransmittance(ShadowView view, vec2 uv, float distanceToLight, float texel) {
    vec3 through = vec3(1.0);
#if SHADOW_GLASS || SHADOW_CAUSTICS
    vec2 halfTexel = 0.5 * view.tile.zw / view.texel.w;
    uv = clamp(uv, view.tile.xy + halfTexel, view.tile.xy + view.tile.zw - halfTexel);
    vec4 glass = textureLod(uShadowGlass, uv, 0.0);
    bool behindGlass = distanceToLight > glass.a + 2.0 * texel;
#if SHADOW_GLASS
    if (behindGlass)
        through = exp(-max(glass.rgb, vec3(0.0)));
#endif
#if SHADOW_CAUSTICS
    vec4 caustic = textureLod(uShadowCaustics, uv, 0.0);
    if (gCausticReceiver && caustic.a < NO_GLASS)
        through = caustic.rgb + (behindGlass ? 0.0 : 1.0);
#endif
#endif
    return through;
}

// What reaches P (normal N, unit L toward the light) of `light` past its casters: 1 unshadowed.
vec3 lightShadow(PunctualLight light, vec3 P, vec3 N, vec3 L) {
#if !SHADOW_MAPS || defined(SKIP_SHADOWS) // glass-bench --skip shadows: every light unshadowed
    return vec3(1.0);
#else
    if (light.cone.y < 0.0)
        return vec3(1.0);
    ShadowView view = shadowViews[shadowView(light, P)];
    float softness = light.cone.z;
    // Offset along the normal toward the light by a few texels at P: no acne on lit slopes.
    float distanceToLight = shadowDistance(view, P);
    float texel = view.texel.x * (perspective(view) ? distanceToLight + view.texel.z : 1.0);
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
#if SHADOW_SOFT
    // Four bilinear taps at (+-d, +-d), d = 0.75 softness texels (0 for a hard light: the four
    // meet): a filter of about the light's radius, each tap four texels.
    vec2 d = 0.75 * softness * view.tile.zw / view.texel.w;
    float visible = 0.25 * (shadowVisibility(view, uv - d, depth) +
                            shadowVisibility(view, uv + d, depth) +
                            shadowVisibility(view, uv + vec2(d.x, -d.y), depth) +
                            shadowVisibility(view, uv + vec2(-d.x, d.y), depth));
#else
    float visible = shadowVisibility(view, uv, depth);
#endif
    return visible * shadowTransmittance(view, uv, distanceToLight, texel);
#endif
}

#endif
