// The traced path (method trace): the GPU's trace through the glass BVH and the Embree reference
// are two implementations of one model, agreeing at the pixel centres; glass behind glass past
// the capture's K layers; and the sub-pixel samples.
#include "WorldRig.h"
#include "support/GlTest.h"

#include "engine/capture/Metrics.h"

#include <string>

namespace {

using test::WorldRig;

class Trace : public test::GlTest {};

TEST_F(Trace, TheGpuTraceIsTheReferencesPathAtPixelCentres) {
    // One ray through each pixel's centre on both sides (no outline blending on the GPU): the
    // same interfaces, media, Fresnel, refraction and lookups, so the images agree but for
    // rounding. DIR's search through the same layers falls short of that by 10-25 dB.
    struct Case {
        const char* scene;
        double floor;
    };
    for (const Case& c : {Case{"glass_spheres.json", 52.0}, Case{"sphere_in_front.json", 45.0}}) {
        WorldRig rig(test::projectScene(c.scene), context());
        rig.set("outline-aa", "off");
        const WorldRig::Reference reference = rig.reference(0.0, true);
        auto psnr = [&](const char* method) {
            rig.set("method", method);
            rig.set("search-steps", "8");
            return capture::score(rig.render(), reference.image, &reference.mask).psnr;
        };
        const double traced = psnr("trace"), searched = psnr("dir");
        std::printf("%s at pixel centres, against the reference: trace %.2f dB, DIR 8 %.2f dB\n",
                    c.scene, traced, searched);
        EXPECT_GE(traced, c.floor) << c.scene;
        EXPECT_GT(traced, searched + 4.0) << c.scene;
    }
}

TEST_F(Trace, GlassBehindGlassPastTheCapturesLayersStaysClean) {
    // A small sphere in front of a large one: four surfaces along most lines of sight. With room
    // for two layers a pixel, DIR walks the overflow's two-surface pair; the trace meets every
    // surface in the BVH (those pixels' entries traced from the camera), as with room for all.
    WorldRig rig(test::projectScene("sphere_in_front.json"), context());
    const WorldRig::Reference reference = rig.reference();
    auto psnr = [&](const char* method, const char* capacity) {
        rig.set("method", method);
        rig.set("search-steps", "8");
        rig.set("layer-capacity", capacity);
        return capture::score(rig.render(), reference.image, &reference.mask).psnr;
    };
    const double roomy = psnr("trace", "4"), tight = psnr("trace", "2"),
                 searched = psnr("dir", "2");
    std::printf("small sphere in front of a large one, against the reference: trace %.2f dB with "
                "K=4, %.2f with K=2; DIR 8 with K=2 %.2f\n",
                roomy, tight, searched);
    EXPECT_GE(tight, roomy - 1.0);
    EXPECT_GT(tight, searched + 5.0);
}

TEST_F(Trace, SubPixelSamplesComeCloserToTheReference) {
    // The reference averages 16 rays a pixel; trace-samples 4 averages four, jittered within it.
    WorldRig rig(test::projectScene("glass_spheres.json"), context());
    rig.set("method", "trace");
    rig.set("outline-aa", "off");
    const WorldRig::Reference reference = rig.reference();
    auto psnr = [&](const char* samples) {
        rig.set("trace-samples", samples);
        return capture::score(rig.render(), reference.image, &reference.mask).psnr;
    };
    const double one = psnr("1"), four = psnr("4");
    std::printf("two overlapping spheres, trace against the 16-ray reference: 1 sample %.2f dB, "
                "4 samples %.2f dB\n",
                one, four);
    EXPECT_GT(four, one + 1.0);
}

} // namespace
