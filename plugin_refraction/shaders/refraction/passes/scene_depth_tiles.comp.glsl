// refraction.scene_depth_tiles (SceneDepthTilesPass.cpp): the opaque scene's nearest depth over
// square tiles of the frame, as a mip chain (level L: tiles of 4 << L pixels a side, the depth
// buffer's values), which each march through the nearby scene tests before its samples
// (march.glsl, segmentInFront): where nothing opaque over a segment's pixels is nearer than its
// far end, none of its samples can meet the scene. A dispatch a level, an invocation a texel:
// level 0 from the depth buffer's 4 x 4 pixels, each coarser one from its finer one's 2 x 2.
layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = SCENE_DEPTH_UNIT) uniform sampler2D uSceneDepth;
layout(binding = SCENE_DEPTH_TILES_UNIT) uniform sampler2D uFiner; // the chain, read a level up
layout(r32f, binding = OUTPUT_IMAGE_UNIT) uniform writeonly image2D uLevel;
uniform int uLevelIndex; // the level written

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(t, imageSize(uLevel))))
        return;
    float nearest = 1.0;
    if (uLevelIndex == 0) {
        ivec2 size = textureSize(uSceneDepth, 0);
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) {
                ivec2 p = min(t * 4 + ivec2(x, y), size - 1);
                nearest = min(nearest, texelFetch(uSceneDepth, p, 0).r);
            }
    } else {
        ivec2 size = textureSize(uFiner, uLevelIndex - 1);
        for (int k = 0; k < 4; ++k) {
            ivec2 q = min(t * 2 + ivec2(k & 1, k >> 1), size - 1);
            nearest = min(nearest, texelFetch(uFiner, q, uLevelIndex - 1).r);
        }
    }
    imageStore(uLevel, t, vec4(nearest));
}
