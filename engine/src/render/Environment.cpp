// Environment upload and prefiltering.
#include "engine/render/Environment.h"

#include "engine/gl/Commands.h"

#include <algorithm>
#include <cmath>

namespace render {
namespace {

constexpr int kPrefilterLevels = 6;

std::vector<float> toRgba(const asset::HdrImage& image) {
    std::vector<float> rgba(std::size_t(image.width) * std::size_t(image.height) * 4u, 1.0f);
    for (std::size_t i = 0; i < std::size_t(image.width) * std::size_t(image.height); ++i)
        for (int c = 0; c < 3; ++c)
            rgba[i * 4 + std::size_t(c)] = image.rgb[i * 3 + std::size_t(c)];
    return rgba;
}

} // namespace

asset::HdrImage Environment::proceduralSky(int width) {
    asset::HdrImage image;
    image.width = width;
    image.height = width / 2;
    image.rgb.resize(std::size_t(image.width) * std::size_t(image.height) * 3u);
    const glm::vec3 sun = glm::normalize(glm::vec3(0.4f, 0.5f, -0.75f));
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const float u = (float(x) + 0.5f) / float(image.width);
            const float v = (float(y) + 0.5f) / float(image.height);
            const float phi = (u - 0.5f) * 6.2831853f, theta = v * 3.1415926f;
            const glm::vec3 d(std::sin(theta) * std::sin(phi), std::cos(theta),
                              -std::sin(theta) * std::cos(phi));
            glm::vec3 c;
            if (d.y > 0.0f) {
                const float t = std::pow(1.0f - d.y, 4.0f);
                c = glm::mix(glm::vec3(0.15f, 0.35f, 0.9f), glm::vec3(1.1f, 1.0f, 0.9f), t);
            } else {
                c = glm::mix(glm::vec3(0.35f, 0.3f, 0.25f), glm::vec3(0.12f, 0.1f, 0.08f),
                             std::min(-d.y * 3.0f, 1.0f));
            }
            const float s = std::max(glm::dot(d, sun), 0.0f);
            c += glm::vec3(40.0f, 32.0f, 24.0f) * std::pow(s, 800.0f) +
                 glm::vec3(0.6f, 0.4f, 0.2f) * std::pow(s, 16.0f);
            for (int k = 0; k < 3; ++k)
                image.rgb[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3 +
                          std::size_t(k)] = c[k];
        }
    return image;
}

core::Result<std::unique_ptr<Environment>> Environment::create(const asset::HdrImage& image,
                                                               const gl::ShaderLibrary& shaders) {
    if (image.width > gl::Texture::maxSize() || image.height > gl::Texture::maxSize())
        return core::Error{"render::Environment::create(): " + std::to_string(image.width) + "x" +
                           std::to_string(image.height) + " is over GL_MAX_TEXTURE_SIZE " +
                           std::to_string(gl::Texture::maxSize())};
    auto prefilter = gl::Program::compute(shaders, "render/prefilter.comp.glsl");
    if (!prefilter)
        return core::Error{"render::Environment::create(): " + prefilter.error().message};
    auto irradiance = gl::Program::compute(shaders, "render/irradiance.comp.glsl");
    if (!irradiance)
        return core::Error{"render::Environment::create(): " + irradiance.error().message};

    auto env = std::make_unique<Environment>();
    const glm::ivec2 size(image.width, image.height);
    env->mSource = gl::Texture({size, gl::Format::RGBA16F, 0});
    const std::vector<float> rgba = toRgba(image);
    env->mSource.upload(0, rgba.data());
    env->mSource.generateMipmaps();
    // The prefilter's compute reads those levels. llvmpipe generates them by blits its
    // rasteriser runs later, and a dispatch need not wait for them: under load the levels were
    // read unfinished now and then (the environment's rough reflections came out darker, in
    // about 1 run of 30 of Layers.TheReferenceAppliesNormalMapsToo). Once, at load.
    gl::finish();
    env->mSource.setSampling(gl::Filter::LinearMipmap, gl::Wrap::Repeat);
    const int levels = std::min(kPrefilterLevels, env->mSource.levels());
    env->mPrefiltered = gl::Texture({size, gl::Format::RGBA16F, levels});
    env->mPrefiltered.setSampling(gl::Filter::LinearMipmap, gl::Wrap::Repeat);
    // Level 0 is the source itself (mirror-sharp); every other level is GGX-convolved.
    env->mPrefiltered.upload(0, rgba.data());
    prefilter->use();
    gl::bindTexture(gl::slot::kSource, env->mSource);
    for (int level = 1; level < levels; ++level) {
        const glm::ivec2 s = env->mPrefiltered.size(level);
        gl::bindImage(gl::slot::kOutputImage, env->mPrefiltered, level, true);
        prefilter->set("uRoughness", float(level) / float(levels - 1));
        prefilter->set("uSampleCount", 128);
        gl::dispatch(std::uint32_t((s.x + 7) / 8), std::uint32_t((s.y + 7) / 8));
    }
    env->mIrradiance = gl::Texture({{32, 16}, gl::Format::RGBA16F, 1});
    env->mIrradiance.setSampling(gl::Filter::Linear, gl::Wrap::Repeat);
    irradiance->use();
    gl::bindImage(gl::slot::kOutputImage, env->mIrradiance, 0, true);
    int sourceLevel = 0;
    while (env->mSource.size(sourceLevel).x > 64 && sourceLevel + 1 < env->mSource.levels())
        ++sourceLevel;
    irradiance->set("uSourceLevel", sourceLevel);
    gl::dispatch(4, 2);
    gl::memoryBarrier(gl::BarrierTexture);
    return env;
}

void Environment::bind(const gl::Program& program, float rotation, float intensity) const {
    gl::bindTexture(gl::slot::kEnvironment, mPrefiltered, 0);
    gl::bindTexture(gl::slot::kEnvironment, mIrradiance, 1);
    program.set("uEnvLevels", levels());
    program.set("uEnvRotation", rotation);
    program.set("uEnvIntensity", intensity);
}

} // namespace render
