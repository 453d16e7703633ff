// SPDX-License-Identifier: MIT
// Private (not installed): conversions between glm and Bullet value types. Bullet is built in
// single precision here (pkg-config `bullet`), so btScalar is float.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace cleave::physics::detail {

inline btVector3 toBt(glm::vec3 v) { return btVector3(v.x, v.y, v.z); }
inline glm::vec3 toGlm(const btVector3& v) { return glm::vec3(v.x(), v.y(), v.z()); }
// glm::quat is constructed as quat(w, x, y, z), btQuaternion as (x, y, z, w).
inline btQuaternion toBt(const glm::quat& q) { return btQuaternion(q.x, q.y, q.z, q.w); }
inline glm::quat toGlm(const btQuaternion& q) { return glm::quat(q.w(), q.x(), q.y(), q.z()); }

inline btTransform toBt(glm::vec3 position, const glm::quat& rotation) {
  return btTransform(toBt(rotation), toBt(position));
}

}  // namespace cleave::physics::detail
