// SPDX-License-Identifier: MIT
// MeshContainer: a mesh ready to be cut (the thesis's MeshContainer). It shares or copies the
// source arrays, welds vertices by position into position ids (so UV and normal seams never break a
// cut loop), and keeps the cut-space positions (model matrix or skinning pose). Failure: setMesh and
// setSkinningPose return a MeshStatus of InvalidInput with a reason for malformed data; nothing
// throws.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/base/status.h"
#include "cleave/geometry/cut_positions.h"
#include "cleave/geometry/mesh_data.h"
#include "cleave/geometry/split_types.h"

namespace cleave::geometry {

// Ok, or InvalidInput with the reason ("invalid mesh: ...", "invalid weld: ...", "skinning pose: ...").
using MeshStatus = base::BasicStatus<SplitStatus>;

class MeshContainer {
 public:
  MeshContainer() = default;
  MeshContainer(const MeshContainer&) = delete;  // source_ may point into the container itself
  MeshContainer& operator=(const MeshContainer&) = delete;

  // Takes a copy of the mesh (the arrays are reused between calls when sizes allow) and welds it.
  // Returns InvalidInput with a message for malformed data.
  MeshStatus setMesh(const MeshData& mesh);
  // The same with a weld worked out before for this mesh (copyWeld of a container that held it, or
  // a SplitPiece's weld): no welding, no closedness or winding check; the mesh checks, the copy and
  // the cut-space positions remain. The weld is checked for size and consistency (InvalidInput
  // otherwise); that it matches the positions is the caller's promise.
  MeshStatus setMesh(const MeshData& mesh, const MeshWeld& weld);
  // The same without a copy: the container shares the mesh (which must not change while it is held).
  // `weld` may be null (the mesh is welded) or a weld worked out before, as above.
  MeshStatus setMesh(std::shared_ptr<const MeshData> mesh, const MeshWeld* weld);
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
  MeshStatus setSkinningPose(std::span<const glm::mat4> jointMatrices, const glm::mat4& model);

  const MeshData& mesh() const { return *source_; }
  // The cut-space positions (cut_positions.h): the source floats while the cut space is the source
  // space (after setMesh, or setTransform with the identity), else the transformed or posed ones.
  CutPositions cutPositions() const {
    return cutIsSource_ ? CutPositions(std::span<const glm::vec3>(source_->positions)) : CutPositions(cutPositions_);
  }
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
  // Axis-aligned bounds of the cut-space positions (infinite, lo > hi, without a mesh).
  const glm::dvec3& boundsMin() const { return boundsMin_; }
  const glm::dvec3& boundsMax() const { return boundsMax_; }
  // The model matrix given to setTransform or setSkinningPose (identity after setMesh).
  const glm::dmat4& model() const { return model_; }
  // The joint matrices of the last setSkinningPose; empty when the cut space is a plain transform.
  std::span<const glm::dmat4> jointMatrices() const { return jointMatrices_; }
  // The first vertex of each position id (ids are numbered in order of their first vertex).
  std::span<const uint32_t> positionRepresentatives() const { return representatives_; }
  // True when, on position ids, every edge is used by exactly two triangles in opposite directions
  // (triangles with a repeated id ignored): the pieces of a capped split are then closed too.
  bool closed() const { return closed_; }
  // True when the mesh is known to be one part: every triangle reaches every other through triangles
  // that share a position id. Worked out by setMesh for a closed mesh (false for an open one: not
  // known), taken from a given weld (MeshWeld::connected, the caller's promise like `closed`). The
  // splitter then needs no island search where the topology settles it (see mesh_splitter.cpp).
  bool connected() const { return connected_; }

  // Builds a new mesh from a subset of triangles (indices into the source triangle list), keeping
  // every attribute and the submesh runs; unused vertices are dropped through an index remap.
  void extractTriangles(std::span<const uint32_t> triangles, MeshData& out) const;

 private:
  void weld();
  MeshStatus validate(const MeshData& mesh);
  MeshStatus adoptWeld(const MeshData& mesh, const MeshWeld& weld);
  MeshStatus take(const MeshWeld* weld);
  void clear();

  MeshData mesh_;                          // the copy, when the mesh was given by reference
  std::shared_ptr<const MeshData> shared_;  // the mesh, when shared
  const MeshData* source_ = &mesh_;         // the mesh held: mesh_ or *shared_
  std::vector<glm::dvec3> cutPositions_;  // empty while the cut space is the source space
  std::vector<uint32_t> positionIds_;
  uint32_t positionIdCount_ = 0;
  bool mirrored_ = false;
  bool inverted_ = false;  // closed and wound inwards in source space
  double boundsDiagonal_ = 0.0;
  glm::dvec3 boundsMin_{INFINITY}, boundsMax_{-INFINITY};
  // Additions (private): see mesh_container.cpp.
  bool weldHashed(double tolerance, const glm::dvec3& lo, const glm::dvec3& hi);
  void weldSorted(double tolerance, const glm::dvec3& lo);
  void computeClosed();
  size_t fileRows(bool& degenerate, bool& inwards);
  bool pairedRows(uint32_t* parts);
  void computeConnected();
  void updateBounds();
  void sourceBounds();  // updateBounds while the cut space is the source space, from the floats
  void setSourceBounds(const glm::vec3& lo, const glm::vec3& hi);  // bounds of the source floats
  // The weld and closedness scratch arrays are per thread (see mesh_container.cpp), not per
  // container: a container made for every cut then reuses warm memory.
  glm::dmat4 model_{1.0};
  std::vector<glm::dmat4> jointMatrices_;
  std::vector<glm::dmat4x3> poseAffine_;  // per joint: model x joint matrix (3 x 4); last: model
  std::vector<uint32_t> representatives_;
  bool closed_ = false;
  bool connected_ = false;
  bool cutIsSource_ = false;  // the cut positions equal the source positions (identity transform)
};

}  // namespace cleave::geometry
