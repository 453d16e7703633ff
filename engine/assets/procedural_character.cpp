// SPDX-License-Identifier: MIT
// The generated humanoid: a signed distance field of capsules meshed by surface nets, skinned by
// distance to the bones, with keyframed idle and walk clips (see procedural_character.h).
//
// Surface nets. Grid nodes sample the field; each cell whose corners change sign gets one vertex at
// the mean of the zero crossings on its 12 edges; each grid edge whose ends change sign gets one
// quad joining the 4 cells around it, wound so its normal points from the inside end to the outside
// end. The grid is padded so the surface never reaches its border: every quad edge is then shared
// by exactly two quads, which makes the mesh closed. Normals are the normalised field gradient.
//
// Skin weights. Each joint owns one or more bone segments; a vertex's raw weight for a joint is
// (d + 0.01)^-6 with d its distance to the nearest of the joint's segments, so the nearest bone
// dominates and two bones blend evenly only where they meet. The four largest are kept, weights
// under 1 % dropped, and the rest renormalised.
#include "cleave/assets/procedural_character.h"

#include "cleave/geometry/primitives.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <numeric>

namespace cleave::assets {

namespace {

constexpr float kPi = 3.14159265358979f;

enum JointId : uint32_t {
  kHips,
  kSpine,
  kChest,
  kNeck,
  kHead,
  kLeftUpperArm,
  kLeftForearm,
  kLeftHand,
  kRightUpperArm,
  kRightForearm,
  kRightHand,
  kLeftThigh,
  kLeftShin,
  kLeftFoot,
  kRightThigh,
  kRightShin,
  kRightFoot,
  kJointCount
};

constexpr const char* kJointNames[kJointCount] = {
    "hips",         "spine",     "chest",           "neck",          "head",       "left_upper_arm",
    "left_forearm", "left_hand", "right_upper_arm", "right_forearm", "right_hand", "left_thigh",
    "left_shin",    "left_foot", "right_thigh",     "right_shin",    "right_foot"};

constexpr int32_t kParents[kJointCount] = {
    -1,           kHips,       kSpine,         kChest,        kNeck, kChest,     kLeftUpperArm,
    kLeftForearm, kChest,      kRightUpperArm, kRightForearm, kHips, kLeftThigh, kLeftShin,
    kHips,        kRightThigh, kRightShin};

// Arms hang 35 degrees out from the body.
const float kArmSin = std::sin(35.f * kPi / 180.f), kArmCos = std::cos(35.f * kPi / 180.f);

glm::vec3 shoulder(float side) { return {0.19f * side, 1.42f, 0.f}; }
glm::vec3 elbow(float side) {
  return shoulder(side) + 0.27f * glm::vec3(kArmSin * side, -kArmCos, 0.f);
}
glm::vec3 wrist(float side) {
  return elbow(side) + 0.24f * glm::vec3(kArmSin * side, -kArmCos, 0.f);
}
glm::vec3 fingerTip(float side) {
  return wrist(side) + 0.11f * glm::vec3(kArmSin * side, -kArmCos, 0.f);
}
glm::vec3 hip(float side) { return {0.11f * side, 0.9f, 0.f}; }
glm::vec3 knee(float side) { return {0.12f * side, 0.5f, 0.f}; }
glm::vec3 ankle(float side) { return {0.13f * side, 0.1f, 0.f}; }
glm::vec3 toe(float side) { return {0.13f * side, 0.05f, 0.15f}; }

// Joint positions in the bind pose (model space).
std::array<glm::vec3, kJointCount> jointPositions() {
  std::array<glm::vec3, kJointCount> p{};
  p[kHips] = {0.f, 0.95f, 0.f};
  p[kSpine] = {0.f, 1.1f, 0.f};
  p[kChest] = {0.f, 1.28f, 0.f};
  p[kNeck] = {0.f, 1.48f, 0.f};
  p[kHead] = {0.f, 1.58f, 0.f};
  for (int s = 0; s < 2; ++s) {
    const float side = s == 0 ? 1.f : -1.f;
    const uint32_t o = s == 0 ? 0u : 3u;
    p[kLeftUpperArm + o] = shoulder(side);
    p[kLeftForearm + o] = elbow(side);
    p[kLeftHand + o] = wrist(side);
    p[kLeftThigh + o] = hip(side);
    p[kLeftShin + o] = knee(side);
    p[kLeftFoot + o] = ankle(side);
  }
  return p;
}

struct Segment {
  glm::vec3 a, b;
};

float segmentDistance(const glm::vec3& p, const Segment& s) {
  const glm::vec3 ab = s.b - s.a;
  const float len2 = glm::dot(ab, ab);
  const float t = len2 > 0.f ? glm::clamp(glm::dot(p - s.a, ab) / len2, 0.f, 1.f) : 0.f;
  return glm::length(p - (s.a + t * ab));
}

// Polynomial smooth minimum (Quilez): blends the two distances within k of each other.
float smoothMin(float a, float b, float k) {
  const float h = std::max(k - std::abs(a - b), 0.f) / k;
  return std::min(a, b) - h * h * k * 0.25f;
}

// The body: negative inside, positive outside (metres, approximately).
float bodyDistance(const glm::vec3& p) {
  constexpr float k = 0.03f;
  // Torso parts are slightly flattened front to back.
  const glm::vec3 q(p.x / 1.05f, p.y, p.z / 0.8f);
  float d = (segmentDistance(q, {{0.f, 0.95f, 0.f}, {0.f, 1.22f, 0.f}}) - 0.14f) * 0.8f;
  d = smoothMin(d, (segmentDistance(q, {{0.f, 1.2f, 0.f}, {0.f, 1.36f, 0.f}}) - 0.16f) * 0.8f, k);
  d = smoothMin(d, segmentDistance(p, {{-0.09f, 0.93f, 0.f}, {0.09f, 0.93f, 0.f}}) - 0.12f, k);
  d = smoothMin(d, segmentDistance(p, {{-0.17f, 1.41f, 0.f}, {0.17f, 1.41f, 0.f}}) - 0.065f, k);
  d = smoothMin(d, segmentDistance(p, {{0.f, 1.4f, 0.f}, {0.f, 1.56f, 0.f}}) - 0.05f, k);
  const glm::vec3 h((p.x) / 1.f, (p.y - 1.67f) / 1.15f, (p.z - 0.01f) / 1.f);
  d = smoothMin(d, (glm::length(h) - 0.11f) * 1.f, k);
  for (int s = 0; s < 2; ++s) {
    const float side = s == 0 ? 1.f : -1.f;
    d = smoothMin(d, segmentDistance(p, {shoulder(side), elbow(side)}) - 0.048f, k);
    d = smoothMin(d, segmentDistance(p, {elbow(side), wrist(side)}) - 0.04f, k);
    d = smoothMin(d, segmentDistance(p, {wrist(side), fingerTip(side)}) - 0.036f, k);
    d = smoothMin(d, segmentDistance(p, {hip(side), knee(side)}) - 0.075f, k);
    d = smoothMin(d, segmentDistance(p, {knee(side), ankle(side)}) - 0.055f, k);
    d = smoothMin(
        d, segmentDistance(p, {ankle(side) + glm::vec3(0.f, -0.04f, -0.03f), toe(side)}) - 0.045f,
        k);
  }
  return d;
}

// Bone segments per joint, for the skin weights.
std::vector<std::pair<uint32_t, Segment>> boneSegments() {
  std::vector<std::pair<uint32_t, Segment>> bones = {
      {kHips, {{0.f, 0.88f, 0.f}, {0.f, 1.0f, 0.f}}},
      {kHips, {{-0.1f, 0.92f, 0.f}, {0.1f, 0.92f, 0.f}}},
      {kSpine, {{0.f, 1.02f, 0.f}, {0.f, 1.2f, 0.f}}},
      {kChest, {{0.f, 1.22f, 0.f}, {0.f, 1.4f, 0.f}}},
      {kChest, {{-0.15f, 1.41f, 0.f}, {0.15f, 1.41f, 0.f}}},
      {kNeck, {{0.f, 1.46f, 0.f}, {0.f, 1.56f, 0.f}}},
      {kHead, {{0.f, 1.6f, 0.f}, {0.f, 1.78f, 0.f}}},
  };
  for (int s = 0; s < 2; ++s) {
    const float side = s == 0 ? 1.f : -1.f;
    const uint32_t o = s == 0 ? 0u : 3u;
    bones.push_back({kLeftUpperArm + o, {shoulder(side), elbow(side)}});
    bones.push_back({kLeftForearm + o, {elbow(side), wrist(side)}});
    bones.push_back({kLeftHand + o, {wrist(side), fingerTip(side)}});
    bones.push_back({kLeftThigh + o, {hip(side), knee(side)}});
    bones.push_back({kLeftShin + o, {knee(side), ankle(side)}});
    bones.push_back({kLeftFoot + o, {ankle(side), toe(side)}});
  }
  return bones;
}

uint32_t materialOfJoint(uint32_t joint) {
  switch (joint) {
    case kHead:
    case kNeck:
    case kLeftHand:
    case kRightHand:
      return 0;  // skin
    case kSpine:
    case kChest:
    case kLeftUpperArm:
    case kRightUpperArm:
    case kLeftForearm:
    case kRightForearm:
      return 2;  // shirt
    case kLeftFoot:
    case kRightFoot:
      return 4;  // shoes
    default:
      return 3;  // trousers: hips, thighs, shins
  }
}

geometry::MeshData surfaceNets(float cell) {
  const glm::vec3 lo(-0.72f, -0.1f, -0.28f), hi(0.72f, 1.92f, 0.32f);
  const int nx = static_cast<int>(std::ceil((hi.x - lo.x) / cell)) + 1;
  const int ny = static_cast<int>(std::ceil((hi.y - lo.y) / cell)) + 1;
  const int nz = static_cast<int>(std::ceil((hi.z - lo.z) / cell)) + 1;
  auto node = [&](int i, int j, int k) {
    return (size_t(k) * size_t(ny) + size_t(j)) * size_t(nx) + size_t(i);
  };
  auto position = [&](int i, int j, int k) {
    return lo + cell * glm::vec3(float(i), float(j), float(k));
  };
  std::vector<float> field(size_t(nx) * size_t(ny) * size_t(nz));
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        float d = bodyDistance(position(i, j, k));
        if (d == 0.f) d = 1e-7f;  // no node exactly on the surface: every sign is strict
        field[node(i, j, k)] = d;
      }

  geometry::MeshData mesh;
  constexpr uint32_t kNoVertex = 0xffffffffu;
  std::vector<uint32_t> cellVertex(field.size(), kNoVertex);  // indexed like the cell's lowest node
  static constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                                        {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  static constexpr int kEdge[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                       {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i) {
        float value[8];
        int inside = 0;
        for (int c = 0; c < 8; ++c) {
          value[c] = field[node(i + kCorner[c][0], j + kCorner[c][1], k + kCorner[c][2])];
          inside += value[c] < 0.f ? 1 : 0;
        }
        if (inside == 0 || inside == 8) continue;
        glm::vec3 sum(0.f);
        int crossings = 0;
        for (const auto& e : kEdge) {
          const float a = value[e[0]], b = value[e[1]];
          if ((a < 0.f) == (b < 0.f)) continue;
          const float t = a / (a - b);
          const glm::vec3 pa(float(kCorner[e[0]][0]), float(kCorner[e[0]][1]),
                             float(kCorner[e[0]][2]));
          const glm::vec3 pb(float(kCorner[e[1]][0]), float(kCorner[e[1]][1]),
                             float(kCorner[e[1]][2]));
          sum += pa + t * (pb - pa);
          ++crossings;
        }
        cellVertex[node(i, j, k)] = static_cast<uint32_t>(mesh.positions.size());
        mesh.positions.push_back(position(i, j, k) + cell * (sum / float(crossings)));
      }

  // One quad per sign-changing grid edge; the 4 cells around it exist because of the padding.
  const int dims[3] = {nx, ny, nz};
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          int at[3] = {i, j, k};
          if (at[axis] + 1 >= dims[axis] || at[u] == 0 || at[v] == 0) continue;
          int next[3] = {i, j, k};
          ++next[axis];
          const float a = field[node(at[0], at[1], at[2])],
                      b = field[node(next[0], next[1], next[2])];
          if ((a < 0.f) == (b < 0.f)) continue;
          uint32_t quad[4];
          static constexpr int kAround[4][2] = {{-1, -1}, {0, -1}, {0, 0}, {-1, 0}};
          for (int c = 0; c < 4; ++c) {
            int cellAt[3] = {i, j, k};
            cellAt[u] += kAround[c][0];
            cellAt[v] += kAround[c][1];
            quad[c] = cellVertex[node(cellAt[0], cellAt[1], cellAt[2])];
          }
          if (!(a < 0.f)) std::swap(quad[1], quad[3]);  // the outside is at the start: reverse
          const float d02 = glm::distance(mesh.positions[quad[0]], mesh.positions[quad[2]]);
          const float d13 = glm::distance(mesh.positions[quad[1]], mesh.positions[quad[3]]);
          if (d02 <= d13) {
            mesh.indices.insert(mesh.indices.end(),
                                {quad[0], quad[1], quad[2], quad[0], quad[2], quad[3]});
          } else {
            mesh.indices.insert(mesh.indices.end(),
                                {quad[0], quad[1], quad[3], quad[1], quad[2], quad[3]});
          }
        }
  }
  // Normals: the field gradient by central differences.
  const float e = cell * 0.25f;
  for (const glm::vec3& p : mesh.positions) {
    const glm::vec3 g(bodyDistance(p + glm::vec3(e, 0, 0)) - bodyDistance(p - glm::vec3(e, 0, 0)),
                      bodyDistance(p + glm::vec3(0, e, 0)) - bodyDistance(p - glm::vec3(0, e, 0)),
                      bodyDistance(p + glm::vec3(0, 0, e)) - bodyDistance(p - glm::vec3(0, 0, e)));
    const float len = glm::length(g);
    mesh.normals.push_back(len > 0.f ? g / len : glm::vec3(0.f, 1.f, 0.f));
  }
  return mesh;
}

void skin(geometry::MeshData& mesh) {
  const auto bones = boneSegments();
  for (const glm::vec3& p : mesh.positions) {
    std::array<double, kJointCount> raw{};
    for (const auto& [joint, segment] : bones) {
      const double w = std::pow(double(segmentDistance(p, segment)) + 0.01, -6.0);
      raw[joint] = std::max(raw[joint], w);
    }
    std::array<uint32_t, kJointCount> order{};
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return raw[a] > raw[b]; });
    double total = 0.0;
    for (int k = 0; k < 4; ++k) total += raw[order[k]];
    glm::u16vec4 joints(0);
    glm::vec4 weights(0.f);
    double kept = 0.0;
    int count = 0;
    for (int k = 0; k < 4; ++k) {
      if (raw[order[k]] / total < 0.01) break;
      kept += raw[order[k]];
      ++count;
    }
    for (int k = 0; k < count; ++k) {
      joints[k] = static_cast<uint16_t>(order[k]);
      weights[k] = static_cast<float>(raw[order[k]] / kept);
    }
    // Make the sum exactly representable as 1 up to rounding of the largest weight.
    float rest = 1.f;
    for (int k = 1; k < count; ++k) rest -= weights[k];
    weights[0] = rest;
    mesh.joints.push_back(joints);
    mesh.weights.push_back(weights);
  }
  // Submeshes by material of the joint with the largest weight over each triangle's corners.
  const size_t triangles = mesh.indices.size() / 3;
  std::vector<uint32_t> material(triangles);
  for (size_t t = 0; t < triangles; ++t) {
    std::array<float, kJointCount> sum{};
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = mesh.indices[3 * t + c];
      for (int k = 0; k < 4; ++k) sum[mesh.joints[v][k]] += mesh.weights[v][k];
    }
    const auto best = static_cast<uint32_t>(std::max_element(sum.begin(), sum.end()) - sum.begin());
    material[t] = materialOfJoint(best);
  }
  std::vector<uint32_t> order(triangles);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return material[a] < material[b]; });
  std::vector<uint32_t> indices;
  indices.reserve(mesh.indices.size());
  for (uint32_t t : order) {
    if (mesh.submeshes.empty() || mesh.submeshes.back().materialId != material[t]) {
      mesh.submeshes.push_back({static_cast<uint32_t>(indices.size()), 0u, material[t]});
    }
    indices.insert(indices.end(),
                   {mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]});
    mesh.submeshes.back().indexCount += 3;
  }
  mesh.indices = std::move(indices);
}

anim::Skeleton makeSkeleton() {
  const auto positions = jointPositions();
  anim::Skeleton skeleton;
  skeleton.joints.resize(kJointCount);
  for (uint32_t j = 0; j < kJointCount; ++j) {
    anim::Joint& joint = skeleton.joints[j];
    joint.name = kJointNames[j];
    joint.parent = kParents[j];
    joint.rest.translation =
        joint.parent < 0 ? positions[j] : positions[j] - positions[size_t(joint.parent)];
  }
  anim::Pose rest;
  anim::restPose(skeleton, rest);
  anim::setBindPose(skeleton, rest);
  return skeleton;
}

// A looping channel sampled from f at `keys` evenly spaced times over `period` (the last key equals
// the first, so the loop is seamless).
anim::Channel rotationChannel(uint32_t joint, float period, int keys, const glm::vec3& axis,
                              float (*f)(float)) {
  anim::Channel c;
  c.joint = joint;
  c.path = anim::ChannelPath::Rotation;
  c.interpolation = anim::Interpolation::Linear;
  for (int k = 0; k <= keys; ++k) {
    const float phase = 2.f * kPi * float(k % keys) / float(keys);
    const glm::quat q = glm::angleAxis(f(phase), axis);
    c.times.push_back(period * float(k) / float(keys));
    c.values.emplace_back(q.x, q.y, q.z, q.w);
  }
  return c;
}

anim::Channel translationChannel(uint32_t joint, float period, int keys, const glm::vec3& base,
                                 const glm::vec3& axis, float (*f)(float)) {
  anim::Channel c;
  c.joint = joint;
  c.path = anim::ChannelPath::Translation;
  c.interpolation = anim::Interpolation::Linear;
  for (int k = 0; k <= keys; ++k) {
    const float phase = 2.f * kPi * float(k % keys) / float(keys);
    c.times.push_back(period * float(k) / float(keys));
    c.values.emplace_back(base + axis * f(phase), 0.f);
  }
  return c;
}

anim::AnimationClip makeWalk(const anim::Skeleton& skeleton) {
  constexpr float kPeriod = 1.f;
  constexpr int kKeys = 16;
  const glm::vec3 x(1, 0, 0), y(0, 1, 0);
  anim::AnimationClip clip;
  clip.name = "walk";
  // Positive rotation about x swings a limb backwards (its lower end towards -z).
  clip.channels.push_back(
      rotationChannel(kLeftThigh, kPeriod, kKeys, x, [](float p) { return 0.45f * std::sin(p); }));
  clip.channels.push_back(rotationChannel(kRightThigh, kPeriod, kKeys, x,
                                          [](float p) { return -0.45f * std::sin(p); }));
  clip.channels.push_back(rotationChannel(kLeftShin, kPeriod, kKeys, x, [](float p) {
    return 0.15f + 0.45f * std::max(0.f, -std::sin(p + 0.6f));
  }));
  clip.channels.push_back(rotationChannel(kRightShin, kPeriod, kKeys, x, [](float p) {
    return 0.15f + 0.45f * std::max(0.f, std::sin(p + 0.6f));
  }));
  clip.channels.push_back(
      rotationChannel(kLeftFoot, kPeriod, kKeys, x, [](float p) { return -0.2f * std::sin(p); }));
  clip.channels.push_back(
      rotationChannel(kRightFoot, kPeriod, kKeys, x, [](float p) { return 0.2f * std::sin(p); }));
  clip.channels.push_back(rotationChannel(kLeftUpperArm, kPeriod, kKeys, x,
                                          [](float p) { return -0.35f * std::sin(p); }));
  clip.channels.push_back(rotationChannel(kRightUpperArm, kPeriod, kKeys, x,
                                          [](float p) { return 0.35f * std::sin(p); }));
  clip.channels.push_back(rotationChannel(kLeftForearm, kPeriod, kKeys, x,
                                          [](float p) { return -0.25f - 0.15f * std::sin(p); }));
  clip.channels.push_back(rotationChannel(kRightForearm, kPeriod, kKeys, x,
                                          [](float p) { return -0.25f + 0.15f * std::sin(p); }));
  clip.channels.push_back(
      rotationChannel(kSpine, kPeriod, kKeys, y, [](float p) { return 0.08f * std::sin(p); }));
  clip.channels.push_back(
      rotationChannel(kChest, kPeriod, kKeys, y, [](float p) { return -0.12f * std::sin(p); }));
  clip.channels.push_back(
      translationChannel(kHips, kPeriod, kKeys, skeleton.joints[kHips].rest.translation, y,
                         [](float p) { return -0.02f + 0.02f * std::cos(2.f * p); }));
  clip.updateDuration();
  return clip;
}

anim::AnimationClip makeIdle(const anim::Skeleton& skeleton) {
  constexpr float kPeriod = 2.f;
  constexpr int kKeys = 12;
  const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  anim::AnimationClip clip;
  clip.name = "idle";
  clip.channels.push_back(
      rotationChannel(kChest, kPeriod, kKeys, x, [](float p) { return 0.03f * std::sin(p); }));
  clip.channels.push_back(
      rotationChannel(kSpine, kPeriod, kKeys, z, [](float p) { return 0.02f * std::sin(p); }));
  clip.channels.push_back(
      rotationChannel(kHead, kPeriod, kKeys, y, [](float p) { return 0.12f * std::sin(p); }));
  clip.channels.push_back(rotationChannel(kLeftUpperArm, kPeriod, kKeys, z,
                                          [](float p) { return 0.05f * std::sin(p); }));
  clip.channels.push_back(rotationChannel(kRightUpperArm, kPeriod, kKeys, z,
                                          [](float p) { return -0.05f * std::sin(p); }));
  clip.channels.push_back(
      translationChannel(kHips, kPeriod, kKeys, skeleton.joints[kHips].rest.translation, y,
                         [](float p) { return -0.005f * (1.f - std::cos(p)); }));
  clip.updateDuration();
  return clip;
}

}  // namespace

ProceduralCharacter makeProceduralCharacter(const CharacterOptions& options) {
  ProceduralCharacter character;
  const float cell = options.cellSize > 0.005f ? options.cellSize : 0.005f;
  character.mesh = surfaceNets(cell);
  skin(character.mesh);
  character.skeleton = makeSkeleton();
  character.idle = makeIdle(character.skeleton);
  character.walk = makeWalk(character.skeleton);
  character.materialColors = {
      {0.80f, 0.58f, 0.45f, 1.f},  // 0 skin
      {0.70f, 0.12f, 0.10f, 1.f},  // 1 cut caps
      {0.18f, 0.36f, 0.70f, 1.f},  // 2 shirt
      {0.20f, 0.20f, 0.24f, 1.f},  // 3 trousers
      {0.35f, 0.22f, 0.12f, 1.f},  // 4 shoes
  };
  return character;
}

geometry::MeshData makeCharacterParts(const ProceduralCharacter& character) {
  const anim::Skeleton& skeleton = character.skeleton;
  const size_t count = skeleton.joints.size();
  std::vector<glm::vec3> at(count);
  for (size_t j = 0; j < count; ++j) at[j] = glm::vec3(glm::inverse(skeleton.joints[j].inverseBind)[3]);
  std::vector<std::vector<size_t>> children(count);
  for (size_t j = 0; j < count; ++j) {
    const int32_t parent = skeleton.joints[j].parent;
    if (parent >= 0 && size_t(parent) < count) children[size_t(parent)].push_back(j);
  }
  auto has = [](const std::string& name, const char* part) { return name.find(part) != std::string::npos; };
  geometry::MeshData parts;
  auto addBox = [&](size_t joint, glm::vec3 from, glm::vec3 to, float halfWidth, float halfDepth, uint32_t material) {
    const glm::vec3 axis = to - from;
    const float length = glm::length(axis);
    if (!(length > 1e-4f)) return;
    const glm::vec3 y = axis / length;
    // A frame with y along the bone and z as close to the character's forward (+z) as possible.
    glm::vec3 z = glm::vec3(0.f, 0.f, 1.f) - y * y.z;
    if (glm::length(z) < 1e-3f) z = glm::vec3(1.f, 0.f, 0.f) - y * y.x;
    z = glm::normalize(z);
    const glm::vec3 x = glm::cross(y, z);
    glm::mat4 frame(1.f);
    frame[0] = glm::vec4(x, 0.f);
    frame[1] = glm::vec4(y, 0.f);
    frame[2] = glm::vec4(z, 0.f);
    frame[3] = glm::vec4(0.5f * (from + to), 1.f);
    geometry::MeshData box = geometry::primitives::box(glm::vec3(halfWidth, 0.5f * length, halfDepth));
    geometry::primitives::transform(box, frame);
    box.joints.assign(box.positions.size(), glm::u16vec4(uint16_t(joint), 0, 0, 0));
    box.weights.assign(box.positions.size(), glm::vec4(1.f, 0.f, 0.f, 0.f));
    box.submeshes = {{0, uint32_t(box.indices.size()), material}};
    parts = parts.positions.empty() ? std::move(box) : geometry::primitives::merge(parts, box);
  };
  constexpr float kGap = 0.035f;  // at each end of a bone: neighbouring parts never touch
  for (size_t j = 0; j < count; ++j) {
    const std::string& name = skeleton.joints[j].name;
    if (has(name, "hips")) continue;  // the thighs and the spine carry the pelvis
    const uint32_t material = has(name, "foot") || has(name, "shin") ? (has(name, "foot") ? 4u : 3u)
                              : has(name, "thigh")                    ? 3u
                              : has(name, "head") || has(name, "hand") || has(name, "neck") ? 0u
                                                                                            : 2u;
    glm::vec3 from = at[j];
    glm::vec3 to;
    if (children[j].size() == 1) {
      to = at[children[j][0]];
    } else if (!children[j].empty()) {
      // The chest: up to the neck only (the shoulders start the arms).
      size_t up = children[j][0];
      for (size_t c : children[j])
        if (at[c].y > at[up].y) up = c;
      to = at[up];
    } else if (has(name, "head")) {
      to = from + glm::vec3(0.f, 0.24f, 0.f);
    } else if (has(name, "foot")) {
      to = glm::vec3(from.x, 0.f, from.z + 0.18f);
      from = glm::vec3(from.x, 0.f, from.z - 0.06f);
      addBox(j, from + glm::vec3(0.f, 0.05f, 0.f), to + glm::vec3(0.f, 0.05f, 0.f), 0.05f, 0.045f, material);
      continue;
    } else {  // hands: along the forearm's direction
      const int32_t parent = skeleton.joints[j].parent;
      const glm::vec3 dir = parent >= 0 ? glm::normalize(from - at[size_t(parent)]) : glm::vec3(0.f, -1.f, 0.f);
      to = from + dir * 0.16f;
    }
    const glm::vec3 dir = glm::normalize(to - from);
    from += dir * kGap;
    to -= dir * kGap;
    const float half = has(name, "spine") || has(name, "chest") ? 0.15f
                       : has(name, "thigh")                     ? 0.065f
                       : has(name, "shin")                      ? 0.05f
                       : has(name, "head")                      ? 0.1f
                       : has(name, "upper_arm")                 ? 0.045f
                       : has(name, "neck")                      ? 0.045f
                                                                : 0.04f;
    const float depth = has(name, "spine") || has(name, "chest") ? 0.1f : has(name, "head") ? 0.11f : half;
    addBox(j, from, to, half, depth, material);
  }
  return parts;
}

}  // namespace cleave::assets
