// The texture coordinates a material's texture slot reads: TEXCOORD_0 or TEXCOORD_1 (each slot's
// texCoord, MaterialTextures::bind sets the mask), through its KHR_texture_transform.
#ifndef COMMON_MATERIAL_UV_GLSL
#define COMMON_MATERIAL_UV_GLSL

const int SLOT_BASE_COLOR = 0, SLOT_METALLIC_ROUGHNESS = 1, SLOT_NORMAL = 2, SLOT_OCCLUSION = 3,
          SLOT_EMISSIVE = 4, SLOT_SPECULAR = 5, SLOT_SPECULAR_COLOR = 6;
uniform int uTexCoords; // bit `slot` set: that slot reads TEXCOORD_1

// `uvs`: TEXCOORD_0 in xy, TEXCOORD_1 in zw (the vertex's, interpolated).
vec2 slotUv(vec4 uvs, mat3 transform, int slot) {
    vec2 uv = ((uTexCoords >> slot) & 1) != 0 ? uvs.zw : uvs.xy;
    return (transform * vec3(uv, 1.0)).xy;
}

#endif
