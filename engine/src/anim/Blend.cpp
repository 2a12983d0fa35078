// The one pose evaluator: a performance's layers and crossfades sampled at a scene time and
// blended per property as three.js's AnimationMixer blends (PropertyMixer), root motion applied
// per layer, morph settings last.
#include "engine/anim/Pose.h"

#include "Pointers.h"

#include "engine/anim/Sampler.h"
#include "engine/core/Check.h"

#include <algorithm>

namespace anim {
namespace {

using scene::Layer;
using scene::MaskEntry;
using scene::MorphSetting;
using scene::Performance;
using scene::RootMotion;

enum Property { T = 0, R = 1, S = 2, W = 3 };

/** One clip's part in the blend: its clip time, weight and the layer it plays as. */
struct Contribution {
    const Layer* layer;
    double weight;
    double clipTime;
    long long loops;  ///< completed loops, for accumulated root motion
    glm::dvec3 shift; ///< added to the clip's motion node (accumulated root motion)
};

int depth(const scene::Model& model, int node) {
    int d = 0;
    for (int n = model.nodes[std::size_t(node)].parent; n >= 0;
         n = model.nodes[std::size_t(n)].parent)
        ++d;
    return d;
}

/** The linear part of the rest transform of `node`'s parent: local to model space. */
glm::dmat3 parentRestLinear(const scene::Model& model, int node) {
    glm::dmat4 m(1.0);
    for (int n = model.nodes[std::size_t(node)].parent; n >= 0;
         n = model.nodes[std::size_t(n)].parent)
        m = model.nodes[std::size_t(n)].restMatrix * m;
    return glm::dmat3(m);
}

/** The part of a local displacement that is horizontal in model space (y up), as a local
 *  displacement. */
glm::dvec3 horizontal(const glm::dmat3& parentLinear, const glm::dvec3& local) {
    glm::dvec3 model = parentLinear * local;
    model.y = 0.0;
    return glm::inverse(parentLinear) * model;
}

glm::dvec3 sample3(const scene::AnimationSampler& sampler, double time) {
    std::array<double, 3> v{};
    sample(sampler, time, false, v);
    return {v[0], v[1], v[2]};
}

glm::dquat sampleRotation(const scene::AnimationSampler& sampler, double time) {
    std::array<double, 4> v{};
    sample(sampler, time, true, v);
    return {v[3], v[0], v[1], v[2]};
}

/** Root motion of one clip: its motion node's translation moved as the mode asks. */
struct RootAdjust {
    int node = -1;
    glm::dvec3 removeFrom{0.0}; ///< in place: the first frame's translation
    glm::dvec3 perLoop{0.0};    ///< accumulate: the horizontal travel of one run
    glm::dmat3 parentLinear{1.0};
};

RootAdjust rootAdjust(const scene::Model& model, int clip, RootMotion mode) {
    RootAdjust adjust;
    if (mode == RootMotion::Baked)
        return adjust;
    adjust.node = motionNode(model, clip);
    if (adjust.node < 0)
        return adjust;
    const scene::Animation& animation = model.animations[std::size_t(clip)];
    for (const scene::AnimationChannel& channel : animation.channels)
        if (channel.node == adjust.node && channel.path == scene::AnimationPath::Translation) {
            const auto& sampler = animation.samplers[std::size_t(channel.sampler)];
            adjust.parentLinear = parentRestLinear(model, adjust.node);
            adjust.removeFrom = sample3(sampler, 0.0);
            adjust.perLoop = horizontal(adjust.parentLinear,
                                        sample3(sampler, animation.duration) - adjust.removeFrom);
            break;
        }
    return adjust;
}

glm::dvec3 moveRoot(const RootAdjust& adjust, RootMotion mode, const glm::dvec3& translation,
                    long long loops) {
    if (mode == RootMotion::InPlace)
        return translation - horizontal(adjust.parentLinear, translation - adjust.removeFrom);
    return translation + double(loops) * adjust.perLoop;
}

/** Per-node weights of a masked layer: each node takes its nearest masked ancestor's weight
 *  (itself included), 0 under none. */
void fillMask(const scene::Model& model, const Layer& layer, Pose& pose) {
    pose.mask.assign(model.nodes.size(), -1.0);
    for (const MaskEntry& entry : layer.mask)
        if (entry.node >= 0 && entry.node < int(model.nodes.size()))
            pose.mask[std::size_t(entry.node)] = entry.weight;
    for (int n : pose.order) { // parents first
        double& m = pose.mask[std::size_t(n)];
        if (m < 0.0) {
            const int parent = model.nodes[std::size_t(n)].parent;
            m = parent < 0 ? 0.0 : pose.mask[std::size_t(parent)];
        }
    }
}

/** Blends `value` into `into` with `weight`: the first contribution is copied, each later one
 *  mixed in by its share of the weight so far (PropertyMixer.accumulate). */
template <class V, class MixFn>
void accumulate(double& total, V& into, const V& value, double weight, MixFn mix) {
    if (total == 0.0) {
        into = value;
        total = weight;
        return;
    }
    total += weight;
    into = mix(into, value, weight / total);
}

glm::dvec3 lerp3(const glm::dvec3& a, const glm::dvec3& b, double s) {
    return a + (b - a) * s;
}

/** Slerp along the shorter arc, as Sampler's slerpShortest, for the blend's one slerp per
 *  rotation and layer. Near rotations (cos theta >= 0.7) take sin(t theta) / sin(theta) from its
 *  series in cos(theta) - 1 (each term the last times (t^2 - i^2) / (i (2i + 1)) (cos - 1)),
 *  summed to double precision in at most 21 terms: no transcendental call, and no
 *  normalisation (the result is a unit quaternion to rounding). */
glm::dquat blendRotation(const glm::dquat& a, const glm::dquat& b, double s) {
    const double dot = glm::dot(a, b);
    const glm::dquat end = dot < 0.0 ? -b : b;
    const double c = std::abs(dot);
    if (c < 0.7) {
        const double theta = std::acos(c), sinTheta = std::sqrt(1.0 - c * c);
        return glm::normalize(a * (std::sin((1.0 - s) * theta) / sinTheta) +
                              end * (std::sin(s * theta) / sinTheta));
    }
    static constexpr auto kInverse = [] { // 1 / (i (2i + 1))
        std::array<double, 24> inverse{};
        for (std::size_t i = 1; i < inverse.size(); ++i)
            inverse[i] = 1.0 / (double(i) * (2.0 * double(i) + 1.0));
        return inverse;
    }();
    const double d = c - 1.0, u = 1.0 - s;
    double termA = u, termB = s, weightA = u, weightB = s;
    for (std::size_t i = 1; i < kInverse.size() && std::abs(termA) + std::abs(termB) > 1e-18; ++i) {
        const double step = d * kInverse[i], square = double(i * i);
        termA *= (u * u - square) * step;
        termB *= (s * s - square) * step;
        weightA += termA;
        weightB += termB;
    }
    return a * weightA + end * weightB; // unit to rounding: the series is exact in doubles
}

/** What a performance plays: one layer per transition (its clip from the transition's time on)
 *  and, with accumulated root motion, the shift that starts each faded-to clip's root where the
 *  character stood when its fade began; then the contributions at one time. */
struct Mix {
    std::vector<Layer> faded;
    std::vector<glm::dvec3> shifts; ///< per transition, added to its clip's motion node
    std::vector<Contribution> contributions;
};

double clipDuration(const scene::Model& model, int clip) {
    return clip >= 0 && clip < int(model.animations.size())
               ? model.animations[std::size_t(clip)].duration
               : -1.0;
}

/** The contributions at `time` of the layers and the first `count` transitions: the newest
 *  transition's clip by its fade, everything before it by what the fade leaves, down to the
 *  layers; additive layers last. Oldest first, as the mixer accumulates its actions. */
void collect(const scene::Model& model, const Performance& performance, double time,
             std::size_t count, const Mix& mix, std::vector<Contribution>& out) {
    out.clear();
    double left = 1.0; // what the newer fades leave
    for (std::size_t j = count; j-- > 0 && left > 0.0;) {
        const scene::Transition& t = performance.transitions[j];
        if (t.at > time)
            continue;
        const double s = t.duration > 0.0 ? std::clamp((time - t.at) / t.duration, 0.0, 1.0) : 1.0;
        if (left * s > 0.0 && clipDuration(model, t.to) >= 0.0)
            out.push_back({&mix.faded[j], left * s, 0.0, 0, mix.shifts[j]});
        left *= 1.0 - s;
    }
    std::reverse(out.begin(), out.end());
    if (left > 0.0) { // the layers under the fades, accumulated before them
        std::size_t inserted = 0;
        for (const Layer& layer : performance.layers)
            if (!layer.additive && layer.weight > 0.0 && clipDuration(model, layer.clip) >= 0.0)
                out.insert(out.begin() + std::ptrdiff_t(inserted++),
                           {&layer, left * layer.weight, 0.0, 0, glm::dvec3(0.0)});
    }
    for (const Layer& layer : performance.layers)
        if (layer.additive && layer.weight > 0.0 && clipDuration(model, layer.clip) >= 0.0)
            out.push_back({&layer, layer.weight, 0.0, 0, glm::dvec3(0.0)});
    for (Contribution& c : out) {
        const double d = clipDuration(model, c.layer->clip);
        c.clipTime = c.layer->clipTime(time, d);
        c.loops = c.layer->completedLoops(time, d);
    }
}

/** The translation of node `node` blended from the contributions at `time` of the layers and
 *  the first `count` transitions, root motion and shifts applied. */
glm::dvec3 blendedRoot(const scene::Model& model, const Performance& performance, double time,
                       std::size_t count, int node, const Mix& mix) {
    std::vector<Contribution> contributions;
    collect(model, performance, time, count, mix, contributions);
    glm::dvec3 root = model.nodes[std::size_t(node)].rest.translation;
    double total = 0.0;
    for (const Contribution& c : contributions) {
        if (c.layer->additive)
            continue;
        const scene::Animation& animation = model.animations[std::size_t(c.layer->clip)];
        for (const scene::AnimationChannel& channel : animation.channels)
            if (channel.node == node && channel.path == scene::AnimationPath::Translation) {
                const RootAdjust adjust = rootAdjust(model, c.layer->clip, performance.rootMotion);
                glm::dvec3 v =
                    sample3(animation.samplers[std::size_t(channel.sampler)], c.clipTime);
                if (adjust.node == node)
                    v = moveRoot(adjust, performance.rootMotion, v, c.loops) + c.shift;
                accumulate(total, root, v, c.weight, lerp3);
                break;
            }
    }
    return total > 0.0 && total < 1.0
               ? lerp3(root, model.nodes[std::size_t(node)].rest.translation, 1.0 - total)
               : root;
}

/** The faded-to layers, and with accumulated root motion the shift of each one that has begun by
 *  `time`: where the character's root stood at its start, less where its clip starts. */
void prepare(const scene::Model& model, const Performance& performance, double time, Mix& mix) {
    const std::size_t count = performance.transitions.size();
    mix.faded.resize(count);
    mix.shifts.assign(count, glm::dvec3(0.0));
    for (std::size_t j = 0; j < count; ++j) {
        mix.faded[j] = Layer{};
        mix.faded[j].clip = performance.transitions[j].to;
        mix.faded[j].timeOffset = -performance.transitions[j].at;
    }
    if (performance.rootMotion != RootMotion::Accumulate)
        return;
    for (std::size_t j = 0; j < count; ++j) {
        const scene::Transition& t = performance.transitions[j];
        const RootAdjust adjust = rootAdjust(model, t.to, RootMotion::Accumulate);
        if (t.at > time || adjust.node < 0)
            continue;
        const glm::dvec3 here = blendedRoot(model, performance, t.at, j, adjust.node, mix);
        mix.shifts[j] = horizontal(adjust.parentLinear, here - adjust.removeFrom);
    }
}

/** A weights channel's sample blended into node `node`'s morph weights (or its additive sum). */
void addMorphWeights(const scene::AnimationSampler& sampler, const Contribution& c, double weight,
                     std::size_t node, Pose& pose) {
    NodeBlend& blend = pose.blend[node];
    const std::size_t n = std::size_t(sampler.components);
    pose.samples.resize(n);
    sample(sampler, c.clipTime, false, pose.samples);
    std::vector<double>& into = c.layer->additive ? blend.addWeights : pose.weights[node];
    if (into.size() < n)
        into.resize(n, 0.0);
    if (c.layer->additive) {
        pose.firstFrame.resize(n);
        sample(sampler, 0.0, false, pose.firstFrame);
        for (std::size_t k = 0; k < n; ++k)
            into[k] += (pose.samples[k] - pose.firstFrame[k]) * weight;
        blend.added[W] += weight;
        return;
    }
    double& total = blend.weight[W];
    const double mix = total == 0.0 ? 1.0 : weight / (total + weight);
    for (std::size_t k = 0; k < n; ++k)
        into[k] = total == 0.0 ? pose.samples[k] : into[k] + (pose.samples[k] - into[k]) * mix;
    total += weight;
}

/** Samples one contribution's clip and adds it to the blend. */
void addContribution(const scene::Model& model, const Performance& performance,
                     const Contribution& c, Pose& pose, double& travelWeight) {
    const scene::Animation& animation = model.animations[std::size_t(c.layer->clip)];
    const bool additive = c.layer->additive;
    const bool masked = !c.layer->mask.empty();
    if (masked)
        fillMask(model, *c.layer, pose);
    const RootAdjust root = rootAdjust(model, c.layer->clip, performance.rootMotion);
    if (root.node >= 0 && !additive && performance.rootMotion == RootMotion::Accumulate) {
        pose.travel += c.weight * (root.parentLinear * (double(c.loops) * root.perLoop + c.shift));
        travelWeight += c.weight;
    }
    for (const scene::AnimationChannel& channel : animation.channels) {
        const auto& sampler = animation.samplers[std::size_t(channel.sampler)];
        if (channel.path == scene::AnimationPath::Pointer) { // no joint to mask
            detail::addPointer(channel, sampler, c.clipTime, c.weight, additive, pose);
            continue;
        }
        const std::size_t node = std::size_t(channel.node);
        const double weight = c.weight * (masked ? pose.mask[node] : 1.0);
        if (weight <= 0.0)
            continue;
        scene::Trs& local = pose.local[node];
        NodeBlend& blend = pose.blend[node];
        pose.useRestMatrix[node] = 0;
        switch (channel.path) {
        case scene::AnimationPath::Translation: {
            glm::dvec3 v = sample3(sampler, c.clipTime);
            if (additive) {
                blend.addTranslation += (v - sample3(sampler, 0.0)) * weight;
                blend.added[T] += weight;
                break;
            }
            if (channel.node == root.node)
                v = moveRoot(root, performance.rootMotion, v, c.loops) + c.shift;
            accumulate(blend.weight[T], local.translation, v, weight, lerp3);
            break;
        }
        case scene::AnimationPath::Scale: {
            const glm::dvec3 v = sample3(sampler, c.clipTime);
            if (additive) {
                blend.addScale += (v - sample3(sampler, 0.0)) * weight;
                blend.added[S] += weight;
                break;
            }
            accumulate(blend.weight[S], local.scale, v, weight, lerp3);
            break;
        }
        case scene::AnimationPath::Rotation: {
            const glm::dquat v = sampleRotation(sampler, c.clipTime);
            if (additive) {
                const glm::dquat delta = glm::conjugate(sampleRotation(sampler, 0.0)) * v;
                blend.addRotation =
                    blendRotation(blend.addRotation, blend.addRotation * delta, weight);
                blend.added[R] += weight;
                break;
            }
            accumulate(blend.weight[R], local.rotation, v, weight, blendRotation);
            break;
        }
        case scene::AnimationPath::Pointer:
            break; // above
        case scene::AnimationPath::Weights:
            addMorphWeights(sampler, c, weight, node, pose);
            break;
        }
    }
}

/** The file's morph weights of node `i`: the node's own, else its mesh's defaults. */
const std::vector<float>& restWeights(const scene::Model& model, std::size_t i) {
    const scene::Node& node = model.nodes[i];
    return node.weights.empty() && node.mesh >= 0
               ? model.meshes[std::size_t(node.mesh)].defaultWeights
               : node.weights;
}

/** Where a property's weights sum under one, the rest pose fills the remainder; the additive
 *  sums then go on top. */
void finishBlend(const scene::Model& model, Pose& pose) {
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        const NodeBlend& b = pose.blend[i];
        const scene::Trs& rest = model.nodes[i].rest;
        scene::Trs& local = pose.local[i];
        if (b.weight[T] > 0.0 && b.weight[T] < 1.0)
            local.translation = lerp3(local.translation, rest.translation, 1.0 - b.weight[T]);
        if (b.weight[R] > 0.0 && b.weight[R] < 1.0)
            local.rotation = blendRotation(local.rotation, rest.rotation, 1.0 - b.weight[R]);
        if (b.weight[S] > 0.0 && b.weight[S] < 1.0)
            local.scale = lerp3(local.scale, rest.scale, 1.0 - b.weight[S]);
        std::vector<double>& weights = pose.weights[i];
        if (b.weight[W] > 0.0 && b.weight[W] < 1.0) {
            const std::vector<float>& r = restWeights(model, i);
            for (std::size_t k = 0; k < weights.size(); ++k)
                weights[k] += ((k < r.size() ? r[k] : 0.0) - weights[k]) * (1.0 - b.weight[W]);
        }
        if (b.added[T] > 0.0)
            local.translation += b.addTranslation;
        if (b.added[R] > 0.0)
            local.rotation = glm::normalize(local.rotation * b.addRotation);
        if (b.added[S] > 0.0)
            local.scale += b.addScale;
        if (b.added[W] > 0.0) {
            if (weights.size() < b.addWeights.size())
                weights.resize(b.addWeights.size(), 0.0);
            for (std::size_t k = 0; k < b.addWeights.size(); ++k)
                weights[k] += b.addWeights[k];
        }
    }
}

void applyMorphSettings(const scene::Model& model, const Performance& performance, Pose& pose) {
    for (const MorphSetting& setting : performance.morphs)
        for (std::size_t i = 0; i < model.nodes.size(); ++i) {
            const int mesh = model.nodes[i].mesh;
            std::vector<double>& weights = pose.weights[i];
            if (mesh < 0 || (setting.mesh >= 0 && setting.mesh != mesh) || setting.target < 0 ||
                std::size_t(setting.target) >= weights.size())
                continue;
            double& w = weights[std::size_t(setting.target)];
            w = setting.add ? w + setting.value : setting.value;
        }
}

} // namespace

int motionNode(const scene::Model& model, int clip) {
    if (clip < 0 || clip >= int(model.animations.size()))
        return -1;
    const auto isJoint = [&](int node) { // every node when the model has no skin
        if (model.skins.empty())
            return true;
        for (const scene::Skin& skin : model.skins)
            if (std::find(skin.joints.begin(), skin.joints.end(), node) != skin.joints.end())
                return true;
        return false;
    };
    int best = -1, bestDepth = 0;
    for (const scene::AnimationChannel& channel : model.animations[std::size_t(clip)].channels) {
        if (channel.path != scene::AnimationPath::Translation || !isJoint(channel.node))
            continue;
        const int d = depth(model, channel.node);
        if (best < 0 || d < bestDepth) {
            best = channel.node;
            bestDepth = d;
        }
    }
    return best;
}

void evaluate(const scene::Model& model, const Performance& performance, double sceneTime,
              Pose& pose) {
    ENGINE_CHECK(pose.local.size() == model.nodes.size(), "pose was built for another model");
    applyClip(model, -1, 0.0, pose); // the rest pose
    pose.travel = glm::dvec3(0.0);
    pose.blend.resize(model.nodes.size());
    for (NodeBlend& b : pose.blend) {
        b.weight = {};
        b.added = {};
        b.addTranslation = b.addScale = glm::dvec3(0.0);
        b.addRotation = glm::dquat(1.0, 0.0, 0.0, 0.0);
        b.addWeights.assign(b.addWeights.size(), 0.0);
    }
    detail::resetPointers(pose);
    thread_local Mix mix;
    const double time = performance.characterTime(sceneTime);
    prepare(model, performance, time, mix);
    collect(model, performance, time, performance.transitions.size(), mix, mix.contributions);
    bool partial = false;
    double travelWeight = 0.0;
    for (const Contribution& c : mix.contributions) {
        addContribution(model, performance, c, pose, travelWeight);
        partial = partial || c.weight < 1.0 || !c.layer->mask.empty() || c.layer->additive;
    }
    if (travelWeight > 1.0)
        pose.travel /= travelWeight;
    if (partial) // one full-weight clip needs no rest fill: its pose is the clip's, bit for bit
        finishBlend(model, pose);
    detail::finishPointers(model, pose);
    applyMorphSettings(model, performance, pose);
    updateWorld(model, pose);
}

const scene::Material* materialOf(const scene::Model& model, const Pose& pose, int material) {
    if (material < 0)
        return nullptr;
    return pose.materials.empty() ? &model.materials[std::size_t(material)]
                                  : &pose.materials[std::size_t(material)];
}

const scene::Light& lightOf(const scene::Model& model, const Pose& pose, int light) {
    return pose.lights.empty() ? model.lights[std::size_t(light)] : pose.lights[std::size_t(light)];
}

const scene::Camera& cameraOf(const scene::Model& model, const Pose& pose, int camera) {
    return pose.cameras.empty() ? model.cameras[std::size_t(camera)]
                                : pose.cameras[std::size_t(camera)];
}

Pose evaluate(const scene::Model& model, const Performance& performance, double sceneTime) {
    Pose pose = restPose(model);
    evaluate(model, performance, sceneTime, pose);
    return pose;
}

} // namespace anim
