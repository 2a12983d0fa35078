// The default character, from an implicit body to a skinned, morphing, animated GLB.
#include "Figure.h"
#include "HammeredHead.h"
#include "SurfaceNets.h"

#include "engine/asset/Glb.h"
#include "engine/capture/Image.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <optional>
#include <string>

namespace generate {
namespace {

using glm::dvec3;

// ---- Skeleton (bind pose: an A-pose facing +z, feet on y = 0, metres)

enum Joint {
    Hips,
    Spine,
    Chest,
    Neck,
    Head,
    LShoulder,
    LUpperArm,
    LForearm,
    LHand,
    RShoulder,
    RUpperArm,
    RForearm,
    RHand,
    LThigh,
    LShin,
    LFoot,
    RThigh,
    RShin,
    RFoot,
    JointCount
};

struct JointSpec {
    std::string name;
    int parent = -1;
    dvec3 position{0.0}; ///< world, bind pose
};

constexpr double kArmDown = 0.70; // radians from vertical
const dvec3 kArmDirection{std::sin(kArmDown), -std::cos(kArmDown), 0.0};
constexpr double kUpperArm = 0.27, kForearm = 0.25, kHand = 0.085;
const dvec3 kShoulder{0.185, 1.435, 0.0};

std::vector<JointSpec> skeleton() {
    std::vector<JointSpec> j(JointCount);
    j[Hips] = {"hips", -1, {0.0, 0.95, 0.0}};
    j[Spine] = {"spine", Hips, {0.0, 1.10, 0.0}};
    j[Chest] = {"chest", Spine, {0.0, 1.28, 0.0}};
    j[Neck] = {"neck", Chest, {0.0, 1.47, 0.0}};
    j[Head] = {"head", Neck, {0.0, 1.57, 0.0}};
    for (int side = 0; side < 2; ++side) {
        const double s = side == 0 ? 1.0 : -1.0;
        const char* prefix = side == 0 ? "left_" : "right_";
        const dvec3 mirror{s, 1.0, 1.0};
        const dvec3 arm = kArmDirection * mirror;
        const int shoulder = side == 0 ? LShoulder : RShoulder;
        j[std::size_t(shoulder)] = {std::string(prefix) + "shoulder", Chest,
                                    dvec3(0.06, 1.43, 0.0) * mirror};
        j[(std::size_t(shoulder) + 1)] = {std::string(prefix) + "upper_arm", shoulder,
                                          kShoulder * mirror};
        j[(std::size_t(shoulder) + 2)] = {std::string(prefix) + "forearm", shoulder + 1,
                                          kShoulder * mirror + arm * kUpperArm};
        j[(std::size_t(shoulder) + 3)] = {std::string(prefix) + "hand", shoulder + 2,
                                          kShoulder * mirror + arm * (kUpperArm + kForearm)};
        const int thigh = side == 0 ? LThigh : RThigh;
        j[std::size_t(thigh)] = {std::string(prefix) + "thigh", Hips, {0.1 * s, 0.90, 0.0}};
        j[(std::size_t(thigh) + 1)] = {std::string(prefix) + "shin", thigh, {0.1 * s, 0.50, 0.0}};
        j[(std::size_t(thigh) + 2)] = {
            std::string(prefix) + "foot", thigh + 1, {0.1 * s, 0.09, 0.0}};
    }
    return j;
}

// ---- The implicit body: capsules and ellipsoids, each bound to a joint, blended smoothly

struct Shape {
    bool ellipsoid = false;
    dvec3 a{0.0}, b{0.0}; ///< capsule segment; ellipsoid: a is the centre
    dvec3 radii{0.0};     ///< capsule: x is the radius, z the depth scale; ellipsoid: semi-axes
    int joint = 0;
    double blend = 0.035; ///< smooth-minimum width when joined to the shapes before it
};

double capsuleDistance(const Shape& s, dvec3 p) {
    // Depth scale: the torso pieces are flatter front to back than side to side.
    p.z = s.a.z + (p.z - s.a.z) / s.radii.z;
    const dvec3 ab = s.b - s.a;
    const double t =
        std::clamp(glm::dot(p - s.a, ab) / std::max(glm::dot(ab, ab), 1e-12), 0.0, 1.0);
    return (glm::length(p - (s.a + t * ab)) - s.radii.x) * std::min(1.0, s.radii.z);
}

double shapeDistance(const Shape& s, const dvec3& p) {
    if (!s.ellipsoid)
        return capsuleDistance(s, p);
    const dvec3 q = (p - s.a) / s.radii;
    return (glm::length(q) - 1.0) * std::min({s.radii.x, s.radii.y, s.radii.z});
}

double smoothMin(double a, double b, double k) {
    const double h = std::clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);
    return b + (a - b) * h - k * h * (1.0 - h);
}

std::vector<Shape> bodyShapes(const std::vector<JointSpec>& joints) {
    auto capsule = [](dvec3 a, dvec3 b, double radius, int joint, double depth = 1.0,
                      double blend = 0.035) {
        return Shape{false, a, b, {radius, 0.0, depth}, joint, blend};
    };
    auto ellipsoid = [](dvec3 centre, dvec3 radii, int joint, double blend) {
        return Shape{true, centre, centre, radii, joint, blend};
    };
    std::vector<Shape> s;
    s.push_back(capsule({-0.075, 0.94, 0.0}, {0.075, 0.94, 0.0}, 0.11, Hips, 0.75));
    s.push_back(capsule({0.0, 0.98, 0.0}, {0.0, 1.17, 0.0}, 0.115, Spine, 0.72, 0.06));
    s.push_back(capsule({0.0, 1.17, 0.0}, {0.0, 1.33, 0.0}, 0.13, Chest, 0.70, 0.06));
    s.push_back(capsule({-0.1, 1.36, 0.0}, {0.1, 1.36, 0.0}, 0.09, Chest, 0.75, 0.06));
    s.push_back(capsule({0.0, 1.42, 0.0}, {0.0, 1.56, 0.0}, 0.048, Neck, 1.0, 0.04));
    s.push_back(ellipsoid({0.0, 1.655, 0.01}, {0.092, 0.112, 0.102}, Head, 0.04));
    s.push_back(ellipsoid({0.0, 1.645, 0.105}, {0.016, 0.026, 0.02}, Head, 0.015)); // nose
    for (int side = 0; side < 2; ++side) {
        const int shoulder = side == 0 ? LShoulder : RShoulder;
        const int thigh = side == 0 ? LThigh : RThigh;
        const dvec3 pShoulder = joints[(std::size_t(shoulder) + 1)].position;
        const dvec3 elbow = joints[(std::size_t(shoulder) + 2)].position;
        const dvec3 wrist = joints[(std::size_t(shoulder) + 3)].position;
        const dvec3 arm = glm::normalize(wrist - elbow);
        s.push_back(
            capsule(joints[std::size_t(shoulder)].position, pShoulder, 0.055, shoulder, 1.0, 0.05));
        s.push_back(capsule(pShoulder, elbow, 0.047, shoulder + 1, 1.0, 0.03));
        s.push_back(capsule(elbow, wrist, 0.038, shoulder + 2, 1.0, 0.025));
        s.push_back(
            capsule(wrist + arm * 0.02, wrist + arm * kHand, 0.034, shoulder + 3, 0.6, 0.02));
        const dvec3 hip = joints[std::size_t(thigh)].position;
        const dvec3 knee = joints[(std::size_t(thigh) + 1)].position;
        const dvec3 ankle = joints[(std::size_t(thigh) + 2)].position;
        s.push_back(capsule(hip, knee, 0.074, thigh, 1.0, 0.05));
        s.push_back(capsule(knee, ankle, 0.053, thigh + 1, 1.0, 0.03));
        s.push_back(capsule(ankle + dvec3(0.0, -0.04, -0.03), ankle + dvec3(0.0, -0.05, 0.13),
                            0.042, thigh + 2, 1.0, 0.03));
    }
    return s;
}

double bodyDistance(const std::vector<Shape>& shapes, const dvec3& p) {
    double d = shapeDistance(shapes[0], p);
    for (std::size_t i = 1; i < shapes.size(); ++i)
        d = smoothMin(d, shapeDistance(shapes[i], p), shapes[i].blend);
    return d;
}

// ---- Skinning and the breathing shape

struct Skinning {
    std::vector<std::array<std::uint8_t, 4>> joints;
    std::vector<std::array<float, 4>> weights;
};

/** Each shape pulls the vertices near its own surface towards its joint; the four strongest
 *  joints are kept and normalised, so blends between shapes bend smoothly. */
Skinning skin(const std::vector<Shape>& shapes, const std::vector<dvec3>& positions) {
    Skinning out;
    for (const dvec3& p : positions) {
        std::array<double, JointCount> w{};
        for (const Shape& shape : shapes)
            w[std::size_t(shape.joint)] += std::exp(-std::max(shapeDistance(shape, p), 0.0) / 0.02);
        std::array<int, JointCount> order{};
        for (int i = 0; i < JointCount; ++i)
            order[std::size_t(i)] = i;
        std::stable_sort(order.begin(), order.end(),
                         [&](int a, int b) { return w[std::size_t(a)] > w[std::size_t(b)]; });
        double total = 0.0;
        for (int i = 0; i < 4; ++i)
            total += w[std::size_t(order[std::size_t(i)])];
        std::array<std::uint8_t, 4> joints{};
        std::array<float, 4> weights{};
        float sum = 0.0f;
        for (std::size_t i = 0; i < 4; ++i) {
            joints[i] = std::uint8_t(order[i]);
            weights[i] = float(w[std::size_t(order[i])] / total);
            if (weights[i] < 1e-3f)
                weights[i] = 0.0f, joints[i] = 0;
            sum += weights[i];
        }
        for (float& weight : weights)
            weight /= sum;
        out.joints.push_back(joints);
        out.weights.push_back(weights);
    }
    return out;
}

double bump(const dvec3& p, const dvec3& centre, double radius) {
    const double t = 1.0 - glm::dot(p - centre, p - centre) / (radius * radius);
    return t > 0.0 ? t * t : 0.0;
}

/** Breathing in: the chest and belly swell along their normals, the shoulders rise. */
std::vector<dvec3> breathe(const std::vector<dvec3>& positions, const std::vector<dvec3>& normals) {
    std::vector<dvec3> delta;
    for (std::size_t i = 0; i < positions.size(); ++i) {
        const dvec3& p = positions[i];
        const double swell =
            0.016 * bump(p, {0.0, 1.27, 0.05}, 0.2) + 0.008 * bump(p, {0.0, 1.07, 0.06}, 0.15);
        const double lift =
            0.008 * (bump(p, {0.16, 1.44, 0.0}, 0.12) + bump(p, {-0.16, 1.44, 0.0}, 0.12));
        delta.push_back(normals[i] * swell + dvec3(0.0, lift, 0.0));
    }
    return delta;
}

// ---- Eyes: small opaque spheres on the head

Surface eyes() {
    Surface s;
    constexpr int kRings = 8, kSegments = 16;
    for (double side : {1.0, -1.0}) {
        const dvec3 centre{0.034 * side, 1.68, 0.088};
        const std::uint32_t base = std::uint32_t(s.positions.size());
        for (int r = 0; r <= kRings; ++r)
            for (int k = 0; k <= kSegments; ++k) {
                const double theta = glm::pi<double>() * r / kRings;
                const double phi = 2.0 * glm::pi<double>() * k / kSegments;
                const dvec3 n{std::sin(theta) * std::sin(phi), std::cos(theta),
                              std::sin(theta) * std::cos(phi)};
                s.positions.push_back(centre + n * 0.016);
                s.normals.push_back(n);
            }
        for (int r = 0; r < kRings; ++r)
            for (int k = 0; k < kSegments; ++k) {
                const std::uint32_t i0 = base + std::uint32_t(r * (kSegments + 1) + k);
                const std::uint32_t i1 = i0 + kSegments + 1;
                s.indices.insert(s.indices.end(), {i0, i1, i0 + 1, i0 + 1, i1, i1 + 1});
            }
    }
    return s;
}

// ---- Clips: each joint's rotation, the hips' offset and the breath, as functions of time

struct Pose {
    std::array<glm::dquat, JointCount> rotation;
    dvec3 hipsOffset{0.0};
    double breath = 0.0;
    Pose() { rotation.fill(glm::dquat(1.0, 0.0, 0.0, 0.0)); }
};

glm::dquat rotation(double pitch, double yaw, double roll) {
    return glm::angleAxis(yaw, dvec3(0, 1, 0)) * glm::angleAxis(roll, dvec3(0, 0, 1)) *
           glm::angleAxis(pitch, dvec3(1, 0, 0));
}

double smoothstep(double a, double b, double t) {
    const double x = std::clamp((t - a) / (b - a), 0.0, 1.0);
    return x * x * (3.0 - 2.0 * x);
}

struct Clip {
    const char* name;
    double duration;
    std::function<Pose(double)> pose;
};

constexpr double kTau = 6.283185307179586;

std::vector<Clip> clips() {
    Clip walk{"walk", 1.2, [](double t) {
                  Pose p;
                  const double phase = kTau * t / 1.2;
                  const double s = std::sin(phase), c = std::cos(phase);
                  p.hipsOffset = {0.0, 0.012 * std::cos(2.0 * phase) - 0.012, 0.0};
                  p.rotation[Hips] = rotation(0.0, 0.08 * s, 0.0);
                  p.rotation[Spine] = rotation(0.02, -0.05 * s, 0.0);
                  p.rotation[Chest] = rotation(0.03, -0.07 * s, 0.0);
                  p.rotation[Head] = rotation(-0.03, 0.06 * s, 0.0);
                  for (int side = 0; side < 2; ++side) {
                      const double sign = side == 0 ? 1.0 : -1.0;
                      const int thigh = side == 0 ? LThigh : RThigh;
                      const int shoulder = side == 0 ? LShoulder : RShoulder;
                      const double swing = -0.42 * sign * s;
                      const double knee = 0.08 + 0.7 * std::pow(std::max(0.0, sign * c), 2.0);
                      p.rotation[std::size_t(thigh)] = rotation(swing, 0.0, 0.0);
                      p.rotation[(std::size_t(thigh) + 1)] = rotation(knee, 0.0, 0.0);
                      p.rotation[(std::size_t(thigh) + 2)] =
                          rotation(-0.8 * (swing + knee), 0.0, 0.0);
                      p.rotation[(std::size_t(shoulder) + 1)] =
                          rotation(0.35 * sign * s, 0.0, -0.3 * sign);
                      p.rotation[(std::size_t(shoulder) + 2)] =
                          rotation(-0.25 - 0.2 * std::max(0.0, -sign * s), 0.0, 0.0);
                  }
                  p.breath = 0.5 + 0.5 * s;
                  return p;
              }};
    Clip wave{"wave", 2.4, [](double t) {
                  Pose p;
                  const double raised = smoothstep(0.0, 0.5, t) * (1.0 - smoothstep(1.9, 2.4, t));
                  const double sway = std::sin(kTau * t / 2.4);
                  const double wag = std::sin(kTau * 2.5 * (t - 0.5));
                  p.hipsOffset = {0.01 * sway, 0.0, 0.0};
                  p.rotation[Chest] = rotation(0.0, 0.0, 0.05 * raised);
                  p.rotation[Head] = rotation(0.05 * raised, -0.1 * raised, -0.1 * raised);
                  p.rotation[RUpperArm] = rotation(-0.25 * raised, 0.0, -1.8 * raised);
                  p.rotation[RForearm] = rotation(0.0, 0.0, (-0.55 + 0.4 * wag) * raised);
                  p.rotation[RHand] = rotation(0.0, 0.0, 0.2 * wag * raised);
                  p.rotation[LUpperArm] = rotation(0.05, 0.0, -0.3);
                  p.rotation[LForearm] = rotation(-0.3, 0.0, 0.0);
                  for (int thigh : {LThigh, RThigh}) {
                      p.rotation[std::size_t(thigh)] = rotation(-0.04, 0.0, 0.0);
                      p.rotation[(std::size_t(thigh) + 1)] = rotation(0.08, 0.0, 0.0);
                      p.rotation[(std::size_t(thigh) + 2)] = rotation(-0.04, 0.0, 0.0);
                  }
                  p.breath = 0.5 + 0.5 * std::sin(kTau * t / 1.2);
                  return p;
              }};
    Clip idle{"idle", 3.0, [](double t) {
                  Pose p;
                  const double slow = std::sin(kTau * t / 3.0);
                  p.hipsOffset = {0.008 * slow, 0.0, 0.0};
                  p.rotation[Hips] = rotation(0.0, 0.03 * slow, 0.015 * slow);
                  p.rotation[Chest] = rotation(0.02, -0.03 * slow, -0.015 * slow);
                  p.rotation[Head] = rotation(0.04 * std::sin(kTau * t / 1.5), 0.15 * slow, 0.0);
                  for (int shoulder : {LShoulder, RShoulder}) {
                      const double sign = shoulder == LShoulder ? 1.0 : -1.0;
                      p.rotation[(std::size_t(shoulder) + 1)] =
                          rotation(0.03 * slow, 0.0, sign * (-0.3 + 0.03 * slow));
                      p.rotation[(std::size_t(shoulder) + 2)] = rotation(-0.2, 0.0, 0.0);
                  }
                  p.breath = 0.5 + 0.5 * std::sin(kTau * t / 1.5);
                  return p;
              }};
    // The walk cycle four times over while the figure advances along its facing (+z), 0.5 m/s
    // from 1.2 m behind its origin to 1.2 m in front: a scene turns it to walk past others.
    Clip stroll{"stroll", 4.8, [walk](double t) {
                    Pose p = walk.pose(std::fmod(t, walk.duration));
                    p.hipsOffset.z += -1.2 + 0.5 * t;
                    return p;
                }};
    return {walk, wave, idle, stroll};
}

// ---- The glTF document

class Document { // NOLINT(bugprone-exception-escape): json members may throw; guardedMain reports
                 // it
public:
    nlohmann::json gltf;
    std::vector<std::uint8_t> bin;

    int view(const void* data, std::size_t bytes, std::optional<int> target) {
        bin.resize((bin.size() + 3) / 4 * 4, 0);
        nlohmann::json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
        if (target)
            v["target"] = *target;
        const auto* begin = static_cast<const std::uint8_t*>(data);
        bin.insert(bin.end(), begin, begin + bytes);
        gltf["bufferViews"].push_back(v);
        return int(gltf["bufferViews"].size()) - 1;
    }

    /** Float accessor of `components` per element; min/max when asked (positions, times). */
    int floats(const std::vector<float>& values, const char* type, int components, bool bounds,
               std::optional<int> target = std::nullopt) {
        nlohmann::json a = {{"bufferView", view(values.data(), values.size() * 4, target)},
                            {"componentType", 5126},
                            {"count", values.size() / std::size_t(components)},
                            {"type", type}};
        if (bounds) {
            std::vector<float> lo(std::size_t(components), 1e30f),
                hi(std::size_t(components), -1e30f);
            for (std::size_t i = 0; i < values.size(); ++i) {
                lo[i % std::size_t(components)] =
                    std::min(lo[i % std::size_t(components)], values[i]);
                hi[i % std::size_t(components)] =
                    std::max(hi[i % std::size_t(components)], values[i]);
            }
            a["min"] = lo;
            a["max"] = hi;
        }
        gltf["accessors"].push_back(a);
        return int(gltf["accessors"].size()) - 1;
    }

    template <class T>
    int integers(const std::vector<T>& values, int componentType, const char* type,
                 std::size_t count, int target) {
        gltf["accessors"].push_back(
            {{"bufferView", view(values.data(), values.size() * sizeof(T), target)},
             {"componentType", componentType},
             {"count", count},
             {"type", type}});
        return int(gltf["accessors"].size()) - 1;
    }
};

std::vector<float> flatten(const std::vector<dvec3>& v) {
    std::vector<float> out;
    for (const dvec3& p : v)
        out.insert(out.end(), {float(p.x), float(p.y), float(p.z)});
    return out;
}

nlohmann::json primitive(Document& doc, const Surface& s, const Skinning& skinning,
                         const std::vector<dvec3>& breath, int material,
                         const std::vector<float>& uv = {},
                         const std::vector<float>& tangents = {}) {
    constexpr int kArray = 34962, kElements = 34963;
    std::vector<std::uint8_t> joints;
    std::vector<float> weights;
    for (std::size_t i = 0; i < s.positions.size(); ++i) {
        joints.insert(joints.end(), skinning.joints[i].begin(), skinning.joints[i].end());
        weights.insert(weights.end(), skinning.weights[i].begin(), skinning.weights[i].end());
    }
    nlohmann::json attributes = {
        {"POSITION", doc.floats(flatten(s.positions), "VEC3", 3, true, kArray)},
        {"NORMAL", doc.floats(flatten(s.normals), "VEC3", 3, false, kArray)},
        {"JOINTS_0", doc.integers(joints, 5121, "VEC4", s.positions.size(), kArray)},
        {"WEIGHTS_0", doc.floats(weights, "VEC4", 4, false, kArray)}};
    if (!uv.empty())
        attributes["TEXCOORD_0"] = doc.floats(uv, "VEC2", 2, false, kArray);
    if (!tangents.empty())
        attributes["TANGENT"] = doc.floats(tangents, "VEC4", 4, false, kArray);
    int indices = 0;
    if (s.positions.size() < 65536) {
        const std::vector<std::uint16_t> narrow(s.indices.begin(), s.indices.end());
        indices = doc.integers(narrow, 5123, "SCALAR", narrow.size(), kElements);
    } else {
        indices = doc.integers(s.indices, 5125, "SCALAR", s.indices.size(), kElements);
    }
    return {{"attributes", attributes},
            {"indices", indices},
            {"material", material},
            {"targets", {{{"POSITION", doc.floats(flatten(breath), "VEC3", 3, true, kArray)}}}}};
}

// ---- The parts variant: a glass per body part, a normal-mapped head

enum Part { Torso, Arms, Legs, HeadPart, PartCount };

Part partOf(int joint) {
    if (joint == Head || joint == Neck)
        return HeadPart;
    if (joint >= LShoulder && joint <= RHand)
        return Arms;
    if (joint >= LThigh && joint <= RFoot)
        return Legs;
    return Torso;
}

/** One part of the surface: its triangles (by the strongest joint of their first vertex) with
 *  the vertices they use, their skinning and breathing deltas. Vertices on a seam are copied
 *  into both parts at the same position, so the parts still close the body. */
struct PartMesh {
    Surface surface;
    Skinning skinning;
    std::vector<dvec3> breath;
};

std::array<PartMesh, PartCount> splitParts(const Surface& s, const Skinning& skinning,
                                           const std::vector<dvec3>& breath) {
    std::array<PartMesh, PartCount> parts;
    std::array<std::vector<std::int64_t>, PartCount> remap;
    for (auto& r : remap)
        r.assign(s.positions.size(), -1);
    for (std::size_t t = 0; t < s.indices.size(); t += 3) {
        const Part part = partOf(skinning.joints[s.indices[t]][0]);
        PartMesh& m = parts[std::size_t(part)];
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t v = s.indices[t + k];
            std::int64_t& to = remap[std::size_t(part)][v];
            if (to < 0) {
                to = std::int64_t(m.surface.positions.size());
                m.surface.positions.push_back(s.positions[v]);
                m.surface.normals.push_back(s.normals[v]);
                m.skinning.joints.push_back(skinning.joints[v]);
                m.skinning.weights.push_back(skinning.weights[v]);
                m.breath.push_back(breath[v]);
            }
            m.surface.indices.push_back(std::uint32_t(to));
        }
    }
    return parts;
}

nlohmann::json glassMaterial(const char* name, double ior, std::array<double, 3> attenuation,
                             double distance) {
    return {{"name", name},
            {"pbrMetallicRoughness",
             {{"baseColorFactor", {1.0, 1.0, 1.0, 1.0}},
              {"metallicFactor", 0.0},
              {"roughnessFactor", 0.04}}},
            {"extensions",
             {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
              {"KHR_materials_volume",
               {{"thicknessFactor", 0.15},
                {"attenuationDistance", distance},
                {"attenuationColor", attenuation}}},
              {"KHR_materials_ior", {{"ior", ior}}}}}};
}

/** The parts figure's glasses (materials 2-5, after the glass and the eyes), the head's with
 *  the hammered normal map (texture 0), and a primitive a part. */
void addParts(Document& doc, const Surface& surface, const Skinning& bodySkin,
              const std::vector<dvec3>& breath, nlohmann::json& primitives) {
    doc.gltf["materials"].push_back(glassMaterial("clear torso", 1.5, {0.85, 0.95, 1.0}, 0.8));
    doc.gltf["materials"].push_back(glassMaterial("blue arms", 1.6, {0.35, 0.55, 1.0}, 0.35));
    doc.gltf["materials"].push_back(glassMaterial("amber legs", 1.55, {1.0, 0.7, 0.3}, 0.4));
    nlohmann::json head = glassMaterial("hammered head", 1.52, {0.9, 1.0, 0.9}, 0.8);
    head["normalTexture"] = {{"index", 0}, {"scale", 1.0}};
    doc.gltf["materials"].push_back(head);
    const std::vector<std::uint8_t> png = capture::encodePng(hammeredNormals());
    doc.gltf["images"] = {{{"bufferView", doc.view(png.data(), png.size(), std::nullopt)},
                           {"mimeType", "image/png"}}};
    doc.gltf["samplers"] = {{{"magFilter", 9729}, {"minFilter", 9987}}};
    doc.gltf["textures"] = {{{"source", 0}, {"sampler", 0}}};
    const auto parts = splitParts(surface, bodySkin, breath);
    for (int part = 0; part < PartCount; ++part) {
        const PartMesh& m = parts[std::size_t(part)];
        if (m.surface.indices.empty())
            continue;
        const bool mapped = part == HeadPart; // the normal-mapped part
        primitives.push_back(primitive(doc, m.surface, m.skinning, m.breath, 2 + part,
                                       mapped ? headUv(m.surface.positions) : std::vector<float>{},
                                       mapped ? headTangents(m.surface.positions, m.surface.normals)
                                              : std::vector<float>{}));
    }
}

/** The nodes (0 the mesh, 1.. the joints: joint j is node j + 1), the skin and the scene. */
void addSkeleton(Document& doc, const std::vector<JointSpec>& joints) {
    doc.gltf["nodes"] = {{{"name", "glass_figure"}, {"mesh", 0}, {"skin", 0}}};
    std::vector<float> inverseBind;
    for (std::size_t j = 0; j < joints.size(); ++j) {
        const dvec3 parent =
            joints[j].parent >= 0 ? joints[std::size_t(joints[j].parent)].position : dvec3(0.0);
        const dvec3 local = joints[j].position - parent;
        nlohmann::json node = {{"name", joints[j].name},
                               {"translation", {local.x, local.y, local.z}}};
        nlohmann::json children = nlohmann::json::array();
        for (std::size_t c = 0; c < joints.size(); ++c)
            if (joints[c].parent == int(j))
                children.push_back(c + 1);
        if (!children.empty())
            node["children"] = children;
        doc.gltf["nodes"].push_back(node);
        const dvec3& p = joints[j].position;
        inverseBind.insert(inverseBind.end(), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, float(-p.x),
                                               float(-p.y), float(-p.z), 1});
    }
    nlohmann::json skinJoints = nlohmann::json::array();
    for (std::size_t j = 0; j < joints.size(); ++j)
        skinJoints.push_back(j + 1);
    doc.gltf["skins"] = {{{"name", "skeleton"},
                          {"inverseBindMatrices", doc.floats(inverseBind, "MAT4", 16, false)},
                          {"joints", skinJoints},
                          {"skeleton", 1}}};
    doc.gltf["scenes"] = {{{"name", "glass figure"}, {"nodes", {0, 1}}}};
}

/** The clips, sampled at 30 frames per second, LINEAR between samples. */
void addClips(Document& doc, const std::vector<JointSpec>& joints) {
    for (const Clip& clip : clips()) {
        const int frames = int(std::lround(clip.duration * 30.0));
        std::vector<float> times;
        std::vector<Pose> poses;
        for (int f = 0; f <= frames; ++f) {
            const double t = clip.duration * f / frames;
            times.push_back(float(t));
            poses.push_back(clip.pose(t));
        }
        nlohmann::json samplers = nlohmann::json::array(), channels = nlohmann::json::array();
        const int input = doc.floats(times, "SCALAR", 1, true);
        auto channel = [&](const std::vector<float>& values, const char* type, int components,
                           int node, const char* path) {
            samplers.push_back({{"input", input},
                                {"output", doc.floats(values, type, components, false)},
                                {"interpolation", "LINEAR"}});
            channels.push_back(
                {{"sampler", samplers.size() - 1}, {"target", {{"node", node}, {"path", path}}}});
        };
        for (std::size_t j = 0; j < joints.size(); ++j) {
            std::vector<float> values;
            glm::dquat previous(1.0, 0.0, 0.0, 0.0);
            for (const Pose& pose : poses) {
                glm::dquat q = glm::normalize(pose.rotation[j]);
                if (glm::dot(q, previous) < 0.0)
                    q = -q; // the short way round between samples
                previous = q;
                values.insert(values.end(), {float(q.x), float(q.y), float(q.z), float(q.w)});
            }
            channel(values, "VEC4", 4, int(j) + 1, "rotation");
        }
        std::vector<float> translation, weights;
        for (const Pose& pose : poses) {
            const dvec3 t = joints[Hips].position + pose.hipsOffset;
            translation.insert(translation.end(), {float(t.x), float(t.y), float(t.z)});
            weights.push_back(float(pose.breath));
        }
        channel(translation, "VEC3", 3, 1, "translation");
        channel(weights, "SCALAR", 1, 0, "weights");
        doc.gltf["animations"].push_back(
            {{"name", clip.name}, {"samplers", samplers}, {"channels", channels}});
    }
}

} // namespace

std::vector<std::uint8_t> buildFigureGlb(const FigureOptions& options) {
    const std::vector<JointSpec> joints = skeleton();
    const std::vector<Shape> shapes = bodyShapes(joints);
    const auto body = [&](const dvec3& p) { return bodyDistance(shapes, p); };
    const Surface surface =
        surfaceNets(body, {-0.72, -0.03, -0.22}, {0.72, 1.82, 0.26}, options.cellSize);
    const Surface eyeSurface = eyes();

    Document doc;
    doc.gltf = {{"asset",
                 {{"version", "2.0"},
                  {"generator", "glass-generate-assets (the glass project's default character)"}}},
                {"scene", 0},
                {"extensionsUsed",
                 {"KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_ior",
                  "KHR_materials_dispersion"}}};
    nlohmann::json glass = glassMaterial("glass", 1.5, {0.80, 0.92, 1.0}, 0.6);
    glass["extensions"]["KHR_materials_dispersion"] = {{"dispersion", 0.3}};
    doc.gltf["materials"] = {glass,
                             {{"name", "eyes"},
                              {"pbrMetallicRoughness",
                               {{"baseColorFactor", {0.02, 0.02, 0.03, 1.0}},
                                {"metallicFactor", 0.0},
                                {"roughnessFactor", 0.25}}}}};

    Skinning eyeSkin;
    eyeSkin.joints.assign(eyeSurface.positions.size(), {std::uint8_t(Head), 0, 0, 0});
    eyeSkin.weights.assign(eyeSurface.positions.size(), {1.0f, 0.0f, 0.0f, 0.0f});
    const Skinning bodySkin = skin(shapes, surface.positions);
    const std::vector<dvec3> breath = breathe(surface.positions, surface.normals);
    nlohmann::json primitives = nlohmann::json::array();
    if (!options.parts) {
        primitives.push_back(primitive(doc, surface, bodySkin, breath, 0));
    } else {
        addParts(doc, surface, bodySkin, breath, primitives);
    }
    primitives.push_back(primitive(doc, eyeSurface, eyeSkin,
                                   std::vector<dvec3>(eyeSurface.positions.size(), dvec3(0.0)), 1));
    doc.gltf["meshes"] = {{{"name", "glass_figure"},
                           {"primitives", primitives},
                           {"weights", {0.0}},
                           {"extras", {{"targetNames", {"breathe"}}}}}};
    addSkeleton(doc, joints);
    addClips(doc, joints);

    doc.bin.resize((doc.bin.size() + 3) / 4 * 4, 0);
    doc.gltf["buffers"] = {{{"byteLength", doc.bin.size()}}};
    return asset::encodeGlb(doc.gltf.dump(), doc.bin);
}

} // namespace generate
