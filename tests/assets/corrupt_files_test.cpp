// SPDX-License-Identifier: MIT
// Bad input of every kind gives a one-line error that names the file, an empty mesh, and no crash.
#include <gtest/gtest.h>

#include "cleave/assets/mesh_io.h"
#include "tests/assets/asset_test_files.h"

namespace cleave::assets {
namespace {

using test::TempDir;

struct CorruptCase {
  const char* label;
  const char* fileName;
  std::string bytes;
  const char* reasonPart;  // a word the reason must contain (lower case), or "" for any reason
};

std::string binaryStlWithCount(uint32_t count, size_t triangles) {
  std::string s = test::cubeStlBinary("binary");
  s.resize(84 + 50 * triangles);
  s[80] = static_cast<char>(count & 0xff);
  s[81] = static_cast<char>((count >> 8) & 0xff);
  s[82] = static_cast<char>((count >> 16) & 0xff);
  s[83] = static_cast<char>((count >> 24) & 0xff);
  return s;
}

std::string plyHeader(const std::string& format, const std::string& vertexCount,
                      const std::string& faceCount) {
  return "ply\nformat " + format + " 1.0\nelement vertex " + vertexCount +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + faceCount +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::vector<CorruptCase> corruptCases() {
  std::vector<CorruptCase> cases;
  const std::string ply = test::cubePlyBinary(false);
  const std::string plyBig = test::cubePlyBinary(true);
  std::string glb;
  {
    geometry::MeshData mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.indices = {0, 1, 2};
    std::vector<uint8_t> bytes;
    writeGlbToMemory(mesh, MeshWriteOptions{}, bytes);
    glb.assign(bytes.begin(), bytes.end());
  }
  cases.push_back({"empty obj", "empty.obj", "", "empty"});
  cases.push_back({"empty stl", "empty.stl", "", "empty"});
  cases.push_back({"empty ply", "empty.ply", "", "empty"});
  cases.push_back({"empty glb", "empty.glb", "", "empty"});
  cases.push_back({"obj without faces", "nofaces.obj", "v 0 0 0\nv 1 0 0\n", "no faces"});
  cases.push_back({"obj truncated face", "cut.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2", "3 corners"});
  cases.push_back({"obj index out of range", "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
                   "out of range"});
  cases.push_back({"obj negative index out of range", "neg.obj",
                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "out of range"});
  cases.push_back({"obj index zero", "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "index 0"});
  cases.push_back({"obj NaN coordinate", "nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                   "non-finite"});
  cases.push_back({"obj infinite coordinate", "inf.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n", ""});
  cases.push_back({"obj bad number", "word.obj", "v 0 zero 0\n", "bad number"});
  cases.push_back({"obj huge index", "huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n",
                   ""});
  cases.push_back({"off absurd counts", "absurd.off", "OFF\n1000000000 1000000000 0\n0 0 0\n", "exceed"});
  cases.push_back({"off truncated", "cut.off", test::cubeOff().substr(0, 60), ""});
  cases.push_back({"off missing face", "face.off", test::cubeOff().substr(0, test::cubeOff().rfind("4 ")),
                   "file ends"});
  cases.push_back({"off index out of range", "range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
                   "out of range"});
  cases.push_back({"off negative count", "neg.off", "OFF\n-3 1 0\n", "bad count"});
  cases.push_back({"off nan", "nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "non-finite"});
  cases.push_back({"stl truncated binary", "cut.stl", binaryStlWithCount(12, 3), "announces"});
  cases.push_back({"stl absurd count", "absurd.stl", binaryStlWithCount(0xffffffffu, 1), "announces"});
  cases.push_back({"stl short header", "short.stl", std::string(40, '\x01'), "header"});
  cases.push_back({"stl zero triangles", "zero.stl", binaryStlWithCount(0, 0), "no triangles"});
  cases.push_back({"stl ascii vertex outside loop", "loop.stl", "solid x\nvertex 0 0 0\nendsolid\n",
                   "outside"});
  cases.push_back({"stl ascii truncated", "cut.stl", test::cubeStlAscii().substr(0, 300), ""});
  cases.push_back({"stl ascii nan", "nan.stl",
                   "solid x\nfacet normal 0 0 1\nouter loop\nvertex nan 0 0\nvertex 1 0 0\n"
                   "vertex 0 1 0\nendloop\nendfacet\nendsolid x\n",
                   "non-finite"});
  cases.push_back({"ply not ply", "not.ply", "plx\n", "not a ply"});
  cases.push_back({"ply no end_header", "open.ply", "ply\nformat ascii 1.0\nelement vertex 3\n",
                   "end_header"});
  cases.push_back({"ply truncated binary", "cut.ply", ply.substr(0, ply.size() - 30), ""});
  cases.push_back({"ply truncated big endian", "cutbe.ply", plyBig.substr(0, plyBig.size() - 7), ""});
  cases.push_back({"ply absurd vertex count", "absurd.ply",
                   plyHeader("binary_little_endian", "4000000000", "1") + std::string(64, '\0'),
                   "more than the file"});
  {
    std::string absurdList = plyHeader("binary_little_endian", "3", "1");
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) test::putF32(absurdList, v);
    absurdList += static_cast<char>(255);  // a face with 255 corners but only 8 bytes left
    test::putU32(absurdList, 0);
    test::putU32(absurdList, 1);
    cases.push_back({"ply absurd list length", "list.ply", absurdList, "list length"});
  }
  cases.push_back({"ply huge element without properties", "empty_element.ply",
                   "ply\nformat ascii 1.0\nelement nothing 4000000000\nelement vertex 1\n"
                   "property float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
                   "no face element"});
  cases.push_back({"ply index out of range", "range.ply",
                   plyHeader("ascii", "3", "1") + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "out of range"});
  cases.push_back({"ply negative index", "negidx.ply",
                   plyHeader("ascii", "3", "1") + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "bad vertex index"});
  cases.push_back({"ply nan", "nan.ply", plyHeader("ascii", "3", "1") + "0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n",
                   "non-finite"});
  cases.push_back({"ply unknown format", "fmt.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n",
                   "unknown ply format"});
  cases.push_back({"ply unknown type", "type.ply",
                   "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
                   "unknown property type"});
  cases.push_back({"gltf required draco", "draco.gltf",
                   test::cubeGltf(R"("extensionsUsed":["KHR_draco_mesh_compression"],)"
                                  R"("extensionsRequired":["KHR_draco_mesh_compression"],)"),
                   "khr_draco_mesh_compression"});
  cases.push_back({"gltf required meshopt", "meshopt.gltf",
                   test::cubeGltf(R"("extensionsRequired":["EXT_meshopt_compression"],)"),
                   "ext_meshopt_compression"});
  cases.push_back({"gltf index out of range", "range.gltf", test::cubeGltf("", 200), "out of range"});
  cases.push_back({"gltf node cycle", "cycle.gltf",
                   test::cubeGltf("", -1, R"([{"mesh":0,"children":[1]},{"children":[0]}])"), "twice"});
  cases.push_back({"gltf self child", "self.gltf", test::cubeGltf("", -1, R"([{"mesh":0,"children":[0]}])"),
                   "twice"});
  cases.push_back({"gltf missing node", "node.gltf", test::cubeGltf("", -1, R"([{"children":[7]}])"), ""});
  cases.push_back({"gltf NaN translation", "nan.gltf",
                   test::cubeGltf("", -1, R"([{"mesh":0,"scale":[1,1e308,1e308],"translation":[0,1e308,0]}])"),
                   ""});
  cases.push_back({"gltf not json", "text.gltf", "this is not json", ""});
  cases.push_back({"gltf missing buffer file", "missing.gltf",
                   R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":96,"uri":"nowhere.bin"}],)"
                   R"("bufferViews":[{"buffer":0,"byteLength":96}],)"
                   R"("accessors":[{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3"}],)"
                   R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                   R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})",
                   ""});
  cases.push_back({"gltf accessor past buffer", "past.gltf",
                   [] {
                     std::string g = test::cubeGltf();
                     const size_t at = g.find(R"("count":8)");
                     g.replace(at, 9, R"("count":9000)");
                     return g;
                   }(),
                   "past the end"});
  cases.push_back({"gltf no triangles", "empty.gltf", R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[]}]})",
                   "no triangle"});
  cases.push_back({"glb truncated", "cut.glb", glb.substr(0, glb.size() / 2), ""});
  cases.push_back({"glb bad magic", "magic.glb", "glTX" + glb.substr(4), ""});
  return cases;
}

TEST(CorruptFiles, EveryCaseGivesAnErrorNamingTheFile) {
  TempDir dir;
  for (const CorruptCase& c : corruptCases()) {
    SCOPED_TRACE(c.label);
    const std::string path = dir.write(c.fileName, c.bytes);
    const MeshReadResult result = loadMesh(path);
    EXPECT_FALSE(result.ok());
    EXPECT_TRUE(result.mesh.positions.empty() && result.mesh.indices.empty());
    EXPECT_EQ(result.message.rfind(path, 0), 0u) << result.message;  // starts with the file name
    EXPECT_EQ(result.message.find('\n'), std::string::npos) << result.message;
    EXPECT_NE(lower(result.message).find(c.reasonPart), std::string::npos) << result.message;
  }
}

TEST(CorruptFiles, TextErrorsCarryTheLineNumber) {
  TempDir dir;
  const std::string path = dir.write("lines.obj", "# header\nv 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n");
  const MeshReadResult result = loadMesh(path);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.message.rfind(path + ":6: ", 0), 0u) << result.message;
}

TEST(CorruptFiles, MissingFileDirectoryAndUnknownExtension) {
  TempDir dir;
  const std::string missing = dir.file("absent.obj");
  MeshReadResult result = loadMesh(missing);
  EXPECT_FALSE(result.ok());
  EXPECT_EQ(result.message, missing + ": no such file");

  const std::string folder = dir.file("folder.stl");
  std::filesystem::create_directories(folder);
  result = loadMesh(folder);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.message.find(folder), std::string::npos);
  EXPECT_NE(result.message.find("directory"), std::string::npos);

  result = loadMesh(dir.write("noext", "v 0 0 0\n"));
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.message.find("extension"), std::string::npos);
}

// Every prefix of every valid cube file reads as a mesh or as an error naming the file.
TEST(CorruptFiles, EveryTruncationOfValidFilesFailsCleanly) {
  const std::vector<std::pair<MeshFormat, std::string>> files = {
      {MeshFormat::Obj, test::cubeObj()},
      {MeshFormat::Off, test::cubeOff()},
      {MeshFormat::Stl, test::cubeStlAscii()},
      {MeshFormat::Stl, test::cubeStlBinary("solid but binary")},
      {MeshFormat::Ply, test::cubePlyAscii()},
      {MeshFormat::Ply, test::cubePlyBinary(true)},
      {MeshFormat::Gltf, test::cubeGltf()},
  };
  for (const auto& [format, bytes] : files) {
    const size_t step = std::max<size_t>(1, bytes.size() / 400);
    for (size_t length = 0; length < bytes.size(); length += step) {
      const std::span<const uint8_t> prefix(reinterpret_cast<const uint8_t*>(bytes.data()), length);
      const MeshReadResult result = readMeshFromMemory(prefix, format, "prefix");
      if (result.ok()) {
        EXPECT_GT(result.mesh.triangleCount(), 0u);
      } else {
        EXPECT_EQ(result.message.rfind("prefix", 0), 0u) << result.message;
      }
    }
  }
}

// Flipping single bytes of binary files never crashes and never reads out of bounds (run under
// the sanitizer build for the second half of that promise).
TEST(CorruptFiles, ByteFlipsOfBinaryFilesFailCleanlyOrStayValid) {
  geometry::MeshData mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  std::vector<uint8_t> glb;
  ASSERT_TRUE(writeGlbToMemory(mesh, MeshWriteOptions{}, glb).ok());
  const std::string stl = test::cubeStlBinary("solid");
  const std::string ply = test::cubePlyBinary(false);
  const std::vector<std::pair<MeshFormat, std::vector<uint8_t>>> files = {
      {MeshFormat::Glb, glb},
      {MeshFormat::Stl, std::vector<uint8_t>(stl.begin(), stl.end())},
      {MeshFormat::Ply, std::vector<uint8_t>(ply.begin(), ply.end())},
  };
  for (const auto& [format, original] : files) {
    for (size_t i = 0; i < original.size(); i += 3) {
      std::vector<uint8_t> bytes = original;
      bytes[i] ^= 0xff;
      const MeshReadResult result = readMeshFromMemory(bytes, format, "flipped");
      EXPECT_TRUE(result.ok() || result.message.rfind("flipped", 0) == 0) << result.message;
    }
  }
}

}  // namespace
}  // namespace cleave::assets
