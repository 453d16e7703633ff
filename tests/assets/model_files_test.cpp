// SPDX-License-Identifier: MIT
// Corpus check on real glTF files when the shared models folder is there (skipped otherwise), and the
// cleave-split tool run end to end on a generated cube.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>


#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cleave/assets/mesh_io.h"
#include "cleave/geometry/mass_properties.h"
#include "tests/assets/asset_test_files.h"
#include "tests/assets/tool_runner.h"

namespace cleave::assets {
namespace {

using test::quote;
using test::runCommand;
using test::splitTool;
using test::TempDir;

std::filesystem::path modelsFolder() {
  if (const char* env = std::getenv("CLEAVE_MODELS_DIR")) return env;
  // The shared folder sits beside the repository.
  return std::filesystem::path(CLEAVE_SOURCE_DIR).parent_path() / "shared" / "models";
}

TEST(ModelFiles, SharedGltfModelsLoadStatically) {
  const std::filesystem::path folder = modelsFolder();
  if (!std::filesystem::is_directory(folder)) GTEST_SKIP() << "no models folder at " << folder;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const MeshFormat format = formatFromPath(entry.path().string());
    if (format == MeshFormat::Gltf || format == MeshFormat::Glb) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) GTEST_SKIP() << "no .gltf or .glb files in " << folder;
  for (const std::filesystem::path& file : files) {
    SCOPED_TRACE(file.string());
    const MeshReadResult result = loadMesh(file.string());
    ASSERT_TRUE(result.ok()) << result.message;
    const geometry::MeshData& mesh = result.mesh;
    EXPECT_GT(mesh.triangleCount(), 0u);
    EXPECT_TRUE(mesh.normals.empty() || mesh.normals.size() == mesh.vertexCount());
    EXPECT_TRUE(mesh.uv0.empty() || mesh.uv0.size() == mesh.vertexCount());
    for (const glm::vec3& n : mesh.normals) EXPECT_NEAR(glm::length(n), 1.f, 1e-3f);
    uint32_t covered = 0;
    for (const geometry::SubMesh& sub : mesh.submeshes) {
      EXPECT_EQ(sub.firstIndex, covered);
      EXPECT_LT(sub.materialId, result.materialNames.size());
      covered += sub.indexCount;
    }
    EXPECT_EQ(covered, mesh.indices.size());
    // The same file through memory (no folder) gives the same mesh: these files embed their data.
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const MeshReadResult fromMemory = readMeshFromMemory(
        std::span(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()),
        formatFromPath(file.string()), file.filename().string());
    ASSERT_TRUE(fromMemory.ok()) << fromMemory.message;
    EXPECT_EQ(fromMemory.mesh.positions, mesh.positions);
    EXPECT_EQ(fromMemory.mesh.indices, mesh.indices);
  }
}

TEST(CleaveSplitTool, JsonReportsPiecesWhoseVolumesAddUp) {
  if (!std::filesystem::exists(splitTool())) GTEST_SKIP() << "cleave-split not built";
  TempDir dir;
  const std::string cube = dir.write("cube.obj", test::cubeObj());
  const std::string out = dir.file("pieces");
  std::string output;
  // The plane 2x = 0.6 is x = 0.3 once normalised.
  const int status = runCommand(quote(splitTool()) + ' ' + quote(cube) + " --plane 2 0 0 0.6 --json --repeat 3 --warmup 2 --out " +
                             quote(out) + " 2>&1",
                         output);
  ASSERT_EQ(status, 0) << output;
  const nlohmann::json report = nlohmann::json::parse(output, nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << output;
  EXPECT_EQ(report["input"]["triangles"], 12);
  EXPECT_EQ(report["input"]["closed"], true);
  EXPECT_NEAR(report["input"]["volume"].get<double>(), 1.0, 1e-9);
  EXPECT_EQ(report["input"]["volume_from_hull"], false);
  // The bounds, to choose a plane by.
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(report["input"]["bounds"]["min"][k].get<double>(), 0.0, 1e-6);
    EXPECT_NEAR(report["input"]["bounds"]["max"][k].get<double>(), 1.0, 1e-6);
    EXPECT_NEAR(report["input"]["bounds"]["centre"][k].get<double>(), 0.5, 1e-6);
  }
  ASSERT_EQ(report["pieces"].size(), 2u);
  double total = 0.0;
  for (const auto& piece : report["pieces"]) {
    total += piece["volume"].get<double>();
    EXPECT_EQ(piece["closed"], true);
    EXPECT_GE(piece["cap_triangles"].get<int>(), 2);
    EXPECT_EQ(piece["cap_loops"], 1);
    EXPECT_EQ(piece["inertia"].size(), 6u);
  }
  EXPECT_NEAR(total, 1.0, 1e-6);
  EXPECT_EQ(report["pieces"][0]["side"], "above");
  EXPECT_NEAR(report["pieces"][0]["volume"].get<double>(), 0.7, 1e-6);
  EXPECT_NEAR(report["pieces"][0]["center_of_mass"][0].get<double>(), 0.65, 1e-6);
  EXPECT_EQ(report["timing"]["repeat"], 3) << "the --warmup runs are not timed";
  EXPECT_GE(report["timing"]["split_ms_median"].get<double>(), report["timing"]["split_ms_min"].get<double>());

  // The written pieces read back closed, with a cap material.
  const MeshReadResult above = loadMesh(out + "/piece_0_above.obj");
  ASSERT_TRUE(above.ok()) << above.message;
  EXPECT_TRUE(geometry::isClosedAndOriented(above.mesh.positions, above.mesh.indices));
  EXPECT_NEAR(geometry::computeMassProperties(above.mesh).volume, 0.7, 1e-6);
  EXPECT_NE(std::find(above.materialNames.begin(), above.materialNames.end(), "cap"),
            above.materialNames.end());
  EXPECT_TRUE(std::filesystem::exists(out + "/piece_1_below.obj"));
}

// Unit cubes at the given offsets, as separate parts of one OBJ (no shared vertices).
std::string cubesObj(const std::vector<glm::vec3>& offsets) {
  std::ostringstream s;
  s << "# separate unit cubes\n";
  for (const glm::vec3& o : offsets) {
    for (const auto& c : test::kCubeCorners) s << "v " << c[0] + o.x << ' ' << c[1] + o.y << ' ' << c[2] + o.z << '\n';
  }
  for (size_t k = 0; k < offsets.size(); ++k) {
    for (const auto& quad : test::kCubeQuads) {
      s << 'f';
      for (int v : quad) s << ' ' << 8 * k + v + 1;
      s << '\n';
    }
  }
  return s.str();
}

TEST(CleaveSplitTool, MultiPartArtGivesOnePiecePerSideAndSkipsWhatThePlaneDidNotReach) {
  if (!std::filesystem::exists(splitTool())) GTEST_SKIP() << "cleave-split not built";
  TempDir dir;
  // Two cubes passing into one another, cut by y = 0.5, and a third far above the plane.
  const std::string parts = dir.write("parts.obj", cubesObj({{0, 0, 0}, {0.5f, 0.2f, 0}, {0, 3, 0}}));
  const std::string tool = quote(splitTool()) + ' ' + quote(parts) + " --plane 0 1 0 0.5 --json";
  auto pieces = [&](const std::string& extra, const std::string& out, int& reached) {
    std::string output;
    EXPECT_EQ(runCommand(tool + extra + " --out " + quote(dir.file(out)) + " 2>&1", output), 0) << output;
    const nlohmann::json report = nlohmann::json::parse(output, nullptr, false);
    EXPECT_FALSE(report.is_discarded()) << output;
    reached = 0;
    if (report.is_discarded()) return nlohmann::json::array();
    for (const auto& piece : report["pieces"]) reached += piece["reached"].get<bool>() ? 1 : 0;
    return report["pieces"];
  };
  auto files = [&](const std::string& out) {
    size_t count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir.file(out))) count += entry.is_regular_file();
    return count;
  };
  int reached = 0;
  // touching (the default): one piece per side; the cube above goes with the upper piece.
  const nlohmann::json touching = pieces("", "touching", reached);
  ASSERT_EQ(touching.size(), 2u);
  EXPECT_EQ(reached, 2);
  EXPECT_NEAR(touching[0]["volume"].get<double>(), 1.0 + 0.5 + 0.7, 1e-5);
  EXPECT_EQ(files("touching"), 2u);
  // connected: every part its own piece; the one the plane did not reach is reported, not written.
  const nlohmann::json connected = pieces(" --islands connected", "connected", reached);
  EXPECT_EQ(connected.size(), 5u);
  EXPECT_EQ(reached, 4);
  EXPECT_EQ(files("connected"), 4u);
  pieces(" --islands connected --all-pieces", "all", reached);
  EXPECT_EQ(files("all"), 5u);
  std::string output;
  EXPECT_EQ(runCommand(tool + " --islands some 2>&1", output), 2);
  EXPECT_NE(output.find("--islands must be touching or connected"), std::string::npos) << output;
}

// robot.glb is built of dozens of separate parts that touch or pass into one another. Cut once in a
// pose, it gives one piece per side plus what the cut really separates (a hand, the feet), not one
// piece per part; its parts' mass adds up.
TEST(CleaveSplitTool, PosedRobotCutOnceStaysInAFewPieces) {
  if (!std::filesystem::exists(splitTool())) GTEST_SKIP() << "cleave-split not built";
  const std::filesystem::path robot = modelsFolder() / "robot.glb";
  if (!std::filesystem::exists(robot)) GTEST_SKIP() << "no " << robot;
  const std::string tool =
      quote(splitTool()) + ' ' + quote(robot.string()) + " --pose Robot_Dance:0.5 --plane 0.2 1 0.1 0.5 --json";
  auto report = [&](const std::string& extra) {
    std::string output;
    EXPECT_EQ(runCommand(tool + extra + " 2>&1", output), 0) << output;
    return nlohmann::json::parse(output, nullptr, false);
  };
  const nlohmann::json touching = report(""), connected = report(" --islands connected");
  ASSERT_FALSE(touching.is_discarded() || connected.is_discarded());
  EXPECT_EQ(touching["pieces"].size(), 5u);
  EXPECT_GE(connected["pieces"].size(), 50u);
  double total = 0.0;
  for (const auto& piece : touching["pieces"]) total += piece["volume"].get<double>();
  EXPECT_NEAR(total, touching["input"]["volume"].get<double>(), 1e-6 * total);
}

TEST(CleaveSplitTool, ErrorsGiveOneLineAndTheDocumentedExitCodes) {
  if (!std::filesystem::exists(splitTool())) GTEST_SKIP() << "cleave-split not built";
  TempDir dir;
  const std::string tool = quote(splitTool()) + ' ';
  std::string output;
  EXPECT_EQ(runCommand(tool + "--help", output), 0);
  EXPECT_NE(output.find("usage"), std::string::npos);
  EXPECT_EQ(runCommand(tool + "cube.obj 2>&1", output), 2);  // no plane
  EXPECT_EQ(runCommand(tool + "cube.obj --plane 0 0 0 1 2>&1", output), 2);
  EXPECT_EQ(runCommand(tool + "cube.obj --plane 1 0 0 --json 2>&1", output), 2);
  EXPECT_EQ(runCommand(tool + "cube.obj --plane 1 0 0 0 --bogus 2>&1", output), 2);
  EXPECT_EQ(runCommand(tool + "cube.obj --plane 1 0 0 0 --warmup -1 2>&1", output), 2);
  EXPECT_NE(output.find("--warmup"), std::string::npos) << output;

  const std::string missing = dir.file("missing.obj");
  EXPECT_EQ(runCommand(tool + quote(missing) + " --plane 1 0 0 0 2>&1", output), 1);
  EXPECT_NE(output.find(missing), std::string::npos);
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;

  const std::string corrupt = dir.write("corrupt.stl", std::string(90, '\x01'));
  EXPECT_EQ(runCommand(tool + quote(corrupt) + " --plane 1 0 0 0 2>&1", output), 1);
  EXPECT_NE(output.find(corrupt), std::string::npos);

  // A plane that misses the mesh is a split failure: reported in JSON, exit 1.
  const std::string cube = dir.write("cube.obj", test::cubeObj());
  EXPECT_EQ(runCommand(tool + quote(cube) + " --plane 0 1 0 5 --json 2>/dev/null", output), 1);
  const nlohmann::json report = nlohmann::json::parse(output, nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << output;
  EXPECT_TRUE(report.contains("message"));  // only present when the split failed
  EXPECT_TRUE(report["pieces"].empty());
  // In text, the failure is told once (on stderr), with the bounds and the offsets that would cut.
  std::string text, errors;
  EXPECT_EQ(runCommand(tool + quote(cube) + " --plane 0 1 0 5 2>/dev/null", text), 1);
  EXPECT_EQ(text.find("status:"), std::string::npos) << text;
  EXPECT_NE(text.find("bounds: (0, 0, 0) to (1, 1, 1), centre (0.5, 0.5, 0.5)"), std::string::npos) << text;
  EXPECT_EQ(runCommand(tool + quote(cube) + " --plane 0 1 0 5 2>&1 >/dev/null", errors), 1);
  EXPECT_EQ(std::count(errors.begin(), errors.end(), '\n'), 1) << errors;
  EXPECT_NE(errors.find("an offset between 0 and 1 crosses its box"), std::string::npos) << errors;
}

}  // namespace
}  // namespace cleave::assets
