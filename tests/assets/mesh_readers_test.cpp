// SPDX-License-Identifier: MIT
// The readers on small files written by the tests: the unit cube in every format and encoding,
// plus the format details each reader promises (welding, negative indices, materials, attributes).
#include <gtest/gtest.h>

#include "cleave/assets/mesh_io.h"
#include "tests/assets/asset_test_files.h"

namespace cleave::assets {
namespace {

using test::TempDir;

TEST(MeshFormat, ExtensionIsCaseInsensitiveAndUnknownIsRejected) {
  EXPECT_EQ(formatFromPath("a/b/Cube.OBJ"), MeshFormat::Obj);
  EXPECT_EQ(formatFromPath("x.Off"), MeshFormat::Off);
  EXPECT_EQ(formatFromPath("x.sTl"), MeshFormat::Stl);
  EXPECT_EQ(formatFromPath("x.PLY"), MeshFormat::Ply);
  EXPECT_EQ(formatFromPath("scene.GLTF"), MeshFormat::Gltf);
  EXPECT_EQ(formatFromPath("scene.glb"), MeshFormat::Glb);
  EXPECT_EQ(formatFromPath("dir.obj/readme"), MeshFormat::Unknown);
  EXPECT_EQ(formatFromPath("mesh.fbx"), MeshFormat::Unknown);
  TempDir dir;
  const std::string path = dir.write("mesh.fbx", "whatever");
  const MeshReadResult result = loadMesh(path);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.message.find(path), std::string::npos);
  EXPECT_NE(result.message.find("extension"), std::string::npos);
}

TEST(ObjReader, CubeWithQuadsIsClosedWithTwoMaterialRuns) {
  TempDir dir;
  const MeshReadResult result = loadMesh(dir.write("cube.obj", test::cubeObj()));
  test::expectUnitCube(result);
  ASSERT_EQ(result.materialNames, (std::vector<std::string>{"wood", "stone"}));
  ASSERT_EQ(result.mesh.submeshes.size(), 3u);  // wood, stone, wood again: runs follow the file
  EXPECT_EQ(result.mesh.submeshes[0].materialId, 0u);
  EXPECT_EQ(result.mesh.submeshes[0].indexCount, 4u * 6u);
  EXPECT_EQ(result.mesh.submeshes[1].materialId, 1u);
  EXPECT_EQ(result.mesh.submeshes[1].firstIndex, 24u);
  EXPECT_EQ(result.mesh.submeshes[1].indexCount, 6u);
  EXPECT_EQ(result.mesh.submeshes[2].materialId, 0u);
  EXPECT_TRUE(result.mesh.normals.empty());
  EXPECT_TRUE(result.mesh.uv0.empty());
}

TEST(ObjReader, PentagonIsFanTriangulatedFromItsFirstCorner) {
  TempDir dir;
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 1 2 3 4 5\n";
  const MeshReadResult result = loadMesh(dir.write("penta.obj", obj));
  ASSERT_TRUE(result.ok()) << result.message;
  EXPECT_EQ(result.mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
  EXPECT_EQ(result.materialNames, std::vector<std::string>{"default"});
}

// An L whose first corner does not see the far corner (CGAL's corner_poly.off has this face): its
// fan folds, an inverted triangle over the others, so the mesh intersects itself and no cut
// through it can be capped. Read in every text format, it must come out without a fold.
void expectUnfoldedL(const MeshReadResult& result) {
  ASSERT_TRUE(result.ok()) << result.message;
  ASSERT_EQ(result.mesh.indices.size(), 12u);
  double area = 0.0;
  for (size_t t = 0; t < result.mesh.indices.size(); t += 3) {
    const glm::vec3 a = result.mesh.positions[result.mesh.indices[t]];
    const glm::vec3 b = result.mesh.positions[result.mesh.indices[t + 1]];
    const glm::vec3 c = result.mesh.positions[result.mesh.indices[t + 2]];
    const float z = glm::cross(b - a, c - a).z;
    EXPECT_GT(z, 0.f) << "triangle " << t / 3 << " is inverted or flat";
    area += 0.5 * z;
  }
  EXPECT_DOUBLE_EQ(area, 3.0);
}

TEST(MeshReaders, ConcavePolygonFacesDoNotFold) {
  TempDir dir;
  const std::string corners = "0 1 1\n1 1 1\n1 0 1\n2 0 1\n2 2 1\n0 2 1\n";
  const std::string obj = "v 0 1 1\nv 1 1 1\nv 1 0 1\nv 2 0 1\nv 2 2 1\nv 0 2 1\nf 1 2 3 4 5 6\n";
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  expectUnfoldedL(loadMesh(dir.write("l.obj", obj)));
  expectUnfoldedL(loadMesh(dir.write("l.off", "OFF\n6 1 0\n" + corners + "6 0 1 2 3 4 5\n")));
  expectUnfoldedL(loadMesh(dir.write("l.ply", ply + corners + "6 0 1 2 3 4 5\n")));
}

TEST(ObjReader, NegativeIndicesCountFromTheLatestVertex) {
  TempDir dir;
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 1\nf 1 -3 4\n";
  const MeshReadResult result = loadMesh(dir.write("neg.obj", obj));
  ASSERT_TRUE(result.ok()) << result.message;
  ASSERT_EQ(result.mesh.vertexCount(), 4u);
  EXPECT_EQ(result.mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 1, 3}));
  EXPECT_EQ(result.mesh.positions[3], glm::vec3(0, 0, 1));
}

TEST(ObjReader, IdenticalTriplesAreWeldedAndSeamsAreNot) {
  TempDir dir;
  // Two triangles sharing an edge; vertex 2 is used with the same vt/vn by both (welded), vertex 1
  // with two different vt (a UV seam: two output vertices).
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
      "vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nvt 0.5 0.5\n"
      "vn 0 0 2\n"
      "f 1/1/1 2/2/1 3/3/1\nf 3/3/1 2/5/1 4/4/1\n";
  const MeshReadResult result = loadMesh(dir.write("seam.obj", obj));
  ASSERT_TRUE(result.ok()) << result.message;
  EXPECT_EQ(result.mesh.vertexCount(), 5u);
  EXPECT_EQ(result.mesh.indices, (std::vector<uint32_t>{0, 1, 2, 2, 3, 4}));
  ASSERT_EQ(result.mesh.uv0.size(), 5u);
  EXPECT_EQ(result.mesh.uv0[3], glm::vec2(0.5f, 0.5f));
  ASSERT_EQ(result.mesh.normals.size(), 5u);
  EXPECT_EQ(result.mesh.normals[0], glm::vec3(0, 0, 1));  // normalised on read
}

TEST(ObjReader, NormalsAreDroppedWhenSomeCornersHaveNone) {
  TempDir dir;
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3\n";
  const MeshReadResult result = loadMesh(dir.write("partial.obj", obj));
  ASSERT_TRUE(result.ok()) << result.message;
  EXPECT_TRUE(result.mesh.normals.empty());
}

TEST(ObjReader, VertexColoursAreRead) {
  TempDir dir;
  const std::string obj = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n";
  const MeshReadResult result = loadMesh(dir.write("colour.obj", obj));
  ASSERT_TRUE(result.ok()) << result.message;
  ASSERT_EQ(result.mesh.colors.size(), 3u);
  EXPECT_EQ(result.mesh.colors[1], glm::vec4(0, 1, 0, 1));
}

TEST(OffReader, CubeWithFaceColoursIsClosed) {
  TempDir dir;
  test::expectUnitCube(loadMesh(dir.write("cube.off", test::cubeOff())));
}

TEST(OffReader, HeaderWithCountsOnTheSameLineAndNormals) {
  TempDir dir;
  const std::string off = "NOFF 3 1 0\n0 0 0 0 0 3\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
  const MeshReadResult result = loadMesh(dir.write("tri.off", off));
  ASSERT_TRUE(result.ok()) << result.message;
  ASSERT_EQ(result.mesh.normals.size(), 3u);
  EXPECT_EQ(result.mesh.normals[0], glm::vec3(0, 0, 1));
}

TEST(StlReader, AsciiCubeIsWeldedAndClosed) {
  TempDir dir;
  test::expectUnitCube(loadMesh(dir.write("cube.stl", test::cubeStlAscii())));
}

TEST(StlReader, BinaryCubeIsWeldedAndClosed) {
  TempDir dir;
  test::expectUnitCube(loadMesh(dir.write("cube.stl", test::cubeStlBinary("binary cube"))));
}

TEST(StlReader, BinaryWhoseHeaderStartsWithSolidIsReadAsBinary) {
  TempDir dir;
  const std::string stl = test::cubeStlBinary("solid cube exported by a tool that writes solid here");
  ASSERT_EQ(stl.substr(0, 5), "solid");
  test::expectUnitCube(loadMesh(dir.write("cube.STL", stl)));
}

TEST(StlReader, BinaryWithTrailingBytesIsAccepted) {
  TempDir dir;
  test::expectUnitCube(loadMesh(dir.write("cube.stl", test::cubeStlBinary("x") + "trailing")));
}

TEST(PlyReader, AsciiCubeWithColoursAndAnExtraElement) {
  TempDir dir;
  const MeshReadResult result = loadMesh(dir.write("cube.ply", test::cubePlyAscii()));
  test::expectUnitCube(result);
  ASSERT_EQ(result.mesh.colors.size(), 8u);
  EXPECT_NEAR(result.mesh.colors[0].r, 1.f, 1e-6f);
  EXPECT_NEAR(result.mesh.colors[0].g, 128.f / 255.f, 1e-6f);
  EXPECT_EQ(result.mesh.colors[0].a, 1.f);
}

TEST(PlyReader, BinaryLittleEndianCubeWithNormalsAndUvs) {
  TempDir dir;
  const MeshReadResult result = loadMesh(dir.write("cube.ply", test::cubePlyBinary(false)));
  test::expectUnitCube(result);
  ASSERT_EQ(result.mesh.normals.size(), 8u);
  EXPECT_NEAR(glm::length(result.mesh.normals[6]), 1.f, 1e-6f);
  EXPECT_GT(result.mesh.normals[6].x, 0.f);
  ASSERT_EQ(result.mesh.uv0.size(), 8u);
  EXPECT_EQ(result.mesh.uv0[2], glm::vec2(1, 1));
}

TEST(PlyReader, BinaryBigEndianGivesTheSameMeshAsLittleEndian) {
  TempDir dir;
  const MeshReadResult little = loadMesh(dir.write("le.ply", test::cubePlyBinary(false)));
  const MeshReadResult big = loadMesh(dir.write("be.ply", test::cubePlyBinary(true)));
  test::expectUnitCube(big);
  ASSERT_TRUE(little.ok());
  EXPECT_EQ(big.mesh.positions, little.mesh.positions);
  EXPECT_EQ(big.mesh.indices, little.mesh.indices);
  EXPECT_EQ(big.mesh.normals, little.mesh.normals);
  EXPECT_EQ(big.mesh.uv0, little.mesh.uv0);
}

TEST(GltfReader, DataUriCubeIsClosed) {
  TempDir dir;
  test::expectUnitCube(loadMesh(dir.write("cube.gltf", test::cubeGltf())));
}

TEST(GltfReader, NodeTransformsAreAppliedAlongTheHierarchy) {
  TempDir dir;
  // Root translated by (10,0,0) and scaled by 2; its child (holding the mesh) rotated 90 degrees
  // about z: the cube [0,1]^3 becomes x in [8,10], y in [0,2], z in [0,2]; volume 8.
  const std::string nodes =
      R"([{"translation":[10,0,0],"scale":[2,2,2],"children":[1]},)"
      R"({"mesh":0,"rotation":[0,0,0.70710678,0.70710678]}])";
  const MeshReadResult result = loadMesh(dir.write("moved.gltf", test::cubeGltf("", -1, nodes)));
  ASSERT_TRUE(result.ok()) << result.message;
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& p : result.mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  EXPECT_NEAR(lo.x, 8.f, 1e-5f);
  EXPECT_NEAR(hi.x, 10.f, 1e-5f);
  EXPECT_NEAR(lo.y, 0.f, 1e-5f);
  EXPECT_NEAR(hi.y, 2.f, 1e-5f);
  EXPECT_NEAR(hi.z, 2.f, 1e-5f);
  EXPECT_NEAR(geometry::computeMassProperties(result.mesh).volume, 8.0, 1e-4);
}

TEST(GltfReader, MirroringNodeKeepsTheMeshOutwardOriented) {
  TempDir dir;
  const std::string nodes = R"([{"mesh":0,"scale":[-1,1,1]}])";
  const MeshReadResult result = loadMesh(dir.write("mirror.gltf", test::cubeGltf("", -1, nodes)));
  ASSERT_TRUE(result.ok()) << result.message;
  EXPECT_TRUE(geometry::isClosedAndOriented(result.mesh.positions, result.mesh.indices));
  EXPECT_NEAR(geometry::computeMassProperties(result.mesh).volume, 1.0, 1e-6);
}

TEST(GltfReader, MeshUsedByTwoNodesIsMergedTwice) {
  TempDir dir;
  const std::string gltf = test::cubeGltf("", -1, R"([{"children":[1,2]},{"mesh":0},{"mesh":0,"translation":[3,0,0]}])");
  const MeshReadResult result = loadMesh(dir.write("two.gltf", gltf));
  ASSERT_TRUE(result.ok()) << result.message;
  EXPECT_EQ(result.mesh.triangleCount(), 24u);
  EXPECT_NEAR(geometry::computeMassProperties(result.mesh).volume, 2.0, 1e-6);
  ASSERT_EQ(result.mesh.submeshes.size(), 1u);  // same (default) material: one run
  EXPECT_EQ(result.materialNames, std::vector<std::string>{"default"});
}

TEST(GltfReader, GeometryNeutralRequiredExtensionIsAccepted) {
  TempDir dir;
  const std::string gltf = test::cubeGltf(
      R"("extensionsUsed":["KHR_materials_unlit"],"extensionsRequired":["KHR_materials_unlit"],)");
  test::expectUnitCube(loadMesh(dir.write("unlit.gltf", gltf)));
}

TEST(MeshReaders, MemoryReadsMatchFileReads) {
  TempDir dir;
  const std::string obj = test::cubeObj();
  const MeshReadResult fromFile = loadMesh(dir.write("cube.obj", obj));
  const MeshReadResult fromMemory = readMeshFromMemory(
      std::span(reinterpret_cast<const uint8_t*>(obj.data()), obj.size()), MeshFormat::Obj, "memory");
  ASSERT_TRUE(fromFile.ok() && fromMemory.ok());
  EXPECT_EQ(fromFile.mesh.positions, fromMemory.mesh.positions);
  EXPECT_EQ(fromFile.mesh.indices, fromMemory.mesh.indices);
}

TEST(MeshReaders, ReadMeshFileIgnoresTheExtension) {
  TempDir dir;
  const std::string path = dir.write("cube.txt", test::cubeOff());
  test::expectUnitCube(readMeshFile(path, MeshFormat::Off));
}

}  // namespace
}  // namespace cleave::assets
