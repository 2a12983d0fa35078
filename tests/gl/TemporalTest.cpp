// Temporal accumulation (docs/methods.md, "Temporal accumulation"): the motion vectors of a
// deforming, moving character seen by a moving camera against finite differences of the CPU
// deformation (skinned and morphed, refined by OpenSubdiv, instanced); still frames that average
// exactly to the mean of their jittered samples and converge as many samples in one frame do; no
// trail behind a character that moves off the background; the resolve's test of a history
// (another body, a disocclusion, a path's exit turned more than a right angle); camera cuts,
// edits of the world, resizes and changed settings that start the history over; every method
// accumulating as lit characters walk past.
#include "MatrixWorlds.h"
#include "support/GlTest.h"
#include "support/TestSupport.h"

#include "engine/asset/HdrImage.h"
#include "engine/deform/CpuDeformer.h"
#include "engine/deform/Subdivision.h"
#include "engine/gl/Buffer.h"
#include "engine/gl/Commands.h"
#include "engine/render/Shared.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <optional>

namespace {

using test::WorldRig;

class Temporal : public test::GlTest {};

float halfToFloat(std::uint32_t bits) {
    const std::uint32_t sign = (bits >> 15) & 1u, exponent = (bits >> 10) & 31u,
                        mantissa = bits & 1023u;
    float value = exponent == 0 ? std::ldexp(float(mantissa), -24)
                                : std::ldexp(float(mantissa | 1024u), int(exponent) - 25);
    return sign ? -value : value;
}

/** A world position's pixel position (x right, y up, GL's rows) through `viewProjection`. */
glm::dvec3 pixelOf(const glm::mat4& viewProjection, const glm::dvec3& p, int size) {
    const glm::dvec4 clip = glm::dmat4(viewProjection) * glm::dvec4(p, 1.0);
    return {(clip.x / clip.w * 0.5 + 0.5) * size, (clip.y / clip.w * 0.5 + 0.5) * size, clip.w};
}

/** How the GPU's motion of a moving character agrees with finite differences of its CPU
 *  deformation (refined by OpenSubdiv as the GPU refines it where `subdivision` > 0). */
struct MotionAgreement {
    std::size_t compared = 0, close = 0;
    double worst = 0.0; ///< pixels
};

/** Renders `rig`'s character at t0 and, moved by `move` and seen by the camera turned a little,
 *  at t1 = t0 + 1/30 s (the opaque pass, which writes every drawn surface's motion), then
 *  compares each drawn triangle's centroid, deformed on the CPU at both times: where its pixel
 *  shows it (its depth there), the GPU's motion must be the centroid's change of pixel
 *  position. */
MotionAgreement motionAgainstCpu(WorldRig& rig, int size, int subdivision, double t0,
                                 const std::function<void(scene::Character&)>& move) {
    rig.set("method", "opaque");
    rig.temporal.enabled = true;
    if (subdivision > 0)
        rig.setSubdivisionLevel(subdivision);
    const double t1 = t0 + 1.0 / 30.0;
    const render::Camera first = rig.camera();
    rig.renderHdr(t0);
    const scene::Character before = rig.character(0);
    move(rig.character(0));
    render::Camera second = first;
    second.view = first.view * glm::rotate(glm::mat4(1.0f), 0.02f, glm::vec3(0.0f, 1.0f, 0.0f));
    rig.setCamera(second);
    rig.renderHdr(t1);
    const std::vector<std::uint32_t> texels = rig.renderer().lastMotion().downloadUint();

    // A primitive's deformed vertices in the world, refined where the frame is.
    auto placed = [&](const deform::DeformedInstance& instance, std::size_t p,
                      const deform::Subdivision* refined) {
        deform::DeformedPrimitive deformed = instance.primitives[p];
        if (refined) {
            const deform::RefinedSurface surface =
                deform::refineCage(*refined, deformed.positions, deformed.tangents);
            deformed = {surface.positions, surface.normals, surface.tangents};
        }
        return deform::toWorld(deformed, instance.meshToWorld);
    };
    const auto now = deform::deformCharacter(rig.character(0), t1);
    const auto then = deform::deformCharacter(before, t0);
    const scene::Model& model = *rig.character(0).model;
    MotionAgreement agreement;
    for (std::size_t i = 0; i < now.size(); ++i)
        for (std::size_t p = 0; p < now[i].primitives.size(); ++p) {
            const scene::Primitive& source = model.meshes[std::size_t(now[i].mesh)].primitives[p];
            std::optional<deform::Subdivision> refined;
            if (subdivision > 0) {
                auto built = deform::buildSubdivision(source, subdivision, "test primitive");
                EXPECT_TRUE(built.ok());
                if (!built.ok())
                    return agreement;
                refined = std::move(*built);
            }
            const auto a = placed(now[i], p, refined ? &*refined : nullptr);
            const auto b = placed(then[i], p, refined ? &*refined : nullptr);
            const auto& indices = refined ? refined->rest.indices : source.indices;
            for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
                glm::dvec3 ca(0.0), cb(0.0);
                for (int k = 0; k < 3; ++k) {
                    ca += a.positions[indices[t + std::size_t(k)]] / 3.0;
                    cb += b.positions[indices[t + std::size_t(k)]] / 3.0;
                }
                const glm::dvec3 q = pixelOf(second.viewProjection(), ca, size);
                const glm::dvec3 r = pixelOf(first.viewProjection(), cb, size);
                const int x = int(std::floor(q.x)), y = int(std::floor(q.y));
                if (x < 1 || y < 1 || x >= size - 1 || y >= size - 1)
                    continue;
                const std::uint32_t* m = &texels[(std::size_t(y) * size + std::size_t(x)) * 4];
                if ((m[0] >> render::kMotionKindShift) != std::uint32_t(render::MotionKind::Opaque))
                    continue;
                const double depth = halfToFloat(m[2] & 0xFFFFu);
                if (std::abs(depth - q.z) > 0.01 * q.z) // another surface shows there
                    continue;
                const glm::dvec2 expected(q.x - r.x, q.y - r.y);
                const glm::dvec2 gpu(halfToFloat(m[1] & 0xFFFFu), halfToFloat(m[1] >> 16));
                const double error = glm::length(gpu - expected);
                ++agreement.compared;
                // The pixel's sample is up to a pixel from the centroid: the motion varies that
                // little over it.
                agreement.close += error < 0.15 + 0.1 * glm::length(expected) ? 1 : 0;
                agreement.worst = std::max(agreement.worst, error);
            }
        }
    return agreement;
}

/** The default figure (skinned, a breathing morph target, walking) refined to `subdivision`,
 *  placed by a transform that moves too, seen by a camera that orbits a little between the two
 *  frames: its motion against the CPU's. */
MotionAgreement walkingFigureMotion(gl::Context& context, int subdivision) {
    constexpr int kSize = 160;
    WorldRig rig(test::generatedWorld("glass_figure.glb"), context, kSize);
    rig.character(0).placement.translation = {0.0, 0.0, 0.0};
    return motionAgainstCpu(rig, kSize, subdivision, 0.4, [](scene::Character& c) {
        c.placement.translation = {0.03, 0.01, -0.02};
    });
}

TEST_F(Temporal, MotionVectorsMatchFiniteDifferencesOfTheCpuDeformation) {
    const MotionAgreement a = walkingFigureMotion(context(), 0);
    ASSERT_GT(a.compared, 100u);
    EXPECT_GT(double(a.close) / double(a.compared), 0.95) << "worst error " << a.worst << " px";
}

TEST_F(Temporal, MotionVectorsOfTheRefinedSurfaceMatchItsCpuRefinement) {
    // Refined by OpenSubdiv on the GPU every frame: the previous frame's refined surface, not
    // its cage, is where each pixel's surface was.
    const MotionAgreement a = walkingFigureMotion(context(), 1);
    ASSERT_GT(a.compared, 400u);
    EXPECT_GT(double(a.close) / double(a.compared), 0.98) << "worst error " << a.worst << " px";
}

TEST_F(Temporal, EachInstanceMovesByItsOwnTransform) {
    // One sphere drawn four times (EXT_mesh_gpu_instancing) by a character that turns: each
    // instance moves its own way, and each must carry its own previous transform.
    constexpr int kSize = 128;
    WorldRig rig(test::matrix::instanced(), context(), kSize);
    const MotionAgreement a = motionAgainstCpu(rig, kSize, 0, 0.0, [](scene::Character& c) {
        c.placement.rotation = glm::angleAxis(0.08, glm::dvec3(0.0, 1.0, 0.0));
        c.placement.translation = {0.02, -0.01, 0.0};
    });
    ASSERT_GT(a.compared, 200u);
    EXPECT_GT(double(a.close) / double(a.compared), 0.95) << "worst error " << a.worst << " px";
}

TEST_F(Temporal, StillFramesAverageToTheMeanOfTheirJitteredSamples) {
    // The same still frame sixteen times: raw (no history weight: each frame its own jittered
    // sample), and converging. The converged frame is the mean of the raw ones.
    constexpr int kFrames = 16;
    WorldRig raw(test::generatedWorld("glass_figure.glb"), context(), 96);
    raw.temporal.enabled = true;
    raw.temporal.convergeStill = false;
    raw.temporal.historyWeight = 0.0f;
    WorldRig converged(test::generatedWorld("glass_figure.glb"), context(), 96);
    converged.temporal.enabled = true;
    std::vector<double> mean;
    std::vector<float> accumulated, first, last;
    for (int k = 0; k < kFrames; ++k) {
        const std::vector<float> frame = raw.renderHdr(0.5);
        accumulated = converged.renderHdr(0.5);
        mean.resize(frame.size(), 0.0);
        for (std::size_t i = 0; i < frame.size(); ++i)
            mean[i] += double(frame[i]) / kFrames;
        (k == 0 ? first : last) = frame;
    }
    double worst = 0.0, moved = 0.0;
    for (std::size_t i = 0; i < mean.size(); i += 4)
        for (std::size_t c = 0; c < 3; ++c) {
            worst = std::max(worst, std::abs(double(accumulated[i + c]) - mean[i + c]) /
                                        std::max(1.0, mean[i + c]));
            moved = std::max(moved, double(std::abs(first[i + c] - last[i + c])));
        }
    EXPECT_GT(moved, 0.05) << "the jitter moved no edge";
    EXPECT_LT(worst, 1e-4);
}

TEST_F(Temporal, StillFramesConvergeAsManySamplesInOneFrameDo) {
    // The trace: one sample a frame over 16 frames against 16 samples in one frame, both scored
    // against the reference.
    WorldRig rig(test::projectScene("glass_spheres.json"), context(), 96);
    rig.set("method", "trace");
    const WorldRig::Reference reference = rig.reference(0.3, WorldRig::Evaluation::Sampled, 64);
    rig.set("trace-samples", "16");
    const double samples = rig.psnrAgainst(reference, 0.3);
    rig.set("trace-samples", "1");
    const double one = rig.psnrAgainst(reference, 0.3);
    rig.temporal.enabled = true;
    for (int k = 1; k < 16; ++k)
        rig.renderHdr(0.3);
    const double frames = rig.psnrAgainst(reference, 0.3);
    EXPECT_GT(frames, samples - 0.5) << "one sample " << one;
    EXPECT_GT(frames, one + 3.0);
}

/** The built-in unit sphere played as glass, over the ground plane where `ground`. */
scene::World glassSphere(bool ground) {
    auto sphere = asset::loadModel("builtin:sphere");
    EXPECT_TRUE(sphere.ok());
    scene::World world =
        scene::singleCharacterWorld(std::make_shared<const scene::Model>(std::move(*sphere)));
    world.characters[0].glass = scene::GlassMode::All;
    world.ground = ground;
    return world;
}

/** A still camera over the glass sphere and the ground around it, with room for the sphere to
 *  move a unit either way. */
render::Camera sphereOverGroundCamera() {
    return render::frameBounds(render::Bounds{{-2.0f, -1.0f, -1.0f}, {2.0f, 1.0f, 1.0f}}, 1.0f);
}

/** The pixels (rows top to bottom) whose centre's ray from `camera` meets the unit sphere at
 *  `centre`, grown by a pixel: what the sphere covers. */
std::vector<bool> sphereMask(const render::Camera& camera, const glm::dvec3& centre, int size) {
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(camera.viewProjection()));
    std::vector<bool> mask(std::size_t(size) * std::size_t(size));
    for (int row = 0; row < size; ++row)
        for (int x = 0; x < size; ++x) {
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const glm::dvec2 ndc((x + dx + 0.5) / size * 2.0 - 1.0,
                                         1.0 - (row + dy + 0.5) / size * 2.0);
                    const glm::dvec4 a = inverse * glm::dvec4(ndc, -1.0, 1.0),
                                     b = inverse * glm::dvec4(ndc, 1.0, 1.0);
                    const glm::dvec3 o = glm::dvec3(a) / a.w,
                                     d = glm::normalize(glm::dvec3(b) / b.w - o);
                    const glm::dvec3 oc = o - centre;
                    const double h = glm::dot(oc, d);
                    if (h * h - glm::dot(oc, oc) + 1.0 >= 0.0)
                        mask[std::size_t(row) * std::size_t(size) + std::size_t(x)] = true;
                }
        }
    return mask;
}

TEST_F(Temporal, ACharacterMovingOffTheBackgroundLeavesNoTrail) {
    // A glass sphere crossing the sky, 0.12 units a frame, the camera still. Where it was three
    // frames ago and is no more, the frame must show the sky as the reference does; kept
    // history would leave a trail of glass there.
    const scene::World world = glassSphere(false);
    auto run = [&](bool reject) {
        WorldRig rig(world, context(), 96);
        rig.setCamera(
            render::frameBounds(render::Bounds{{-2.5f, -1.0f, -1.0f}, {2.5f, 1.0f, 1.0f}}, 1.0f));
        rig.character(0).placement.translation = {-1.2, 0.0, 0.0};
        rig.temporal.enabled = true;
        rig.temporal.rejectHistory = reject;
        constexpr int kFrames = 12;
        std::vector<float> last;
        for (int k = 0; k < kFrames; ++k) {
            rig.character(0).placement.translation = {-1.2 + 0.12 * k, 0.0, 0.0};
            last = rig.renderHdr(0.0);
        }
        const std::vector<bool> then =
            sphereMask(rig.camera(), {-1.2 + 0.12 * (kFrames - 4), 0.0, 0.0}, 96);
        const std::vector<bool> now =
            sphereMask(rig.camera(), {-1.2 + 0.12 * (kFrames - 1), 0.0, 0.0}, 96);
        std::vector<bool> uncovered(now.size());
        std::size_t count = 0;
        for (std::size_t p = 0; p < now.size(); ++p)
            count += (uncovered[p] = then[p] && !now[p]) ? 1 : 0;
        EXPECT_GT(count, 100u);
        const WorldRig::Reference reference = rig.reference(0.0);
        const capture::Image frame{96, 96, render::cpu::tonemap(last, 1.0f)};
        return capture::score(frame, reference.image, &uncovered).psnr;
    };
    const double rejecting = run(true), keeping = run(false);
    std::printf("uncovered region against the reference: %.2f dB, %.2f dB keeping the history\n",
                rejecting, keeping);
    EXPECT_GT(rejecting, 40.0);
    EXPECT_LT(keeping, rejecting - 10.0) << "the history kept without rejection left no trail";
}

/** The probe's own storage slot, past the engine's. */
constexpr gl::StorageSlot kProbeOut{70, "PROBE_BINDING", "Probe"};
constexpr gl::Shared kProbeTable[] = {kProbeOut};

// The resolve's test (showsSame) on texels made by hand: a path through glass that left it
// along x on the previous frame and now i degrees away (kept[i], i = 0..180); the same texel
// of another glass body; an opaque point whose depth the history holds 4% and 6% away; the
// path's glass reflecting now (its own glass, then another).
const gl::ShaderFile kShowsSameProbe[] = {
    {"shows_same.comp.glsl",
     "#include \"common/motion.glsl\"\n"
     "layout(local_size_x = 1) in;\n"
     "layout(std430, binding = PROBE_BINDING) buffer Probe { uint kept[]; };\n"
     "void main() {\n"
     "    uint glass = motionIdentity(MOTION_THROUGH_GLASS, 7u);\n"
     "    uvec4 before = packMotion(glass, vec2(0.0), 0.0, 0.0, motionDirection(vec3(1, 0, 0)));\n"
     "    for (int i = 0; i <= 180; ++i) {\n"
     "        float a = radians(float(i));\n"
     "        uint now = motionDirection(vec3(cos(a), sin(a), 0.0));\n"
     "        kept[i] = uint(showsSame(packMotion(glass, vec2(0.0), 0.0, 0.0, now), before));\n"
     "    }\n"
     "    uvec4 other = before;\n"
     "    other.x = motionIdentity(MOTION_THROUGH_GLASS, 8u);\n"
     "    kept[181] = uint(showsSame(other, before));\n"
     "    uint opaque = motionIdentity(MOTION_OPAQUE, 3u);\n"
     "    uvec4 m = packMotion(opaque, vec2(0.0), 2.0, 1.0, 0u);\n"
     "    kept[182] = uint(showsSame(m, packMotion(opaque, vec2(0.0), 1.04, 1.0, 0u)));\n"
     "    kept[183] = uint(showsSame(m, packMotion(opaque, vec2(0.0), 1.06, 1.0, 0u)));\n"
     "    uvec4 reflects = packMotion(motionIdentity(MOTION_GLASS, 7u), vec2(0.0), 0.0, 0.0, 0u);\n"
     "    kept[184] = uint(showsSame(reflects, before));\n"
     "    reflects.x = motionIdentity(MOTION_GLASS, 8u);\n"
     "    kept[185] = uint(showsSame(reflects, before));\n"
     "}\n"}};

TEST_F(Temporal, TheHistoryIsRejectedWhereThePathNowLeavesTheGlassAnotherWay) {
    // The rule (common/motion.glsl, kExitTurn): a path's exit turned by more than a right angle
    // is a jump (the path now leaves the glass another way) and rejects the history; a turn
    // short of it is what a bending limb does from frame to frame, and the clip bounds it.
    // Rejecting at 15 degrees cost every playing row 0.04-0.51 dB (docs/accuracy.md). A glass
    // pixel's history is its glass's, whether the light came through it or was reflected
    // (motionSubject: rejected when what the path ended on changed, every playing row scored
    // 0.01-0.22 dB less).
    gl::ShaderLibrary library = shaders(); // the engine's, and the probe
    library.add(kShowsSameProbe);
    ASSERT_TRUE(library.share("probe", kProbeTable).ok());
    auto program = gl::Program::compute(library, "shows_same.comp.glsl");
    ASSERT_TRUE(program.ok()) << program.error().message;
    constexpr int kCount = 186;
    gl::Buffer out(kCount * sizeof(std::uint32_t));
    program->use();
    gl::bindStorage(kProbeOut, out);
    gl::dispatch(1);
    gl::memoryBarrier(gl::BarrierAll);
    std::uint32_t kept[kCount];
    std::memcpy(kept, out.download().data(), sizeof kept);
    for (int degrees = 0; degrees <= 180; ++degrees) {
        if (degrees == 90)
            continue; // the bound itself, within the directions' 16-bit quantization
        EXPECT_EQ(kept[degrees], degrees < 90 ? 1u : 0u)
            << "an exit turned " << degrees << " degrees";
    }
    EXPECT_EQ(kept[181], 0u) << "another glass body";
    EXPECT_EQ(kept[182], 1u) << "a depth 4% away";
    EXPECT_EQ(kept[183], 0u) << "a depth 6% away (a disocclusion)";
    EXPECT_EQ(kept[184], 1u) << "the same glass, reflecting now";
    EXPECT_EQ(kept[185], 0u) << "another glass, reflecting";
}

TEST_F(Temporal, TheEnvironmentFollowsTheCameraAsItTurns) {
    // The camera turning about a pixel a frame over the sunset sky's coloured blocks, a glass
    // sphere in view. The environment's pixels carry no motion of their own (the motion target
    // is cleared to their texel): the resolve reprojects them by the camera's turn, and the
    // accumulated sky scores at least as one frame does against the reference (39.8 dB
    // against 37.7). Taken where they lie, their history smears the blocks sideways (31.9 dB).
    auto sky = asset::loadHdr(std::string(GLASS_SOURCE_DIR) + "/assets/env/sunset_sky.hdr");
    ASSERT_TRUE(sky.ok()) << sky.error().message;
    const scene::World world = glassSphere(false);
    WorldRig rig(world, context(), 96, &*sky), single(world, context(), 96, &*sky);
    rig.temporal.enabled = true;
    const render::Camera start = rig.camera();
    render::Camera camera = start;
    std::vector<float> accumulated;
    for (int k = 0; k < 12; ++k) {
        camera.view = glm::rotate(glm::mat4(1.0f), 0.01f * float(k), glm::vec3(0.0f, 1.0f, 0.0f)) *
                      start.view;
        rig.setCamera(camera);
        accumulated = rig.renderHdr(0.0);
    }
    single.setCamera(camera);
    const WorldRig::Reference reference = single.reference(0.0);
    std::vector<bool> outside(reference.mask.size());
    for (std::size_t p = 0; p < outside.size(); ++p)
        outside[p] = !reference.mask[p];
    const auto score = [&](const std::vector<float>& hdr) {
        return capture::score({96, 96, render::cpu::tonemap(hdr, 1.0f)}, reference.image, &outside)
            .psnr;
    };
    const double turned = score(accumulated), one = score(single.renderHdr(0.0));
    std::printf("the sky against the reference, the camera turning: %.2f dB accumulated, %.2f dB "
                "one frame\n",
                turned, one);
    EXPECT_GT(turned, one - 1.0);
}

TEST_F(Temporal, ACameraCutStartsTheHistoryOver) {
    WorldRig rig(test::generatedWorld("glass_figure.glb"), context(), 96);
    WorldRig fresh(test::generatedWorld("glass_figure.glb"), context(), 96);
    rig.temporal.enabled = fresh.temporal.enabled = true;
    const render::Camera front = rig.camera();
    render::Camera side = front;
    side.view = front.view * glm::rotate(glm::mat4(1.0f), 1.2f, glm::vec3(0.0f, 1.0f, 0.0f));
    for (int k = 0; k < 6; ++k)
        rig.renderHdr(0.1 * k);
    // A turn past 45 degrees is a cut: the frame is the history's first, as a fresh one's.
    rig.setCamera(side);
    fresh.setCamera(side);
    EXPECT_EQ(rig.renderHdr(0.6), fresh.renderHdr(0.6));
    // A small move is not: the history shows.
    render::Camera near = side;
    near.view = side.view * glm::rotate(glm::mat4(1.0f), 0.01f, glm::vec3(0.0f, 1.0f, 0.0f));
    rig.setCamera(near);
    WorldRig other(test::generatedWorld("glass_figure.glb"), context(), 96);
    other.temporal.enabled = true;
    other.setCamera(near);
    const std::vector<float> kept = rig.renderHdr(0.7), started = other.renderHdr(0.7);
    EXPECT_NE(kept, started);
    // A cut the caller names (Renderer::resetHistory) starts over too, however small the move.
    WorldRig third(test::generatedWorld("glass_figure.glb"), context(), 96);
    third.temporal.enabled = true;
    third.setCamera(near);
    rig.renderer().resetHistory();
    EXPECT_EQ(rig.renderHdr(0.8), third.renderHdr(0.8));
}

TEST_F(Temporal, EditsResizesAndChangedSettingsStartTheHistoryOver) {
    // Each change, made to a rig with a history and to a fresh one: the frame after it is the
    // history's first, as the fresh rig's is (TemporalHistory::begin). The resolve's own weight
    // is no such change: the history shows.
    struct Change {
        const char* name;
        std::function<void(WorldRig&)> apply;
        bool resets;
    };
    const std::vector<Change> changes{
        {"the clip", [](WorldRig& r) { r.character(0).play(1); }, true},
        {"the character's time offset", [](WorldRig& r) { r.character(0).performance.shift(0.3); },
         true},
        {"a plugin parameter", [](WorldRig& r) { r.set("ior", "1.4"); }, true},
        {"the frame's size", [](WorldRig& r) { r.setSize(80); }, true},
        {"the shadows", [](WorldRig& r) { r.shadows = false; }, true},
        {"the history weight", [](WorldRig& r) { r.temporal.historyWeight = 0.8f; }, false},
    };
    for (const Change& change : changes) {
        SCOPED_TRACE(change.name);
        WorldRig rig(test::generatedWorld("glass_figure.glb"), context(), 96);
        WorldRig fresh(test::generatedWorld("glass_figure.glb"), context(), 96);
        rig.temporal.enabled = fresh.temporal.enabled = true;
        for (int k = 0; k < 4; ++k)
            rig.renderHdr(0.1 * k);
        change.apply(rig);
        change.apply(fresh);
        const bool same = rig.renderHdr(0.4) == fresh.renderHdr(0.4);
        EXPECT_EQ(same, change.resets)
            << (same ? "the history started over" : "the frame differs from a fresh history's");
    }
}

/** The figure walking, then (with `fade`) crossfading to its idle clip over 0.4 s from 0.5 s,
 *  accumulating at 96x96, 30 frames a second: the mean masked PSNR against the reference of
 *  every other frame from 0.6 s to 0.8 s (the fade's middle). */
double walkingFigure(gl::Context& context, bool fade) {
    scene::World world = test::generatedWorld("glass_figure.glb");
    scene::Performance& p = world.characters[0].performance;
    if (fade)
        p.transitions = {{0.5, *world.characters[0].model->findAnimation("idle"), 0.4}};
    WorldRig rig(std::move(world), context, 96);
    rig.temporal.enabled = true;
    double sum = 0.0;
    int scored = 0;
    for (int k = 0; k <= 24; ++k) {
        const double time = k / 30.0;
        if (k < 18 || k % 2 != 0) {
            rig.renderHdr(time);
            continue;
        }
        sum += rig.psnrAgainstReference(time);
        ++scored;
    }
    return sum / scored;
}

TEST_F(Temporal, AScheduledCrossfadeKeepsTheHistory) {
    // A crossfade is declared with the character: playing through it is no edit of the world,
    // so the history stays (TemporalHistory keys on the performance, not on what plays now).
    scene::World world = test::generatedWorld("glass_figure.glb");
    world.characters[0].performance.transitions = {{0.25, 1, 0.3}};
    WorldRig rig(world, context(), 64), fresh(world, context(), 64);
    rig.temporal.enabled = fresh.temporal.enabled = true;
    for (int k = 0; k < 4; ++k)
        rig.renderHdr(0.1 * k); // 0.3: into the fade
    EXPECT_NE(rig.renderHdr(0.4), fresh.renderHdr(0.4)) << "the history started over";
    // Over the fade, accumulation scores as it does on the clip alone.
    const double alone = walkingFigure(context(), false), fading = walkingFigure(context(), true);
    std::printf("the figure accumulating: %.2f dB walking, %.2f dB crossfading to idle\n", alone,
                fading);
    EXPECT_GT(fading, alone - 1.0);
}

/** The glass sphere translating over the ground, half a pixel a frame, the camera still, the
 *  trace at 128x128: the mean masked PSNR against the reference of every other frame after 16,
 *  with accumulation or without. */
double sphereCrossingTheGround(gl::Context& context, bool temporal, float movingJitter = 0.5f) {
    WorldRig rig(glassSphere(true), context, 128);
    rig.setCamera(sphereOverGroundCamera());
    rig.set("method", "trace");
    rig.temporal.enabled = temporal;
    rig.temporal.movingJitter = movingJitter;
    double sum = 0.0;
    int scored = 0;
    for (int k = 0; k < 24; ++k) {
        rig.character(0).placement.translation = {-0.5 + 0.015 * k, 0.0, 0.0};
        if (k < 16 || k % 2 != 0) { // warm-up, and every other frame scored
            rig.renderHdr(0.0);
            continue;
        }
        sum += rig.psnrAgainstReference();
        ++scored;
    }
    return sum / scored;
}

TEST_F(Temporal, AGlassBodyCarriesWhatItRefractsWithIt) {
    // A glass pixel's history is where the glass it enters was (docs/methods.md, "Temporal
    // accumulation"). Looked for where its path's end was (the sky, the ground: still), the
    // history smears what the sphere refracts, 5 dB under the frame without it.
    const double without = sphereCrossingTheGround(context(), false),
                 with = sphereCrossingTheGround(context(), true);
    std::printf("a glass sphere crossing the ground: %.2f dB, %.2f dB accumulating\n", without,
                with);
    EXPECT_GT(with, without - 1.0);
}

TEST_F(Temporal, HalfAPixelOfJitterWhileMovingScoresBetterThanTheWhole) {
    // While anything moves the history is clipped toward the frame's one sample, and a sample
    // nearer the pixel's centre is nearer the pixel's mean (docs/accuracy.md).
    const double half = sphereCrossingTheGround(context(), true, 0.5f),
                 whole = sphereCrossingTheGround(context(), true, 1.0f);
    std::printf("the sphere crossing the ground, accumulating: %.2f dB jittered over half the "
                "pixel while moving, %.2f dB over all of it\n",
                half, whole);
    EXPECT_GT(half, whole + 0.25);
}

/** Adds the glass pixels of the frame `rig` rendered last to `walked`, and those of them that
 *  took the fresh samples to `fresh`. */
void countFresh(const WorldRig& rig, double& fresh, double& walked) {
    const refraction::LayerStats stats = rig.plugin().layerStats();
    fresh += stats.freshPixels;
    walked += stats.walkedPixels;
}

/** A character walking at 30 frames a second from `start`, `method` at 96x96, accumulating
 *  with `fresh` samples where the history is rejected or differs from the first sample by
 *  `contrast`: the mean masked PSNR against the reference of its frames 12-15; into
 *  `freshShare`, the share of their glass pixels that took them. */
double walking(gl::Context& context, scene::World world, double start, const char* method,
               int fresh, double contrast, double& freshShare) {
    WorldRig rig(std::move(world), context, 96);
    rig.set("method", method);
    rig.set("glass", "all");
    rig.set("fresh-samples", std::to_string(fresh));
    rig.set("fresh-contrast", std::to_string(contrast));
    rig.temporal.enabled = true;
    double sum = 0.0, freshPixels = 0.0, walked = 0.0;
    int scored = 0;
    for (int k = 0; k < 16; ++k) {
        const double time = start + k / 30.0;
        if (k < 12) {
            rig.renderHdr(time);
            continue;
        }
        sum += rig.psnrAgainstReference(time);
        countFresh(rig, freshPixels, walked);
        ++scored;
    }
    freshShare = freshPixels / std::max(walked, 1.0);
    return sum / scored;
}

/** An opaque box sliding away from in front of the glass sphere, three pixels a frame (the trace
 *  at 128x128, the camera still), accumulating with `fresh` samples where the history is rejected
 *  alone: the mean masked PSNR against the reference of its frames 12-19; into `freshShare`,
 *  the share of their glass pixels that took them. */
double sphereUncovered(gl::Context& context, int fresh, double& freshShare) {
    scene::World world = glassSphere(true);
    auto box = asset::loadModel("builtin:box");
    EXPECT_TRUE(box.ok());
    scene::Character cover;
    cover.name = "cover";
    cover.model = std::make_shared<const scene::Model>(std::move(*box));
    cover.glass = scene::GlassMode::None;
    cover.placement.translation = {0.0, 0.0, 1.3};
    cover.placement.scale = glm::dvec3(0.9);
    world.characters.push_back(std::move(cover));
    WorldRig rig(std::move(world), context, 128);
    rig.setCamera(sphereOverGroundCamera());
    rig.set("method", "trace");
    rig.set("fresh-samples", std::to_string(fresh));
    rig.set("fresh-contrast", "0");
    rig.temporal.enabled = true;
    double sum = 0.0, freshPixels = 0.0, walked = 0.0;
    int scored = 0;
    for (int k = 0; k < 20; ++k) {
        rig.character(1).placement.translation = {-0.1 * k, 0.0, 1.3};
        if (k < 12) {
            rig.renderHdr(0.0);
            continue;
        }
        sum += rig.psnrAgainstReference();
        countFresh(rig, freshPixels, walked);
        ++scored;
    }
    freshShare = freshPixels / std::max(walked, 1.0);
    return sum / scored;
}

TEST_F(Temporal, PixelsWithoutHistoryTakeFreshSamples) {
    // The pixels whose history the resolve will reject (the glass the box uncovers: the box
    // was in front of it there a frame before) take four samples instead of one, and the
    // frames score higher.
    double share = 0.0, none = 0.0;
    const double fresh = sphereUncovered(context(), 4, share),
                 one = sphereUncovered(context(), 1, none);
    std::printf("a box sliding off the sphere, accumulating: %.2f dB with 4 fresh samples on "
                "%.1f%% of the glass, %.2f dB with one\n",
                fresh, 100.0 * share, one);
    EXPECT_EQ(none, 0.0);
    EXPECT_GT(share, 0.01);
    EXPECT_GT(fresh, one + 0.25);
}

TEST_F(Temporal, OnlyFramesThatTakeFreshSamplesCompileTheirTest) {
    // The test of whether a pixel takes the fresh samples reads the history's motion around it
    // at every glass pixel, which a CPU rasteriser runs even where no frame takes them: only
    // the walk's variants for frames that take them compile it (FRESH_SAMPLES).
    const auto walkVariants = [&](const char* method, const char* fresh) {
        WorldRig rig(test::projectScene("glass_pair.json"), context(), 32);
        rig.useSceneCamera();
        rig.set("method", method);
        rig.set("fresh-samples", fresh);
        rig.temporal.enabled = true;
        for (int k = 0; k < 3; ++k)
            rig.renderHdr(0.5 + k / 30.0);
        std::vector<std::string> found;
        for (const std::string& key : rig.renderer().programVariantKeys())
            if (key.find("walk.frag.glsl") != std::string::npos)
                found.push_back(key);
        return found;
    };
    const auto with = [](const std::vector<std::string>& keys, const char* define) {
        return std::count_if(keys.begin(), keys.end(), [&](const std::string& k) {
            return k.find(std::string("\n") + define + "\n") != std::string::npos;
        });
    };
    const auto dir = walkVariants("dir", "4"), hybrid = walkVariants("hybrid", "4");
    EXPECT_FALSE(dir.empty());
    EXPECT_EQ(with(dir, "FRESH_SAMPLES 0"), std::ptrdiff_t(dir.size()));
    EXPECT_GE(with(hybrid, "FRESH_SAMPLES 1"), 1); // moving frames, after the first
    EXPECT_GE(with(hybrid, "FRESH_SAMPLES 0"), 1); // the first, without a history
}

TEST_F(Temporal, FreshSamplesCoverTheirPixelAndWeighAsManySamples) {
    // A pixel listed on frame after frame (its first sample differing from its history) takes
    // its later samples over the pixel itself, at points turned every frame, and the resolve
    // weighs them as the samples they are: listing 32% of CesiumMan's glass gains 1.65 dB over
    // listing the 0.2% whose history is rejected. When 10% was rejected (the exit turned by 15
    // degrees), the gain of 1.44 dB was 1.12 with the same points every frame, 0.89 with them
    // around the frame's jittered centre, and 0.11 with them weighed as one sample.
    GLASS_REQUIRE_SHARED();
    auto loaded =
        asset::loadModel((test::sharedDir() / "assets/gltf/CesiumMan/CesiumMan.glb").string());
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    const auto model = std::make_shared<const scene::Model>(std::move(*loaded));
    auto world = [&] {
        scene::World w = scene::singleCharacterWorld(model);
        w.characters[0].play(0);
        return w;
    };
    double listed = 0.0, rejected = 0.0;
    const double wide = walking(context(), world(), 1.0, "trace", 4, 0.3, listed),
                 narrow = walking(context(), world(), 1.0, "trace", 4, 0.0, rejected);
    std::printf("CesiumMan walking, accumulating: %.2f dB with fresh samples on %.1f%% of the "
                "glass (contrast 0.3), %.2f dB on %.1f%% (rejected history only)\n",
                wide, 100.0 * listed, narrow, 100.0 * rejected);
    EXPECT_GT(listed, rejected + 0.05);
    EXPECT_GT(wide, narrow + 1.25);
}

TEST_F(Temporal, EveryMethodAccumulatesWhileLitCharactersWalkPast) {
    // The cross-product while playing: two glass figures and an opaque one walking over the
    // ground under a sun that casts shadows, in an HDR environment, each method accumulating
    // from a history of earlier frames of the clip. Its last frame against the reference at
    // that time: no method loses to its frame without accumulation, and the trace gains.
    constexpr int kSize = 96, kFrames = 8;
    scene::World world = test::projectScene("walk_past.json");
    ASSERT_TRUE(world.environment);
    auto sky = asset::loadHdr(*world.environment);
    ASSERT_TRUE(sky.ok()) << sky.error().message;
    WorldRig rig(std::move(world), context(), kSize, &*sky);
    rig.useSceneCamera();
    const double last = 0.5 + (kFrames - 1) / 30.0;
    const WorldRig::Reference reference = rig.reference(last);
    for (const char* method : {"sir", "isr", "dir", "trace", "hybrid"}) {
        rig.set("method", method);
        rig.temporal.enabled = false;
        const double one = rig.psnrAgainst(reference, last);
        rig.temporal.enabled = true;
        std::vector<float> hdr;
        for (int k = 0; k < kFrames; ++k)
            hdr = rig.renderHdr(0.5 + k / 30.0);
        const double accumulated =
            capture::score(capture::Image{kSize, kSize, render::cpu::tonemap(hdr, 1.0f)},
                           reference.image, &reference.mask)
                .psnr;
        rig.temporal.enabled = false;
        std::printf("walk_past.json, %s: %.2f dB, %.2f dB accumulating\n", method, one,
                    accumulated);
        EXPECT_GT(accumulated, one - 0.25) << method;
        if (std::string(method) == "trace") {
            EXPECT_GT(accumulated, one + 1.5) << method;
        }
    }
}

} // namespace
