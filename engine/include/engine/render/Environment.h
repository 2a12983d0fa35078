// The environment on the GPU: the equirectangular radiance with a GGX-prefiltered mip chain
// (roughness = level / (levels - 1)) and a small diffuse irradiance map.
#pragma once

#include "engine/asset/HdrImage.h"
#include "engine/core/Result.h"
#include "engine/gl/Program.h"
#include "engine/gl/Texture.h"

#include <memory>

namespace render {

class Environment {
public:
    /** Uploads `image` and computes the prefiltered levels and irradiance (compute shaders). */
    static core::Result<std::unique_ptr<Environment>> create(const asset::HdrImage& image,
                                                             const gl::ShaderLibrary& shaders);

    /** A small procedural sky (used when no --env is given): blue zenith, bright horizon band
     *  with a warm sun, darker ground. */
    static asset::HdrImage proceduralSky(int width = 256);

    const gl::Texture& prefiltered() const { return mPrefiltered; }
    const gl::Texture& irradiance() const { return mIrradiance; }
    float levels() const { return float(mPrefiltered.levels()); }

    /** Binds the textures to gl::slot::kEnvironment's units and sets the environment uniforms
     *  of common/environment.glsl on `program`. */
    void bind(const gl::Program& program, float rotation, float intensity) const;

private:
    gl::Texture mSource, mPrefiltered, mIrradiance;
};

} // namespace render
