// SPDX-License-Identifier: MIT
// Closed meshes wound inwards (negative signed volume): the container treats them as mirrored, so
// the splitter caps them like any other mesh; the pieces keep the input's winding, caps included,
// and report positive volumes. Real files come this way (CGAL's beam.off, tetrahedron.off and
// ellipe0.003.off); before, every section loop of such a mesh looked like a hole and the split was
// refused with TriangulationFailed.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"
#include "tests/geometry/test_meshes.h"

namespace cleave::geometry {
namespace {

MeshData reversed(MeshData mesh) {
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
  }
  return mesh;
}

// CGAL's data/meshes/tetrahedron.off as it is (faces 0 1 2, 0 3 1, 0 2 3, 1 3 2): the face 0 1 2 is
// counter-clockwise seen from -z, which is inside.
MeshData cgalTetrahedron() { return reversed(testing::cornerTetrahedron()); }

void expectSplitKeepsWinding(const MeshData& mesh, const glm::mat4& model, const Plane& plane) {
  MeshContainer container;
  ASSERT_EQ(container.setMesh(mesh).code, SplitStatus::Ok);
  container.setTransform(model);
  const std::vector<glm::dvec3> cut(container.cutPositions().begin(),
                                    container.cutPositions().end());
  const double inputVolume = testing::signedVolume(cut, mesh.indices);
  ASSERT_LT(inputVolume, 0.0) << "the case must be wound inwards in cut space";
  SplitOptions options;
  options.capMaterialId = 7;
  const std::unique_ptr<IMeshSplitter> splitters[2] = {makeConcaveSplitter(), makeConvexSplitter()};
  for (const std::unique_ptr<IMeshSplitter>& splitter : splitters) {
    SplitResult result;
    ASSERT_EQ(splitter->split(container, plane, options, result), SplitStatus::Ok)
        << result.message;
    ASSERT_EQ(result.pieces.size(), 2u);
    double volume = 0.0;
    for (const SplitPiece& piece : result.pieces) {
      const std::vector<glm::dvec3> p = testing::toCutSpace(piece.mesh, glm::dmat4(model));
      EXPECT_TRUE(testing::closedAndOriented(p, piece.mesh.indices, 1e-9));
      // The input's winding: the piece's own signed volume is negative, the reported one positive.
      EXPECT_LT(testing::signedVolume(p, piece.mesh.indices), 0.0);
      EXPECT_GT(piece.mass.volume, 0.0);
      // The pieces are written as float, the mass is integrated on the double cut positions.
      EXPECT_NEAR(piece.mass.volume, -testing::signedVolume(p, piece.mesh.indices),
                  1e-6 * piece.mass.volume);
      EXPECT_EQ(piece.capLoops, 1u);
      const double section = -testing::sectionArea(cut, mesh.indices, plane);
      EXPECT_NEAR(testing::capArea(piece.mesh, options.capMaterialId, glm::dmat4(model)), section,
                  1e-6 * section);
      volume += piece.mass.volume;
      // The piece's weld says it is closed and wound inwards, and it cuts again with it: the
      // pieces of the piece keep the winding and positive volumes.
      EXPECT_TRUE(piece.weld.closed);
      EXPECT_TRUE(piece.weld.inverted);
      MeshContainer again;
      ASSERT_EQ(again.setMesh(piece.mesh, piece.weld).code, SplitStatus::Ok);
      EXPECT_TRUE(again.inverted());
      again.setTransform(model);
      glm::dvec3 lo, hi;
      testing::bounds(again.cutPositions(), lo, hi);
      const glm::dvec3 middle = 0.5 * (lo + hi);
      const Plane across{{0.2, 1.0, 0.3}, glm::dot(glm::dvec3(0.2, 1.0, 0.3), middle)};
      SplitResult twice;
      ASSERT_EQ(splitter->split(again, across, options, twice), SplitStatus::Ok) << twice.message;
      double twiceVolume = 0.0;
      for (const SplitPiece& small : twice.pieces) {
        EXPECT_GT(small.mass.volume, 0.0);
        EXPECT_TRUE(small.weld.inverted);
        twiceVolume += small.mass.volume;
      }
      // The piece was written as float (its mass integrated on double positions): float rounding.
      EXPECT_NEAR(twiceVolume, piece.mass.volume, 1e-6 * piece.mass.volume);
    }
    EXPECT_NEAR(volume, -inputVolume, 1e-12 * std::abs(inputVolume));
  }
}

TEST(InvertedWinding, ContainerTreatsAnInwardClosedMeshAsMirrored) {
  MeshContainer c;
  ASSERT_EQ(c.setMesh(cgalTetrahedron()).code, SplitStatus::Ok);
  EXPECT_TRUE(c.closed());
  EXPECT_TRUE(c.inverted());
  EXPECT_TRUE(c.mirrored());
  // A mirroring transform turns it outward again in cut space.
  c.setTransform(glm::scale(glm::mat4(1.f), glm::vec3(-1.f, 1.f, 1.f)));
  EXPECT_TRUE(c.inverted());
  EXPECT_FALSE(c.mirrored());
  c.setTransform(glm::mat4(1.f));
  EXPECT_TRUE(c.mirrored());
  // Outward and open meshes are not inverted; an open mesh has no inside to be wound towards.
  ASSERT_EQ(c.setMesh(primitives::box(glm::vec3(1.f))).code, SplitStatus::Ok);
  EXPECT_FALSE(c.inverted());
  EXPECT_FALSE(c.mirrored());
  MeshData open = reversed(primitives::box(glm::vec3(1.f)));
  open.indices.resize(open.indices.size() - 3);
  ASSERT_EQ(c.setMesh(open).code, SplitStatus::Ok);
  EXPECT_FALSE(c.closed());
  EXPECT_FALSE(c.inverted());
}

TEST(InvertedWinding, CgalTetrahedronSplitsAndKeepsItsWinding) {
  // The corpus test's first plane for this file (x = 0.5137 of the bounds) and an oblique one.
  expectSplitKeepsWinding(cgalTetrahedron(), glm::mat4(1.f), Plane{{1.0, 0.0, 0.0}, 0.5137});
  expectSplitKeepsWinding(cgalTetrahedron(), glm::mat4(1.f), Plane{{0.31, 0.77, -0.22}, 0.25});
}

TEST(InvertedWinding, InwardBoxUnderATransform) {
  const MeshData box = reversed(primitives::box(glm::vec3(1.f, 0.5f, 0.25f)));
  const glm::mat4 model = glm::translate(glm::mat4(1.f), glm::vec3(3.f, -1.f, 2.f)) *
                          glm::rotate(glm::mat4(1.f), 0.4f, glm::vec3(0.f, 1.f, 0.f));
  expectSplitKeepsWinding(box, model, Plane{{1.0, 0.2, 0.1}, 2.9});
}

TEST(InvertedWinding, InwardTorusSectionsWithTwoBordersAndWithAHole) {
  // Across the tube: two outer borders, neither may be taken for a hole. Across the axis: a border
  // with a hole, which must stay a hole.
  const MeshData torus = reversed(primitives::torus(1.f, 0.3f, 32, 16));
  MeshContainer container;
  ASSERT_EQ(container.setMesh(torus).code, SplitStatus::Ok);
  ASSERT_TRUE(container.mirrored());
  const std::vector<glm::dvec3> p = testing::toCutSpace(torus, glm::dmat4(1.0));
  const double inputVolume = testing::signedVolume(p, torus.indices);
  for (const Plane& plane : {Plane{{1.0, 0.0, 0.0}, 0.05}, Plane{{0.0, 1.0, 0.0}, 0.05}}) {
    SplitResult result;
    ASSERT_EQ(makeConcaveSplitter()->split(container, plane, SplitOptions{}, result),
              SplitStatus::Ok)
        << result.message;
    EXPECT_EQ(result.sectionLoops, 2u);
    double volume = 0.0, capAbove = 0.0;
    for (const SplitPiece& piece : result.pieces) {
      EXPECT_GT(piece.mass.volume, 0.0);
      volume += piece.mass.volume;
      if (piece.side > 0)
        capAbove += testing::capArea(piece.mesh, SplitOptions{}.capMaterialId, glm::dmat4(1.0));
    }
    EXPECT_NEAR(volume, -inputVolume, 1e-9 * -inputVolume);
    const double section = -testing::sectionArea(p, torus.indices, plane);
    EXPECT_NEAR(capAbove, section, 1e-6 * section);
  }
}

}  // namespace
}  // namespace cleave::geometry
