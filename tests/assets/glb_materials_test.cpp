// SPDX-License-Identifier: MIT
// GLB pieces keep their materials. The model loader keeps a glTF file's images as the bytes the
// file stores (with their mime type), its textures, samplers and material properties; the static
// and the skinned GLB writers copy them (MeshWriteOptions::materials) into the pieces of a cut, the
// cap keeping its own plain material; cleave-split does so for a glTF input, with and without
// --pose. The textured input is made here (a cube with two PNG images encoded by the test); the
// shared Fox.glb is cut too when it is there, and the Khronos validator checks the pieces when it
// is installed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "cleave/anim/animation_clip.h"
#include "cleave/anim/skeleton.h"
#include "cleave/assets/model.h"
#include "cleave/assets/procedural_character.h"
#include "cleave/geometry/mesh_splitter.h"
#include "tests/assets/asset_test_files.h"
#include "tests/assets/tool_runner.h"

namespace cleave::assets {
namespace {

using test::putU32;
using test::quote;
using test::runCommand;
using test::splitTool;
using test::TempDir;

// ---- A PNG encoded here ----

void putBigEndian(std::string& s, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) s += static_cast<char>((v >> shift) & 0xff);
}

uint32_t crc32(std::string_view bytes) {
  uint32_t crc = 0xffffffffu;
  for (const char byte : bytes) {
    crc ^= static_cast<uint8_t>(byte);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void addPngChunk(std::string& png, const std::string& type, const std::string& data) {
  putBigEndian(png, static_cast<uint32_t>(data.size()));
  png += type + data;
  putBigEndian(png, crc32(type + data));
}

uint8_t pixelValue(int x, int y, int channel, uint8_t seed) {
  return static_cast<uint8_t>(seed + 40 * x + 70 * y + 25 * channel);
}

// A width x height RGBA8 PNG (values from pixelValue) in one stored, uncompressed deflate block: a
// valid file made without an encoder from elsewhere. Small images only (one block).
std::string makePng(int width, int height, uint8_t seed) {
  std::string raw;
  for (int y = 0; y < height; ++y) {
    raw += '\0';  // filter: none
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 4; ++c) raw += static_cast<char>(pixelValue(x, y, c, seed));
  }
  const uint32_t length = static_cast<uint32_t>(raw.size());
  std::string zlib = "\x78\x01\x01";  // zlib header, then a final stored block
  for (const uint32_t v : {length, ~length}) {
    zlib += static_cast<char>(v & 0xff);
    zlib += static_cast<char>((v >> 8) & 0xff);
  }
  zlib += raw;
  uint32_t a = 1, b = 0;
  for (const char byte : raw) {
    a = (a + static_cast<uint8_t>(byte)) % 65521;
    b = (b + a) % 65521;
  }
  putBigEndian(zlib, (b << 16) | a);
  std::string header;
  putBigEndian(header, static_cast<uint32_t>(width));
  putBigEndian(header, static_cast<uint32_t>(height));
  header += std::string("\x08\x06\x00\x00\x00", 5);  // 8 bits, RGBA, deflate, no interlace
  std::string png = "\x89PNG\r\n\x1a\n";
  addPngChunk(png, "IHDR", header);
  addPngChunk(png, "IDAT", zlib);
  addPngChunk(png, "IEND", "");
  return png;
}

std::vector<uint8_t> bytesOf(const std::string& s) { return {s.begin(), s.end()}; }

// ---- The textured cube ----

// The cube's two images: the base colour (4 x 4) and the normal map (2 x 2).
struct CubeImages {
  std::string base = makePng(4, 4, 10);
  std::string normal = makePng(2, 2, 200);
};

const CubeImages& cubeImages() {
  static const CubeImages images;
  return images;
}

// Where the cube file keeps its images: in buffer views of its binary chunk (GLB), or in files
// beside it ("base.png", "normal.png"; a .gltf with its buffer in a data: URI).
enum class ImageStorage { BufferViews, Files };

// The cube's buffer: 8 corners, their uvs and 36 ushort indices, then (BufferViews) the images.
std::string cubeBuffer(ImageStorage storage) {
  std::string bin;
  for (const auto& c : test::kCubeCorners)
    for (float v : c) test::putF32(bin, v);
  for (const auto& c : test::kCubeCorners) {
    test::putF32(bin, c[0] + 0.5f * c[2]);
    test::putF32(bin, c[1]);
  }
  for (const auto& t : test::cubeTriangles()) {
    for (int k : t) {
      bin += static_cast<char>(k);
      bin += '\0';
    }
  }
  if (storage == ImageStorage::BufferViews) bin += cubeImages().base + cubeImages().normal;
  while (bin.size() % 4 != 0) bin += '\0';
  return bin;
}

// The cube's JSON: material "painted" with a base colour texture (texture 0, image 0, a NEAREST /
// LINEAR sampler that clamps s and mirrors t), a normal texture (texture 1, image 1, default
// sampler, scale 0.5), factors and doubleSided. The buffer is the GLB's (no uri) or `bufferUri`.
std::string cubeJson(ImageStorage storage, size_t bufferBytes, const std::string& bufferUri) {
  const size_t base = cubeImages().base.size(), normal = cubeImages().normal.size();
  const bool views = storage == ImageStorage::BufferViews;
  std::string json = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)"
                     R"("nodes":[{"name":"cube","mesh":0}],"meshes":[{"primitives":[{"attributes":)"
                     R"({"POSITION":0,"TEXCOORD_0":1},"indices":2,"material":0}]}],)"
                     R"("materials":[{"name":"painted","doubleSided":true,"pbrMetallicRoughness":)"
                     R"({"baseColorFactor":[0.8,0.6,0.4,1],"metallicFactor":0.25,)"
                     R"("roughnessFactor":0.75,"baseColorTexture":{"index":0}},)"
                     R"("normalTexture":{"index":1,"scale":0.5}}],)"
                     R"("textures":[{"sampler":0,"source":0},{"source":1}],)"
                     R"("samplers":[{"magFilter":9728,"minFilter":9729,)"
                     R"("wrapS":33071,"wrapT":33648}],)";
  json += views ? R"("images":[{"bufferView":3,"mimeType":"image/png","name":"base"},)"
                  R"({"bufferView":4,"mimeType":"image/png","name":"normal"}],)"
                : R"("images":[{"uri":"base.png"},{"uri":"normal.png"}],)";
  json += R"("accessors":[{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3",)"
          R"("min":[0,0,0],"max":[1,1,1]},{"bufferView":1,"componentType":5126,"count":8,)"
          R"("type":"VEC2"},{"bufferView":2,"componentType":5123,"count":36,"type":"SCALAR"}],)"
          R"("bufferViews":[{"buffer":0,"byteLength":96},{"buffer":0,"byteOffset":96,)"
          R"("byteLength":64},{"buffer":0,"byteOffset":160,"byteLength":72})";
  if (views) {
    json += R"(,{"buffer":0,"byteOffset":232,"byteLength":)" + std::to_string(base) +
            R"(},{"buffer":0,"byteOffset":)" + std::to_string(232 + base) +
            R"(,"byteLength":)" + std::to_string(normal) + "}";
  }
  json += R"(],"buffers":[{"byteLength":)" + std::to_string(bufferBytes);
  if (!bufferUri.empty()) json += R"(,"uri":")" + bufferUri + '"';
  return json + "}]}";
}

// A GLB container: the JSON chunk (padded with spaces) and the binary chunk.
std::string glbFile(std::string json, const std::string& bin) {
  while (json.size() % 4 != 0) json += ' ';
  std::string glb = "glTF";
  putU32(glb, 2);
  putU32(glb, static_cast<uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
  putU32(glb, static_cast<uint32_t>(json.size()));
  glb += "JSON" + json;
  putU32(glb, static_cast<uint32_t>(bin.size()));
  glb += std::string("BIN\0", 4) + bin;
  return glb;
}

std::string writeCubeGlb(const TempDir& dir) {
  const std::string bin = cubeBuffer(ImageStorage::BufferViews);
  return dir.write("cube.glb", glbFile(cubeJson(ImageStorage::BufferViews, bin.size(), ""), bin));
}

std::string writeCubeGltfWithImageFiles(const TempDir& dir) {
  const std::string bin = cubeBuffer(ImageStorage::Files);
  dir.write("base.png", cubeImages().base);
  dir.write("normal.png", cubeImages().normal);
  const std::string uri = "data:application/octet-stream;base64," + test::base64(bin);
  return dir.write("cube.gltf", cubeJson(ImageStorage::Files, bin.size(), uri));
}

// ---- What a model read back must hold ----

const ModelMaterial* findMaterial(const Model& model, const std::string& name) {
  for (const ModelMaterial& m : model.materials) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

// The model has the cube's material "painted" with both textures (the only ones of the file:
// textures 0 and 1), their samplers and the images' bytes exactly as the cube file stores them.
void expectPaintedMaterial(const Model& model) {
  const ModelMaterial* painted = findMaterial(model, "painted");
  ASSERT_NE(painted, nullptr);
  const ModelMaterial& m = *painted;
  EXPECT_TRUE(m.doubleSided);
  EXPECT_EQ(m.baseColorFactor, glm::vec4(0.8f, 0.6f, 0.4f, 1.f));
  EXPECT_EQ(m.metallicFactor, 0.25f);
  EXPECT_EQ(m.roughnessFactor, 0.75f);
  EXPECT_EQ(m.normalScale, 0.5f);
  ASSERT_EQ(model.textures.size(), 2u);
  EXPECT_EQ(m.baseColorTexture.texture, 0);
  EXPECT_EQ(m.baseColorTexture.texCoord, 0);
  EXPECT_EQ(m.normalTexture.texture, 1);
  EXPECT_EQ(m.normalTexture.texCoord, 0);
  const ModelTexture& base = model.textures[0];
  const ModelTexture& normal = model.textures[1];
  ASSERT_GE(base.image, 0);
  ASSERT_GE(normal.image, 0);
  EXPECT_EQ(m.baseColorImage, base.image);
  EXPECT_EQ(m.normalImage, normal.image);
  const ModelImage& baseImage = model.images[static_cast<size_t>(base.image)];
  EXPECT_EQ(baseImage.mimeType, "image/png");
  EXPECT_EQ(baseImage.encoded, bytesOf(cubeImages().base)) << "the same bytes, not re-encoded";
  EXPECT_EQ(baseImage.width, 4);
  EXPECT_EQ(model.images[static_cast<size_t>(normal.image)].encoded, bytesOf(cubeImages().normal));
  ASSERT_GE(base.sampler, 0);
  const ModelSampler& sampler = model.samplers[static_cast<size_t>(base.sampler)];
  EXPECT_EQ(sampler.magFilter, 9728);
  EXPECT_EQ(sampler.minFilter, 9729);
  EXPECT_EQ(sampler.wrapS, 33071);
  EXPECT_EQ(sampler.wrapT, 33648);
  EXPECT_EQ(normal.sampler, -1);
}

// The material named "cap" is there and plain: no texture, one-sided.
void expectPlainCap(const Model& model) {
  size_t caps = 0;
  for (const ModelMaterial& m : model.materials) {
    if (m.name != "cap") continue;
    ++caps;
    EXPECT_EQ(m.baseColorTexture.texture, -1);
    EXPECT_EQ(m.normalTexture.texture, -1);
    EXPECT_FALSE(m.doubleSided);
  }
  EXPECT_EQ(caps, 1u);
}

ModelLoadResult readGlb(const std::vector<uint8_t>& bytes) {
  return readModelFromMemory(std::span<const uint8_t>(bytes.data(), bytes.size()), "piece.glb");
}

// The cube read with the model loader, cut by y = 0.5 into two capped pieces (cap material 1).
std::vector<geometry::SplitPiece> cutCube(const Model& cube) {
  geometry::MeshContainer container;
  EXPECT_EQ(container.setMesh(cube.meshes.at(0).mesh).code, geometry::SplitStatus::Ok);
  geometry::SplitOptions options;
  options.capMaterialId = 1;
  geometry::SplitResult result;
  geometry::makeConcaveSplitter()->split(container, geometry::Plane{{0, 1, 0}, 0.5}, options,
                                         result);
  EXPECT_EQ(result.status, geometry::SplitStatus::Ok) << result.message;
  EXPECT_EQ(result.pieces.size(), 2u);
  return result.pieces;
}

MeshWriteOptions cubeWriteOptions(const Model& cube) {
  MeshWriteOptions options;
  options.capMaterialId = 1;
  options.materialNames = {"painted"};
  options.materials = cube.materialSource();
  return options;
}

// ---- The loader and the writers ----

TEST(ModelMaterials, LoaderKeepsImagesAsTheFileStoresThemWithTexturesAndSamplers) {
  TempDir dir;
  for (const std::string& path : {writeCubeGlb(dir), writeCubeGltfWithImageFiles(dir)}) {
    SCOPED_TRACE(path);
    const ModelLoadResult loaded = loadModel(path);
    ASSERT_TRUE(loaded.ok()) << loaded.message;
    EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
    expectPaintedMaterial(loaded.model);
    // Decoded too, for the renderer: the pixels the PNG was made of.
    const ModelImage& base = loaded.model.images[0];
    ASSERT_EQ(base.rgba.size(), 4u * 4u * 4u);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 4; ++c)
          ASSERT_EQ(base.rgba[size_t((y * 4 + x) * 4 + c)], pixelValue(x, y, c, 10));
  }
}

TEST(GlbMaterials, StaticPiecesKeepTheTexturesImageBytesAndDoubleSided) {
  TempDir dir;
  const ModelLoadResult cube = loadModel(writeCubeGlb(dir));
  ASSERT_TRUE(cube.ok()) << cube.message;
  for (const geometry::SplitPiece& piece : cutCube(cube.model)) {
    std::vector<uint8_t> bytes;
    const MeshWriteResult written =
        writeGlbToMemory(piece.mesh, cubeWriteOptions(cube.model), bytes);
    ASSERT_TRUE(written.ok()) << written.message;
    const ModelLoadResult loaded = readGlb(bytes);
    ASSERT_TRUE(loaded.ok()) << loaded.message;
    ASSERT_EQ(loaded.model.meshes.size(), 1u);
    const geometry::MeshData& mesh = loaded.model.meshes[0].mesh;
    EXPECT_EQ(mesh.triangleCount(), piece.mesh.triangleCount());
    EXPECT_EQ(mesh.uv0.size(), mesh.vertexCount()) << "TEXCOORD_0 for the textures";
    expectPaintedMaterial(loaded.model);
    expectPlainCap(loaded.model);
    EXPECT_EQ(loaded.model.images.size(), 2u) << "each image once";
  }
}

// The procedural character with uvs, and skinned write options that give it the cube's material as
// material 0 and, to show that the cap never takes a source material, as material 1 (the cap) too.
struct TexturedCharacter {
  explicit TexturedCharacter(const Model& cube) : materials{cube.materials[0], cube.materials[0]} {
    mesh.uv0.clear();
    for (const glm::vec3& p : mesh.positions) mesh.uv0.emplace_back(p.x + p.z, p.y);
    options = cubeWriteOptions(cube);
    options.materialNames = {"painted", "cap", "shirt", "trousers", "shoes"};
    options.materialColors = character.materialColors;
    options.materials.materials = materials;
  }
  TexturedCharacter(const TexturedCharacter&) = delete;  // options views `materials`
  TexturedCharacter& operator=(const TexturedCharacter&) = delete;

  MeshWriteResult write(const std::string& path) const {
    return writeSkinnedGlb(path, mesh, character.skeleton, clips, options);
  }

  ProceduralCharacter character = makeProceduralCharacter();
  geometry::MeshData mesh = character.mesh;
  std::vector<ModelMaterial> materials;
  std::vector<anim::AnimationClip> clips = {character.idle, character.walk};
  MeshWriteOptions options;
};

// Pieces of the textured character cut in its walk pose, each with a cap (material 1).
std::vector<geometry::SplitPiece> cutCharacter(const TexturedCharacter& textured) {
  anim::Pose pose;
  anim::sampleClip(textured.character.skeleton, textured.character.walk, 0.3f, true, pose);
  std::vector<glm::mat4> joints;
  anim::poseToJointMatrices(textured.character.skeleton, pose, joints);
  geometry::MeshContainer container;
  EXPECT_EQ(container.setMesh(textured.mesh).code, geometry::SplitStatus::Ok);
  EXPECT_EQ(container.setSkinningPose(joints, glm::mat4(1.f)).code, geometry::SplitStatus::Ok);
  geometry::SplitResult result;
  geometry::makeConcaveSplitter()->split(container, geometry::Plane{{0.2, 1, 0.1}, 1.0},
                                         geometry::SplitOptions{}, result);
  EXPECT_EQ(result.status, geometry::SplitStatus::Ok) << result.message;
  EXPECT_GE(result.pieces.size(), 2u);
  return result.pieces;
}

TEST(GlbMaterials, SkinnedWriterCopiesTheSourceMaterialsButNotOntoTheCap) {
  TempDir dir;
  const ModelLoadResult cube = loadModel(writeCubeGlb(dir));
  ASSERT_TRUE(cube.ok()) << cube.message;
  const TexturedCharacter textured(cube.model);
  const MeshWriteResult written = textured.write(dir.file("character.glb"));
  ASSERT_TRUE(written.ok()) << written.message;
  const ModelLoadResult loaded = loadModel(dir.file("character.glb"));
  ASSERT_TRUE(loaded.ok()) << loaded.message;
  ASSERT_EQ(loaded.model.skins.size(), 1u);
  expectPaintedMaterial(loaded.model);
  // Ids the source does not have keep their colours, as without a source.
  bool shirt = false;
  for (const ModelMaterial& m : loaded.model.materials) {
    if (m.name != "shirt") continue;
    shirt = true;
    EXPECT_EQ(m.baseColorFactor, textured.character.materialColors[2]);
    EXPECT_EQ(m.baseColorTexture.texture, -1);
  }
  EXPECT_TRUE(shirt);
  // Pieces: the cap stays plain although the source has a textured material 1.
  for (const geometry::SplitPiece& piece : cutCharacter(textured)) {
    std::vector<uint8_t> bytes;
    ASSERT_TRUE(writeSkinnedGlbToMemory(piece.mesh, textured.character.skeleton, textured.clips,
                                        textured.options, bytes)
                    .ok());
    const ModelLoadResult read = readGlb(bytes);
    ASSERT_TRUE(read.ok()) << read.message;
    expectPlainCap(read.model);
  }
}

TEST(GlbMaterials, ATextureThePieceCannotUseIsLeftOutAndTheFileStaysValid) {
  TempDir dir;
  const ModelLoadResult cube = loadModel(writeCubeGlb(dir));
  ASSERT_TRUE(cube.ok()) << cube.message;
  const std::vector<geometry::SplitPiece> pieces = cutCube(cube.model);
  ASSERT_FALSE(pieces.empty());
  // Without uvs there is no TEXCOORD_0 to sample with: the factors stay, the textures go.
  geometry::MeshData noUv = pieces[0].mesh;
  noUv.uv0.clear();
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(writeGlbToMemory(noUv, cubeWriteOptions(cube.model), bytes).ok());
  ModelLoadResult loaded = readGlb(bytes);
  ASSERT_TRUE(loaded.ok()) << loaded.message;
  EXPECT_TRUE(loaded.model.materials[0].doubleSided);
  EXPECT_EQ(loaded.model.materials[0].roughnessFactor, 0.75f);
  EXPECT_EQ(loaded.model.materials[0].baseColorTexture.texture, -1);
  EXPECT_TRUE(loaded.model.textures.empty());
  EXPECT_TRUE(loaded.model.images.empty());
  // An image without its encoded bytes cannot be embedded: only the normal map is written, and
  // it becomes texture 0 and image 0 of the piece (what is written is numbered by first use).
  Model source = cube.model;
  source.images[0].encoded.clear();
  MeshWriteOptions options = cubeWriteOptions(cube.model);
  options.materials = source.materialSource();
  ASSERT_TRUE(writeGlbToMemory(pieces[0].mesh, options, bytes).ok());
  loaded = readGlb(bytes);
  ASSERT_TRUE(loaded.ok()) << loaded.message;
  EXPECT_EQ(loaded.model.materials[0].baseColorTexture.texture, -1);
  EXPECT_EQ(loaded.model.materials[0].normalTexture.texture, 0);
  ASSERT_EQ(loaded.model.images.size(), 1u);
  EXPECT_EQ(loaded.model.images[0].encoded, bytesOf(cubeImages().normal));
}

// ---- cleave-split ----

// Cuts `input` into GLB pieces in `out` with `arguments` (the plane, --pose); the files written.
std::vector<std::string> cutToGlbPieces(const std::string& input, const std::string& arguments,
                                        const std::string& out) {
  std::string output;
  const int status = runCommand(quote(splitTool()) + ' ' + quote(input) + ' ' + arguments +
                                    " --out " + quote(out) + " --format glb --json",
                                output);
  EXPECT_EQ(status, 0) << output;
  const nlohmann::json report = nlohmann::json::parse(output, nullptr, false);
  std::vector<std::string> files;
  if (report.is_discarded() || !report.contains("files")) return files;
  for (const auto& file : report["files"]) files.push_back(file.get<std::string>());
  return files;
}

// The pieces cleave-split writes of the cube (static, from the GLB and from the .gltf with image
// files), then those of the textured character (--pose).
struct TexturedPieces {
  std::vector<std::string> cube, character;
};

TexturedPieces texturedPieces(const TempDir& dir) {
  TexturedPieces pieces;
  const std::string glb = writeCubeGlb(dir);
  const ModelLoadResult cube = loadModel(glb);
  EXPECT_TRUE(cube.ok()) << cube.message;
  const std::string gltf = writeCubeGltfWithImageFiles(dir);
  const std::string character = dir.file("character.glb");
  EXPECT_TRUE(TexturedCharacter(cube.model).write(character).ok());
  const std::vector<std::pair<std::string, std::string>> cuts = {
      {glb, "--plane 0 1 0 0.5"},
      {gltf, "--plane 0 1 0 0.5"},
      {character, "--pose walk:0.3 --plane 0.2 1 0.1 1.0"}};
  for (size_t k = 0; k < cuts.size(); ++k) {
    const std::string out = dir.file("pieces_" + std::to_string(k));
    const std::vector<std::string> written = cutToGlbPieces(cuts[k].first, cuts[k].second, out);
    EXPECT_GE(written.size(), 2u) << cuts[k].first;
    std::vector<std::string>& files = k + 1 < cuts.size() ? pieces.cube : pieces.character;
    files.insert(files.end(), written.begin(), written.end());
  }
  return pieces;
}

TEST(CleaveSplitTool, GlbPiecesOfATexturedGltfKeepItsMaterials) {
  if (!std::filesystem::exists(splitTool())) GTEST_SKIP() << "cleave-split not built";
  TempDir dir;
  const TexturedPieces pieces = texturedPieces(dir);
  ASSERT_EQ(pieces.cube.size(), 4u);
  ASSERT_GE(pieces.character.size(), 2u);
  size_t painted = 0;  // character pieces with some of the character's material 0
  for (const std::vector<std::string>* files : {&pieces.cube, &pieces.character}) {
    for (const std::string& file : *files) {
      SCOPED_TRACE(file);
      const ModelLoadResult loaded = loadModel(file);
      ASSERT_TRUE(loaded.ok()) << loaded.message;
      expectPlainCap(loaded.model);
      if (files == &pieces.character && findMaterial(loaded.model, "painted") == nullptr) continue;
      painted += files == &pieces.character ? 1 : 0;
      expectPaintedMaterial(loaded.model);
    }
  }
  EXPECT_GE(painted, 1u);
}

// The same pieces through the Khronos glTF validator (its own test, so that the checks above count
// as passed where the validator is not installed).
TEST(CleaveSplitTool, TexturedGlbPiecesPassTheKhronosValidator) {
  if (!std::filesystem::exists(splitTool())) GTEST_SKIP() << "cleave-split not built";
  std::string why;
  const std::string validator = test::gltfValidatorDir(why);
  if (validator.empty()) GTEST_SKIP() << why;
  TempDir dir;
  const TexturedPieces pieces = texturedPieces(dir);
  std::vector<std::string> files = pieces.cube;
  files.insert(files.end(), pieces.character.begin(), pieces.character.end());
  ASSERT_GE(files.size(), 6u);
  std::string report;
  EXPECT_EQ(test::validateGltf(validator, files, report), 0) << report;
  EXPECT_EQ(std::count(report.begin(), report.end(), '\n'), static_cast<long>(files.size()))
      << report;
  // No error, and no warning but the one the cube itself gets: a normal map on a mesh without
  // tangents (the viewer generates them).
  std::istringstream lines(report);
  for (std::string line; std::getline(lines, line);) {
    const nlohmann::json file = nlohmann::json::parse(line, nullptr, false);
    ASSERT_FALSE(file.is_discarded()) << line;
    EXPECT_EQ(file["errors"], 0) << line;
    for (const auto& message : file["messages"])
      EXPECT_EQ(message.get<std::string>().rfind("MESH_PRIMITIVE_GENERATED_TANGENT_SPACE ", 0), 0u)
          << line;
  }
}

std::filesystem::path modelsFolder() {
  if (const char* env = std::getenv("CLEAVE_MODELS_DIR")) return env;
  return std::filesystem::path(CLEAVE_SOURCE_DIR).parent_path() / "shared" / "models";
}

// Fox.glb of the shared models folder, when it is there: its pieces, static and posed, keep the
// fox's texture (the same PNG bytes, sampler and factors).
TEST(CleaveSplitTool, FoxPiecesKeepTheFoxTexture) {
  if (!std::filesystem::exists(splitTool())) GTEST_SKIP() << "cleave-split not built";
  const std::string fox = (modelsFolder() / "Fox.glb").string();
  if (!std::filesystem::exists(fox)) GTEST_SKIP() << "no " << fox;
  const ModelLoadResult input = loadModel(fox);
  ASSERT_TRUE(input.ok()) << input.message;
  const ModelMaterial& material = input.model.materials.at(0);
  ASSERT_GE(material.baseColorImage, 0);
  const ModelImage& image = input.model.images[static_cast<size_t>(material.baseColorImage)];
  ASSERT_FALSE(image.encoded.empty());
  TempDir dir;
  std::vector<std::string> files = cutToGlbPieces(fox, "--plane 0 1 0 40", dir.file("static"));
  const std::vector<std::string> posed =
      cutToGlbPieces(fox, "--pose Walk:0.3 --plane 0 1 0 40", dir.file("posed"));
  files.insert(files.end(), posed.begin(), posed.end());
  ASSERT_GE(files.size(), 4u);
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    const ModelLoadResult loaded = loadModel(file);
    ASSERT_TRUE(loaded.ok()) << loaded.message;
    const ModelMaterial& piece = loaded.model.materials.at(0);
    EXPECT_EQ(piece.name, material.name);
    EXPECT_EQ(piece.roughnessFactor, material.roughnessFactor);
    EXPECT_EQ(piece.metallicFactor, material.metallicFactor);
    ASSERT_GE(piece.baseColorImage, 0);
    const ModelImage& copy = loaded.model.images[static_cast<size_t>(piece.baseColorImage)];
    EXPECT_EQ(copy.mimeType, image.mimeType);
    EXPECT_EQ(copy.encoded, image.encoded);
    expectPlainCap(loaded.model);
  }
  std::string why;
  const std::string validator = test::gltfValidatorDir(why);
  if (validator.empty()) return;  // the checks above stand on their own
  std::string report;
  EXPECT_EQ(test::validateGltf(validator, files, report), 0) << report;
}

}  // namespace
}  // namespace cleave::assets
