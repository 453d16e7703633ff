// SPDX-License-Identifier: MIT
// Skinned pieces on one rigid body: kept animating (drawn with their skin in bind space, the parent's
// animator copied and playing in the body's frame; the collider from the piece in its pose), or
// baked into their pose (a static mesh from then on, its collider parts kept for its own cuts).
#include "cleave/components/piece_kind.h"

namespace cleave::components {

namespace {

class KeepAnimatingPieces final : public PieceKindStrategy {
 public:
  const char* name() const override { return "keep-animating"; }
  bool keepsSkin() const override { return true; }
  bool colliderFromPose() const override { return true; }
  bool keepsParts(bool) const override { return false; }  // the parts are posed, the mesh is not
};

class BakedPieces final : public PieceKindStrategy {
 public:
  const char* name() const override { return "baked"; }
  bool keepsParts(bool) const override { return true; }
};

}  // namespace

const PieceKindStrategy& keepAnimatingPieces() {
  static const KeepAnimatingPieces kind;
  return kind;
}

const PieceKindStrategy& bakedPieces() {
  static const BakedPieces kind;
  return kind;
}

}  // namespace cleave::components
