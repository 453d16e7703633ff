// SPDX-License-Identifier: MIT
// Splitable and Splitter: the thesis's two components as plain data.
//
// Put a Splitable on an object (with a MeshRenderer and a RigidBody) and touch it with a Splitter:
// the Triggers phase turns the touch into a SplitRequest, and from the next tick the split system
// cuts it within the split budget and replaces it by physics pieces that move on as it did.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/components/piece_budget.h"
#include "cleave/components/shatter.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/physics/physics_ids.h"
#include "cleave/render/renderer.h"

namespace cleave::components {

enum class MassMode : uint8_t {
  Density,          // piece mass = density x piece volume
  KeepParentMass,   // the parent's mass shared out by volume: pieces always sum to the parent
};

enum class SmallPieceMode : uint8_t {
  Remove,  // pieces under minPieceVolume disappear
  Debris,  // they stay as render-only debris with no collider, fall and fade
};

enum class ColliderMode : uint8_t {
  // The convex collider parts carried with the mesh (ColliderParts): decomposed once per authored
  // mesh, clipped by every cut's plane into the pieces; a convex mesh is one part.
  Auto,
  ConvexHull,  // always the convex hull of the piece (cheapest, fills concavities)
  Compound,    // the carried parts too (the name scenes used for the decomposition)
  ConcaveMesh, // GImpact triangle mesh (exact, slowest)
};

// What the pieces of a skinned (animated) mesh become. Every mode cuts in the current pose and
// shares the parent's mass by posed volume.
enum class SkinnedPieceMode : uint8_t {
  // Each piece stays a skinned mesh with a copy of the animator (same clip, time and crossfade), so
  // it keeps playing in sync with an uncut character. Its body is a dynamic rigid body whose
  // collider and mass properties are those of the pose at the cut; it moves on with the velocity the
  // character had at that point (no ragdoll), and the animation plays in the body's frame.
  KeepAnimating,
  // Capsules per bone the piece keeps, joined by cone-twist and hinge joints, started from the
  // pose and the character's velocity; the piece's skin follows the bodies.
  Ragdoll,
  // The piece is baked into the pose (CPU skinning) and becomes an ordinary static-mesh piece.
  Bake,
};

// What a piece becomes at commit. Each kind is a strategy (piece_kind.h) with its plan (compute)
// and its commit; a game or a test adds kinds of its own with registerPieceKind, numbered after these.
enum class PieceKind : uint8_t {
  Rigid,          // a dynamic rigid body with the spec's collider (piece_rigid.cpp)
  Debris,         // render-only, falls and fades (small pieces, or no collider could hold it; piece_debris.cpp)
  KeepAnimating,  // a skinned piece on a rigid body, its animator copied from the parent (piece_skinned.cpp)
  Ragdoll,        // a skinned piece on capsule bones joined by joints (piece_ragdoll.cpp)
  Baked,          // a skinned piece baked into its pose: a static-mesh rigid piece (piece_skinned.cpp)
};
const char* toString(PieceKind kind);

struct Splitable {
  bool convexHint = false;                  // the mesh is convex: use the convex splitter (fan caps)
  bool cap = true;                          // false: hollow pieces (open or thin objects)
  uint32_t capMaterialId = 1;               // submesh material id of cap triangles
  render::Material capMaterial;             // drawn on caps (placed at capMaterialId)
  geometry::CapUvMode capUvMode = geometry::CapUvMode::WorldPlanar;
  double capUvPerMetre = 1.0;
  glm::vec4 capAtlasRect{0.f, 0.f, 1.f, 1.f};
  bool capUvPerBorder = false;
  MassMode massMode = MassMode::Density;
  double density = 500.0;                   // kg/m^3 (Density mode and authored objects)
  double splitImpulse = 0.0;                // m/s added along the plane normal, away from the cut
  double minPieceVolume = 1e-6;             // m^3
  SmallPieceMode smallPieces = SmallPieceMode::Debris;
  bool separateIslands = true;
  // With separate islands: parts that touch or pass into one another stay one piece (Touching, for
  // multi-part art), or every separate part of the mesh is its own piece (Connected).
  geometry::IslandMode islands = geometry::IslandMode::Touching;
  // Art that is not watertight where it is cut: cut anyway, capping the closed loops (default), or
  // keep the object whole.
  geometry::OpenSectionMode openSections = geometry::OpenSectionMode::CapClosedLoops;
  ColliderMode collider = ColliderMode::Auto;
  uint32_t maxDepth = 12;                   // pieces this many cuts deep are no longer splitable
  std::string handler;                      // a custom split handler registered under this name
  SkinnedPieceMode skinnedPieces = SkinnedPieceMode::Ragdoll;  // skinned meshes only
  // What the pieces of a static mesh become when big enough for a body: Rigid, or a kind a game
  // registered (piece_kind.h). Small pieces are debris whatever this says.
  PieceKind rigidPieces = PieceKind::Rigid;
  // How the piece budget retires this object's pieces when a limit is passed (piece_budget.h);
  // Default: the budget's policy.
  PieceRetirement retirement = PieceRetirement::Default;
};

enum class SplitterLifetime : uint8_t {
  Persistent,  // cuts everything it touches, each object once (the thesis's energy disc)
  OneTick,     // cuts what it touches during one physics step, then is gone (the sword swing)
};

enum class SplitterKind : uint8_t {
  Plane,    // cuts by its plane (the default)
  Shatter,  // breaks what it touches into cells (`shatter`; the impact point is the splitter's position)
};

// The cutting plane is the splitter's local up axis (+Y) through its position, in world space. A
// splitter with a trigger only cuts bodies its trigger volume touches.
struct Splitter {
  SplitterKind kind = SplitterKind::Plane;
  ShatterSpec shatter;          // Shatter: the impact point is the splitter's position unless impactGiven
  SplitterLifetime lifetime = SplitterLifetime::OneTick;
  bool playerCaused = false;
  physics::TriggerId trigger;   // the finite trigger shape (a thin box along the plane)
  glm::vec3 halfExtents{1.f, 0.02f, 1.f};  // of the trigger box, in the splitter frame
  uint32_t cuts = 0;            // how many split requests it has issued
  // Persistent splitters: state-dump ids of the objects cut in the current pass and of the pieces
  // those cuts made, while they still touch the trigger. They are not cut again until they have
  // stopped touching it (a new pass); the split system keeps the list.
  std::vector<uint64_t> passing;
};

}  // namespace cleave::components
