// SPDX-License-Identifier: MIT
// The compute stage of a split: a pure function of a SplitJob (split_job.h). It runs on any thread:
// it touches no world, no physics and no renderer, only the job's shared immutable data and the
// scratch it is given. The same job gives the same outcome, byte for byte, on every thread.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/components/split_job.h"
#include "cleave/geometry/collider_parts.h"
#include "cleave/geometry/mesh_splitter.h"

namespace cleave::components {

// Reusable memory of one compute thread (each worker has its own).
struct SplitComputeScratch {
  geometry::MeshContainer container;
  std::unique_ptr<geometry::IMeshSplitter> concave = geometry::makeConcaveSplitter();
  std::unique_ptr<geometry::IMeshSplitter> convex = geometry::makeConvexSplitter();
  geometry::SplitResult result;
};

// Splits the job's mesh and plans every piece (SplitOutcome). On failure the outcome holds the
// status and a reason, and no piece; the original is then kept whole at commit.
void computeSplit(const SplitJob& job, SplitComputeScratch& scratch, SplitOutcome& out);

// A collider for a mesh, planned without physics: hulls in the body frame (mesh space mapped by
// `meshOffset`), each shrunk by its margin, min(physics::kMaxConvexMargin,
// physics::kRelativeConvexMargin x its width), so the physics bridge only wraps them.
//   ConvexHull (or `knownConvex`): one hull of the mesh's points.
//   Auto, Compound: the `carried` parts (mesh space); when null, the mesh is decomposed; when
//                   empty (a piece no carried part reached), the hull of its points.
//   ConcaveMesh: the triangles in the body frame, and one hull as a fallback.
// `parts` gets the parts used (mesh space), for the mesh's own later cuts. No hull: no collider.
struct ColliderPlan {
  std::vector<HullSpec> hulls;
  std::vector<glm::vec3> concavePositions;
  std::vector<uint32_t> concaveIndices;
  double colliderVolume = 0.0;  // of the unshrunk parts, body frame units
  geometry::SharedColliderParts parts;
};
ColliderPlan planCollider(const geometry::MeshData& mesh, const glm::dmat4& meshOffset, ColliderMode mode,
                          bool knownConvex, geometry::SharedColliderParts carried,
                          geometry::IMeshSplitter& splitter);

// Parts (mesh space) as body-frame hulls: mapped by `meshOffset`, shrunk by their margin; flat parts
// (width under 10 micrometres) are left out. `volume` gets the mapped parts' volume.
std::vector<HullSpec> hullsInBodyFrame(const geometry::ColliderPartSet& parts, const glm::dmat4& meshOffset,
                                       double* volume = nullptr);

// The world plane {x : dot(n, x) = d} in the mesh space of `model` (mesh -> world).
geometry::Plane planeInMeshSpace(const geometry::Plane& world, const glm::dmat4& model);

}  // namespace cleave::components
