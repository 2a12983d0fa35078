// The frame's shadow atlases as its frame graph holds them (plugin::kShadowDepth, kShadowGlass,
// kShadowCaustics; render/Shadows.h, common/shadows.glsl). A pass whose program shades with the
// lights declares reads of them where it records and binds them at their units where it
// executes: no unit stays bound across the frame.
#pragma once

#include "engine/fg/FrameGraph.h"

namespace gl {
class Sampler;
}

namespace render {

struct ShadowAtlases {
    /** The casters' depth, the glass's optical depth and nearest distance, and the caustics a
     *  plugin focused (else the engine's, which holds none). */
    fg::TextureHandle depth, glass, caustics;

    /** Declares reads of the three on `b` (a pass's setup); returns the versions read. */
    ShadowAtlases read(fg::Builder& b) const;
    /** Binds them at gl::slot::kShadowDepth (through `compare`, the renderer's comparing
     *  sampler: FrameInfo::shadowSampler), kShadowGlass and kShadowCaustics. */
    void bind(const fg::Resources& r, const gl::Sampler& compare) const;
};

} // namespace render
