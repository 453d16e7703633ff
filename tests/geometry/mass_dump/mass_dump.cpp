// SPDX-License-Identifier: MIT
// Prints the mass properties of a set of generated meshes with every double in hex (%a), so that
// two builds of the mass integration (the vector kernels and the scalar loop, CLEAVE_MASS_SCALAR)
// can be compared byte for byte: the claim that they agree bit for bit is tested, not assumed.
// `mass_dump KERNEL` (sse2, avx2, avx512) uses that vector kernel; it exits with 77 when this CPU
// cannot run it and with 2 on an unknown name.
#include <cstdio>
#include <cstring>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/mass_kernel.h"
#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/primitives.h"

namespace prim = cleave::geometry::primitives;
using cleave::geometry::MassProperties;
using cleave::geometry::MeshData;

int main(int argc, char** argv) {
  using cleave::geometry::detail::MassKernel;
  if (argc > 1) {
    const bool known = std::strcmp(argv[1], "avx512") == 0 || std::strcmp(argv[1], "avx2") == 0 ||
                       std::strcmp(argv[1], "sse2") == 0;
    if (!known) {
      std::fprintf(stderr, "mass_dump: unknown kernel '%s' (sse2, avx2, avx512)\n", argv[1]);
      return 2;
    }
    const MassKernel kernel = std::strcmp(argv[1], "avx512") == 0 ? MassKernel::Avx512
                              : std::strcmp(argv[1], "avx2") == 0 ? MassKernel::Avx2
                                                                  : MassKernel::Sse2;
    if (!cleave::geometry::detail::massKernelRuns(kernel)) return 77;
    cleave::geometry::detail::useMassKernel(kernel);
  }
  std::vector<MeshData> meshes = {prim::uvSphere(0.7f, 48, 25), prim::torus(1.f, 0.3f, 40, 16),
                                  prim::box(glm::vec3(0.5f, 0.2f, 0.3f)), prim::combPrism(8),
                                  prim::tetrahedron(1.f), prim::hollowSphere(1.f, 0.6f, 24, 12)};
  const glm::dmat4 transforms[] = {glm::dmat4(1.0),
                                   glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, -2.0, 5.0)) *
                                       glm::rotate(glm::dmat4(1.0), 0.7, glm::dvec3(0.2, 1.0, 0.3)),
                                   glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, -1.5, 2.0))};  // mirrored
  for (size_t k = 0; k < meshes.size(); ++k) {
    for (const glm::dmat4& m : transforms) {
      const MassProperties p = cleave::geometry::computeMassProperties(meshes[k], m);
      std::printf("mesh %zu closed %d volume %a centre %a %a %a inertia", k, int(p.closed), p.volume, p.centerOfMass.x,
                  p.centerOfMass.y, p.centerOfMass.z);
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) std::printf(" %a", p.inertia[c][r]);
      std::printf("\n");
    }
  }
  return 0;
}
