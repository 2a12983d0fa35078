// What glass.vert.glsl passes to the fragment shaders drawn with it (view space).
#ifndef REFRACTION_GLASS_INPUTS_GLSL
#define REFRACTION_GLASS_INPUTS_GLSL
in vec3 vViewPosition;
in vec3 vViewNormal;
in vec4 vViewTangent;
in vec4 vUv; // TEXCOORD_0 in xy, TEXCOORD_1 in zw
in float vNormalDistance; // ISR: d_N in view units (-1: no far side)
in vec4 vClip, vPreviousClip; // where the frame accumulates: the motion's (common/motion.glsl)
#endif
