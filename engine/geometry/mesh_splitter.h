// The split core: cut a triangle mesh by a plane, cap the holes, separate islands, and compute the
// mass properties of every piece. Plain data in and out; no engine types; deterministic output.
//
// Spaces. A MeshContainer holds the source mesh in its own (object, or bind) space and a second set
// of positions, the "cut space" (world space for a static mesh: the model matrix applied; the current
// pose for a skinned mesh). Classification, loops, caps and mass properties are computed in cut
// space; every output piece is written back in the source space by interpolating the source
// attributes with the same edge parameter, so UVs, normals, tangents and skin data stay exact.
//
// Winding: input and output triangles are counter-clockwise seen from outside. A mirroring model
// matrix (negative determinant) is detected and the winding in cut space is flipped accordingly; so
// is a closed mesh wound inwards (negative signed volume), whose pieces keep its winding.
//
// Failure: split() returns a status; on anything but Ok the result holds no pieces and the caller
// keeps its original object. No exceptions.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/geometry/mass_properties.h"
#include "engine/geometry/mesh_data.h"

namespace cleave::geometry {

// The plane {x : dot(normal, x) = offset} in cut space. `normal` need not be unit length; the
// splitter normalises it. "Above" means dot(normal, x) > offset.
struct Plane {
  glm::dvec3 normal{0.0, 1.0, 0.0};
  double offset = 0.0;
};

enum class SplitStatus : uint8_t {
  Ok = 0,
  PlaneMissesMesh,      // every vertex on one side (or on the plane): nothing to cut
  InvalidInput,         // NaN/Inf position, index out of range, index count not a multiple of 3, ...
  OpenSection,          // the section has open chains (open or non-manifold input) and caps were asked for
  TriangulationFailed,  // a cap polygon could not be triangulated without overlap
};
const char* toString(SplitStatus status);

enum class CapUvMode : uint8_t {
  WorldPlanar,       // u,v = cut-space coordinates on the cap plane times texelsPerMetre: stable over re-cuts
  NormalizedBounds,  // u,v in [0,1] over the bounds of the cap (per border or per cap), as in the thesis
};

// What a capped split does with a section that is not made of closed loops only (art that is not
// watertight, or non-manifold where it is cut).
enum class OpenSectionMode : uint8_t {
  Refuse,          // the split fails with OpenSection; the caller keeps its object whole
  CapClosedLoops,  // cut everything, cap the closed loops, leave the open chains uncapped (reported
                   // in SplitResult::openChains); pieces along an open chain are open, and their mass
                   // properties come from their convex hull (MassProperties::fromConvexHull). When
                   // the pieces are open anyway, a loop that cannot be capped is left open too
                   // (SplitResult::uncappedLoops) instead of failing the split.
};

struct SplitOptions {
  bool cap = true;                      // false: hollow mode, no cap triangles, open sections allowed
  OpenSectionMode openSections = OpenSectionMode::CapClosedLoops;
  uint32_t capMaterialId = 1;           // material of the cap submesh (reused if the mesh already has it)
  CapUvMode uvMode = CapUvMode::WorldPlanar;
  double uvPerMetre = 1.0;              // WorldPlanar scale: UV units per metre of cut space
  glm::vec4 atlasRect{0.f, 0.f, 1.f, 1.f};  // x, y, width, height: cap UVs are mapped into this rectangle
  bool uvPerBorder = false;             // NormalizedBounds: normalise per outer border, not per whole cap
  bool separateIslands = true;          // false: each side stays one piece even if disconnected
  double relativeTolerance = 1e-6;      // on-plane tolerance, times the cut-space bounding-box diagonal
  bool computeMass = true;              // mass properties per piece (cut space)
};

// The weld of a mesh: position ids (vertices at one point share an id), closedness and winding,
// kept with the mesh so that cutting it again does not weld it again. MeshContainer::setMesh works
// it out from the positions (copyWeld gives it); a split gives each piece the weld of its own
// topology (SplitPiece::weld), so re-cutting pieces never re-welds.
struct MeshWeld {
  std::vector<uint32_t> positionIds;      // per vertex
  std::vector<uint32_t> representatives;  // per position id: its first vertex (ascending)
  bool closed = false;                    // see MeshContainer::closed
  bool inverted = false;                  // closed and wound inwards: see MeshContainer::inverted
};

struct SplitPiece {
  MeshData mesh;                // in the source space of the container
  // The position ids of `mesh` as the split made them (vertices at one cut point or one source
  // position share an id; merged near-coincident cut points too) and whether the piece is closed:
  // give it to MeshContainer::setMesh with the mesh to cut the piece again without a weld. Empty
  // (unknown) when a degenerate section loop was left uncapped; the piece is then welded anew.
  MeshWeld weld;
  int side = 0;                 // +1 above the plane, -1 below
  uint32_t capTriangles = 0;     // triangles in the cap-material run (earlier cuts' caps included)
  uint32_t capLoops = 0;        // boundary loops capped on this piece (outer borders and holes)
  MassProperties mass;          // in cut space
  // Skinned meshes: the joints this piece still uses (some vertex weight > 0), ascending. Joint ids
  // in the mesh stay those of the source skeleton, so the piece renders with the same joint
  // matrices; joints not listed are unused by this piece (a ragdoll builds bones for these only).
  // Empty for meshes without skin.
  std::vector<uint16_t> joints;
};

struct SplitResult {
  SplitStatus status = SplitStatus::Ok;
  std::string message;          // a reason a person can act on, empty when Ok
  std::vector<SplitPiece> pieces;  // above pieces first, then below; each side ordered deterministically
  uint32_t sectionLoops = 0;    // closed loops found in the section
  uint32_t openChains = 0;      // open chains of the section, left uncapped (CapClosedLoops)
  // Closed loops of open art that could not be capped (wound against the others, or overlapping
  // themselves) and were left open instead of failing the split (CapClosedLoops, open pieces only).
  uint32_t uncappedLoops = 0;
  bool sidesDisagree = false;   // the section differed between the two sides (non-manifold where cut)
};

// The thesis's MeshContainer: caches the source arrays, welds vertices by position into position ids
// (so UV and normal seams never break a cut loop), and keeps the cut-space positions.
class MeshContainer {
 public:
  MeshContainer() = default;
  MeshContainer(const MeshContainer&) = delete;  // source_ may point into the container itself
  MeshContainer& operator=(const MeshContainer&) = delete;

  // Takes a copy of the mesh (the arrays are reused between calls when sizes allow) and welds it.
  // Returns InvalidInput with a message for malformed data.
  SplitStatus setMesh(const MeshData& mesh, std::string* message = nullptr);
  // The same with a weld worked out before for this mesh (copyWeld of a container that held it, or
  // a SplitPiece's weld): no welding, no closedness or winding check; the mesh checks, the copy and
  // the cut-space positions remain. The weld is checked for size and consistency (InvalidInput
  // otherwise); that it matches the positions is the caller's promise.
  SplitStatus setMesh(const MeshData& mesh, const MeshWeld& weld, std::string* message = nullptr);
  // The same without a copy: the container shares the mesh (which must not change while it is held).
  // `weld` may be null (the mesh is welded) or a weld worked out before, as above.
  SplitStatus setMesh(std::shared_ptr<const MeshData> mesh, const MeshWeld* weld, std::string* message = nullptr);
  // Drops the mesh (a shared one is no longer held); the arrays keep their memory for the next one.
  void release() { clear(); }
  // The weld of the mesh held, to keep with it.
  void copyWeld(MeshWeld& out) const;

  // Cut space = model * source position. Non-uniform scale, shear and mirroring are allowed.
  void setTransform(const glm::mat4& model);
  // Cut space = linear blend skinning: sum_k w_k * jointMatrices[j_k] * p, where each joint matrix is
  // already (joint world transform * inverse bind matrix), times `model`. Needs joints and weights.
  // mirrored() is decided once for the pose when every model * joint matrix is a similarity with a
  // determinant of one sign, else by the majority of the vertices' blended matrices.
  SplitStatus setSkinningPose(std::span<const glm::mat4> jointMatrices, const glm::mat4& model,
                              std::string* message = nullptr);

  const MeshData& mesh() const { return *source_; }
  std::span<const glm::dvec3> cutPositions() const { return cutPositions_; }
  // Position id per vertex: vertices at the same position (within the weld tolerance) share an id.
  std::span<const uint32_t> positionIds() const { return positionIds_; }
  uint32_t positionIdCount() const { return positionIdCount_; }
  // True when the cut-space winding is clockwise seen from outside: a mirroring transform or pose,
  // or else a closed mesh wound inwards (exclusive or). The splitter then flips every triangle for
  // its work, so loops and caps follow the mesh's own winding, and flips back on output.
  bool mirrored() const { return mirrored_; }
  // True for a closed mesh whose source triangles are wound inwards (negative signed volume). It is
  // split as if mirrored: its pieces keep that winding (caps included) and report positive volumes.
  bool inverted() const { return inverted_; }
  double boundsDiagonal() const { return boundsDiagonal_; }
  // The model matrix given to setTransform or setSkinningPose (identity after setMesh).
  const glm::dmat4& model() const { return model_; }
  // The joint matrices of the last setSkinningPose; empty when the cut space is a plain transform.
  std::span<const glm::dmat4> jointMatrices() const { return jointMatrices_; }
  // The first vertex of each position id (ids are numbered in order of their first vertex).
  std::span<const uint32_t> positionRepresentatives() const { return representatives_; }
  // True when, on position ids, every edge is used by exactly two triangles in opposite directions
  // (triangles with a repeated id ignored): the pieces of a capped split are then closed too.
  bool closed() const { return closed_; }

  // Builds a new mesh from a subset of triangles (indices into the source triangle list), keeping
  // every attribute and the submesh runs; unused vertices are dropped through an index remap.
  void extractTriangles(std::span<const uint32_t> triangles, MeshData& out) const;

 private:
  void weld();
  bool validate(const MeshData& mesh, std::string* message);
  bool consistent(const MeshData& mesh, const MeshWeld& weld, std::string* message);
  SplitStatus take(const MeshWeld* weld, std::string* message);
  void clear();

  MeshData mesh_;                          // the copy, when the mesh was given by reference
  std::shared_ptr<const MeshData> shared_;  // the mesh, when shared
  const MeshData* source_ = &mesh_;         // the mesh held: mesh_ or *shared_
  std::vector<glm::dvec3> cutPositions_;
  std::vector<uint32_t> positionIds_;
  uint32_t positionIdCount_ = 0;
  bool mirrored_ = false;
  bool inverted_ = false;  // closed and wound inwards in source space
  double boundsDiagonal_ = 0.0;
  // Additions (private): see mesh_container.cpp.
  bool weldHashed(double tolerance, const glm::dvec3& lo, const glm::dvec3& hi);
  void weldSorted(double tolerance, const glm::dvec3& lo);
  void computeClosed();
  void updateBounds();
  // The weld and closedness scratch arrays are per thread (see mesh_container.cpp), not per
  // container: a container made for every cut then reuses warm memory.
  glm::dmat4 model_{1.0};
  std::vector<glm::dmat4> jointMatrices_;
  std::vector<glm::dmat4x3> poseAffine_;  // per joint: model x joint matrix (3 x 4); last: model
  std::vector<uint32_t> representatives_;
  bool closed_ = false;
  bool cutIsSource_ = false;  // the cut positions equal the source positions (identity transform)
};

// One interface, two implementations (the thesis's IMeshSplitter). A splitter owns reusable scratch
// memory: after a warm-up on meshes of a given size, splitting a same-size mesh into a reused
// SplitResult performs no heap allocation. Not thread-safe; use one splitter per thread.
class IMeshSplitter {
 public:
  virtual ~IMeshSplitter() = default;
  virtual SplitStatus split(const MeshContainer& container, const Plane& plane,
                            const SplitOptions& options, SplitResult& result) = 0;
};

// General path: loops -> polygons with holes (any nesting) -> triangulation.
std::unique_ptr<IMeshSplitter> makeConcaveSplitter();
// Fast path for convex meshes: fan cap after an angular sort. Verifies that the section is one
// convex loop and falls back to the concave path when it is not.
std::unique_ptr<IMeshSplitter> makeConvexSplitter();

}  // namespace cleave::geometry
