// SPDX-License-Identifier: MIT
// Clip sampling and the crossfading Animator.
//
// Key search is a binary search over the channel's times (upper_bound), so sampling costs
// O(channels * log keys). Cubic splines follow the glTF 2.0 specification, appendix C:
// p(s) = (2s^3 - 3s^2 + 1) v0 + (s^3 - 2s^2 + s) d b0 + (-2s^3 + 3s^2) v1 + (s^3 - s^2) d a1,
// with d the key interval, b0 the out-tangent of the first key and a1 the in-tangent of the second.
#include "cleave/anim/animation_clip.h"

#include <algorithm>
#include <cmath>

namespace cleave::anim {

namespace {

size_t valuesPerKey(const Channel& channel) {
  return channel.interpolation == Interpolation::CubicSpline ? 3u : 1u;
}

bool wellFormed(const Channel& channel) {
  return !channel.times.empty() &&
         channel.values.size() == channel.times.size() * valuesPerKey(channel);
}

glm::quat toQuat(const glm::vec4& v) { return glm::quat(v.w, v.x, v.y, v.z); }

glm::quat normalizedOrIdentity(const glm::quat& q) {
  const float len = glm::length(q);
  return len > 0.f && std::isfinite(len) ? q / len : glm::quat(1.f, 0.f, 0.f, 0.f);
}

// The value of a channel at time t (already wrapped or clamped to the clip).
glm::vec4 evaluate(const Channel& channel, float t, bool rotation) {
  const std::vector<float>& times = channel.times;
  const size_t stride = valuesPerKey(channel);
  const size_t centre = stride == 3 ? 1 : 0;
  auto value = [&](size_t key) { return channel.values[key * stride + centre]; };
  if (t <= times.front()) return value(0);
  if (t >= times.back()) return value(times.size() - 1);
  const size_t k1 =
      static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  const size_t k0 = k1 - 1;
  const float interval = times[k1] - times[k0];
  const float s = interval > 0.f ? (t - times[k0]) / interval : 0.f;
  switch (channel.interpolation) {
    case Interpolation::Step:
      return value(k0);
    case Interpolation::Linear: {
      if (!rotation) return glm::mix(value(k0), value(k1), s);
      const glm::quat a = toQuat(value(k0));
      glm::quat b = toQuat(value(k1));
      if (glm::dot(a, b) < 0.f) b = -b;
      const glm::quat q = glm::slerp(a, b, s);
      return glm::vec4(q.x, q.y, q.z, q.w);
    }
    case Interpolation::CubicSpline: {
      const glm::vec4 v0 = value(k0), v1 = value(k1);
      const glm::vec4 b0 = channel.values[k0 * 3 + 2] * interval;
      const glm::vec4 a1 = channel.values[k1 * 3 + 0] * interval;
      const float s2 = s * s, s3 = s2 * s;
      return (2.f * s3 - 3.f * s2 + 1.f) * v0 + (s3 - 2.f * s2 + s) * b0 +
             (-2.f * s3 + 3.f * s2) * v1 + (s3 - s2) * a1;
    }
  }
  return value(k0);
}

}  // namespace

void AnimationClip::updateDuration() {
  duration = 0.f;
  for (const Channel& channel : channels) {
    if (!channel.times.empty()) duration = std::max(duration, channel.times.back());
  }
}

base::Status validateClip(const AnimationClip& clip, size_t jointCount) {
  for (size_t c = 0; c < clip.channels.size(); ++c) {
    const Channel& channel = clip.channels[c];
    auto fail = [&](const std::string& why) {
      return base::Status::failure(base::StatusCode::InvalidArgument,
                                   "clip '" + clip.name + "' channel " + std::to_string(c) + ": " + why);
    };
    if (channel.joint >= jointCount)
      return fail("joint " + std::to_string(channel.joint) + " is not in the skeleton");
    if (channel.times.empty()) return fail("no keys");
    if (!wellFormed(channel)) {
      return fail(std::to_string(channel.values.size()) + " values for " +
                  std::to_string(channel.times.size()) + " keys");
    }
    for (size_t k = 0; k < channel.times.size(); ++k) {
      if (!std::isfinite(channel.times[k]))
        return fail("key " + std::to_string(k) + " has a non-finite time");
      if (k > 0 && !(channel.times[k] > channel.times[k - 1])) {
        return fail("key times are not strictly increasing at key " + std::to_string(k));
      }
    }
    for (const glm::vec4& v : channel.values) {
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) ||
          !std::isfinite(v.w)) {
        return fail("a value is not finite");
      }
    }
  }
  return {};
}

float clipTime(const AnimationClip& clip, float time, bool loop) {
  if (!(clip.duration > 0.f) || !std::isfinite(time)) return 0.f;
  if (!loop) return std::clamp(time, 0.f, clip.duration);
  float t = std::fmod(time, clip.duration);
  if (t < 0.f) t += clip.duration;
  return t >= clip.duration ? 0.f : t;
}

void sampleClip(const Skeleton& skeleton, const AnimationClip& clip, float time, bool loop,
                Pose& out) {
  restPose(skeleton, out);
  const float t = clipTime(clip, time, loop);
  for (const Channel& channel : clip.channels) {
    if (channel.joint >= out.size() || !wellFormed(channel)) continue;
    Transform& target = out[channel.joint];
    switch (channel.path) {
      case ChannelPath::Translation:
        target.translation = glm::vec3(evaluate(channel, t, false));
        break;
      case ChannelPath::Scale:
        target.scale = glm::vec3(evaluate(channel, t, false));
        break;
      case ChannelPath::Rotation:
        target.rotation = normalizedOrIdentity(toQuat(evaluate(channel, t, true)));
        break;
    }
  }
}

void Animator::play(const AnimationClip* clip, float fadeSeconds, bool loop, float startTime) {
  if (fadeSeconds > 0.f && (current_.clip != nullptr || previous_.clip != nullptr)) {
    // Fading out of a fade: the outgoing track is whichever has the larger weight now.
    if (fadeDuration_ > 0.f && blendWeight() < 0.5f) current_ = previous_;
    previous_ = current_;
    fadeDuration_ = fadeSeconds;
  } else {
    previous_ = Track{};
    fadeDuration_ = 0.f;
  }
  fadeElapsed_ = 0.f;
  current_ = Track{clip, startTime, loop};
}

void Animator::advance(float dt) {
  if (!(dt > 0.f)) return;
  current_.time += dt;
  if (fadeDuration_ > 0.f) {
    previous_.time += dt;
    fadeElapsed_ += dt;
    if (fadeElapsed_ >= fadeDuration_) {
      fadeDuration_ = 0.f;
      fadeElapsed_ = 0.f;
      previous_ = Track{};
    }
  }
}

float Animator::blendWeight() const {
  if (!(fadeDuration_ > 0.f)) return 1.f;
  return std::clamp(fadeElapsed_ / fadeDuration_, 0.f, 1.f);
}

void Animator::sample(const Track& track, Pose& out) const {
  if (track.clip == nullptr) {
    restPose(*skeleton_, out);
    return;
  }
  sampleClip(*skeleton_, *track.clip, track.time, track.loop, out);
}

void Animator::evaluate(Pose& out) {
  if (skeleton_ == nullptr) {
    out.clear();
    return;
  }
  sample(current_, out);
  if (fadeDuration_ > 0.f) {
    sample(previous_, scratch_);
    blendPoses(scratch_, out, blendWeight(), out);
  }
}

void Animator::evaluateJointMatrices(std::vector<glm::mat4>& out) {
  evaluate(pose_);
  if (skeleton_ == nullptr) {
    out.clear();
    return;
  }
  poseToJointMatrices(*skeleton_, pose_, out);
}

}  // namespace cleave::anim
