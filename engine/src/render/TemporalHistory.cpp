// The temporal history: its textures and each frame's place in it.
#include "TemporalHistory.h"

#include "engine/gl/Program.h"

#include <glm/gtc/matrix_access.hpp>

#include <cmath>

namespace render {

namespace {

float halton(std::uint32_t index, std::uint32_t base) {
    float f = 1.0f, r = 0.0f;
    for (std::uint32_t i = index; i > 0; i /= base) {
        f /= float(base);
        r += f * float(i % base);
    }
    return r;
}

/** The settings whose change starts the history over: all but the resolve's own weight and
 *  debug view, the jitter's extent and how passes are timed. */
RenderSettings historyKey(RenderSettings s) {
    s.temporal.historyWeight = 0.0f;
    s.temporal.movingJitter = 0.0f;
    s.temporal.view = TemporalSettings::View::Off;
    s.exactPassTimes = false;
    return s;
}

/** A camera cut: another projection, or a turn of more than 45 degrees. */
bool cut(const Camera& from, const Camera& to) {
    if (from.projection != to.projection)
        return true;
    const glm::vec3 a = -glm::vec3(glm::row(from.view, 2)), b = -glm::vec3(glm::row(to.view, 2));
    return glm::dot(glm::normalize(a), glm::normalize(b)) < std::cos(glm::radians(45.0f));
}

} // namespace

glm::vec2 TemporalHistory::jitter(std::uint32_t index) {
    return {halton(index + 1, 2) - 0.5f, halton(index + 1, 3) - 0.5f};
}

Camera TemporalHistory::jittered(const Camera& camera, glm::vec2 jitter, glm::ivec2 size) {
    Camera c = camera;
    // The third column multiplies the view depth, which is -w: clip x and y move by -2 * jitter
    // / size times w, the whole image by -jitter pixels, and each pixel's centre sees what the
    // unjittered frame shows at its centre plus jitter.
    c.projection[2][0] += 2.0f * jitter.x / float(size.x);
    c.projection[2][1] += 2.0f * jitter.y / float(size.y);
    return c;
}

TemporalFrame TemporalHistory::begin(const scene::World& world, const Camera& camera,
                                     const RenderSettings& settings, double time,
                                     std::span<const DrawItem> items,
                                     std::uint64_t pluginRevision) {
    TemporalFrame frame;
    frame.viewProjection = frame.previousViewProjection = camera.viewProjection();
    if (!settings.temporal.enabled) { // the textures stay for the next time it is on
        mValid = false;
        return frame;
    }
    std::vector<CharacterKey> keys;
    keys.reserve(world.characters.size());
    for (const scene::Character& c : world.characters)
        keys.push_back({c.model.get(), c.performance, c.variant, c.glass, c.overrides});
    const bool resized = !mColor[0] || mColor[0].size() != settings.size;
    const bool reset = !mValid || mResetRequested || resized ||
                       historyKey(settings) != historyKey(mSettings) || keys != mWorld ||
                       world.lights.size() != mLights || pluginRevision != mPluginRevision ||
                       cut(mCamera, camera);
    bool placed = true;
    for (const DrawItem& item : items)
        placed = placed && item.world == item.previousWorld;
    const bool still = !reset && placed && time == mTime && camera.view == mCamera.view;
    if (resized)
        for (int i = 0; i < 2; ++i) {
            mColor[i] = gl::Texture({settings.size, gl::Format::RGBA32F, 1});
            mColor[i].setSampling(gl::Filter::Linear, gl::Wrap::Clamp); // the reprojection's
            mMotion[i] = gl::Texture({settings.size, gl::Format::RGBA32UI, 1});
        }
    frame.enabled = true;
    frame.index = reset ? 0 : mIndex + 1;
    frame.still = still;
    // A history's first frame has nothing to clip against: the whole pixel, as still frames.
    frame.jitter =
        jitter(frame.index) * (still || frame.index == 0 ? 1.0f : settings.temporal.movingJitter);
    if (!reset)
        frame.previousViewProjection = mViewProjection;
    mIndex = frame.index;
    mValid = true;
    mResetRequested = false;
    mSettings = settings;
    mWorld = std::move(keys);
    mLights = world.lights.size();
    mPluginRevision = pluginRevision;
    mCamera = camera;
    mTime = time;
    mViewProjection = frame.viewProjection;
    return frame;
}

std::size_t TemporalHistory::bytes() const {
    std::size_t total = 0;
    for (int i = 0; i < 2; ++i)
        for (const gl::Texture* t : {&mColor[i], &mMotion[i]})
            if (*t)
                total += std::size_t(t->size().x) * std::size_t(t->size().y) *
                         gl::bytesPerTexel(t->desc().format);
    return total;
}

void setMotionUniforms(const gl::Program& program, const FrameInfo& frame) {
    program.set("uMotionViewProjection", frame.temporal.viewProjection);
    program.set("uPreviousViewProjection", frame.temporal.previousViewProjection);
    program.set("uMotionInverseViewProjection", glm::inverse(frame.temporal.viewProjection));
    program.set("uMotionSize", glm::vec2(frame.settings.size));
    program.set("uWriteMotion", frame.temporal.enabled ? 1 : 0);
}

} // namespace render
