// The frame's shadow atlases as its frame graph holds them (plugin::kShadowDepth, kShadowGlass,
// kShadowCaustics; render/Shadows.h, common/shadows.glsl). A pass whose program shades with the
// lights declares reads of them where it records and binds them at their units where it
// executes: no unit stays bound across the frame. The engine's shading is recorded before the
// plugins draw their glass and caustics into the atlases, so it reads them as the frame leaves
// them.
#pragma once

#include "engine/fg/Blackboard.h"
#include "engine/fg/FrameGraph.h"

namespace gl {
class Sampler;
}

namespace render {

struct ShadowAtlases {
    /** The casters' depth, the glass's optical depth and nearest distance, and the caustics a
     *  plugin focused (else the engine's, which holds none). */
    fg::TextureHandle depth, glass, caustics;

    /** The three as `blackboard` holds them now, under plugin::kShadowDepth, kShadowGlass and
     *  kShadowCaustics. */
    static ShadowAtlases of(const fg::Blackboard& blackboard);
    /** Declares reads of the three on `b` (a pass's setup); returns the versions read. */
    ShadowAtlases read(fg::Builder& b) const;
    /** Declares reads of the versions `blackboard` holds once the frame is recorded, whoever
     *  writes them later (fg::Builder::readFinal); `blackboard` outlives the graph's compile. */
    static ShadowAtlases readFinal(fg::Builder& b, const fg::Blackboard& blackboard);
    /** Binds them at gl::slot::kShadowDepth (through `compare`, the renderer's comparing
     *  sampler: FrameInfo::shadowSampler), kShadowGlass and kShadowCaustics. */
    void bind(const fg::Resources& r, const gl::Sampler& compare) const;
};

} // namespace render
