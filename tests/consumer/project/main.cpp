// SPDX-License-Identifier: MIT
// Splits a box through the installed library and checks the two halves.
#include <cstdio>

#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"

int main() {
  using namespace cleave::geometry;
  MeshContainer container;
  if (container.setMesh(primitives::box(glm::vec3(0.5f))) != SplitStatus::Ok) return 1;
  auto splitter = makeConcaveSplitter();
  SplitResult result;
  const SplitStatus status = splitter->split(container, Plane{{1.0, 0.0, 0.0}, 0.0}, {}, result);
  if (status != SplitStatus::Ok || result.pieces.size() != 2) return 2;
  const double total = result.pieces[0].mass.volume + result.pieces[1].mass.volume;
  std::printf("consumer: %zu pieces, volume %.6f\n", result.pieces.size(), total);
  return (total > 0.999 && total < 1.001) ? 0 : 3;
}
