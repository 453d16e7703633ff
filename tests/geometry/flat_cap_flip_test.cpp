// SPDX-License-Identifier: MIT
// A cap triangle that is thin in double and flat once written as float: the splitter flips it with
// its neighbour (flipFlatCapTriangles in mesh_splitter.cpp), so the pieces stay closed on their
// float positions. Generated cases that need the flip: a cylinder of 1,000 segments turned and moved
// (its float positions baked), cut by a plane x = c across its end fans. The section crosses each
// end along a straight chord through hundreds of fan edges; rounding in double keeps three of those
// collinear points apart, the triangulator makes a sliver of them, and float rounding puts them back
// on one line. About one such cut in 500 has one; these three were found by a search over seeded
// rigid motions and planes, and each fails the float check without the flip.
#include <gtest/gtest.h>

#include <string>

#include "cleave/geometry/mesh_container.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"
#include "tests/geometry/test_meshes.h"

namespace cleave::geometry {
namespace {

struct FlipCase {
  glm::mat4 motion;  // columns, as glm stores them
  double planeX;     // the plane x = planeX, after the motion
};

const FlipCase kCases[] = {
    {glm::mat4(glm::vec4(-0x1.a96826p-2f, 0x1.4f5a1ep-1f, 0x1.432c18p-1f, 0.f),
               glm::vec4(0x1.b6cdcep-1f, 0x1.0759e8p-1f, 0x1.f10cp-6f, 0.f),
               glm::vec4(-0x1.381aep-2f, 0x1.1b6c8ep-1f, -0x1.8cd0bcp-1f, 0.f),
               glm::vec4(-0x1.17ab18p+0f, 0x1.d4b26p-1f, 0x1.2242fap+1f, 1.f)),
     -0x1.36242bd4bcb89p+0},
    {glm::mat4(glm::vec4(0x1.09f114p-2f, -0x1.15afd4p-1f, 0x1.991674p-1f, 0.f),
               glm::vec4(0x1.e7b8ecp-1f, 0x1.1e6fa6p-2f, -0x1.ea8478p-4f, 0.f),
               glm::vec4(-0x1.44b4fp-3f, 0x1.959d24p-1f, 0x1.2db6f4p-1f, 0.f),
               glm::vec4(0x1.1bb77cp+1f, -0x1.7650dcp+1f, -0x1.54a50cp+1f, 1.f)),
     0x1.2c24ada3ad9dfp+1},
    {glm::mat4(glm::vec4(0x1.dc0426p-2f, -0x1.23676ep-2f, 0x1.ad436ep-1f, 0.f),
               glm::vec4(0x1.0bc16p-1f, 0x1.b46828p-1f, -0x1.541cp-11f, 0.f),
               glm::vec4(-0x1.6dca8ep-1f, 0x1.c148ap-2f, 0x1.17106ep-1f, 0.f),
               glm::vec4(-0x1.32d0bep+1f, -0x1.e0fa02p-4f, -0x1.5193ccp+1f, 1.f)),
     -0x1.2a549fcbd12acp+1},
};

TEST(FlatCapFlip, ChordsAcrossFineEndFansGivePiecesClosedOnTheirFloats) {
  auto splitter = makeConcaveSplitter();
  for (size_t k = 0; k < std::size(kCases); ++k) {
    SCOPED_TRACE("case " + std::to_string(k));
    MeshData mesh = primitives::cylinder(0.5f, 0.3f, 1000);
    primitives::transform(mesh, kCases[k].motion);
    // The input is closed on its own float positions, so its pieces must be too.
    ASSERT_TRUE(testing::manifoldOnFloats(mesh));
    MeshContainer container;
    ASSERT_EQ(container.setMesh(mesh).code, SplitStatus::Ok);
    SplitResult result;
    ASSERT_EQ(splitter->split(container, Plane{glm::dvec3(1.0, 0.0, 0.0), kCases[k].planeX}, SplitOptions{}, result),
              SplitStatus::Ok)
        << result.message;
    ASSERT_EQ(result.pieces.size(), 2u);
    EXPECT_EQ(result.sectionLoops, 1u);
    for (const SplitPiece& piece : result.pieces) {
      EXPECT_TRUE(testing::manifoldOnFloats(piece.mesh)) << "side " << piece.side;
      EXPECT_TRUE(piece.mass.closed);
    }
  }
}

}  // namespace
}  // namespace cleave::geometry
