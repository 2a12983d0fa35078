// A material's texture slots as MaterialTextures::bind sets them: whether each has a texture,
// the texture, and the texture coordinates it reads: TEXCOORD_0 or TEXCOORD_1 (each slot's
// texCoord, a mask) through its KHR_texture_transform.
#ifndef COMMON_MATERIAL_UV_GLSL
#define COMMON_MATERIAL_UV_GLSL

// The slots (SLOT_*, SLOTS: MaterialTextures::Slot through render/Shared.h), their textures at
// the units of MATERIAL_UNIT.
uniform int uHasTexture[SLOTS];
layout(binding = MATERIAL_UNIT) uniform sampler2D uTexture[SLOTS];
uniform mat3 uTextureUv[SLOTS]; // KHR_texture_transform (identity without it)
uniform int uTexCoords;         // bit `slot` set: that slot reads TEXCOORD_1

// `uvs`: TEXCOORD_0 in xy, TEXCOORD_1 in zw (the vertex's, interpolated).
vec2 slotUv(vec4 uvs, mat3 transform, int slot) {
    vec2 uv = ((uTexCoords >> slot) & 1) != 0 ? uvs.zw : uvs.xy;
    return (transform * vec3(uv, 1.0)).xy;
}

vec2 slotUv(vec4 uvs, int slot) {
    return slotUv(uvs, uTextureUv[slot], slot);
}

bool hasTexture(int slot) {
    return uHasTexture[slot] != 0;
}

vec4 readTexture(int slot, vec4 uvs) {
    return texture(uTexture[slot], slotUv(uvs, slot));
}

#endif
