// SPDX-License-Identifier: MIT
// Shatter jobs (a request's ShatterSpec): the target broken into the Voronoi cells of seeds around
// the impact instead of cut by one plane. What a shatter changes in the compute: the geometry
// (shatterInto, through geometry::fracture; a posed character is baked first, so its cells are
// baked pieces), the carried collider parts clipped by each piece's cell (clipPartsToCells), and
// the pieces' names and outward impulse (finishShatterPiece). Internal to the components library.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "cleave/components/split_compute.h"
#include "cleave/components/split_job.h"
#include "cleave/geometry/fracture.h"

namespace cleave::components {

// The container of `s` broken into the cells of the request's seeds (cut space); the pieces put into
// s.result as a split's would be (side +1, their cell's caps as the cap run), and each piece's cell.
geometry::SplitStatus shatterInto(const SplitJob& job, SplitComputeScratch& s, std::string& message,
                                  std::vector<geometry::ConvexCell>& cells, std::vector<uint32_t>& pieceCell);

// The carried parts (mesh space) clipped by each piece's cell (exact, no hull computed): clipped[i]
// for pieces[i]; a part of a cell with several pieces goes to the piece whose bounds hold its
// centroid (the nearest, the larger on a tie).
void clipPartsToCells(const geometry::ColliderPartSet& parts, const glm::dmat4& model,
                      const std::vector<geometry::SplitPiece>& pieces, std::span<const geometry::ConvexCell> cells,
                      std::span<const uint32_t> pieceCell, std::vector<geometry::ColliderPartSet>& clipped);

// A shatter piece: named by its order, moving with the parent plus the outward impulse.
void finishShatterPiece(const SplitJob& job, uint32_t k, PieceSpec& spec);

}  // namespace cleave::components
