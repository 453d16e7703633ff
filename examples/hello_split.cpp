// SPDX-License-Identifier: MIT
// Hello, split: the split core alone (Cleave::geometry, which needs only GLM). A one-metre box is
// cut by the plane y = 0.25; the pieces come back capped, closed, with exact mass properties.
#include <cstdio>

#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"

int main() {
  using namespace cleave::geometry;
  const MeshData box = primitives::box(glm::vec3(0.5f));   // half extents: a 1 m cube at the origin
  const Plane plane{glm::dvec3(0.0, 1.0, 0.0), 0.25};      // normal . x = offset
  const SplitResult result = splitMesh(box, glm::mat4(1.f), plane, SplitOptions{});
  if (result.status != SplitStatus::Ok) {
    std::fprintf(stderr, "hello_split: %s\n", result.message.c_str());
    return 1;
  }
  for (const SplitPiece& piece : result.pieces) {
    std::printf("%s: %zu triangles (%u of the cap), volume %.4f m^3, centre of mass y %.4f m\n",
                piece.side > 0 ? "above" : "below", piece.mesh.indices.size() / 3, piece.capTriangles,
                piece.mass.volume, piece.mass.centerOfMass.y);
  }
  return 0;
}
