// The layered path: glass seen through glass against the Embree reference (grazing entries
// included), every glass material and normal map in one geometry pass, overflowing pixels
// counted and degraded to the two-surface pair, the stored layers matching the surfaces the
// reference counts, and ISR ending on an open surface where DIR does.
#include "WorldRig.h"
#include "support/GlTest.h"
#include "support/TestSupport.h"

#include "engine/asset/ModelLoader.h"
#include "engine/asset/SceneFile.h"
#include "engine/capture/Metrics.h"
#include "engine/render/Renderer.h"
#include "refraction/ReferenceTracer.h"
#include "refraction/RefractionPlugin.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include <sys/resource.h>

namespace {

using test::WorldRig;

/** A scene written out as `json` and loaded (models by builtin name: nothing outside it). */
scene::World sceneFromText(const std::string& json) {
    test::TempDir dir;
    const std::filesystem::path path = dir / "scene.json";
    std::ofstream(path) << json;
    auto world = asset::loadScene(path.string());
    EXPECT_TRUE(world.ok()) << (world.ok() ? "" : world.error().message);
    return world ? std::move(*world) : scene::World{};
}

class Layers : public test::GlTest {};

// A variant the plugin cannot compile fails the frame, naming what failed, rather than rendering
// a frame that silently lacks its glass (and a tool exiting 0 with it).
TEST_F(Layers, AGlassProgramThatDoesNotCompileFailsTheFrame) {
    WorldRig rig(test::generatedWorld("glass_figure.glb"), context(), 32);
    const gl::ShaderFile broken[] = {
        {"refraction/passes/walk.frag.glsl", "void main() { not glsl }"}};
    rig.renderer().shaders().add(broken);
    render::RenderSettings settings;
    settings.size = {32, 32};
    const auto frame = rig.renderer().render(rig.world(), rig.camera(), settings, 0.0);
    ASSERT_FALSE(frame.ok());
    EXPECT_NE(frame.error().message.find("refraction: "), std::string::npos)
        << frame.error().message;
    EXPECT_NE(frame.error().message.find("walk.frag.glsl"), std::string::npos)
        << frame.error().message;
    acceptErrors(); // the driver's report of the compile that failed, on purpose
}

// The scene's depth tiles let a march through the nearby scene skip a segment nothing opaque
// comes near: the frame is the one the march makes without them, to the bit, with every method
// that marches; a frame with no opaque geometry has nothing to march through, and no tiles.
TEST_F(Layers, TheScenesDepthTilesChangeNoPixel) {
    WorldRig rig(test::projectScene("walk_past.json"), context(), 48);
    rig.useSceneCamera();
    for (const char* method : {"dir", "hybrid", "isr"}) {
        rig.set("method", method);
        std::vector<std::string> passes;
        rig.skippedSteps.clear();
        const std::vector<float> tiled = rig.renderHdr(0.5, &passes);
        EXPECT_NE(std::find(passes.begin(), passes.end(), "refraction.scene_depth_tiles"),
                  passes.end())
            << method;
        rig.skippedSteps = {"scene_tiles"};
        EXPECT_EQ(rig.renderHdr(0.5), tiled) << method;
    }
    WorldRig glassOnly(test::generatedWorld("glass_figure.glb"), context(), 48);
    glassOnly.set("glass", "all");
    std::vector<std::string> passes;
    glassOnly.renderHdr(0.0, &passes);
    EXPECT_EQ(std::find(passes.begin(), passes.end(), "refraction.scene_depth_tiles"),
              passes.end());
}

// SIR's walk reads no pixel's layers but its own: it takes their depths from the arrays, and its
// frame makes no depth maps (1.3 ms of CesiumMan's 20 at 512 x 512). Every method that looks
// past a pixel's own layers searches the maps.
TEST_F(Layers, OnlyTheMethodsThatSearchMakeTheDepthMaps) {
    WorldRig rig(test::projectScene("glass_pair.json"), context(), 48);
    rig.useSceneCamera();
    for (const char* method : {"sir", "isr", "dir", "hybrid", "trace"}) {
        rig.set("method", method);
        std::vector<std::string> passes;
        rig.renderHdr(0.5, &passes);
        const bool maps =
            std::find(passes.begin(), passes.end(), "refraction.layer_depths") != passes.end();
        EXPECT_EQ(maps, std::string(method) != "sir") << method;
    }
}

TEST_F(Layers, GlassBehindGlassBeatsTheTwoSurfaceModel) {
    // Two spheres overlapping on screen: the far one is refracted at its own surfaces through
    // the near one only when the walk goes on after the first glass.
    WorldRig rig(test::projectScene("glass_spheres.json"), context());
    rig.set("method", "dir");
    rig.set("search-steps", "8");
    const auto reference = rig.reference();
    auto psnr = [&](const char* surfaces, const char* interfaces) {
        rig.set("surfaces", surfaces);
        rig.set("interfaces", interfaces);
        const double p = capture::score(rig.render(), reference.image, &reference.mask).psnr;
        std::printf(
            "two overlapping glass spheres, DIR 8, %s, %s interfaces: masked PSNR %.2f dB\n",
            surfaces, interfaces, p);
        return p;
    };
    const double layered = psnr("layers", "8"), firstGlassOnly = psnr("layers", "2"),
                 twoSurface = psnr("two-surface", "8");
    EXPECT_GE(layered, 30.0);
    EXPECT_GT(layered, firstGlassOnly + 5.0);
    EXPECT_GT(layered, twoSurface + 8.0);
    // The two being beaten are working images (21.7 and 20.7 dB here), not a black frame that
    // would make the margins easy.
    EXPECT_GE(firstGlassOnly, 19.0);
    EXPECT_GE(twoSurface, 19.0);
    EXPECT_EQ(reference.traced.trappedSamples, 0u);
}

TEST_F(Layers, GrazingEntriesIntoTheFarGlassRefract) {
    // Rays leaving the near sphere's left side meet the far sphere at grazing incidence, close
    // to its outline. Light entering a sphere from air cannot be totally reflected inside it,
    // yet with the pixel's own normal at the entry (or one filtered over the front layers only,
    // which end at the outline) the error of a few degrees made the exit reflect totally: a
    // band of the near sphere far off the reference. The entry's normal is filtered as the
    // exit's, across front and back layers, texels past the outline counting with the normal
    // square to the line of sight there, and a TIR within 2.5 degrees of the critical angle
    // leaves grazing (4 degrees in a segment that entered near an outline, where the normal is
    // good to no better). 37.8 dB here; 37.4 with 2.5 degrees throughout, 31.6 with the front
    // layers only, 31.0 with the pixel's own normal at entries, 36.0 without the band, 35.2
    // without the texels past the outline.
    WorldRig rig(test::projectScene("glass_spheres.json"), context(), 256);
    rig.useSceneCamera();
    rig.set("method", "dir");
    rig.set("search-steps", "8");
    rig.set("tir", "reflect");
    const double psnr = rig.psnrAgainstReference();
    std::printf("two overlapping glass spheres, 256x256, DIR 8, TIR reflect: masked PSNR %.2f dB\n",
                psnr);
    EXPECT_GE(psnr, 37.6);
}

TEST_F(Layers, OutlinesOfSmoothGlassAreAntialiased) {
    // The reference's pixels average 16 rays: along the small sphere's outline they mix it with
    // the large sphere behind. The outline pass places the outline within each pixel from the
    // normals and mixes in the neighbour's colour across it (35.2 dB here, 34.1 without).
    WorldRig rig(test::projectScene("sphere_in_front.json"), context(), 256);
    rig.useSceneCamera();
    rig.set("method", "dir");
    rig.set("search-steps", "8");
    const auto reference = rig.reference();
    auto psnr = [&](const char* outlines) {
        rig.set("outline-aa", outlines);
        const double p = capture::score(rig.render(), reference.image, &reference.mask).psnr;
        std::printf("small sphere in front of a large one, 256x256, DIR 8, outline-aa %s: masked "
                    "PSNR %.2f dB\n",
                    outlines, p);
        return p;
    };
    const double antialiased = psnr("on"), aliased = psnr("off");
    EXPECT_GT(antialiased, aliased + 0.8);
}

TEST_F(Layers, RaysLeavingGlassBehindAnOpaquePartDoNotSeeIt) {
    // The figure's eyes are opaque spheres at the front of its glass head. Rays through the
    // lower face leave the head and pass behind them. The nearby-scene lookup meets a surface
    // only where the ray goes from in front of the depth map to behind that surface (its last
    // point in front within the refined step of it), not wherever it is behind and within a
    // thickness: there a ring of eye images filled the lower face. 27.5 dB here; 23.7 with the
    // old test, 23.3 with only the start of the ray checked (28.0 before the walk met the eyes
    // on its way: at this size they come out a pixel larger than the reference's).
    WorldRig rig(test::generatedWorld("glass_figure.glb"), context(), 256);
    rig.set("method", "dir");
    rig.set("search-steps", "8");
    const double psnr = rig.psnrAgainstReference(0.3);
    std::printf("default figure, 256x256, DIR 8: masked PSNR %.2f dB\n", psnr);
    EXPECT_GE(psnr, 27.0);
}

TEST_F(Layers, TheWalkMeetsOpaquePartsInsideTheGlass) {
    // An opaque marble inside a glass sphere, off centre. The capture keeps the glass behind the
    // marble (the sphere's far side there), and the walk meets the marble on its way: rays that
    // refract past it see it, magnified, and rays that leave the sphere beside it see the sky.
    // Glass hidden behind the opaque part, as the capture once dropped it, left the far side
    // missing in those pixels: rays crossed it elsewhere, or ended on the marble from behind.
    // 30.2 dB here; 26.5 with the old capture, with or without the march; 19.5 with the hidden
    // glass kept and no march (rays went through the marble).
    WorldRig rig(sceneFromText(R"({
      "characters": [
        {"name": "marble", "model": "builtin:sphere", "translation": [0.3, 0.2, 0.1],
         "scale": [0.3, 0.3, 0.3], "glass": "none"},
        {"name": "glass", "model": "builtin:sphere", "glass": "all"}
      ]
    })"),
                 context(), 256);
    rig.set("method", "dir");
    rig.set("search-steps", "8");
    const double psnr = rig.psnrAgainstReference();
    std::printf("marble inside a glass sphere, 256x256, DIR 8: masked PSNR %.2f dB\n", psnr);
    EXPECT_GE(psnr, 29.0);
}

TEST_F(Layers, RaysMeetTheGroundAtGrazingAngles) {
    // A glass sphere on the ground seen from low: its upper half shows the ground behind the
    // camera upside down, met by rays that fall to it at grazing angles, far away, where one
    // step of the nearby-scene march goes deep behind the ground. The crossing is refined first
    // and judged where it is (within the thickness of the surface found), not at the step:
    // judged at the step, most such rays were refused and saw the sky, a stripe pattern.
    // 38.1 dB here; 27.8 judged at the step.
    WorldRig rig(sceneFromText(R"({
      "ground": true,
      "camera": {"position": [0.0, 0.5, 4.0], "target": [0.0, 0.45, 0.0], "yfov": 0.6},
      "characters": [
        {"name": "glass", "model": "builtin:sphere", "translation": [0.0, 0.5, 0.0],
         "scale": [0.5, 0.5, 0.5], "glass": "all"}
      ]
    })"),
                 context(), 256);
    rig.useSceneCamera();
    rig.set("method", "dir");
    rig.set("search-steps", "8");
    const double psnr = rig.psnrAgainstReference();
    std::printf("glass sphere on the ground seen from low, 256x256, DIR 8: masked PSNR %.2f dB\n",
                psnr);
    EXPECT_GE(psnr, 34.0);
}

TEST_F(Layers, RaysPastTheNearbyDistanceMeetTheGround) {
    // A figure behind a glass pane on the ground: rays leaving the pane low toward the horizon
    // meet the ground far beyond the nearby-scene march's reach. They are intersected with the
    // ground square exactly and see it shaded there (the environment instead: a stripe of sky
    // along the ground's far edge through the pane, 26.2 dB against 27.5).
    WorldRig rig(test::projectScene("glass_pane.json"), context(), 256);
    rig.useSceneCamera();
    rig.set("method", "dir");
    rig.set("search-steps", "8");
    const double psnr = rig.psnrAgainstReference(0.5);
    std::printf("figure behind a pane, 256x256, DIR 8: masked PSNR %.2f dB\n", psnr);
    EXPECT_GE(psnr, 27.0);
}

TEST_F(Layers, EveryMaterialAndNormalMapInOneGeometryPass) {
    // The parts figure: four glasses (IOR 1.5 to 1.6, each its own tint, the head hammered by a
    // normal map) and opaque eyes. The layered path draws the glass once and shades each
    // fragment with its own material: nearer the reference than the same figure made of any one
    // of its glasses, unmapped, scored against the same reference (23.8 dB against 22.5 at
    // best, 19.3 all blue). The two-surface path falls back to the papers' two passes.
    const std::string parts = "glass_figure_parts.glb";
    WorldRig rig(test::generatedWorld(parts), context());
    rig.set("method", "dir");
    rig.set("search-steps", "8");
    const auto reference = rig.reference(0.3);
    std::vector<std::string> layered, twoSurface;
    const capture::Image image = rig.render(0.3, &layered);
    const double mixed = capture::score(image, reference.image, &reference.mask).psnr;

    // The same figure made of each one of its glasses, unmapped.
    const scene::World ownWorld = test::generatedWorld(parts);
    double best = 0.0;
    for (const scene::Material& glass : ownWorld.characters[0].model->materials) {
        if (!glass.isTransmissive())
            continue;
        scene::World oneGlass = test::generatedWorld(parts, false);
        auto model = std::make_shared<scene::Model>(*oneGlass.characters[0].model);
        for (scene::Material& m : model->materials)
            if (m.isTransmissive())
                m = glass, m.normalTexture = {};
        oneGlass.characters[0].model = model;
        WorldRig single(std::move(oneGlass), context());
        single.set("method", "dir");
        single.set("search-steps", "8");
        const double psnr =
            capture::score(single.render(0.3), reference.image, &reference.mask).psnr;
        std::printf("parts figure all of '%s' glass: masked PSNR %.2f dB\n", glass.name.c_str(),
                    psnr);
        best = std::max(best, psnr);
    }
    std::printf("parts figure, DIR 8, one geometry pass, its own materials: %.2f dB\n", mixed);
    EXPECT_GT(mixed, best + 0.8);

    rig.set("surfaces", "two-surface");
    rig.render(0.3, &twoSurface);
    auto has = [](const std::vector<std::string>& passes, const char* name) {
        return std::find(passes.begin(), passes.end(), name) != passes.end();
    };
    EXPECT_TRUE(has(layered, "refraction.layer_capture"));
    EXPECT_FALSE(has(layered, "refraction.pair_surface.back"));
    EXPECT_FALSE(has(layered, "refraction.pair_surface.front"));
    EXPECT_TRUE(has(twoSurface, "refraction.pair_surface.back"));
    EXPECT_TRUE(has(twoSurface, "refraction.pair_surface.front"));
}

TEST_F(Layers, TheCaptureAppliesNormalMaps) {
    // The parts figure's head is hammered glass (a normal map): the same figure without that
    // texture renders differently, and only there.
    auto image = [&](bool normalMap) {
        WorldRig rig(test::generatedWorld("glass_figure_parts.glb", normalMap), context());
        rig.set("method", "dir");
        return rig.render(0.3);
    };
    const capture::Image withMap = image(true), without = image(false);
    std::size_t differing = 0;
    for (std::size_t i = 0; i < withMap.rgba.size(); ++i)
        differing += std::abs(int(withMap.rgba[i]) - int(without.rgba[i])) > 4 ? 1 : 0;
    std::printf("parts figure with and without its normal map: %zu channels differ\n", differing);
    EXPECT_GT(differing, 100u);
}

TEST_F(Layers, TheReferenceAppliesNormalMapsToo) {
    // The reference perturbs the normals of every surface with a normal map as the GPU does
    // (common/normal_map.glsl), so the hammered head is scored against hammered glass. The
    // GPU's image averaged over 4x4 pixels (as the reference averages its rays) is nearer the
    // reference of the mapped figure than that of the smooth one where the map changes it
    // (24.8 dB against 17.9).
    constexpr int kSmall = 128, kFactor = 4;
    const std::string parts = "glass_figure_parts.glb";
    WorldRig fine(test::generatedWorld(parts), context(), kSmall * kFactor),
        mapped(test::generatedWorld(parts), context(), kSmall),
        smooth(test::generatedWorld(parts, false), context(), kSmall);
    for (WorldRig* rig : {&fine, &mapped, &smooth})
        rig->set("method", "dir");
    const std::vector<float> hdr = fine.renderHdr(0.3);
    std::vector<float> averaged(std::size_t(kSmall) * kSmall * 4, 0.0f);
    for (int y = 0; y < kSmall * kFactor; ++y)
        for (int x = 0; x < kSmall * kFactor; ++x)
            for (std::size_t c = 0; c < 4; ++c)
                averaged[(std::size_t(y / kFactor) * kSmall + std::size_t(x / kFactor)) * 4 + c] +=
                    hdr[(std::size_t(y) * kSmall * kFactor + std::size_t(x)) * 4 + c] /
                    float(kFactor * kFactor);
    const capture::Image image{kSmall, kSmall, render::cpu::tonemap(averaged, 1.0f)};
    const capture::Image withMap = mapped.render(0.3), without = smooth.render(0.3);
    std::vector<bool> head(image.rgba.size() / 4, false);
    for (std::size_t i = 0; i < image.rgba.size(); ++i)
        if (std::abs(int(withMap.rgba[i]) - int(without.rgba[i])) > 4)
            head[i / 4] = true;
    const auto reference = mapped.reference(0.3), smoothReference = smooth.reference(0.3);
    const double psnr = capture::score(image, reference.image, &head).psnr,
                 againstSmooth = capture::score(image, smoothReference.image, &head).psnr;
    std::printf("parts figure, DIR at 512x512 averaged to 128x128, %zu pixels the map changes: "
                "PSNR %.2f dB against the mapped reference, %.2f against the smooth one\n",
                std::size_t(std::count(head.begin(), head.end(), true)), psnr, againstSmooth);
    EXPECT_GT(psnr, againstSmooth + 4.0);
}

TEST_F(Layers, TouchingGlassGivesOneFrameInEitherDrawOrder) {
    // Two glass boxes, one behind the other, touching: the near one's back face and the far
    // one's front face lie at one depth, to the bit (square to the line of sight). A pixel's
    // slots take its fragments in the order they arrive, which a GPU does not fix; here the
    // characters' order decides it. The walk crosses layers at one depth one after the other,
    // whichever slot holds which (docs/methods.md, "Order-independent writes"), so either order
    // gives the same frame.
    auto touching = [](bool farFirst) {
        auto box = asset::loadModel("builtin:box");
        EXPECT_TRUE(box.ok()) << box.error().message;
        scene::World world =
            scene::singleCharacterWorld(std::make_shared<const scene::Model>(*box));
        scene::Character far = world.characters[0];
        world.characters[0].placement.translation = glm::dvec3(0.0, 0.0, 0.5);
        far.placement.translation = glm::dvec3(0.0, 0.0, -0.5);
        world.characters.insert(farFirst ? world.characters.begin() : world.characters.end(), far);
        return world;
    };
    std::vector<std::vector<float>> frames;
    for (bool farFirst : {false, true})
        for (const char* method : {"dir", "isr"}) {
            WorldRig rig(touching(farFirst), context(), 64);
            rig.setCamera(render::frameBounds(render::worldBounds(rig.world()), 1.0f, 0.7f, 0.0f,
                                              0.0f, 1.0f));
            rig.set("method", method);
            frames.push_back(rig.renderHdr());
        }
    EXPECT_TRUE(frames[0] == frames[2]) << "DIR: the frame follows the draw order";
    EXPECT_TRUE(frames[1] == frames[3]) << "ISR: the frame follows the draw order";
}

TEST_F(Layers, IsrOnAnOpenSurfaceEndsWhereDirDoes) {
    // One face of the box, toward the camera: a sheet with nothing behind it and no d_N. ISR has no
    // exit to estimate there; like DIR's search it finds none, and the ray leaves through the sheet
    // (it used to bounce on the sheet itself up to N interfaces).
    auto box = asset::loadModel("builtin:box");
    ASSERT_TRUE(box.ok()) << box.error().message;
    scene::Primitive& sheet = box->meshes[0].primitives[0];
    sheet.indices = {sheet.indices.begin() + 24, sheet.indices.begin() + 30}; // the +z face
    scene::World world = scene::singleCharacterWorld(std::make_shared<const scene::Model>(*box));
    WorldRig rig(std::move(world), context());
    rig.set("debug", "steps"); // blue: interfaces crossed / N
    auto stepsView = [&](const char* method) {
        rig.set("method", method);
        return rig.render();
    };
    const capture::Image dir = stepsView("dir"), isr = stepsView("isr");
    std::size_t glass = 0, same = 0;
    for (std::size_t i = 0; i < dir.rgba.size(); i += 4)
        if (dir.rgba[i + 2] > 0) {
            ++glass;
            same += std::abs(int(isr.rgba[i + 2]) - int(dir.rgba[i + 2])) <= 2 ? 1 : 0;
        }
    EXPECT_GT(glass, 500u) << "the sheet covers part of the frame";
    EXPECT_EQ(same, glass) << "pixels where ISR crossed other interfaces than DIR";
    // And the sheet as both shade it: what the reference sees through it.
    rig.set("debug", "none");
    const WorldRig::Reference reference = rig.reference();
    for (const char* method : {"dir", "isr"}) {
        rig.set("method", method);
        const double psnr = rig.psnrAgainst(reference);
        std::printf("an open sheet, %s against the reference: %.2f dB\n", method, psnr);
        EXPECT_GE(psnr, 50.0) << method; // 56.1 here
    }
}

TEST_F(Layers, OverflowingPixelsKeepTheirNearestFrontAndFarthestBack) {
    // One layer per pixel: every glass pixel of a sphere overflows and keeps its nearest front
    // and farthest back, which for a sphere are all its surfaces: the image barely changes.
    WorldRig rig(test::projectScene("glass_spheres.json"), context());
    rig.set("method", "dir");
    const capture::Image full = rig.render();
    const auto fullStats = rig.plugin().layerStats();
    rig.set("layer-capacity", "1");
    const capture::Image one = rig.render();
    const auto oneStats = rig.plugin().layerStats();
    EXPECT_EQ(fullStats.capacity, 4);
    EXPECT_EQ(oneStats.capacity, 1);
    EXPECT_LE(fullStats.bytesPerPixel, 84u);
    EXPECT_EQ(fullStats.overflowPixels, 0u);
    EXPECT_GT(oneStats.overflowPixels, 1000u);
    const double psnr = capture::score(one, full).psnr;
    std::printf("glass spheres, K=1 (%u pixels over) against K=4: PSNR %.2f dB\n",
                oneStats.overflowPixels, psnr);
    EXPECT_GE(psnr, 25.0);
    rig.set("debug", "overflow");
    const capture::Image view = rig.render();
    std::size_t red = 0;
    for (std::size_t i = 0; i < view.rgba.size(); i += 4)
        red += view.rgba[i] > 200 && view.rgba[i + 1] < 60 ? 1 : 0;
    EXPECT_GT(red, 1000u) << "the overflow view marks the overflowing pixels red";
}

TEST_F(Layers, StoredLayersMatchTheSurfacesTheReferenceCounts) {
    // The layer-count view (count / K, grey) against the reference's count of the surfaces on
    // each glass pixel's line of sight: the share of pixels with four.
    WorldRig rig(test::projectScene("sphere_in_front.json"), context());
    rig.set("method", "dir");
    const auto reference = rig.reference();
    const auto& histogram = reference.traced.surfaceHistogram;
    ASSERT_GE(histogram.size(), 5u);
    std::size_t traced = 0;
    for (std::size_t n : histogram)
        traced += n;
    rig.set("debug", "layer-count");
    const std::vector<float> view = rig.renderHdr();
    std::size_t glass = 0, four = 0;
    for (std::size_t i = 0; i < view.size(); i += 4) {
        if (!reference.mask[i / 4])
            continue;
        const float count = view[i + 1] * 4.0f; // green: count / K (red alone: overflow)
        ++glass;
        four += std::abs(count - 4.0f) < 0.1f ? 1 : 0;
    }
    const double gpuShare = double(four) / double(std::max<std::size_t>(glass, 1));
    // The reference counts from one sample per pixel, the mask from its coverage: close.
    const double referenceShare = double(histogram[4]) / double(std::max<std::size_t>(traced, 1));
    std::printf("small sphere in front of a large one: pixels with 4 layers %.3f (GPU) vs %.3f "
                "(reference)\n",
                gpuShare, referenceShare);
    EXPECT_GT(referenceShare, 0.1);
    EXPECT_NEAR(gpuShare, referenceShare, 0.03);
}

// llvmpipe bins a refined pair's triangles, drawn on both faces, in tens of MiB of heap a frame
// and frees them when the frame is drawn. Alternating DIR and ISR (the viewer's split, the
// bench's interleave) once made glibc hand that memory back between frames, and every capture
// faulted it in again: 13 thousand page faults a frame here, three times the capture's time at
// level 2. The renderer keeps the heap on a CPU rasteriser (Renderer.cpp).
TEST_F(Layers, AlternatingMethodsFaultNoHeapBackInEachFrame) {
    const std::string renderer = gl::rendererString();
    if (renderer.find("llvmpipe") == std::string::npos)
        GTEST_SKIP() << "a CPU rasteriser's heap; this is " << renderer;
    WorldRig rig(test::projectScene("glass_pair.json"), context(), 128);
    rig.useSceneCamera();
    rig.setSubdivisionLevel(1);
    const auto round = [&] {
        for (const char* method : {"dir", "isr"}) {
            rig.set("method", method);
            rig.renderHdr();
        }
    };
    const auto faults = [] {
        rusage usage{};
        getrusage(RUSAGE_SELF, &usage);
        return usage.ru_minflt;
    };
    for (int i = 0; i < 2; ++i) // every program and llvmpipe's variants of it compiled
        round();
    const long before = faults();
    for (int i = 0; i < 3; ++i)
        round();
    const double perFrame = double(faults() - before) / 6.0;
    std::printf("page faults a frame, alternating DIR and ISR at level 1: %.0f\n", perFrame);
    // None here (after one warm-up round, 700-1,350: the first frames' own); 13 thousand with
    // the heap handed back.
    EXPECT_LT(perFrame, 3000.0);
}

} // namespace
