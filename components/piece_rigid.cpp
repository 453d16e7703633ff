// SPDX-License-Identifier: MIT
// Rigid pieces: a dynamic body with the collider planned in compute (the parts of the mesh clipped
// by the cut, or decomposed), which stay with the piece for its own cuts.
#include "cleave/components/piece_kind.h"

namespace cleave::components {

namespace {

class RigidPieces final : public PieceKindStrategy {
 public:
  const char* name() const override { return "rigid"; }
};

}  // namespace

const PieceKindStrategy& rigidPieces() {
  static const RigidPieces kind;
  return kind;
}

}  // namespace cleave::components
