// SPDX-License-Identifier: MIT
#include "cleave/components/split_log.h"

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cleave/log/log.h"

namespace cleave::components {

void SplitLog::record(uint64_t tick, const SplitEvent& event) {
  SplitLogEntry entry;
  entry.tick = tick;
  entry.original = event.originalName;
  entry.status = geometry::toString(event.status);
  entry.pieces = event.pieces.size();
  entry.parentMass = event.parentMass;
  entry.piecesMass = event.piecesMass;
  entry.posedVolume = event.posedVolume;
  entry.piecesVolume = event.piecesVolume;
  entry.milliseconds = event.times.total();
  entry.geometryMilliseconds = event.times.compute.geometry;
  entry.colliderMilliseconds = event.times.compute.collider;
  entry.uploadMilliseconds = event.times.uploads;
  entries_.push_back(std::move(entry));
}

void SplitLog::writeJson(nlohmann::json& out) const {
  out = nlohmann::json::array();
  for (const SplitLogEntry& s : entries_) {
    nlohmann::json row = {{"tick", s.tick},
                          {"original", s.original},
                          {"status", s.status},
                          {"pieces", s.pieces},
                          {"parent_mass", s.parentMass},
                          {"pieces_mass", s.piecesMass},
                          {"ms", s.milliseconds},
                          {"geometry_ms", s.geometryMilliseconds},
                          {"collider_ms", s.colliderMilliseconds},
                          {"upload_ms", s.uploadMilliseconds}};
    if (s.posedVolume > 0.0) {
      row["posed_volume"] = s.posedVolume;
      row["pieces_volume"] = s.piecesVolume;
    }
    out.push_back(std::move(row));
  }
}

// Writes the mesh of a failed split in cut space (an OBJ with the plane in its header) so the case
// can be reproduced with cleave-split or a unit test.
void writeFailureCase(const std::string& directory, const std::string& name, uint64_t tick,
                      ecs::Entity target, const geometry::MeshData& mesh, const glm::dmat4& model,
                      const geometry::Plane& plane, const char* status, const std::string& message) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  const std::string path = (std::filesystem::path(directory) /
                            ("split_failure_tick" + std::to_string(tick) + "_e" +
                             std::to_string(target.index) + ".obj")).string();
  std::ofstream out(path);
  if (!out) return;
  out.precision(17);
  out << "# split failure: " << (name.empty() ? "unnamed" : name) << ", tick " << tick << ", " << status
      << ": " << message << "\n";
  out << "# plane (cut space = world, after the model matrix): normal " << plane.normal.x << " " << plane.normal.y << " "
      << plane.normal.z << " offset " << plane.offset << "\n";
  // Vertices in mesh space exactly as stored (floats print exactly with 9 digits), and the model
  // matrix (column-major) that takes them to cut space, so the failing case replays bit for bit.
  out << "# model";
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out << " " << float(model[c][r]);
  out << "\n";
  out.precision(9);
  for (const glm::vec3& p : mesh.positions) out << "v " << p.x << " " << p.y << " " << p.z << "\n";
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
    out << "f " << mesh.indices[i] + 1 << " " << mesh.indices[i + 1] + 1 << " " << mesh.indices[i + 2] + 1 << "\n";
  log::warning("cleave", "failed split written to %s", path.c_str());
}

}  // namespace cleave::components
