// Diffuse irradiance (cosine-weighted, divided by pi) of the environment, brute force over a
// small mip of the source; each source texel weighted by its solid angle.
#include "common/math.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba16f, binding = OUTPUT_IMAGE_UNIT) uniform writeonly image2D uTarget;
layout(binding = SOURCE_UNIT) uniform sampler2D uSource;
uniform int uSourceLevel;

void main() {
    ivec2 size = imageSize(uTarget);
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, size)))
        return;
    vec3 N = equirectDirection((vec2(texel) + 0.5) / vec2(size));
    ivec2 sourceSize = textureSize(uSource, uSourceLevel);
    vec3 sum = vec3(0.0);
    for (int y = 0; y < sourceSize.y; ++y) {
        float theta = (float(y) + 0.5) / float(sourceSize.y) * PI;
        float solidAngle = (2.0 * PI / float(sourceSize.x)) * (PI / float(sourceSize.y)) * sin(theta);
        for (int x = 0; x < sourceSize.x; ++x) {
            vec3 L = equirectDirection((vec2(x, y) + 0.5) / vec2(sourceSize));
            float NoL = dot(N, L);
            if (NoL > 0.0)
                sum += texelFetch(uSource, ivec2(x, y), uSourceLevel).rgb * NoL * solidAngle;
        }
    }
    imageStore(uTarget, texel, vec4(sum / PI, 1.0));
}
