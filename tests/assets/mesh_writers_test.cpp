// SPDX-License-Identifier: MIT
// Writers read back by the readers (OBJ and GLB), and a glTF built with tinygltf itself then read.
#include <cstring>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "cleave/assets/mesh_io.h"
#include "cleave/geometry/primitives.h"
#include "tests/assets/asset_test_files.h"

namespace cleave::assets {
namespace {

using test::TempDir;

// A quad (two triangles, material 0) and a triangle (the cap, material 5), with normals and uvs.
geometry::MeshData twoMaterialMesh() {
  geometry::MeshData mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
  mesh.uv0 = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.25f, 0.5f}, {0.75f, 0.5f}, {0.5f, 0.125f}};
  mesh.indices = {0, 1, 2, 0, 2, 3, 4, 5, 6};
  mesh.submeshes = {{0, 6, 0}, {6, 3, 5}};
  return mesh;
}

MeshWriteOptions capOptions() {
  MeshWriteOptions options;
  options.capMaterialId = 5;
  options.materialNames = {"skin"};
  return options;
}

// The written mesh and the read mesh agree triangle by triangle (positions, normals, uvs).
void expectSameTriangles(const geometry::MeshData& a, const geometry::MeshData& b) {
  ASSERT_EQ(a.indices.size(), b.indices.size());
  for (size_t i = 0; i < a.indices.size(); ++i) {
    EXPECT_EQ(a.positions[a.indices[i]], b.positions[b.indices[i]]) << "corner " << i;
    if (!a.normals.empty()) {
      ASSERT_FALSE(b.normals.empty());
      EXPECT_EQ(a.normals[a.indices[i]], b.normals[b.indices[i]]) << "corner " << i;
    }
    if (!a.uv0.empty()) {
      ASSERT_FALSE(b.uv0.empty());
      EXPECT_EQ(a.uv0[a.indices[i]], b.uv0[b.indices[i]]) << "corner " << i;
    }
  }
}

TEST(ObjWriter, RoundTripKeepsAttributesAndNamesTheCap) {
  TempDir dir;
  const geometry::MeshData mesh = twoMaterialMesh();
  const std::string path = dir.file("piece.obj");
  const MeshWriteResult written = writeObj(path, mesh, capOptions());
  ASSERT_TRUE(written.ok()) << written.message;
  const MeshReadResult read = loadMesh(path);
  ASSERT_TRUE(read.ok()) << read.message;
  expectSameTriangles(mesh, read.mesh);
  EXPECT_EQ(read.mesh.vertexCount(), mesh.vertexCount());
  EXPECT_EQ(read.materialNames, (std::vector<std::string>{"skin", "cap"}));
  ASSERT_EQ(read.mesh.submeshes.size(), 2u);
  EXPECT_EQ(read.mesh.submeshes[1].indexCount, 3u);
  EXPECT_EQ(read.mesh.submeshes[1].materialId, 1u);
}

TEST(ObjWriter, FloatsRoundTripExactly) {
  geometry::MeshData mesh;
  mesh.positions = {{0.1f, 1e-7f, -123456.789f}, {3.14159265f, 2.5e10f, 1.f / 3.f}, {0, 0, 0}};
  mesh.indices = {0, 1, 2};
  std::string text;
  ASSERT_TRUE(writeObjToString(mesh, MeshWriteOptions{}, text).ok());
  const MeshReadResult read = readMeshFromMemory(
      std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()), MeshFormat::Obj, "mem");
  ASSERT_TRUE(read.ok()) << read.message;
  EXPECT_EQ(read.mesh.positions, mesh.positions);
  EXPECT_NE(text.find("usemtl material_0"), std::string::npos);
}

TEST(ObjWriter, InvalidMeshIsAnErrorNamingTheFile) {
  TempDir dir;
  geometry::MeshData mesh;
  mesh.positions = {{0, 0, 0}};
  mesh.indices = {0, 0, 3};
  const std::string path = dir.file("bad.obj");
  const MeshWriteResult written = writeObj(path, mesh, MeshWriteOptions{});
  EXPECT_FALSE(written.ok());
  EXPECT_NE(written.message.find(path), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(ObjWriter, UnwritablePathIsAnError) {
  TempDir dir;
  const std::string path = dir.file("missing_folder/piece.obj");
  const MeshWriteResult written = writeObj(path, twoMaterialMesh(), capOptions());
  EXPECT_FALSE(written.ok());
  EXPECT_NE(written.message.find(path), std::string::npos);
}

TEST(GlbWriter, RoundTripKeepsAttributesAndOnePrimitivePerSubmesh) {
  TempDir dir;
  const geometry::MeshData mesh = twoMaterialMesh();
  const std::string path = dir.file("piece.glb");
  const MeshWriteResult written = writeGlb(path, mesh, capOptions());
  ASSERT_TRUE(written.ok()) << written.message;
  const MeshReadResult read = loadMesh(path);
  ASSERT_TRUE(read.ok()) << read.message;
  expectSameTriangles(mesh, read.mesh);
  EXPECT_EQ(read.materialNames, (std::vector<std::string>{"skin", "cap"}));
  ASSERT_EQ(read.mesh.submeshes.size(), 2u);
  EXPECT_EQ(read.mesh.submeshes[0].indexCount, 6u);
  EXPECT_EQ(read.mesh.submeshes[1].materialId, 1u);

  // The file itself: one mesh with two primitives and positions with bounds, as tinygltf sees it.
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, path)) << err;
  ASSERT_EQ(model.meshes.size(), 1u);
  EXPECT_EQ(model.meshes[0].primitives.size(), 2u);
  const int position = model.meshes[0].primitives[0].attributes.at("POSITION");
  EXPECT_EQ(model.accessors[static_cast<size_t>(position)].minValues, (std::vector<double>{0, 0, 0}));
  EXPECT_EQ(model.accessors[static_cast<size_t>(position)].maxValues, (std::vector<double>{1, 1, 1}));
}

TEST(GlbWriter, ClosedPrimitiveStaysClosedThroughTheFile) {
  const geometry::MeshData sphere = geometry::primitives::uvSphere(1.f, 16, 9);
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(writeGlbToMemory(sphere, MeshWriteOptions{}, bytes).ok());
  const MeshReadResult read = readMeshFromMemory(bytes, MeshFormat::Glb, "sphere.glb");
  ASSERT_TRUE(read.ok()) << read.message;
  EXPECT_EQ(read.mesh.positions, sphere.positions);
  EXPECT_EQ(read.mesh.indices, sphere.indices);
  EXPECT_NEAR(geometry::computeMassProperties(read.mesh).volume,
              geometry::computeMassProperties(sphere).volume, 1e-9);
}

// A model built with tinygltf in code: two meshes (one with an unsigned-byte index list and
// normalized ushort UVs, one non-indexed without normals), a parent node with a matrix.
TEST(GltfReader, ModelBuiltWithTinygltfIsMergedWithTransformsAndMaterials) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.buffers.emplace_back();
  std::vector<unsigned char>& data = model.buffers[0].data;
  auto append = [&](const void* bytes, size_t size) {
    while (data.size() % 4) data.push_back(0);
    const size_t offset = data.size();
    data.insert(data.end(), static_cast<const unsigned char*>(bytes),
                static_cast<const unsigned char*>(bytes) + size);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = size;
    model.bufferViews.push_back(view);
    return static_cast<int>(model.bufferViews.size() - 1);
  };
  auto accessor = [&](int view, int componentType, int type, size_t count, bool normalized = false) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = componentType;
    a.type = type;
    a.count = count;
    a.normalized = normalized;
    model.accessors.push_back(a);
    return static_cast<int>(model.accessors.size() - 1);
  };
  const float quadPositions[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const float quadNormals[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const uint16_t quadUvs[] = {0, 0, 65535, 0, 65535, 65535, 0, 65535};
  const uint8_t quadIndices[] = {0, 1, 2, 0, 2, 3};
  const float triPositions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const int quadP = accessor(append(quadPositions, sizeof(quadPositions)), TINYGLTF_COMPONENT_TYPE_FLOAT,
                             TINYGLTF_TYPE_VEC3, 4);
  model.accessors.back().minValues = {0, 0, 0};
  model.accessors.back().maxValues = {1, 1, 0};
  const int quadN = accessor(append(quadNormals, sizeof(quadNormals)), TINYGLTF_COMPONENT_TYPE_FLOAT,
                             TINYGLTF_TYPE_VEC3, 4);
  const int quadT = accessor(append(quadUvs, sizeof(quadUvs)), TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                             TINYGLTF_TYPE_VEC2, 4, true);
  const int quadI = accessor(append(quadIndices, sizeof(quadIndices)),
                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_SCALAR, 6);
  const int triP = accessor(append(triPositions, sizeof(triPositions)), TINYGLTF_COMPONENT_TYPE_FLOAT,
                            TINYGLTF_TYPE_VEC3, 3);
  model.accessors.back().minValues = {0, 0, 0};
  model.accessors.back().maxValues = {1, 1, 0};

  tinygltf::Material red;
  red.name = "red";
  model.materials.push_back(red);
  model.materials.emplace_back();  // unnamed

  tinygltf::Primitive quad;
  quad.attributes = {{"POSITION", quadP}, {"NORMAL", quadN}, {"TEXCOORD_0", quadT}};
  quad.indices = quadI;
  quad.material = 1;
  quad.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Primitive tri;
  tri.attributes = {{"POSITION", triP}};
  tri.material = 0;
  tri.mode = TINYGLTF_MODE_TRIANGLES;
  model.meshes.resize(2);
  model.meshes[0].primitives = {quad};
  model.meshes[1].primitives = {tri};

  tinygltf::Node parent;
  // Column-major: a translation by (0, 0, 5).
  parent.matrix = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1};
  parent.children = {1, 2};
  tinygltf::Node quadNode;
  quadNode.mesh = 0;
  tinygltf::Node triNode;
  triNode.mesh = 1;
  triNode.translation = {0, 0, 1};
  model.nodes = {parent, quadNode, triNode};
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  tinygltf::TinyGLTF writer;
  std::ostringstream stream;
  ASSERT_TRUE(writer.WriteGltfSceneToStream(&model, stream, true, false));
  TempDir dir;
  const std::string path = dir.write("built.gltf", stream.str());

  const MeshReadResult read = loadMesh(path);
  ASSERT_TRUE(read.ok()) << read.message;
  ASSERT_EQ(read.mesh.triangleCount(), 3u);
  ASSERT_EQ(read.mesh.vertexCount(), 7u);
  EXPECT_EQ(read.mesh.positions[2], glm::vec3(1, 1, 5));
  EXPECT_EQ(read.mesh.positions[5], glm::vec3(1, 0, 6));
  EXPECT_EQ(read.mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 4, 5, 6}));
  EXPECT_TRUE(read.mesh.normals.empty());  // the triangle has none: dropped for all
  ASSERT_EQ(read.mesh.uv0.size(), 7u);
  EXPECT_EQ(read.mesh.uv0[2], glm::vec2(1, 1));
  EXPECT_EQ(read.mesh.uv0[5], glm::vec2(0, 0));  // missing uvs are zero
  ASSERT_EQ(read.mesh.submeshes.size(), 2u);
  EXPECT_EQ(read.mesh.submeshes[0].materialId, 1u);
  EXPECT_EQ(read.mesh.submeshes[1].materialId, 0u);
  EXPECT_EQ(read.materialNames, (std::vector<std::string>{"red", "material_1"}));
}

}  // namespace
}  // namespace cleave::assets
