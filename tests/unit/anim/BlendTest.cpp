// The one pose evaluator: layers, crossfades, additive and masked layers, loop modes, pause, root
// motion and morph settings, on the generated figure (four clips, a skin, a morph target).
#include "support/TestSupport.h"

#include "engine/anim/Pose.h"
#include "engine/anim/Sampler.h"
#include "engine/asset/ModelLoader.h"
#include "engine/deform/CpuDeformer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cstring>

namespace {

const scene::Model& figure() {
    static const scene::Model model = [] {
        auto loaded =
            asset::loadModel(std::string(GLASS_SOURCE_DIR) + "/assets/models/glass_figure.glb");
        EXPECT_TRUE(loaded.ok()) << loaded.error().message;
        return std::move(loaded).value();
    }();
    return model;
}

int clip(const scene::Model& model, const char* name) {
    const auto found = model.findAnimation(name);
    EXPECT_TRUE(found.has_value()) << name;
    return found.value_or(-1);
}

int node(const scene::Model& model, const char* name) {
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
        if (model.nodes[i].name == name)
            return int(i);
    ADD_FAILURE() << "no node " << name;
    return -1;
}

scene::Layer layer(int clipIndex, double weight = 1.0) {
    scene::Layer l;
    l.clip = clipIndex;
    l.weight = weight;
    return l;
}

/** Every deformed vertex of the pose, in model space. */
std::vector<glm::dvec3> vertices(const scene::Model& model, const anim::Pose& pose) {
    std::vector<glm::dvec3> out;
    for (const auto& instance : deform::deformScene(model, pose))
        for (const auto& primitive : instance.primitives)
            for (const glm::dvec3& p : primitive.positions)
                out.push_back(glm::dvec3(instance.meshToWorld * glm::dvec4(p, 1.0)));
    return out;
}

double largestMove(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
    double largest = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        largest = std::max(largest, glm::length(a[i] - b[i]));
    return largest;
}

bool sameBits(const std::vector<glm::dmat4>& a, const std::vector<glm::dmat4>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

glm::dvec3 worldPosition(const anim::Pose& pose, int n) {
    return glm::dvec3(pose.world[std::size_t(n)][3]);
}

TEST(Blend, AFullLayerBesideAnEmptyOneIsTheClipBitForBit) {
    const scene::Model& model = figure();
    const int walk = clip(model, "walk"), wave = clip(model, "wave");
    scene::Performance p;
    p.layers = {layer(walk, 1.0), layer(wave, 0.0)};
    for (double t : {0.0, 0.37, 1.1, 5.3}) {
        const double clipTime =
            p.layers[0].clipTime(t, model.animations[std::size_t(walk)].duration);
        const anim::Pose blended = anim::evaluate(model, p, t);
        const anim::Pose alone = anim::evaluate(model, walk, clipTime);
        EXPECT_TRUE(sameBits(anim::skinMatrices(model, blended, model.meshNodes()[0]),
                             anim::skinMatrices(model, alone, model.meshNodes()[0])))
            << "t = " << t;
        EXPECT_EQ(blended.weights, alone.weights);
    }
}

TEST(Blend, EvaluatingIsPureWhateverWasEvaluatedBefore) {
    const scene::Model& model = figure();
    scene::Performance p;
    p.layers = {layer(clip(model, "walk"), 0.6), layer(clip(model, "idle"), 0.3)};
    p.layers.push_back(layer(clip(model, "wave"), 0.8));
    p.layers.back().additive = true;
    p.transitions = {{1.0, clip(model, "stroll"), 0.5}};
    anim::Pose played = anim::restPose(model);
    for (int frame = 0; frame <= 90; ++frame) // from 0 to 1.5 s at 60 Hz, one pose reused
        anim::evaluate(model, p, frame / 60.0, played);
    const anim::Pose fresh = anim::evaluate(model, p, 90 / 60.0);
    EXPECT_EQ(std::memcmp(played.world.data(), fresh.world.data(),
                          played.world.size() * sizeof(glm::dmat4)),
              0);
    EXPECT_EQ(played.weights, fresh.weights);
}

TEST(Blend, ACrossfadeStartsTheNewClipAtItsBeginningAndMovesTheWeightsLinearly) {
    const scene::Model& model = figure();
    const int walk = clip(model, "walk"), wave = clip(model, "wave");
    scene::Performance p = scene::Performance::single(walk);
    p.transitions = {{2.0, wave, 0.4}};
    const int hips = node(model, "hips");
    // Before: the walk alone; after the fade: the wave, from its own time 0 at 2 s.
    const double walkRun = model.animations[std::size_t(walk)].duration;
    EXPECT_EQ(
        anim::evaluate(model, p, 1.9).local[std::size_t(hips)].translation,
        anim::evaluate(model, walk, std::fmod(1.9, walkRun)).local[std::size_t(hips)].translation);
    EXPECT_EQ(anim::evaluate(model, p, 2.5).local[std::size_t(hips)].translation,
              anim::evaluate(model, wave, 0.5).local[std::size_t(hips)].translation);
    // A quarter of the way: three parts walk, one part wave.
    const double t = 2.1;
    const glm::dvec3 a =
        anim::evaluate(model, walk, std::fmod(t, walkRun)).local[std::size_t(hips)].translation;
    const glm::dvec3 b = anim::evaluate(model, wave, t - 2.0).local[std::size_t(hips)].translation;
    const glm::dvec3 mixed = anim::evaluate(model, p, t).local[std::size_t(hips)].translation;
    EXPECT_NEAR(glm::length(mixed - (0.75 * a + 0.25 * b)), 0.0, 1e-12);
}

TEST(Blend, ACrossfadeDoesNotPop) {
    const scene::Model& model = figure();
    const int walk = clip(model, "walk"), idle = clip(model, "idle");
    const double at = 1.0, duration = 0.4, dt = 1.0 / 60.0;
    scene::Performance p = scene::Performance::single(walk), a = p,
                       b = scene::Performance::single(idle);
    p.transitions = {{at, idle, duration}};
    b.layers[0].timeOffset = -at;
    double fade = 0.0, own = 0.0;
    std::vector<glm::dvec3> previous, previousA, previousB;
    for (double t = at - 2.0 * dt; t <= at + duration + 2.0 * dt; t += dt) {
        auto now = vertices(model, anim::evaluate(model, p, t));
        auto nowA = vertices(model, anim::evaluate(model, a, t));
        auto nowB = vertices(model, anim::evaluate(model, b, t));
        if (!previous.empty()) {
            fade = std::max(fade, largestMove(previous, now));
            own = std::max({own, largestMove(previousA, nowA), largestMove(previousB, nowB)});
        }
        previous = std::move(now);
        previousA = std::move(nowA);
        previousB = std::move(nowB);
    }
    EXPECT_GT(own, 0.0);
    EXPECT_LE(fade, 1.25 * own) << "largest move in the fade " << fade << ", in the clips " << own;
}

TEST(Blend, WeightsUnderOneLeaveTheRestToTheRestPose) {
    const scene::Model& model = figure();
    const int walk = clip(model, "walk"), hips = node(model, "hips");
    scene::Performance p;
    p.layers = {layer(walk, 0.25)};
    const glm::dvec3 clipT = anim::evaluate(model, walk, 0.3).local[std::size_t(hips)].translation;
    const glm::dvec3 rest = model.nodes[std::size_t(hips)].rest.translation;
    EXPECT_NEAR(glm::length(anim::evaluate(model, p, 0.3).local[std::size_t(hips)].translation -
                            (0.25 * clipT + 0.75 * rest)),
                0.0, 1e-12);
    // Weights over one are normalised: 2 and 2 blend half and half.
    p.layers = {layer(walk, 2.0), layer(clip(model, "idle"), 2.0)};
    const glm::dvec3 idleT =
        anim::evaluate(model, clip(model, "idle"), 0.3).local[std::size_t(hips)].translation;
    EXPECT_NEAR(glm::length(anim::evaluate(model, p, 0.3).local[std::size_t(hips)].translation -
                            0.5 * (clipT + idleT)),
                0.0, 1e-12);
}

TEST(Blend, AnAdditiveLayerAddsItsChangeFromItsFirstFrame) {
    const scene::Model& model = figure();
    const int idle = clip(model, "idle"), wave = clip(model, "wave");
    const int arm = node(model, "right_upper_arm"), head = node(model, "head");
    scene::Performance p = scene::Performance::single(idle);
    p.layers.push_back(layer(wave, 1.0));
    p.layers.back().additive = true;
    const anim::Pose base = anim::evaluate(model, idle, 1.0);
    const anim::Pose added = anim::evaluate(model, p, 1.0);
    const glm::dquat delta =
        glm::conjugate(anim::evaluate(model, wave, 0.0).local[std::size_t(arm)].rotation) *
        anim::evaluate(model, wave, 1.0).local[std::size_t(arm)].rotation;
    const glm::dquat expected = base.local[std::size_t(arm)].rotation * delta;
    EXPECT_NEAR(std::abs(glm::dot(added.local[std::size_t(arm)].rotation, expected)), 1.0, 1e-12);
    EXPECT_GT(1.0 - std::abs(glm::dot(added.local[std::size_t(arm)].rotation,
                                      base.local[std::size_t(arm)].rotation)),
              1e-3)
        << "the wave raises the arm";
    (void)head;
    // At the additive clip's first frame it adds nothing.
    p.layers.back().timeOffset = -1.0;
    const anim::Pose none = anim::evaluate(model, p, 1.0);
    EXPECT_NEAR(std::abs(glm::dot(none.local[std::size_t(arm)].rotation,
                                  base.local[std::size_t(arm)].rotation)),
                1.0, 1e-12);
}

TEST(Blend, AMaskedLayerDrivesItsSubtreeOnly) {
    const scene::Model& model = figure();
    const int walk = clip(model, "walk"), wave = clip(model, "wave");
    const int shoulder = node(model, "right_shoulder"), hand = node(model, "right_hand");
    const int leftArm = node(model, "left_upper_arm");
    scene::Performance p = scene::Performance::single(walk);
    p.layers.push_back(layer(wave, 1.0));
    p.layers.back().mask = {{shoulder, 1.0}};
    const anim::Pose walking = anim::evaluate(model, walk, 0.5);
    const anim::Pose waving = anim::evaluate(model, wave, 0.5);
    const anim::Pose masked = anim::evaluate(model, p, 0.5);
    // Outside the subtree: the walk's, exactly (the wave's weight there is 0).
    EXPECT_EQ(masked.local[std::size_t(leftArm)].rotation,
              walking.local[std::size_t(leftArm)].rotation);
    // Inside: walk and wave half and half (two full weights).
    EXPECT_NEAR(
        std::abs(glm::dot(masked.local[std::size_t(hand)].rotation,
                          anim::slerpShortest(walking.local[std::size_t(hand)].rotation,
                                              waving.local[std::size_t(hand)].rotation, 0.5))),
        1.0, 1e-12);
}

TEST(Blend, LoopModes) {
    scene::Layer l;
    l.loop = scene::Loop::Repeat;
    EXPECT_NEAR(l.clipTime(2.5, 1.0), 0.5, 1e-12);
    EXPECT_NEAR(l.clipTime(-0.25, 1.0), 0.75, 1e-12);
    l.repetitions = 2;
    EXPECT_NEAR(l.clipTime(1.5, 1.0), 0.5, 1e-12);
    EXPECT_EQ(l.clipTime(2.5, 1.0), 1.0) << "two runs, then the last frame";
    EXPECT_EQ(l.completedLoops(7.0, 1.0), 1);
    l.repetitions = 0;
    EXPECT_EQ(l.completedLoops(-0.5, 1.0), -1);
    l.loop = scene::Loop::Clamp;
    EXPECT_EQ(l.clipTime(-3.0, 1.0), 0.0);
    EXPECT_EQ(l.clipTime(3.0, 1.0), 1.0);
    l.loop = scene::Loop::PingPong;
    EXPECT_NEAR(l.clipTime(0.25, 1.0), 0.25, 1e-12);
    EXPECT_NEAR(l.clipTime(1.25, 1.0), 0.75, 1e-12);
    EXPECT_NEAR(l.clipTime(2.25, 1.0), 0.25, 1e-12);
    l.speed = 2.0;
    l.timeOffset = 0.5;
    EXPECT_NEAR(l.clipTime(0.125, 1.0), 0.75, 1e-12) << "(0.125 + 0.5) * 2 = 1.25";
}

TEST(Blend, APausedCharacterHoldsItsClipTime) {
    const scene::Model& model = figure();
    scene::Performance p = scene::Performance::single(clip(model, "walk"));
    p.layers[0].speed = 2.0;
    p.layers[0].timeOffset = 0.1;
    p.pausedAt = 0.7;
    const anim::Pose held = anim::evaluate(model, p, 3.0);
    EXPECT_EQ(anim::evaluate(model, p, 9.0).world, held.world);
    const anim::Pose expected = anim::evaluate(model, clip(model, "walk"), 0.7);
    for (std::size_t n = 0; n < held.world.size(); ++n)
        EXPECT_NEAR(glm::length(glm::dvec3(held.world[n][3] - expected.world[n][3])), 0.0, 1e-12);
    EXPECT_EQ(p.period(model), 0.0);
}

TEST(Blend, InPlaceHoldsTheHipsOverTheirFirstFrame) {
    const scene::Model& model = figure();
    const int stroll = clip(model, "stroll"), hips = node(model, "hips");
    EXPECT_EQ(anim::motionNode(model, stroll), hips);
    scene::Performance p = scene::Performance::single(stroll);
    p.rootMotion = scene::RootMotion::InPlace;
    const glm::dvec3 start = worldPosition(anim::evaluate(model, stroll, 0.0), hips);
    double baked = 0.0, held = 0.0;
    const double run = model.animations[std::size_t(stroll)].duration;
    for (double t = 0.0; t < 9.6; t += 0.05) {
        const glm::dvec3 a = worldPosition(anim::evaluate(model, stroll, std::fmod(t, run)), hips);
        const glm::dvec3 b = worldPosition(anim::evaluate(model, p, t), hips);
        baked = std::max(baked, glm::length(glm::dvec2(a.x - start.x, a.z - start.z)));
        held = std::max(held, glm::length(glm::dvec2(b.x - start.x, b.z - start.z)));
        EXPECT_NEAR(b.y, a.y, 1e-9) << "the height is the clip's";
    }
    EXPECT_GT(baked, 1.0) << "the stroll travels 2.4 m";
    EXPECT_LT(held, 1e-9);
}

TEST(Blend, AccumulatedRootMotionWalksOnAcrossLoops) {
    const scene::Model& model = figure();
    const int stroll = clip(model, "stroll"), hips = node(model, "hips");
    scene::Performance p = scene::Performance::single(stroll);
    p.rootMotion = scene::RootMotion::Accumulate;
    const double dt = 1.0 / 60.0;
    double normal = 0.0, boundary = 0.0;
    glm::dvec3 previous = worldPosition(anim::evaluate(model, p, 4.8 - 30 * dt), hips);
    for (int frame = -29; frame <= 30; ++frame) {
        const double t = 4.8 + frame * dt;
        const glm::dvec3 now = worldPosition(anim::evaluate(model, p, t), hips);
        const double step = glm::length(now - previous);
        (frame == 0 || frame == 1 ? boundary : normal) =
            std::max(frame == 0 || frame == 1 ? boundary : normal, step);
        previous = now;
    }
    EXPECT_GT(normal, 0.0);
    EXPECT_LE(boundary, 1.5 * normal) << "no jump back at the loop";
    // Two loops on, the hips are two runs' travel ahead of where they were.
    const anim::Pose later = anim::evaluate(model, p, 1.0 + 2 * 4.8);
    const glm::dvec3 travel =
        worldPosition(later, hips) - worldPosition(anim::evaluate(model, p, 1.0), hips);
    EXPECT_NEAR(glm::length(glm::dvec2(travel.x, travel.z)), 4.8, 1e-6) << "2 x 2.4 m";
    EXPECT_NEAR(glm::length(later.travel), 4.8, 1e-6);
}

TEST(Blend, MorphWeightsAreSetOrAdded) {
    const scene::Model& model = figure();
    const int meshNode = model.meshNodes()[0];
    scene::Performance p = scene::Performance::single(clip(model, "walk"));
    const double clipWeight = anim::evaluate(model, p, 0.3).weights[std::size_t(meshNode)][0];
    p.morphs = {{-1, 0, 0.8, false}};
    EXPECT_EQ(anim::evaluate(model, p, 0.3).weights[std::size_t(meshNode)][0], 0.8);
    p.morphs = {{0, 0, 0.1, true}};
    EXPECT_NEAR(anim::evaluate(model, p, 0.3).weights[std::size_t(meshNode)][0], clipWeight + 0.1,
                1e-12);
}

} // namespace
