// Corpus test over real models that the set-up installs from Debian packages (see
// tools/install-deps.sh): the meshes of CGAL's data set (libcgal-demo ships them as
// /usr/share/doc/libcgal-dev/data.tar.gz, unpacked here with tar) and assimp's test models
// (assimp-testmodels, /usr/share/assimp/models, broken files included), plus the shared models
// folder beside the repository when it is there. Every source that is missing is skipped with the
// reason; the test skips as a whole only when none is there.
//
// Every file is read. A file that does not read must give a one-line error naming the file, and so
// must (or read fine) each truncation of it; nothing may crash. A mesh that reads is split by
// several planes through its bounding box:
//  - closed input, with caps: either Ok, with every piece closed and consistently oriented, the
//    piece volumes summing to the input volume within 1e-6 relative, the cap area on each side equal
//    to the section area computed independently within 1e-6 relative, and no vertex on the wrong
//    side beyond the tolerance; or a refusal (OpenSection, TriangulationFailed: real meshes can
//    intersect themselves) with a message and no pieces;
//  - open input, hollow mode: Ok (or PlaneMissesMesh), the piece areas summing to the input area.
// The counts are printed, and recorded as test properties.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <sys/wait.h>

#include <gtest/gtest.h>

#include "engine/assets/mesh_io.h"
#include "engine/geometry/mass_properties.h"
#include "engine/geometry/mesh_splitter.h"
#include "tests/assets/asset_test_files.h"
#include "tests/geometry/test_meshes.h"

namespace cleave::assets {
namespace {

namespace fs = std::filesystem;
using geometry::MeshContainer;
using geometry::MeshData;
using geometry::Plane;
using geometry::SplitOptions;
using geometry::SplitResult;
using geometry::SplitStatus;

constexpr const char* kCgalArchive = "/usr/share/doc/libcgal-dev/data.tar.gz";
constexpr const char* kAssimpModels = "/usr/share/assimp/models";
// Meshes above this size are read and checked but split by fewer planes, to keep the run short.
constexpr size_t kLargeTriangles = 200000;

bool readable(const fs::path& path) {
  const MeshFormat format = formatFromPath(path.string());
  return format != MeshFormat::Unknown;
}

void collect(const fs::path& root, std::vector<fs::path>& files) {
  std::error_code ec;
  for (fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec), end;
       !ec && it != end; it.increment(ec)) {
    if (it->is_regular_file(ec) && readable(it->path())) files.push_back(it->path());
  }
}

fs::path sharedModels() {
  if (const char* env = std::getenv("CLEAVE_MODELS_DIR")) return env;
  return fs::path(CLEAVE_SOURCE_DIR).parent_path() / "shared" / "models";
}

// Three axis planes and two oblique ones through points of the box, none through its centre exactly
// (real meshes are often symmetric about it, with whole vertex rings on such a plane).
std::vector<Plane> planesThrough(const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 size = hi - lo;
  auto at = [&](double fx, double fy, double fz) { return lo + size * glm::dvec3(fx, fy, fz); };
  auto plane = [](glm::dvec3 n, const glm::dvec3& point) {
    n = glm::normalize(n);
    return Plane{n, glm::dot(n, point)};
  };
  return {
      plane({1, 0, 0}, at(0.5137, 0.5, 0.5)),
      plane({0, 1, 0}, at(0.5, 0.4719, 0.5)),
      plane({0, 0, 1}, at(0.5, 0.5, 0.5291)),
      plane({0.31, 0.77, -0.22}, at(0.43, 0.57, 0.61)),
      plane({-0.64, 0.18, 0.75}, at(0.37, 0.41, 0.66)),
  };
}

struct Tally {
  size_t files = 0, loaded = 0, rejected = 0, truncations = 0;
  size_t closedMeshes = 0, openMeshes = 0, splitMeshes = 0;
  size_t splitsOk = 0, refused = 0, missed = 0, piecesChecked = 0;
  std::map<std::string, size_t> refusals;
  std::vector<std::string> refusedCases, rejectedFiles;
};

void expectCleanError(const MeshReadResult& result, const std::string& name) {
  EXPECT_FALSE(result.error.empty());
  EXPECT_EQ(result.error.find('\n'), std::string::npos) << result.error;
  EXPECT_NE(result.error.find(name), std::string::npos) << "the error does not name the file: " << result.error;
  EXPECT_TRUE(result.mesh.positions.empty() && result.mesh.indices.empty());
}

// Truncations of the file's bytes read from memory: a clean error or a mesh, never a crash.
void checkTruncations(const fs::path& file, Tally& tally) {
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  if (ec || size > (1u << 20)) return;
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const MeshFormat format = formatFromPath(file.string());
  const std::string name = file.filename().string();
  for (size_t cut : {bytes.size() / 7, bytes.size() / 2, bytes.size() - bytes.size() / 9}) {
    if (cut >= bytes.size()) continue;
    const MeshReadResult result =
        readMeshFromMemory(std::span(reinterpret_cast<const uint8_t*>(bytes.data()), cut), format, name);
    ++tally.truncations;
    if (!result.ok) expectCleanError(result, name);
  }
}

double surfaceArea(std::span<const glm::dvec3> p, std::span<const uint32_t> indices) {
  double area = 0.0;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    area += geometry::testing::triangleArea(p[indices[t]], p[indices[t + 1]], p[indices[t + 2]]);
  }
  return area;
}

// Total length of the intersection segments of the triangles with the plane (exact classification).
double sectionLength(std::span<const glm::dvec3> p, std::span<const uint32_t> indices, const Plane& plane) {
  double length = 0.0;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    glm::dvec3 points[2];
    int found = 0;
    for (int e = 0; e < 3 && found < 2; ++e) {
      const glm::dvec3 a = p[indices[t + e]], b = p[indices[t + (e + 1) % 3]];
      const double da = glm::dot(plane.normal, a) - plane.offset, db = glm::dot(plane.normal, b) - plane.offset;
      if ((da > 0.0) != (db > 0.0)) points[found++] = a + (da / (da - db)) * (b - a);
    }
    if (found == 2) length += glm::length(points[1] - points[0]);
  }
  return length;
}

void splitAndCheck(const std::string& name, const MeshData& mesh, Tally& tally) {
  MeshContainer container;
  std::string why;
  if (container.setMesh(mesh, &why) != SplitStatus::Ok) {
    ADD_FAILURE() << name << ": the reader returned a mesh the container refuses: " << why;
    return;
  }
  const std::span<const glm::dvec3> cut = container.cutPositions();
  glm::dvec3 lo, hi;
  geometry::testing::bounds(cut, lo, hi);
  const double diagonal = glm::length(hi - lo);
  if (!(diagonal > 0.0)) return;
  const bool closed = container.closed();
  ++(closed ? tally.closedMeshes : tally.openMeshes);
  ++tally.splitMeshes;
  const double inputVolume = geometry::integrateClosedSurface(cut, mesh.indices, false).volume;
  const double orientation = inputVolume < 0.0 ? -1.0 : 1.0;
  const double inputArea = surfaceArea(cut, mesh.indices);
  // Pieces are written as float in the source space: a coordinate of magnitude M carries a rounding
  // of up to M * 2^-24, which for a small mesh far from the origin exceeds the cut tolerance.
  double magnitude = 0.0;
  for (const glm::dvec3& q : cut) magnitude = std::max({magnitude, std::abs(q.x), std::abs(q.y), std::abs(q.z)});
  const double rounding = 2.0 * magnitude * 0x1.0p-24;

  SplitOptions options;
  options.cap = closed;
  uint32_t capMaterial = 1;
  for (const geometry::SubMesh& run : mesh.submeshes) capMaterial = std::max(capMaterial, run.materialId + 1);
  options.capMaterialId = capMaterial;
  const double tolerance = options.relativeTolerance * diagonal;

  auto splitter = geometry::makeConcaveSplitter();
  std::vector<Plane> planes = planesThrough(lo, hi);
  if (mesh.triangleCount() > kLargeTriangles) planes.resize(2);
  for (size_t k = 0; k < planes.size(); ++k) {
    const Plane& plane = planes[k];
    SCOPED_TRACE(name + ", plane " + std::to_string(k));
    SplitResult result;
    const SplitStatus status = splitter->split(container, plane, options, result);
    if (status == SplitStatus::PlaneMissesMesh) {
      ++tally.missed;
      EXPECT_TRUE(result.pieces.empty());
      continue;
    }
    if (status != SplitStatus::Ok) {
      // Only a closed mesh that intersects itself at the cut may be refused, with a reason.
      EXPECT_TRUE(closed) << "hollow split refused: " << result.message;
      EXPECT_TRUE(status == SplitStatus::OpenSection || status == SplitStatus::TriangulationFailed)
          << geometry::toString(status) << ": " << result.message;
      EXPECT_FALSE(result.message.empty());
      EXPECT_TRUE(result.pieces.empty());
      ++tally.refused;
      ++tally.refusals[geometry::toString(status)];
      tally.refusedCases.push_back(name + " plane " + std::to_string(k) + ": " + result.message);
      continue;
    }
    ++tally.splitsOk;
    EXPECT_GE(result.pieces.size(), 2u);
    double volumeSum = 0.0, areaSum = 0.0, capAbove = 0.0, capBelow = 0.0;
    for (const geometry::SplitPiece& piece : result.pieces) {
      ++tally.piecesChecked;
      const std::vector<glm::dvec3> p = geometry::testing::toCutSpace(piece.mesh, glm::dmat4(1.0));
      // No vertex on the wrong side beyond the tolerance (plus float rounding of the output).
      double worst = 0.0;
      for (const glm::dvec3& q : p) {
        worst = std::max(worst, -double(piece.side) * (glm::dot(plane.normal, q) - plane.offset));
      }
      EXPECT_LE(worst, tolerance + rounding + 1e-9 * diagonal) << "a vertex lies on the wrong side";
      if (closed) {
        EXPECT_TRUE(geometry::testing::closedAndOriented(p, piece.mesh.indices, 1e-7 * diagonal));
        volumeSum += piece.mass.volume;
        const double cap = geometry::testing::capArea(piece.mesh, options.capMaterialId, glm::dmat4(1.0));
        (piece.side > 0 ? capAbove : capBelow) += cap;
      } else {
        areaSum += surfaceArea(p, piece.mesh.indices);
      }
    }
    if (closed) {
      EXPECT_NEAR(volumeSum, inputVolume, 1e-6 * std::abs(inputVolume)) << "piece volumes do not add up";
      const double section = orientation * geometry::testing::sectionArea(cut, mesh.indices, plane);
      EXPECT_NEAR(capAbove, section, 1e-6 * section + 1e-9 * diagonal * diagonal) << "cap above vs section";
      EXPECT_NEAR(capBelow, section, 1e-6 * section + 1e-9 * diagonal * diagonal) << "cap below vs section";
    } else {
      // Each new vertex may move by the output rounding: bounded by that times the section length.
      const double length = sectionLength(cut, mesh.indices, plane);
      EXPECT_NEAR(areaSum, inputArea, 1e-6 * inputArea + 2.0 * rounding * length)
          << "hollow pieces do not keep the surface area";
    }
  }
}

void runFile(const fs::path& file, Tally& tally) {
  const std::string name = file.filename().string();
  SCOPED_TRACE(file.string());
  ++tally.files;
  const MeshReadResult result = loadMesh(file.string());
  checkTruncations(file, tally);
  if (!result.ok) {
    ++tally.rejected;
    tally.rejectedFiles.push_back(result.error);
    expectCleanError(result, name);
    return;
  }
  ++tally.loaded;
  splitAndCheck(name, result.mesh, tally);
}

TEST(Corpus, PackagedRealModelsReadAndSplitWithTheInvariants) {
  std::vector<std::string> notes;
  std::vector<fs::path> files;

  // CGAL's meshes, unpacked from the archive the package ships.
  test::TempDir unpacked;
  if (fs::exists(kCgalArchive)) {
    const std::string command = "tar -xzf '" + std::string(kCgalArchive) + "' -C '" + unpacked.path().string() +
                                "' --wildcards '*.off' '*.obj' '*.ply' '*.stl' 2>/dev/null";
    // tar exits non-zero when one of the patterns matches nothing; what counts is what was unpacked.
    const int status = std::system(command.c_str());
    const size_t before = files.size();
    collect(unpacked.path(), files);
    if (files.size() == before) {
      notes.push_back("nothing unpacked from " + std::string(kCgalArchive) + " (tar status " +
                      std::to_string(status) + ")");
    } else {
      notes.push_back("libcgal-demo: " + std::to_string(files.size() - before) + " mesh files");
    }
  } else {
    notes.push_back("libcgal-demo not installed (no " + std::string(kCgalArchive) + ")");
  }
  if (fs::is_directory(kAssimpModels)) {
    const size_t before = files.size();
    collect(kAssimpModels, files);
    notes.push_back("assimp-testmodels: " + std::to_string(files.size() - before) + " files");
  } else {
    notes.push_back("assimp-testmodels not installed (no " + std::string(kAssimpModels) + ")");
  }
  if (fs::is_directory(sharedModels())) {
    const size_t before = files.size();
    collect(sharedModels(), files);
    notes.push_back("shared models: " + std::to_string(files.size() - before) + " files");
  } else {
    notes.push_back("no shared models folder");
  }
  std::string summary;
  for (const std::string& note : notes) summary += note + "; ";
  if (files.empty()) GTEST_SKIP() << "no corpus installed: " << summary << "run tools/install-deps.sh";
  std::sort(files.begin(), files.end());

  Tally tally;
  for (const fs::path& file : files) runFile(file, tally);

  std::string refusals;
  for (const auto& [status, count] : tally.refusals) refusals += " " + status + "=" + std::to_string(count);
  std::printf("[ corpus   ] %s\n", summary.c_str());
  std::printf("[ corpus   ] %zu files: %zu read, %zu rejected with an error; %zu truncations read\n", tally.files,
              tally.loaded, tally.rejected, tally.truncations);
  std::printf("[ corpus   ] %zu meshes split (%zu closed with caps, %zu open hollow): %zu splits ok, %zu "
              "refused (%s ), %zu planes missed; %zu pieces checked\n",
              tally.splitMeshes, tally.closedMeshes, tally.openMeshes, tally.splitsOk, tally.refused,
              refusals.empty() ? " none" : refusals.c_str(), tally.missed, tally.piecesChecked);
  if (std::getenv("CLEAVE_CORPUS_VERBOSE")) {
    for (const std::string& line : tally.rejectedFiles) std::printf("[ rejected ] %s\n", line.c_str());
    for (const std::string& line : tally.refusedCases) std::printf("[ refused  ] %s\n", line.c_str());
  }
  RecordProperty("files", static_cast<int>(tally.files));
  RecordProperty("loaded", static_cast<int>(tally.loaded));
  RecordProperty("splits_ok", static_cast<int>(tally.splitsOk));
  RecordProperty("pieces_checked", static_cast<int>(tally.piecesChecked));
  EXPECT_GT(tally.loaded, 0u);
  EXPECT_GT(tally.splitsOk, 0u);
}

}  // namespace
}  // namespace cleave::assets
