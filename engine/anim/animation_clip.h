// SPDX-License-Identifier: MIT
// Animation clips: keyframed translation, rotation and scale channels per joint (the glTF model),
// sampled into a local Pose; and an Animator that plays one clip at a time with crossfades.
//
// Keys. `times` are seconds, strictly increasing. `values` hold, per key, one value (Step, Linear)
// or three (CubicSpline: in-tangent, value, out-tangent, in that order, as in glTF). Translation
// and scale use xyz of each vec4; rotation uses (x, y, z, w) of a quaternion, the glTF order.
// Interpolation: Step holds the previous key; Linear lerps translation and scale and slerps
// rotation (shortest path); CubicSpline is the Hermite spline of glTF 2.0 with tangents scaled by
// the key interval, the rotation normalised afterwards. Before the first key a channel gives its
// first value, after the last key its last value.
//
// Time. A clip lasts `duration` seconds (at least its last key). Looping wraps the time into
// [0, duration); without looping the time is clamped to [0, duration]. Sampling is a pure function:
// the same clip, time and skeleton give bit-identical poses.
//
// Failure: validateClip() reports malformed channels with a reason; sampleClip() skips a channel
// that is malformed or targets a joint outside the skeleton (it never reads out of range).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "cleave/anim/skeleton.h"
#include "cleave/base/status.h"

namespace cleave::anim {

enum class Interpolation : uint8_t { Step, Linear, CubicSpline };
enum class ChannelPath : uint8_t { Translation, Rotation, Scale };

struct Channel {
  uint32_t joint = 0;
  ChannelPath path = ChannelPath::Rotation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;       // seconds, strictly increasing
  std::vector<glm::vec4> values;  // one per key, or three per key for CubicSpline
};

struct AnimationClip {
  std::string name;
  float duration = 0.f;  // seconds; see updateDuration()
  std::vector<Channel> channels;

  // Sets duration to the last key time over all channels (0 for a clip without keys).
  void updateDuration();
};

// Ok when every channel has keys, increasing finite times, the right number of finite values and a
// joint inside `jointCount`; otherwise InvalidArgument with a reason naming the channel.
base::Status validateClip(const AnimationClip& clip, size_t jointCount);

// The clip time that `time` maps to: wrapped into [0, duration) when looping, else clamped.
float clipTime(const AnimationClip& clip, float time, bool loop);

// Samples the clip at `time` (wrapped or clamped by clipTime) over the rest pose: joints without a
// channel keep their rest transform. `out` is resized to the skeleton.
void sampleClip(const Skeleton& skeleton, const AnimationClip& clip, float time, bool loop,
                Pose& out);

// Plays clips on one skeleton. play() with a fade starts a crossfade from the pose being shown
// (the previous clip keeps advancing during the fade). Holds pointers to the skeleton and clips:
// the caller keeps them alive while the animator uses them.
class Animator {
 public:
  Animator() = default;
  explicit Animator(const Skeleton* skeleton) : skeleton_(skeleton) {}

  // Starts `clip` at time `startTime`; fadeSeconds > 0 blends in from the current clip over that
  // time. A null clip shows the rest pose.
  void play(const AnimationClip* clip, float fadeSeconds = 0.f, bool loop = true,
            float startTime = 0.f);
  // Advances both clips and the fade by dt seconds (dt >= 0).
  void advance(float dt);
  // The current local pose. Allocates only while its scratch poses grow to the skeleton's size.
  void evaluate(Pose& out);
  // Joint matrices of the current pose (see skeleton.h).
  void evaluateJointMatrices(std::vector<glm::mat4>& out);

  const AnimationClip* clip() const { return current_.clip; }
  float time() const { return current_.time; }
  // Weight of the current clip: 1 outside a fade, rising from 0 to 1 during one.
  float blendWeight() const;

 private:
  struct Track {
    const AnimationClip* clip = nullptr;
    float time = 0.f;
    bool loop = true;
  };
  void sample(const Track& track, Pose& out) const;

  const Skeleton* skeleton_ = nullptr;
  Track current_;
  Track previous_;
  float fadeDuration_ = 0.f;
  float fadeElapsed_ = 0.f;
  Pose scratch_;  // the outgoing clip's pose during a fade
  Pose pose_;     // evaluateJointMatrices' pose
};

}  // namespace cleave::anim
