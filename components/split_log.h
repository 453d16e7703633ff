// SPDX-License-Identifier: MIT
// SplitLog: every split of a run, for state dumps and replay tests (mass before and after each cut,
// piece count, status, time spent). Games record the split system's events each tick and write the
// log into their state dump; tests check mass conservation per cut from it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "cleave/components/split_system.h"

namespace cleave::components {

struct SplitLogEntry {
  uint64_t tick = 0;
  std::string original;  // the Name of the object that was cut
  std::string status;    // geometry::toString(SplitStatus)
  size_t pieces = 0;
  double parentMass = 0.0;
  double piecesMass = 0.0;
  double posedVolume = 0.0;   // SplitEvent::posedVolume
  double piecesVolume = 0.0;
  double milliseconds = 0.0;          // the whole split
  double geometryMilliseconds = 0.0;  // of which: the cut, caps, islands, mass properties
  double colliderMilliseconds = 0.0;  // of which: colliders
  double uploadMilliseconds = 0.0;    // of which: GPU uploads
};

class SplitLog {
 public:
  void record(uint64_t tick, const SplitEvent& event);
  void record(uint64_t tick, const std::vector<SplitEvent>& events) {
    for (const SplitEvent& event : events) record(tick, event);
  }
  const std::vector<SplitLogEntry>& entries() const { return entries_; }
  // The log as a JSON array of objects: tick, original, status, pieces, parent_mass, pieces_mass,
  // ms, geometry_ms, collider_ms, upload_ms.
  void writeJson(nlohmann::json& out) const;

 private:
  std::vector<SplitLogEntry> entries_;
};

// Writes the mesh of a failed split (an OBJ in mesh space with the model matrix and the plane in its
// header, so the case replays bit for bit with cleave-split or a unit test) into `directory` as
// split_failure_tick<T>_e<index>.obj, and logs where.
void writeFailureCase(const std::string& directory, const std::string& name, uint64_t tick, ecs::Entity target,
                      const geometry::MeshData& mesh, const glm::dmat4& model, const geometry::Plane& plane,
                      const char* status, const std::string& message);

}  // namespace cleave::components
