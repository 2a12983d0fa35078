// The temporal history the renderer keeps across frames (RenderSettings::temporal): the last
// resolved colour and the motion texels it was resolved with, two of each (one read, one
// written, swapped after every frame), and what decides each frame's place in it: when it starts
// over (a cut, an edit, a resize, a changed setting), when nothing moved (still frames
// converge), the jitter of the projection. The frame graph imports the textures every frame;
// only the temporal resolve pass (passes/TemporalPass.cpp) writes them.
#pragma once

#include "engine/gl/Texture.h"
#include "engine/render/Camera.h"
#include "engine/render/FrameInfo.h"
#include "engine/scene/World.h"

#include <cstdint>
#include <span>
#include <vector>

namespace render {

class TemporalHistory {
public:
    /** This frame's place in the history: reset (index 0) on the history's first frame after
     *  it was off, a requested cut (requestReset), a camera cut (its projection changed, or it
     *  turned more than 45 degrees), an edit of the world (characters, models, clips, variants,
     *  glass modes and overrides, scene lights), a resize, a changed setting or plugin
     *  parameter (`pluginRevision`); still when the camera, the time and every item's placement
     *  are the previous frame's. Allocates the textures for the frame's size (kept while it is
     *  off, for when it is on again). Off: returns a frame that is not enabled. */
    TemporalFrame begin(const scene::World& world, const Camera& camera,
                        const RenderSettings& settings, double time,
                        std::span<const DrawItem> items, std::uint64_t pluginRevision);
    /** Swaps the textures after a frame that wrote them. */
    void end() { mRead ^= 1; }
    /** The next frame starts the history over (a camera cut the caller knows of). */
    void requestReset() { mResetRequested = true; }

    /** The previous frame's resolved colour (rgb; a: the frames it holds) and motion texels. */
    gl::Texture& previousColor() { return mColor[mRead]; }
    gl::Texture& previousMotion() { return mMotion[mRead]; }
    const gl::Texture& previousMotion() const { return mMotion[mRead]; }
    /** What this frame's resolve writes. */
    gl::Texture& nextColor() { return mColor[mRead ^ 1]; }
    gl::Texture& nextMotion() { return mMotion[mRead ^ 1]; }
    /** GPU memory of the history's textures (allocated the first frame it is on). */
    std::size_t bytes() const;

    /** The jitter of frame `index` of a history, pixels in -0.5..0.5: Halton's (2, 3). */
    static glm::vec2 jitter(std::uint32_t index);
    /** `camera` with its projection offset by `jitter` pixels of a `size` frame. */
    static Camera jittered(const Camera& camera, glm::vec2 jitter, glm::ivec2 size);

private:
    /** What an edit changes: a reset when it differs. */
    struct CharacterKey {
        const scene::Model* model = nullptr;
        scene::Performance performance; ///< declared: a scheduled crossfade changes no key
        int variant = -1;
        scene::GlassMode glass = scene::GlassMode::Auto;
        scene::GlassOverrides overrides;
        bool operator==(const CharacterKey&) const = default;
    };
    gl::Texture mColor[2], mMotion[2];
    int mRead = 0;
    bool mValid = false, mResetRequested = false;
    std::uint32_t mIndex = 0;
    RenderSettings mSettings;
    std::vector<CharacterKey> mWorld;
    std::size_t mLights = 0;
    std::uint64_t mPluginRevision = 0;
    Camera mCamera;
    double mTime = 0.0;
    glm::mat4 mViewProjection{1.0f};
};

} // namespace render
