// Shadows against the Embree reference (assets/scenes/shadows.json: a red glass ball and an
// opaque ball on the ground under a spot): the GPU's shadow maps and the reference's shadow rays
// agree over the frame; on the ground the opaque ball's shadow removes the spot's light and the
// glass ball's, with its light going straight (caustics off), lets it through reddened; switched
// off (RenderSettings::shadows, the plugin's glass-shadows), the frame no longer agrees. The
// caustics (assets/scenes/caustics.json: the spot low behind a yellow glass ball): the ball
// focuses the light to a peak well above the lit ground, coloured by the glass, inside a ring
// of shadow, where the reference's photons put it; with caustics off there is no peak.
#include "WorldRig.h"
#include "support/GlTest.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
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
    rig.set("caustics", "off"); // the glass's light straight through
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

/** The brightest pixel (luminance) of `hdr` among those where `which` is `value`: its index. */
std::size_t brightestWhere(const std::vector<float>& hdr, const std::vector<int>& which,
                           int value) {
    std::size_t best = 0;
    double peak = -1.0;
    for (std::size_t i = 0; i < which.size(); ++i) {
        const double y = 0.2126 * hdr[i * 4] + 0.7152 * hdr[i * 4 + 1] + 0.0722 * hdr[i * 4 + 2];
        if (which[i] == value && y > peak) {
            peak = y;
            best = i;
        }
    }
    return best;
}

/** The mean colour of `hdr` over a (2 r + 1)^2 square of pixels around pixel `i`. */
glm::dvec3 around(const std::vector<float>& hdr, std::size_t i, int r) {
    const int cx = int(i) % kSize, cy = int(i) / kSize;
    glm::dvec3 sum(0.0);
    int n = 0;
    for (int y = std::max(cy - r, 0); y <= std::min(cy + r, kSize - 1); ++y)
        for (int x = std::max(cx - r, 0); x <= std::min(cx + r, kSize - 1); ++x, ++n)
            for (int c = 0; c < 3; ++c)
                sum[c] += hdr[std::size_t(y * kSize + x) * 4 + std::size_t(c)];
    return sum / double(n);
}

TEST_F(Shadows, GlassFocusesCausticsWhereTheReferenceDoes) {
    test::WorldRig rig(test::projectScene("caustics.json"), context(), kSize);
    rig.useSceneCamera();
    rig.set("caustic-photons", "32");
    const auto reference = rig.reference(0.0, test::WorldRig::Evaluation::Sampled, 4);
    const auto focused = rig.renderHdr();
    rig.set("caustics", "off");
    const auto straight = rig.renderHdr();
    const auto score = [&](const std::vector<float>& hdr) {
        return capture::score({kSize, kSize, render::cpu::tonemap(hdr, 1.0f)}, reference.image,
                              nullptr)
            .psnr;
    };
    const double on = score(focused), off = score(straight);
    std::printf("caustics.json against the reference (4 spp), whole frame: %.2f dB, caustics "
                "off %.2f dB\n",
                on, off);
    EXPECT_GT(on, 30.0);
    EXPECT_GT(on, off + 1.0);

    // On the ground in the glass ball's shadow (1), against the same ground unshadowed.
    rig.shadows = false;
    const auto unshadowed = rig.renderHdr();
    const std::vector<int> which = groundShadows(rig.world(), rig.camera());
    const std::vector<float>& traced = reference.traced.rgba;
    const std::size_t referencePeak = brightestWhere(traced, which, 1);
    for (const std::vector<float>* hdr : {&focused, &traced, &straight}) {
        const char* who = hdr == &focused ? "GPU" : hdr == &traced ? "reference" : "caustics off";
        const std::size_t at = brightestWhere(*hdr, which, 1);
        const glm::dvec3 peak = around(*hdr, at, 1), open = around(unshadowed, at, 1);
        const double distance =
            glm::length(glm::vec2(int(at) % kSize - int(referencePeak) % kSize,
                                  int(at) / kSize - int(referencePeak) / kSize));
        // The shadow's typical pixel: the median of what it keeps of the unshadowed light.
        std::vector<double> kept;
        for (std::size_t i = 0; i < which.size(); ++i)
            if (which[i] == 1)
                kept.push_back((*hdr)[i * 4 + 1] / std::max(unshadowed[i * 4 + 1], 1e-6f));
        std::nth_element(kept.begin(), kept.begin() + std::ptrdiff_t(kept.size() / 2), kept.end());
        const double median = kept.empty() ? 0.0 : kept[kept.size() / 2];
        std::printf("%s: caustic peak %.2f of the unshadowed ground (green) at (%d, %d), %.1f px "
                    "from the reference's; the shadow's median %.3f; peak red/blue %.2f, "
                    "unshadowed %.2f\n",
                    who, peak.g / open.g, int(at) % kSize, int(at) / kSize, distance, median,
                    peak.r / peak.b, open.r / open.b);
        if (hdr == &straight) { // no focus: nothing in the shadow outshines the open ground
            EXPECT_LT(peak.g, open.g) << who;
            continue;
        }
        EXPECT_GT(peak.g, 1.5 * open.g) << who; // a peak well above the lit ground
        EXPECT_LT(median, 0.6) << who;          // inside a ring of shadow
        EXPECT_GT(peak.r / peak.b, 1.3 * open.r / open.b) << who; // yellow glass, yellow light
        EXPECT_LT(distance, 6.0) << who;
    }
    const double gpuPeak = around(focused, brightestWhere(focused, which, 1), 1).g,
                 referencePeakValue = around(traced, referencePeak, 1).g;
    EXPECT_NEAR(gpuPeak, referencePeakValue, 0.35 * referencePeakValue);
}

TEST_F(Shadows, AlternatingMethodsAndLightsCompilesEachVariantOnce) {
    test::WorldRig rig(test::projectScene("shadows.json"), context(), 32);
    rig.useSceneCamera();
    // Two rounds of frames as the viewer's split and the bench alternate them: DIR, the hybrid
    // (its trace too) and the opaque frame, with the shadows and without.
    std::size_t afterFirstRound = 0;
    for (int round = 0; round < 2; ++round) {
        for (const char* method : {"dir", "hybrid", "opaque"})
            for (bool shadows : {true, false}) {
                rig.set("method", method);
                rig.shadows = shadows;
                rig.renderHdr();
            }
        if (round == 0)
            afterFirstRound = rig.renderer().programVariants();
    }
    EXPECT_GT(afterFirstRound, 6u);
    EXPECT_EQ(rig.renderer().programVariants(), afterFirstRound);
}

// glass-bench --skip's steps reach the programs that test them, and leave no variant behind:
// the frame without them is the frame it was.
TEST_F(Shadows, SkippedStepsChangeTheFramesThatSkipThemAlone) {
    test::WorldRig rig(test::projectScene("shadows.json"), context(), 32);
    rig.useSceneCamera();
    const std::vector<float> whole = rig.renderHdr();
    for (const char* step : {"shadows", "walk", "interface"}) {
        rig.skippedSteps = {step};
        EXPECT_NE(rig.renderHdr(), whole) << step;
    }
    rig.skippedSteps.clear();
    EXPECT_EQ(rig.renderHdr(), whole);
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
