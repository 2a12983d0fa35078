#include "engine/render/ShadowAtlases.h"

#include "engine/gl/Commands.h"
#include "engine/gl/Registry.h"
#include "engine/plugin/Plugin.h"

namespace render {

ShadowAtlases ShadowAtlases::of(const fg::Blackboard& blackboard) {
    return {blackboard.get<fg::TextureHandle>(plugin::kShadowDepth),
            blackboard.get<fg::TextureHandle>(plugin::kShadowGlass),
            blackboard.get<fg::TextureHandle>(plugin::kShadowCaustics)};
}

ShadowAtlases ShadowAtlases::read(fg::Builder& b) const {
    return {b.read(depth), b.read(glass), b.read(caustics)};
}

ShadowAtlases ShadowAtlases::readFinal(fg::Builder& b, const fg::Blackboard& blackboard) {
    return {b.readFinal<fg::TextureHandle>(blackboard, plugin::kShadowDepth),
            b.readFinal<fg::TextureHandle>(blackboard, plugin::kShadowGlass),
            b.readFinal<fg::TextureHandle>(blackboard, plugin::kShadowCaustics)};
}

void ShadowAtlases::bind(const fg::Resources& r, const gl::Sampler& compare) const {
    gl::bindTexture(gl::slot::kShadowDepth, r.texture(depth));
    compare.bind(gl::slot::kShadowDepth);
    gl::bindTexture(gl::slot::kShadowGlass, r.texture(glass));
    gl::bindTexture(gl::slot::kShadowCaustics, r.texture(caustics));
}

} // namespace render
