// SPDX-License-Identifier: MIT
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
//
// The types are in split_types.h, the container in mesh_container.h; this header has the
// splitters and the one-call splitMesh.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/mesh_container.h"
#include "cleave/geometry/mesh_data.h"
#include "cleave/geometry/split_types.h"

namespace cleave::geometry {

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

// One call, for users who want no container or splitter of their own: `mesh` mapped into cut space
// by `model` (the pieces stay in the mesh's space, their mass properties in cut space), split by
// `plane` (cut space) with the concave splitter. The result's status says how it went; pieces only
// when Ok. Thread-safe (each call has its own container and splitter), so it allocates every call.
SplitResult splitMesh(const MeshData& mesh, const glm::mat4& model, const Plane& plane,
                      const SplitOptions& options = {});

}  // namespace cleave::geometry
