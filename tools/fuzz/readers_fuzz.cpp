// SPDX-License-Identifier: MIT
// Fuzz driver for the mesh file readers. Input: one byte choosing the format (modulo 6: OBJ, OFF,
// STL, PLY, glTF, GLB), then the file bytes. Every accepted mesh must satisfy the MeshData contract
// and survive an OBJ and a GLB round trip through the writers and readers.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "cleave/assets/mesh_io.h"
#include "tools/fuzz/fuzz_driver.h"

namespace cleave::fuzz {

namespace {

using assets::MeshFormat;

constexpr MeshFormat kFormats[] = {MeshFormat::Obj, MeshFormat::Off, MeshFormat::Stl,
                                   MeshFormat::Ply, MeshFormat::Gltf, MeshFormat::Glb};

std::vector<uint8_t> seed(uint8_t format, const std::string& text) {
  std::vector<uint8_t> bytes(text.size() + 1);
  bytes[0] = format;
  std::copy(text.begin(), text.end(), bytes.begin() + 1);
  return bytes;
}

void appendF32(std::string& s, float f) {
  uint32_t bits;
  static_assert(sizeof(bits) == sizeof(f));
  std::memcpy(&bits, &f, sizeof(f));
  for (int i = 0; i < 4; ++i) s += static_cast<char>((bits >> (8 * i)) & 0xff);
}

void checkMesh(const assets::MeshReadResult& result) {
  const geometry::MeshData& mesh = result.mesh;
  if (!result.message.empty()) fail("an accepted mesh has an error message");
  if (mesh.indices.empty() || mesh.indices.size() % 3 != 0) fail("bad index count");
  for (uint32_t index : mesh.indices) {
    if (index >= mesh.positions.size()) fail("index out of range");
  }
  for (const glm::vec3& p : mesh.positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) fail("non-finite position");
  }
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) fail("normal count");
  if (!mesh.uv0.empty() && mesh.uv0.size() != mesh.positions.size()) fail("uv count");
  if (!mesh.colors.empty() && mesh.colors.size() != mesh.positions.size()) fail("colour count");
  uint64_t covered = 0;
  for (const geometry::SubMesh& sub : mesh.submeshes) {
    if (sub.firstIndex != covered) fail("submesh gap");
    if (sub.materialId >= result.materialNames.size()) fail("submesh material without a name");
    covered += sub.indexCount;
  }
  if (!mesh.submeshes.empty() && covered != mesh.indices.size()) fail("submeshes do not cover");
}

}  // namespace

std::vector<std::vector<uint8_t>> fuzzSeeds() {
  std::vector<std::vector<uint8_t>> seeds;
  seeds.push_back(seed(0,
                       "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                       "vt 0 0\nvt 1 1\nvn 0 0 1\nusemtl a\nf 1/1/1 4/2/1 3/1/1 2/2/1\nf 5 6 7 8\n"
                       "usemtl b\nf 1 2 6 5\nf 4 8 7 3\nf -8 -4 -1 -5\nf 2 3 7 6\n"));
  seeds.push_back(seed(1, "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"));
  seeds.push_back(seed(2,
                       "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                       "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n"));
  {
    std::string stl = "solid binary header";
    stl.resize(80, ' ');
    stl += std::string("\x02\0\0\0", 4);
    const float tris[2][9] = {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 0, 1, 0, 0, 0, 1}};
    for (const auto& t : tris) {
      for (int i = 0; i < 3; ++i) appendF32(stl, 0.f);
      for (float v : t) appendF32(stl, v);
      stl += std::string(2, '\0');
    }
    seeds.push_back(seed(2, stl));
  }
  seeds.push_back(seed(3,
                       "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                       "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                       "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
                       "0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 9 9 9\n3 0 1 2\n3 0 2 3\n"));
  {
    std::string ply =
        "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar ushort vertex_indices\nend_header\n";
    const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    for (float f : v) {
      std::string le;
      appendF32(le, f);
      ply += std::string(le.rbegin(), le.rend());
    }
    ply += std::string("\x03\0\0\0\x01\0\x02", 7);
    seeds.push_back(seed(3, ply));
  }
  seeds.push_back(seed(4,
                       R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)"
                       R"("nodes":[{"mesh":0,"translation":[1,2,3],"children":[1]},{"mesh":0,"scale":[-1,1,1]}],)"
                       R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                       R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
                       R"("min":[0,0,0],"max":[1,1,0]}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
                       R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
                       R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})"));
  {
    geometry::MeshData mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    mesh.uv0 = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    mesh.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    mesh.submeshes = {{0, 9, 0}, {9, 3, 1}};
    std::vector<uint8_t> glb;
    assets::writeGlbToMemory(mesh, assets::MeshWriteOptions{}, glb);
    glb.insert(glb.begin(), uint8_t{5});
    seeds.push_back(glb);
  }
  return seeds;
}

}  // namespace cleave::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace cleave;
  if (size < 1) return 0;
  const assets::MeshFormat format = fuzz::kFormats[data[0] % 6];
  const std::string name = "fuzz-input";
  const assets::MeshReadResult result =
      assets::readMeshFromMemory(std::span(data + 1, size - 1), format, name);
  if (!result.ok()) {
    if (result.message.rfind(name, 0) != 0) fuzz::fail("an error does not name the input");
    if (result.message.find('\n') != std::string::npos) fuzz::fail("an error spans several lines");
    if (!result.mesh.positions.empty() || !result.mesh.indices.empty()) fuzz::fail("error with a mesh");
    return -1;  // rejected input: not worth keeping in a corpus
  }
  fuzz::checkMesh(result);

  // Round trips through both writers keep the triangle count.
  assets::MeshWriteOptions options;
  options.materialNames = result.materialNames;
  options.capMaterialId = static_cast<uint32_t>(result.materialNames.size());
  std::string obj;
  if (!assets::writeObjToString(result.mesh, options, obj).ok()) fuzz::fail("OBJ writer refused a read mesh");
  const assets::MeshReadResult objBack = assets::readMeshFromMemory(
      std::span(reinterpret_cast<const uint8_t*>(obj.data()), obj.size()), assets::MeshFormat::Obj, "obj");
  if (!objBack.ok() || objBack.mesh.triangleCount() != result.mesh.triangleCount()) {
    fuzz::fail("OBJ round trip changed the mesh");
  }
  std::vector<uint8_t> glb;
  if (!assets::writeGlbToMemory(result.mesh, options, glb).ok()) fuzz::fail("GLB writer refused a read mesh");
  const assets::MeshReadResult glbBack = assets::readMeshFromMemory(glb, assets::MeshFormat::Glb, "glb");
  if (!glbBack.ok() || glbBack.mesh.positions != result.mesh.positions ||
      glbBack.mesh.indices != result.mesh.indices) {
    fuzz::fail("GLB round trip changed the mesh");
  }
  return 0;
}
