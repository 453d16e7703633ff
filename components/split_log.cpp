// SPDX-License-Identifier: MIT
#include "cleave/components/split_log.h"

#include <nlohmann/json.hpp>

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
  entry.milliseconds = event.milliseconds;
  entry.geometryMilliseconds = event.geometryMilliseconds;
  entry.colliderMilliseconds = event.colliderMilliseconds;
  entry.uploadMilliseconds = event.uploadMilliseconds;
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

}  // namespace cleave::components
