// Shadows against the Embree reference (assets/scenes/shadows.json: a red glass ball and an
// opaque ball on the ground under a spot): the GPU's shadow maps and the reference's shadow rays
// agree over the frame; on the ground the opaque ball's shadow removes the spot's light and the
// glass ball's lets it through reddened; switched off (RenderSettings::shadows, the plugin's
// glass-shadows), the frame no longer agrees.
#include "WorldRig.h"
#include "support/GlTest.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace {

constexpr int kSize = 160;

/** Which ground pixels the spot's straight line from them crosses a ball: 1 the glass ball,
 *  2 the opaque one, 0 neither (or not ground). From the scene file's geometry. */
std::vector<int> groundShadows(const scene::World& world, const render::Camera& camera) {
    const glm::vec3 light = world.lights.at(0).position;
    const glm::mat4 inverse = glm::inverse(camera.viewProjection());
    std::vector<int> which(std::size_t(kSize * kSize), 0);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec2 ndc((float(x) + 0.5f) / float(kSize) * 2.0f - 1.0f,
                                1.0f - (float(y) + 0.5f) / float(kSize) * 2.0f);
            glm::vec4 far = inverse * glm::vec4(ndc, 1.0f, 1.0f);
            const glm::vec3 dir = glm::normalize(glm::vec3(far) / far.w - camera.position);
            if (dir.y >= -1e-3f)
                continue;
            const glm::vec3 ground = camera.position + dir * (-camera.position.y / dir.y);
            bool seen = true; // the camera's ray meets the ground before either ball (grown)
            for (std::size_t c = 0; c < 2; ++c) {
                const glm::vec3 center(world.characters[c].placement.translation);
                const float t = glm::dot(center - camera.position, dir);
                seen = seen && glm::length(camera.position + dir * t - center) >
                                   1.1f * float(world.characters[c].placement.scale.x);
            }
            for (std::size_t c = 0; seen && c < 2; ++c) {
                const glm::vec3 center(world.characters[c].placement.translation);
                const auto radius = float(world.characters[c].placement.scale.x);
                // The segment ground -> light against the ball, a little grown or shrunk so
                // that the filtered edges count neither way.
                const glm::vec3 d = glm::normalize(light - ground);
                const float t = glm::dot(center - ground, d);
                const float miss = glm::length(ground + d * t - center);
                if (t > 0.0f && miss < radius * 0.8f)
                    which[std::size_t(y * kSize + x)] = int(c) + 1;
                else if (t > 0.0f && miss < radius * 1.3f)
                    which[std::size_t(y * kSize + x)] = -1; // the edge: neither
            }
        }
    return which;
}

/** The mean linear colour of `hdr` (RGBA rows) over the pixels where `which` is `value`. */
glm::dvec3 meanWhere(const std::vector<float>& hdr, const std::vector<int>& which, int value) {
    glm::dvec3 sum(0.0);
    int n = 0;
    for (std::size_t i = 0; i < which.size(); ++i)
        if (which[i] == value) {
            sum += glm::dvec3(hdr[i * 4], hdr[i * 4 + 1], hdr[i * 4 + 2]);
            ++n;
        }
    EXPECT_GT(n, 20) << "pixels of kind " << value;
    return n ? sum / double(n) : sum;
}

class Shadows : public test::GlTest {};

TEST_F(Shadows, CastByOpaqueAndGlassOnTheGpuAndInTheReference) {
    test::WorldRig rig(test::projectScene("shadows.json"), context(), kSize);
    rig.useSceneCamera();
    const auto reference = rig.reference(0.0, test::WorldRig::Evaluation::Sampled, 8);
    const auto shadowed = rig.renderHdr();
    const capture::Image frame{kSize, kSize, render::cpu::tonemap(shadowed, 1.0f)};
    const double whole = capture::score(frame, reference.image, nullptr).psnr;
    rig.shadows = false;
    const auto unshadowed = rig.renderHdr();
    const double off = capture::score({kSize, kSize, render::cpu::tonemap(unshadowed, 1.0f)},
                                      reference.image, nullptr)
                           .psnr;
    std::printf("shadows.json against the reference (8 spp), whole frame: %.2f dB, shadows off "
                "%.2f dB\n",
                whole, off);
    EXPECT_GT(whole, 34.0);
    EXPECT_GT(whole, off + 4.0);

    // On the ground: the opaque ball's shadow keeps a fraction of the lit ground's light, the
    // glass ball's most of it, redder than the light (white) is.
    const std::vector<int> which = groundShadows(rig.world(), rig.camera());
    const std::vector<float>& traced = reference.traced.rgba;
    for (const std::vector<float>* hdr : {&shadowed, &traced}) {
        const glm::dvec3 opaqueOn = meanWhere(*hdr, which, 2),
                         opaqueOff = meanWhere(unshadowed, which, 2);
        const glm::dvec3 glassOn = meanWhere(*hdr, which, 1),
                         glassOff = meanWhere(unshadowed, which, 1);
        const char* who = hdr == &shadowed ? "GPU" : "reference";
        std::printf("%s: opaque shadow %.3f of unshadowed (green), glass shadow r %.3f g %.3f\n",
                    who, opaqueOn.g / opaqueOff.g, glassOn.r / glassOff.r, glassOn.g / glassOff.g);
        EXPECT_LT(opaqueOn.g, 0.5 * opaqueOff.g) << who;
        EXPECT_GT(glassOn.r, 0.6 * glassOff.r) << who;
        EXPECT_GT(glassOn.r / glassOff.r, 1.5 * glassOn.g / glassOff.g) << who;
    }
}

TEST_F(Shadows, GlassCastsNothingWithItsShadowsOff) {
    test::WorldRig rig(test::projectScene("shadows.json"), context(), kSize);
    rig.useSceneCamera();
    const std::vector<int> which = groundShadows(rig.world(), rig.camera());
    const glm::dvec3 on = meanWhere(rig.renderHdr(), which, 1);
    rig.set("glass-shadows", "off");
    const glm::dvec3 off = meanWhere(rig.renderHdr(), which, 1);
    rig.shadows = false;
    const glm::dvec3 none = meanWhere(rig.renderHdr(), which, 1);
    EXPECT_LT(on.g, 0.8 * off.g);
    EXPECT_NEAR(off.g, none.g, 1e-3 * none.g);
}

} // namespace
