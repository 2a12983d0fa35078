// The traced path (method trace): the GPU's trace through the glass BVH and the Embree reference
// are two implementations of one model, agreeing at the pixel centres; glass behind glass past
// the capture's K layers; the normal maps at every hit; the sub-pixel samples, a draw each, and
// the trace's counts.
#include "WorldRig.h"
#include "support/GlTest.h"

#include "engine/capture/Metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace {

using test::WorldRig;

class Trace : public test::GlTest {};

/** Masked PSNR of `rig`'s frame at `time` with `samples` rays a pixel, against `reference`. */
double psnrWithSamples(WorldRig& rig, const WorldRig::Reference& reference, const char* samples,
                       double time = 0.0) {
    rig.set("trace-samples", samples);
    return rig.psnrAgainst(reference, time);
}

TEST_F(Trace, TheGpuTraceIsTheReferencesPathAtPixelCentres) {
    // One ray through each pixel's centre on both sides (no outline blending on the GPU): the
    // same interfaces, media, Fresnel, refraction and lookups, so the images agree but for
    // rounding. DIR's search through the same layers falls short of that by 10-25 dB.
    struct Case {
        const char* scene;
        double floor;
    };
    for (const Case& c : {Case{"glass_spheres.json", 58.0}, Case{"sphere_in_front.json", 58.0}}) {
        WorldRig rig(test::projectScene(c.scene), context());
        rig.set("outline-aa", "off");
        const WorldRig::Reference reference =
            rig.reference(0.0, WorldRig::Evaluation::Deterministic);
        auto psnr = [&](const char* method) {
            rig.set("method", method);
            rig.set("search-steps", "8");
            return rig.psnrAgainst(reference);
        };
        const double traced = psnr("trace"), searched = psnr("dir");
        std::printf("%s at pixel centres, against the reference: trace %.2f dB, DIR 8 %.2f dB\n",
                    c.scene, traced, searched);
        EXPECT_GE(traced, c.floor) << c.scene;
        EXPECT_GT(traced, searched + 4.0) << c.scene;
    }
}

TEST_F(Trace, TheGpuTraceIsTheReferencesPathAtPixelCentresThroughACharacter) {
    // The default figure mid-stride, each channel traced (its glass disperses): the trace and
    // the reference part where a ray through a pixel's centre grazes a surface, whose deformed
    // vertices they hold in float and in double (30-33 dB here, and about 28 on the two glass
    // figures at 192x192); DIR's search through the layers lies 7 dB below.
    WorldRig rig(test::generatedWorld("glass_figure.glb"), context(), 192);
    rig.set("outline-aa", "off");
    rig.set("dispersion-search", "per-channel");
    rig.set("interfaces", "32");
    rig.set("search-steps", "8");
    const WorldRig::Reference reference = rig.reference(0.3, WorldRig::Evaluation::Deterministic);
    auto psnr = [&](const char* method) {
        rig.set("method", method);
        return rig.psnrAgainst(reference, 0.3);
    };
    const double traced = psnr("trace"), searched = psnr("dir");
    std::printf("default figure at pixel centres, against the reference: trace %.2f dB, DIR 8 "
                "%.2f dB\n",
                traced, searched);
    EXPECT_GE(traced, 29.0);
    EXPECT_GT(traced, searched + 4.0);
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
        return rig.psnrAgainst(reference);
    };
    const double roomy = psnr("trace", "4"), tight = psnr("trace", "2"),
                 searched = psnr("dir", "2");
    std::printf("small sphere in front of a large one, against the reference: trace %.2f dB with "
                "K=4, %.2f with K=2; DIR 8 with K=2 %.2f\n",
                roomy, tight, searched);
    EXPECT_GE(tight, roomy - 1.0);
    EXPECT_GT(tight, searched + 5.0);
}

TEST_F(Trace, ARayMeetsAnOpaquePartInTheBvh) {
    // An opaque sphere inside a glass one: a refracted ray meets the core at points the frame
    // does not show (its sides, magnified), which a search on screen cannot find. The trace
    // meets it in the BVH and shades it by its material; without the opaque parts in the BVH it
    // does not see the core at all (13.7 dB).
    WorldRig rig(test::projectScene("sphere_with_core.json"), context(), 192);
    const WorldRig::Reference reference = rig.reference();
    auto psnr = [&](const char* method) {
        rig.set("method", method);
        rig.set("search-steps", "8");
        return rig.psnrAgainst(reference);
    };
    const double traced = psnr("trace"), searched = psnr("dir");
    std::printf("opaque core in a glass sphere, against the reference: trace %.2f dB, DIR 8 %.2f\n",
                traced, searched);
    EXPECT_GE(traced, 33.0);
    EXPECT_GT(traced, searched + 8.0);
}

TEST_F(Trace, ACrowdOfOverlappingCharactersPastKStaysClean) {
    // Five glass figures overlapping (assets/scenes/glass_crowd.json; two of them made of
    // interpenetrating parts): lines of sight cross up to 12 glass surfaces, past K=4 on a
    // twelfth of the glass. DIR walks those pixels' two-surface pair and speckles; the trace
    // meets every surface: 25.0 dB against DIR's 18.2 here.
    WorldRig rig(test::projectScene("glass_crowd.json"), context(), 192);
    rig.useSceneCamera();
    rig.set("search-steps", "8");
    const WorldRig::Reference reference = rig.reference(0.5);
    auto psnr = [&](const char* method, const char* samples) {
        rig.set("method", method);
        rig.set("trace-samples", samples);
        return rig.psnrAgainst(reference, 0.5);
    };
    const double searched = psnr("dir", "1"), traced = psnr("trace", "4");
    std::printf("crowd of five glass figures, 192x192, against the reference: DIR 8 %.2f dB, "
                "trace (4 samples) %.2f dB\n",
                searched, traced);
    EXPECT_GT(traced, searched + 5.0);
    EXPECT_GE(traced, 23.5);
}

TEST_F(Trace, SubPixelSamplesComeCloserToTheReference) {
    // The reference averages 16 rays a pixel; trace-samples 4 averages four, jittered within it.
    WorldRig rig(test::projectScene("glass_spheres.json"), context());
    rig.set("method", "trace");
    rig.set("outline-aa", "off");
    const WorldRig::Reference reference = rig.reference();
    const double one = psnrWithSamples(rig, reference, "1"),
                 four = psnrWithSamples(rig, reference, "4");
    std::printf("two overlapping spheres, trace against the 16-ray reference: 1 sample %.2f dB, "
                "4 samples %.2f dB\n",
                one, four);
    EXPECT_GT(four, one + 1.0);
}

TEST_F(Trace, ManySamplesAddUpWithoutDrift) {
    // Each of 64 samples adds a 64th of its colour to the walk's target. In half floats every
    // sum rounded and the glass came out darker the more samples it took (on the sphere, 512x512,
    // 64 samples scored 49.5 dB against 52.2 at 16); the tracing methods add up in single
    // precision, so the mean over the glass is the reference's whatever the count.
    WorldRig rig(test::projectScene("glass_spheres.json"), context());
    rig.set("method", "trace");
    rig.set("outline-aa", "off");
    const WorldRig::Reference reference = rig.reference();
    auto meanOverGlass = [&](const std::vector<float>& rgba) {
        double sum = 0.0;
        for (std::size_t i = 0; i < reference.mask.size(); ++i)
            if (reference.mask[i])
                sum += double(rgba[4 * i]) + rgba[4 * i + 1] + rgba[4 * i + 2];
        return sum;
    };
    const double traced = meanOverGlass(reference.traced.rgba);
    auto drift = [&](const char* samples) {
        rig.set("trace-samples", samples);
        return meanOverGlass(rig.renderHdr()) / traced - 1.0;
    };
    const double sixteen = drift("16"), many = drift("64");
    std::printf("two overlapping spheres, the glass's mean against the reference's: 16 samples "
                "%+.5f, 64 samples %+.5f\n",
                sixteen, many);
    EXPECT_LT(std::abs(many), 2e-3);
}

TEST_F(Trace, TheHybridTracesThePixelsTheLayersCannotHold) {
    // A small sphere in front of a large one with room for two layers a pixel: the overlap
    // overflows. The hybrid walks the layers and hands to the trace (criterion 1) every pixel
    // that overflowed or whose walk crossed a surface at an overflowing pixel, and the trace
    // meets all four surfaces; handing over only where the walk left the layers (criterion 2)
    // leaves the overflow to the two-surface pair, as DIR does.
    WorldRig rig(test::projectScene("sphere_in_front.json"), context());
    rig.set("layer-capacity", "2");
    rig.set("search-steps", "8");
    const WorldRig::Reference reference = rig.reference();
    auto psnr = [&](const char* method, const char* criteria) {
        rig.set("method", method);
        rig.set("hybrid-criteria", criteria);
        return rig.psnrAgainst(reference);
    };
    const double searched = psnr("dir", "15"), traced = psnr("trace", "15");
    const double overflow = psnr("hybrid", "1");
    const refraction::LayerStats stats = rig.plugin().layerStats();
    // Its trace pass traces each handed-over pixel trace-samples times.
    rig.set("trace-samples", "4");
    const double sampled = psnr("hybrid", "1");
    const refraction::LayerStats sampledStats = rig.plugin().layerStats();
    rig.set("trace-samples", "1");
    const double offLayers = psnr("hybrid", "2");
    std::printf("small sphere in front, K=2, against the reference: DIR 8 %.2f dB, trace %.2f, "
                "hybrid tracing the overflow %.2f (%u of %u glass pixels; 4 samples %.2f, %llu "
                "rays against %llu), tracing only where the walk left the layers %.2f\n",
                searched, traced, overflow, stats.hybridTraced, stats.walkedPixels, sampled,
                static_cast<unsigned long long>(sampledStats.traceRays),
                static_cast<unsigned long long>(stats.traceRays), offLayers);
    EXPECT_EQ(sampledStats.hybridTraced, stats.hybridTraced);
    EXPECT_GT(sampledStats.traceRays, 3 * stats.traceRays);
    EXPECT_GT(sampled, overflow);
    EXPECT_GT(stats.overflowPixels, 100u);
    EXPECT_GE(stats.hybridBy[0], stats.overflowPixels); // every overflowing pixel traced
    EXPECT_EQ(stats.hybridTraced, stats.hybridBy[0]);   // for that reason alone
    EXPECT_GT(overflow, searched + 5.0);
    EXPECT_GT(overflow, offLayers + 5.0);
    EXPECT_GE(overflow, traced - 1.0);
}

TEST_F(Trace, TheHybridSamplesTheShareItWalks) {
    // The default figure's hammered head and limbs, where the hybrid walks most pixels (handing
    // over only the overflow): with trace-samples its walk also runs once a sample, each
    // jittered ray entering where the layers around it place the surface, so the walked pixels
    // are anti-aliased as the traced ones are.
    WorldRig rig(test::generatedWorld("glass_figure.glb"), context(), 256);
    rig.set("method", "hybrid");
    rig.set("hybrid-criteria", "1");
    const WorldRig::Reference reference = rig.reference(0.3);
    const double one = psnrWithSamples(rig, reference, "1", 0.3),
                 eight = psnrWithSamples(rig, reference, "8", 0.3);
    const refraction::LayerStats stats = rig.plugin().layerStats();
    std::printf("default figure, hybrid handing over the overflow, against the reference: 1 "
                "sample %.2f dB, 8 samples %.2f dB (%u of %u glass pixels traced)\n",
                one, eight, stats.hybridTraced, stats.walkedPixels);
    EXPECT_LT(stats.hybridTraced, stats.walkedPixels / 4);
    EXPECT_GT(eight, one + 0.8); // 1.3 dB here
}

TEST_F(Trace, TheHybridsSamplesEnterWhereTheLayersAroundThemPlaceTheSurface) {
    // The glass spheres, where the hybrid walks nearly every pixel: a sample at another point of
    // the pixel enters where the layers of the pixels around that point place the surface (its
    // normal interpolated between them, the scene behind where it misses the glass), so each
    // point of a curved pixel bends its own way and the samples converge. Entered on the plane
    // of the pixel's nearest layer, every sample of a pixel bent alike: 16 samples scored
    // 33.62 dB against one sample's 34.39 (35.77 now).
    WorldRig rig(test::projectScene("glass_spheres.json"), context(), 96);
    rig.useSceneCamera();
    rig.set("method", "hybrid");
    const WorldRig::Reference reference = rig.reference(0.0);
    const double one = psnrWithSamples(rig, reference, "1"),
                 sixteen = psnrWithSamples(rig, reference, "16");
    std::printf("glass spheres, hybrid against the reference: 1 sample %.2f dB, 16 samples %.2f "
                "dB\n",
                one, sixteen);
    EXPECT_GT(sixteen, one + 1.0);
}

TEST_F(Trace, TheHybridWalksALoneReflectionAtOneSample) {
    // The default figure, the hybrid handing over for total internal reflection alone: at one
    // sample a pixel a reflection inside a lone piece that sends the ray on deeper stays with
    // the walk, so fewer pixels go to the trace than with two samples, where every reflection
    // the walk follows does (most of the figure's reflect where a limb lies in front of the
    // body: more glass on the line of sight).
    WorldRig rig(test::generatedWorld("glass_figure.glb"), context(), 256);
    rig.set("method", "hybrid");
    rig.set("hybrid-criteria", "4");
    auto traced = [&](const char* samples) {
        rig.set("trace-samples", samples);
        rig.render(0.3);
        return rig.plugin().layerStats().hybridBy[2];
    };
    const std::uint32_t one = traced("1"), two = traced("2");
    std::printf("default figure, hybrid handing over for reflection: %u pixels at one sample, "
                "%u at two\n",
                one, two);
    EXPECT_GT(one, 0u);
    EXPECT_LT(one, two * 9 / 10);
}

TEST_F(Trace, UnderSubdivisionTheTraceMeetsTheRefinedSurface) {
    // A glass box refined to level 2 is a rounded blob: the trace's BVH holds the triangles as
    // drawn (not the box's twelve), and the reference traces the same refined surface, so the
    // trace through each pixel's centre is the reference's deterministic path; DIR's search
    // over the layers comes close to the reference too.
    scene::World world = scene::singleCharacterWorld(
        std::make_shared<const scene::Model>(*asset::loadModel("builtin:box")));
    WorldRig rig(std::move(world), context(), 192);
    rig.set("glass", "all");
    rig.set("search-steps", "8");
    rig.setSubdivisionLevel(2);
    const WorldRig::Reference exact = rig.reference(0.0, WorldRig::Evaluation::Deterministic);
    rig.set("method", "trace");
    rig.set("outline-aa", "off");
    const double traced = rig.psnrAgainst(exact);
    rig.set("method", "dir");
    const double searched = rig.psnrAgainst(exact);
    std::printf("glass box at level 2 against the reference's deterministic path: the trace "
                "%.2f dB, DIR 8 %.2f dB\n",
                traced, searched);
    EXPECT_GE(traced, 55.0);   // 63.5 here; far off with the box's own triangles in the BVH
    EXPECT_GE(searched, 50.0); // 59.1 here
}

TEST_F(Trace, EveryHitReadsItsNormalMap) {
    // The parts figure's hammered head: the capture's entry and every surface the trace meets
    // after it are normal-mapped, as the reference maps them. With the vertex normal at the
    // traced hits (the entry alone mapped) the head shows another pattern: 25.7 dB here, 29.7
    // with the maps.
    WorldRig rig(test::generatedWorld("glass_figure_parts.glb"), context(), 256);
    rig.set("method", "trace");
    rig.set("trace-samples", "16");
    const WorldRig::Reference reference = rig.reference(0.9);
    const double psnr = rig.psnrAgainst(reference, 0.9);
    std::printf("parts figure, trace (16 samples) against the reference: %.2f dB\n", psnr);
    EXPECT_GE(psnr, 28.0);
}

TEST_F(Trace, EachSampleIsADrawOfItsOwnAndCounted) {
    // Mesa's llvmpipe ends every loop of a shader invocation after 65535 iterations in all. 16
    // samples of the dispersive default figure, each channel traced through up to 32
    // interfaces, went past that in one invocation and came out dark where the paths were cut
    // (6 dB below 4 samples); a draw a sample keeps each far within it.
    WorldRig rig(test::generatedWorld("glass_figure.glb"), context(), 256);
    rig.set("method", "trace");
    rig.set("dispersion-search", "per-channel");
    rig.set("interfaces", "32");
    const WorldRig::Reference reference = rig.reference(0.3);
    const double four = psnrWithSamples(rig, reference, "4", 0.3),
                 sixteen = psnrWithSamples(rig, reference, "16", 0.3);
    const refraction::LayerStats stats = rig.plugin().layerStats();
    std::printf("default figure, per channel, 32 interfaces, trace against the reference: 4 "
                "samples %.2f dB, 16 samples %.2f dB; %llu rays, %.1f nodes a ray, at most %u "
                "nodes in one pixel's draw\n",
                four, sixteen, static_cast<unsigned long long>(stats.traceRays),
                double(stats.traceSteps) / double(std::max<std::uint64_t>(stats.traceRays, 1)),
                stats.traceMaxSteps);
    EXPECT_GT(sixteen, four + 0.5);
    EXPECT_GT(stats.traceRays, 16u * 1000u); // every glass pixel's 16 rays and their interfaces
    EXPECT_GT(stats.traceSteps, stats.traceRays);
    EXPECT_LT(stats.traceMaxSteps, 65535u / 4);
    rig.set("method", "dir");
    rig.render(0.3);
    EXPECT_EQ(rig.plugin().layerStats().traceRays, 0u); // no trace, no rays
}

TEST_F(Trace, LightsAndTheTraceShareTheFrame) {
    // A glass ball, an opaque box and three lights (assets/scenes/lights.json): the trace, the
    // hybrid and ISR build the glass BVH, whose buffers once took the lights' storage binding
    // (and the glass materials'): the ball came out black (the trace 5.1 dB, the hybrid 16.2,
    // ISR 17.5). The registry gives every buffer a binding of its own.
    // The lights' caustics are the Shadows tests' (they cost 0.7-1.9 dB here, docs/accuracy.md).
    WorldRig rig(test::projectScene("lights.json"), context(), 192);
    rig.useSceneCamera();
    rig.set("caustics", "off");
    const WorldRig::Reference reference = rig.reference();
    auto psnr = [&](const char* method) {
        rig.set("method", method);
        return rig.psnrAgainst(reference);
    };
    const double traced = psnr("trace"), hybrid = psnr("hybrid"), isr = psnr("isr"),
                 dir = psnr("dir");
    std::printf("lights.json, against the reference: trace %.2f dB, hybrid %.2f, ISR %.2f, DIR "
                "%.2f\n",
                traced, hybrid, isr, dir);
    EXPECT_GE(traced, 33.0);
    EXPECT_GE(hybrid, 33.0);
    EXPECT_GE(isr, 25.0);
}

} // namespace
