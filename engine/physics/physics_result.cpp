// SPDX-License-Identifier: MIT
#include "cleave/physics/physics_result.h"
#include "cleave/physics/joint_def.h"

#include "cleave/physics/physics_events.h"

namespace cleave::physics {

const char* toString(PhysicsStatus status) {
  switch (status) {
    case PhysicsStatus::Ok: return "ok";
    case PhysicsStatus::InvalidArgument: return "invalid argument";
    case PhysicsStatus::StaleHandle: return "stale handle";
    case PhysicsStatus::DegenerateShape: return "degenerate shape";
    case PhysicsStatus::UnsupportedCombination: return "unsupported combination";
  }
  return "unknown status";
}

const char* toString(TriggerEventKind kind) {
  switch (kind) {
    case TriggerEventKind::Begin: return "begin";
    case TriggerEventKind::Stay: return "stay";
    case TriggerEventKind::End: return "end";
  }
  return "unknown trigger event";
}

const char* toString(JointType type) {
  switch (type) {
    case JointType::ConeTwist: return "cone-twist";
    case JointType::Hinge: return "hinge";
  }
  return "unknown joint type";
}

}  // namespace cleave::physics
