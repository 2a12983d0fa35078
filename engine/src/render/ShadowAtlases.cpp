#include "engine/render/ShadowAtlases.h"

#include "engine/gl/Commands.h"
#include "engine/gl/Registry.h"

namespace render {

ShadowAtlases ShadowAtlases::read(fg::Builder& b) const {
    return {b.read(depth), b.read(glass), b.read(caustics)};
}

void ShadowAtlases::bind(const fg::Resources& r, const gl::Sampler& compare) const {
    gl::bindTexture(gl::slot::kShadowDepth, r.texture(depth));
    compare.bind(gl::slot::kShadowDepth);
    gl::bindTexture(gl::slot::kShadowGlass, r.texture(glass));
    gl::bindTexture(gl::slot::kShadowCaustics, r.texture(caustics));
}

} // namespace render
