// SPDX-License-Identifier: MIT
// Corpus test over real models that the set-up installs (see tools/install-deps.sh): from Debian
// packages, the meshes of CGAL's data set (libcgal-demo ships them as
// /usr/share/doc/libcgal-dev/data.tar.gz, unpacked here with tar) and assimp's test models
// (assimp-testmodels, /usr/share/assimp/models, broken files included); from npm, the Stanford
// bunny of the package `bunny` (./cleave test installs it into <build>/npm, CLEAVE_NPM_DIR
// overrides; its index.js is `exports.positions=[[x,y,z],...]` then `exports.cells=[[a,b,c],...]`,
// read by parseMeshModule below); plus the shared models folder beside the repository when it is
// there. Every source that is missing is skipped with the reason; the test skips as a whole only
// when none is there.
//
// Every file is read. A file that does not read must give a one-line error naming the file, and so
// must (or read fine) each truncation of it; nothing may crash. The bunny's module must parse, and
// each truncation of it must be rejected with a one-line error. A mesh that reads is split by
// several planes through its bounding box (whether it is closed is the container's finding: the
// bunny is closed, its scan holes filled):
//  - closed input, with caps: either Ok, with every piece closed and consistently oriented (and, when
//    the input is closed on its exact float positions, the pieces too: see cutOnFloats), the
//    piece volumes summing to the input volume within 1e-6 relative, the cap area on each side equal
//    to the section area computed independently within 1e-6 relative, and no vertex on the wrong
//    side beyond the tolerance; or a refusal (OpenSection, TriangulationFailed: real meshes can
//    intersect themselves) with a message and no pieces;
//  - open input, hollow mode: Ok (or PlaneMissesMesh), the piece areas summing to the input area.
// The counts are printed, and recorded as test properties.
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <sys/wait.h>

#include <gtest/gtest.h>

#include "cleave/assets/mesh_io.h"
#include "cleave/geometry/fracture.h"
#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/mesh_splitter.h"
#include "tests/assets/asset_test_files.h"
#include "tests/geometry/cap_fixtures.h"
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

// ---- Meshes of npm packages: a CommonJS module of arrays of triples ----

// Reads a module of the form `exports.positions=[[x,y,z],...];exports.cells=[[a,b,c],...]` (the
// npm package bunny's index.js): each export once, in either order, separated by optional `;` and
// white space. Coordinates are JavaScript number literals that must be finite as float; cells index
// the positions. Returns an empty string and fills `mesh`, or a one-line error naming `name` and
// the byte where the text goes wrong, leaving `mesh` empty.
class MeshModuleParser {
 public:
  MeshModuleParser(std::string_view text, std::string name) : text_(text), name_(std::move(name)) {}

  std::string parse(MeshData& mesh) {
    mesh = MeshData{};
    std::vector<std::array<double, 3>> positions, cells;
    bool havePositions = false, haveCells = false;
    skipSeparators();
    while (at_ < text_.size()) {
      const size_t start = at_;
      if (!literal("exports.")) return fail("expected 'exports.<name>='");
      const std::string_view export_ = identifier();
      if (export_ != "positions" && export_ != "cells") {
        at_ = start;
        return fail("unknown export '" + std::string(export_) + "' (expected positions or cells)");
      }
      bool& seen = export_ == "positions" ? havePositions : haveCells;
      if (seen) {
        at_ = start;
        return fail("exports." + std::string(export_) + " is given twice");
      }
      seen = true;
      skipSpace();
      if (!literal("=")) return fail("expected '=' after exports." + std::string(export_));
      if (std::string error = triples(export_, export_ == "positions" ? positions : cells); !error.empty()) {
        return error;
      }
      skipSeparators();
    }
    if (!havePositions || !haveCells) {
      return name_ + ": no exports." + (havePositions ? "cells" : "positions") + " in the module";
    }
    if (positions.empty() || cells.empty()) {
      return name_ + ": exports." + (positions.empty() ? "positions" : "cells") + " is empty";
    }
    MeshData out;
    out.positions.reserve(positions.size());
    for (size_t k = 0; k < positions.size(); ++k) {
      for (double v : positions[k]) {
        if (std::abs(v) > double(std::numeric_limits<float>::max())) {
          return name_ + ": position " + std::to_string(k) + " has coordinate " + number(v) + ", beyond float";
        }
      }
      out.positions.emplace_back(float(positions[k][0]), float(positions[k][1]), float(positions[k][2]));
    }
    out.indices.reserve(cells.size() * 3);
    for (size_t k = 0; k < cells.size(); ++k) {
      for (double v : cells[k]) {
        if (!(v >= 0.0) || v != std::floor(v) || v >= double(positions.size())) {
          return name_ + ": cell " + std::to_string(k) + " has index " + number(v) + ", not one of the " +
                 std::to_string(positions.size()) + " positions";
        }
        out.indices.push_back(static_cast<uint32_t>(v));
      }
    }
    mesh = std::move(out);
    return {};
  }

 private:
  static std::string number(double v) {  // shortest text that reads back as v
    char buffer[64];
    return std::string(buffer, std::to_chars(buffer, buffer + sizeof(buffer), v).ptr);
  }
  std::string fail(const std::string& what) const {
    std::string found = "the end of the text";
    if (at_ < text_.size()) {
      const unsigned char c = static_cast<unsigned char>(text_[at_]);
      found = c >= 0x20 && c < 0x7f ? "'" + std::string(1, char(c)) + "'" : "byte 0x" + hex(c);
    }
    return name_ + ": at byte " + std::to_string(at_) + ": " + what + ", found " + found;
  }
  static std::string hex(unsigned char c) {
    const char* digits = "0123456789abcdef";
    return {digits[c >> 4], digits[c & 15]};
  }
  void skipSpace() {
    while (at_ < text_.size() && (text_[at_] == ' ' || text_[at_] == '\t' || text_[at_] == '\n' ||
                                  text_[at_] == '\r')) {
      ++at_;
    }
  }
  void skipSeparators() {
    for (skipSpace(); at_ < text_.size() && text_[at_] == ';'; skipSpace()) ++at_;
  }
  bool literal(std::string_view word) {
    if (text_.substr(at_, word.size()) != word) return false;
    at_ += word.size();
    return true;
  }
  std::string_view identifier() {
    const size_t start = at_;
    while (at_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[at_])) || text_[at_] == '_')) {
      ++at_;
    }
    return text_.substr(start, at_ - start);
  }
  // A JavaScript number literal: -?digits[.digits][(e|E)[+-]digits], finite.
  bool numberLiteral(double& value) {
    const size_t start = at_;
    auto digits = [&] {
      const size_t from = at_;
      while (at_ < text_.size() && text_[at_] >= '0' && text_[at_] <= '9') ++at_;
      return at_ > from;
    };
    auto reject = [&] {
      at_ = start;
      return false;
    };
    if (at_ < text_.size() && text_[at_] == '-') ++at_;
    if (!digits()) return reject();
    if (at_ < text_.size() && text_[at_] == '.') {
      ++at_;
      if (!digits()) return reject();
    }
    if (at_ < text_.size() && (text_[at_] == 'e' || text_[at_] == 'E')) {
      ++at_;
      if (at_ < text_.size() && (text_[at_] == '+' || text_[at_] == '-')) ++at_;
      if (!digits()) return reject();
    }
    const auto [end, ec] = std::from_chars(text_.data() + start, text_.data() + at_, value);
    if (ec != std::errc() || end != text_.data() + at_ || !std::isfinite(value)) return reject();
    // A number must end at a separator, not run into letters ("1x") or another literal ("1.5.2").
    if (at_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[at_])) || text_[at_] == '.' ||
                               text_[at_] == '_')) {
      return reject();
    }
    return true;
  }
  // [[a,b,c],...] with white space allowed between tokens and no trailing commas.
  std::string triples(std::string_view export_, std::vector<std::array<double, 3>>& out) {
    const std::string where = "exports." + std::string(export_);
    skipSpace();
    if (!literal("[")) return fail("expected '[' to open " + where);
    skipSpace();
    if (literal("]")) return {};
    for (;;) {
      const std::string item = where + "[" + std::to_string(out.size()) + "]";
      skipSpace();
      if (!literal("[")) return fail("expected '[' to open " + item);
      std::array<double, 3> triple{};
      for (int k = 0; k < 3; ++k) {
        skipSpace();
        if (!numberLiteral(triple[k])) {
          return fail("expected a finite number as element " + std::to_string(k) + " of " + item);
        }
        skipSpace();
        if (k < 2 && !literal(",")) {
          return fail("expected ',' after element " + std::to_string(k) + " of " + item + " (3 numbers)");
        }
      }
      if (!literal("]")) return fail("expected ']' to close " + item + " (3 numbers)");
      out.push_back(triple);
      skipSpace();
      if (literal("]")) return {};
      if (!literal(",")) return fail("expected ',' or ']' after " + item);
    }
  }

  std::string_view text_;
  std::string name_;
  size_t at_ = 0;
};

std::string parseMeshModule(std::string_view text, const std::string& name, MeshData& mesh) {
  return MeshModuleParser(text, name).parse(mesh);
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
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
  size_t files = 0, loaded = 0, rejected = 0, truncations = 0, modules = 0;
  size_t closedMeshes = 0, openMeshes = 0, splitMeshes = 0;
  size_t splitsOk = 0, refused = 0, missed = 0, piecesChecked = 0;
  std::map<std::string, size_t> refusals;
  std::vector<std::string> refusedCases, rejectedFiles;
};

void expectCleanError(const MeshReadResult& result, const std::string& name) {
  EXPECT_FALSE(result.message.empty());
  EXPECT_EQ(result.message.find('\n'), std::string::npos) << result.message;
  EXPECT_NE(result.message.find(name), std::string::npos) << "the error does not name the file: " << result.message;
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
    if (!result.ok()) expectCleanError(result, name);
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
  if (const geometry::MeshStatus set = container.setMesh(mesh); !set.ok()) {
    ADD_FAILURE() << name << ": the reader returned a mesh the container refuses: " << set.message;
    return;
  }
  std::vector<glm::dvec3> cutScratch;
  const std::span<const glm::dvec3> cut = container.cutPositions().doubles(cutScratch);
  glm::dvec3 lo, hi;
  geometry::testing::bounds(cut, lo, hi);
  const double diagonal = glm::length(hi - lo);
  if (!(diagonal > 0.0)) return;
  const bool closed = container.closed();
  // Pieces of a mesh that is closed on its own float positions must be too (see cutOnFloats).
  const bool closedOnFloats = closed && geometry::testing::floatWeldReport(mesh).manifold();
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
        if (closedOnFloats) {
          EXPECT_TRUE(geometry::testing::manifoldOnFloats(piece.mesh));
        }
        volumeSum += piece.mass.volume;
        const double cap = geometry::testing::capArea(piece.mesh, options.capMaterialId, glm::dmat4(1.0));
        (piece.side > 0 ? capAbove : capBelow) += cap;
      } else {
        areaSum += surfaceArea(p, piece.mesh.indices);
      }
    }
    if (closed) {
      // A mesh wound inwards is split as if mirrored: its pieces report positive volumes.
      EXPECT_NEAR(volumeSum, orientation * inputVolume, 1e-6 * std::abs(inputVolume))
          << "piece volumes do not add up";
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
  if (!result.ok()) {
    ++tally.rejected;
    tally.rejectedFiles.push_back(result.message);
    expectCleanError(result, name);
    return;
  }
  ++tally.loaded;
  splitAndCheck(name, result.mesh, tally);
}

// A mesh module of an npm package: it must parse; each truncation of it must be rejected with a
// one-line error naming it (a cut text always ends inside an array or lacks an export).
void runModule(const fs::path& file, const std::string& name, Tally& tally) {
  SCOPED_TRACE(file.string());
  ++tally.modules;
  const std::string text = readText(file);
  for (size_t cut : {text.size() / 7, text.size() / 2, text.size() - text.size() / 9}) {
    if (cut >= text.size()) continue;
    MeshData truncated;
    const std::string error = parseMeshModule(std::string_view(text).substr(0, cut), name, truncated);
    ++tally.truncations;
    EXPECT_FALSE(error.empty()) << "a truncation at byte " << cut << " parsed";
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_EQ(error.rfind(name, 0), 0u) << error;
    EXPECT_TRUE(truncated.positions.empty() && truncated.indices.empty());
  }
  MeshData mesh;
  const std::string error = parseMeshModule(text, name, mesh);
  if (!error.empty()) {
    ADD_FAILURE() << error;
    return;
  }
  splitAndCheck(name, mesh, tally);
}

TEST(Corpus, MeshModuleParserReadsArraysOfTriplesAndRejectsMalformedText) {
  // A tetrahedron, with the number forms JavaScript writes, white space, and semicolons.
  const std::string tetra =
      "exports.positions=[[0,0,0],[1.5e0,-0,0],\n[0, 2.5E-1 ,0],[0,0,-1e+1]];\r\n"
      "exports.cells = [ [0,2,1] , [0,1,3],[0,3,2],[1,2,3] ];\n";
  MeshData mesh;
  ASSERT_EQ(parseMeshModule(tetra, "tetra.js", mesh), "");
  ASSERT_EQ(mesh.positions.size(), 4u);
  EXPECT_EQ(mesh.positions[1], glm::vec3(1.5f, 0.f, 0.f));
  EXPECT_EQ(mesh.positions[2], glm::vec3(0.f, 0.25f, 0.f));
  EXPECT_EQ(mesh.positions[3], glm::vec3(0.f, 0.f, -10.f));
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}));
  // Cells first is the same mesh.
  MeshData swapped;
  ASSERT_EQ(parseMeshModule("exports.cells=[[0,2,1],[0,1,3],[0,3,2],[1,2,3]]\n"
                            "exports.positions=[[0,0,0],[1.5,0,0],[0,0.25,0],[0,0,-10]]",
                            "tetra.js", swapped),
            "");
  EXPECT_EQ(swapped.positions, mesh.positions);
  EXPECT_EQ(swapped.indices, mesh.indices);

  const std::string cells = "exports.cells=[[0,1,2]]";
  const std::string positions = "exports.positions=[[0,0,0],[1,0,0],[0,1,0]];";
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"", "no exports.positions"},
      {positions, "no exports.cells"},
      {"module.exports={}", "expected 'exports.<name>='"},
      {"exports.normals=[];" + positions + cells, "unknown export 'normals'"},
      {positions + positions + cells, "given twice"},
      {"exports.positions=[];" + cells, "exports.positions is empty"},
      {"exports.positions [[0,0,0]];" + cells, "expected '='"},
      {"exports.positions=[[0,0,0],[1,0,0],[0,1]];" + cells, "expected ',' after element 1 of exports.positions[2]"},
      {"exports.positions=[[0,0,0,0]];" + cells, "expected ']' to close exports.positions[0]"},
      {"exports.positions=[[0,0,0],[1,0,0],[0,1,0],];" + cells, "expected '[' to open exports.positions[3]"},
      {"exports.positions=[[0,0,0] [1,0,0]];" + cells, "expected ',' or ']' after exports.positions[0]"},
      {"exports.positions=[[0,0,0],[1,x,0]];" + cells, "expected a finite number as element 1"},
      {"exports.positions=[[0,0,0],[1,.5,0]];" + cells, "expected a finite number as element 1"},
      {"exports.positions=[[0,0,0],[1,1.5.2,0]];" + cells, "expected a finite number as element 1"},
      {"exports.positions=[[0,0,0],[1,1e,0]];" + cells, "expected a finite number as element 1"},
      {"exports.positions=[[0,0,0],[1,+1,0]];" + cells, "expected a finite number as element 1"},
      {"exports.positions=[[0,0,0],[1,NaN,0]];" + cells, "expected a finite number as element 1"},
      {"exports.positions=[[0,0,0],[1,1e999,0]];" + cells, "expected a finite number as element 1"},
      {"exports.positions=[[0,0,0],[1,1e39,0],[0,1,0]];" + cells, "position 1 has coordinate 1e+39, beyond float"},
      {positions + "exports.cells=[[0,1,3]]", "cell 0 has index 3, not one of the 3 positions"},
      {positions + "exports.cells=[[0,1,-1]]", "cell 0 has index -1"},
      {positions + "exports.cells=[[0,1,1.5]]", "cell 0 has index 1.5"},
      {positions + "exports.cells=[[0,1,2]", "expected ',' or ']' after exports.cells[0], found the end"},
      {positions + cells + " garbage", "expected 'exports.<name>='"},
      {positions + cells + "\x01", "found byte 0x01"},
  };
  for (const auto& [text, expected] : bad) {
    SCOPED_TRACE(text);
    MeshData out;
    const std::string error = parseMeshModule(text, "bad.js", out);
    EXPECT_NE(error.find(expected), std::string::npos) << error;
    EXPECT_EQ(error.rfind("bad.js: ", 0), 0u) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_TRUE(out.positions.empty() && out.indices.empty());
  }
}

// CGAL's meshes, unpacked from the archive the package ships into `into`; a note on what was found.
std::string unpackCgal(const fs::path& into, std::vector<fs::path>& files) {
  if (!fs::exists(kCgalArchive)) return "libcgal-demo not installed (no " + std::string(kCgalArchive) + ")";
  const std::string command = "tar -xzf '" + std::string(kCgalArchive) + "' -C '" + into.string() +
                              "' --wildcards '*.off' '*.obj' '*.ply' '*.stl' 2>/dev/null";
  // tar exits non-zero when one of the patterns matches nothing; what counts is what was unpacked.
  const int status = std::system(command.c_str());
  const size_t before = files.size();
  collect(into, files);
  if (files.size() == before) {
    return "nothing unpacked from " + std::string(kCgalArchive) + " (tar status " + std::to_string(status) + ")";
  }
  return "libcgal-demo: " + std::to_string(files.size() - before) + " mesh files";
}

TEST(Corpus, PackagedRealModelsReadAndSplitWithTheInvariants) {
  std::vector<std::string> notes;
  std::vector<fs::path> files;

  test::TempDir unpacked;
  notes.push_back(unpackCgal(unpacked.path(), files));
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
  // The Stanford bunny of the npm package bunny, in the set-up's npm folder.
  const fs::path bunny = test::npmDir() / "node_modules" / "bunny" / "index.js";
  const bool haveBunny = fs::is_regular_file(bunny);
  notes.push_back(haveBunny ? "npm bunny: 1 mesh module"
                            : "npm package bunny not installed (no " + bunny.string() + ")");
  std::string summary;
  for (const std::string& note : notes) summary += note + "; ";
  if (files.empty() && !haveBunny) GTEST_SKIP() << "no corpus installed: " << summary << "run tools/install-deps.sh";
  std::sort(files.begin(), files.end());

  Tally tally;
  for (const fs::path& file : files) runFile(file, tally);
  if (haveBunny) runModule(bunny, "bunny/index.js", tally);

  std::string refusals;
  for (const auto& [status, count] : tally.refusals) refusals += " " + status + "=" + std::to_string(count);
  std::printf("[ corpus   ] %s\n", summary.c_str());
  std::printf("[ corpus   ] %zu files: %zu read, %zu rejected with an error; %zu mesh module(s) parsed; %zu "
              "truncations read\n",
              tally.files, tally.loaded, tally.rejected, tally.modules, tally.truncations);
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
  RecordProperty("modules", static_cast<int>(tally.modules));
  RecordProperty("meshes_split", static_cast<int>(tally.splitMeshes));
  RecordProperty("splits_ok", static_cast<int>(tally.splitsOk));
  RecordProperty("pieces_checked", static_cast<int>(tally.piecesChecked));
  EXPECT_GT(tally.loaded + tally.modules, 0u);
  EXPECT_GT(tally.splitsOk, 0u);
}

// Art that is not watertight. Every open mesh of the corpus (and the shared models) is cut with
// caps by the five corpus planes in each open-section mode that cuts: nothing may be refused (a
// plane may miss), and Bridge never leaves more chains open than CapClosedLoops. The counts are
// printed.
struct OpenTally {
  size_t meshes = 0, cuts = 0, refused = 0, missed = 0, loops = 0, uncapped = 0;
  size_t openChains[2] = {0, 0}, bridged = 0;
};

void cutOpenArt(const std::string& name, const MeshData& mesh, OpenTally& tally) {
  MeshContainer container;
  if (container.setMesh(mesh).code != SplitStatus::Ok || container.closed()) return;
  ++tally.meshes;
  glm::dvec3 lo, hi;
  geometry::testing::bounds(container.cutPositions(), lo, hi);
  auto splitter = geometry::makeConcaveSplitter();
  SplitResult result;
  for (const Plane& plane : planesThrough(lo, hi)) {
    uint32_t open[2] = {0, 0};
    for (int mode = 0; mode < 2; ++mode) {
      SplitOptions options;
      options.openSections = mode == 0 ? geometry::OpenSectionMode::CapClosedLoops : geometry::OpenSectionMode::Bridge;
      const SplitStatus status = splitter->split(container, plane, options, result);
      if (status == SplitStatus::PlaneMissesMesh) {
        tally.missed += mode == 0;
        break;
      }
      EXPECT_EQ(status, SplitStatus::Ok) << name << ": " << result.message;
      if (status != SplitStatus::Ok) {
        ++tally.refused;
        break;
      }
      open[mode] = result.openChains;
      tally.openChains[mode] += result.openChains;
      if (mode == 0) {
        ++tally.cuts;
        tally.loops += result.sectionLoops;
        tally.uncapped += result.uncappedLoops;
      } else {
        tally.bridged += result.bridgedChains;
        EXPECT_LE(open[1], open[0]) << name;
      }
    }
  }
}

TEST(Corpus, OpenArtIsCutWithItsClosedLoopsCapped) {
  test::TempDir unpacked;
  std::vector<fs::path> files;
  const std::string note = unpackCgal(unpacked.path(), files);
  if (fs::is_directory(kAssimpModels)) collect(kAssimpModels, files);
  if (fs::is_directory(sharedModels())) collect(sharedModels(), files);
  if (files.empty()) GTEST_SKIP() << note << "; no assimp test models, no shared models";
  std::sort(files.begin(), files.end());
  OpenTally tally;
  for (const fs::path& file : files) {
    const MeshReadResult read = loadMesh(file.string());
    if (read.ok() && read.mesh.triangleCount() <= kLargeTriangles) cutOpenArt(file.filename().string(), read.mesh, tally);
  }
  std::printf("[ open art ] %zu open meshes, %zu cuts with caps, %zu refused, %zu planes missed: %zu closed loops "
              "(%zu left open), %zu open chains left open with cap-closed, %zu with bridge (%zu bridged)\n",
              tally.meshes, tally.cuts, tally.refused, tally.missed, tally.loops, tally.uncapped, tally.openChains[0],
              tally.openChains[1], tally.bridged);
  RecordProperty("open_cuts", static_cast<int>(tally.cuts));
  EXPECT_GT(tally.cuts, 100u);
}

// Exact float output. Every closed CGAL mesh that is itself closed and free of zero-area triangles
// on its float positions is cut by 30 seeded random planes, one in five exactly through one of its
// vertices; each piece, welded by exact float position as a file written from it would be, must have
// every edge used once in each direction and no triangle of zero area. The counts are printed.
struct FloatTally {
  size_t meshes = 0, skippedInput = 0, cuts = 0, throughVertex = 0, refused = 0, pieces = 0;
  size_t capPolygons = 0, capPolygonsFailed = 0;
  size_t badPieces = 0, zeroArea = 0, coincident = 0, openEdges = 0, overusedEdges = 0;
};

void cutOnFloats(const std::string& name, const MeshData& mesh, FloatTally& tally) {
  MeshContainer container;
  if (container.setMesh(mesh).code != SplitStatus::Ok || !container.closed()) return;
  if (!geometry::testing::floatWeldReport(mesh).manifold()) {
    ++tally.skippedInput;
    return;
  }
  ++tally.meshes;
  std::vector<glm::dvec3> cutScratch;
  const std::span<const glm::dvec3> cut = container.cutPositions().doubles(cutScratch);
  glm::dvec3 lo, hi;
  geometry::testing::bounds(cut, lo, hi);
  uint64_t seed = 1469598103934665603ull;  // FNV-1a of the name: a stable seed per mesh
  for (char c : name) seed = (seed ^ uint8_t(c)) * 1099511628211ull;
  std::vector<Plane> planes = geometry::testing::randomPlanes(seed, 30, lo, hi);
  geometry::testing::SeededRandom rng(seed + 1);
  for (size_t k = 0; k < planes.size(); k += 5) {
    const glm::dvec3 vertex = cut[rng.next() % cut.size()];
    planes[k].offset = glm::dot(planes[k].normal, vertex);
  }
  auto splitter = geometry::makeConcaveSplitter();
  SplitResult result;
  for (size_t k = 0; k < planes.size(); ++k) {
    const SplitStatus status = splitter->split(container, planes[k], SplitOptions{}, result);
    if (status == SplitStatus::PlaneMissesMesh) continue;
    ++tally.cuts;
    tally.throughVertex += k % 5 == 0;
    if (status != SplitStatus::Ok) {
      ++tally.refused;
      continue;
    }
    // The caps taken back out as polygons (as the fixture corpus of tests/geometry/data/caps holds
    // them) triangulate again with every edge used and no flat triangle. Taken from float positions,
    // their points carry rounding folds a few float steps wide: the areas agree to 1e-5 (the worst
    // here, pinion_small.off, is 7e-6).
    for (geometry::testing::CapFixture& f : geometry::testing::capPolygonsOf(result, planes[k])) {
      f.tolerance = 4.0 * 0x1.0p-24 * container.boundsDiagonal();
      const geometry::testing::Triangulated t = geometry::testing::triangulateFixture(f);
      ++tally.capPolygons;
      if (t.ok && t.ringEdgesMissing == 0 && t.flat == 0 && t.deviation <= 1e-5) continue;
      ++tally.capPolygonsFailed;
      ADD_FAILURE() << name << ", plane " << k << ": a cap polygon of " << f.rings.size() << " ring(s) does not "
                    << "triangulate again cleanly (ok " << t.ok << ", " << t.ringEdgesMissing << " edges missing, "
                    << t.flat << " flat, deviation " << t.deviation << ")";
    }
    for (const geometry::SplitPiece& piece : result.pieces) {
      ++tally.pieces;
      const geometry::testing::FloatWeldReport report = geometry::testing::floatWeldReport(piece.mesh);
      if (report.manifold()) continue;
      ++tally.badPieces;
      tally.zeroArea += report.zeroArea;
      tally.coincident += report.coincident;
      tally.openEdges += report.openEdges;
      tally.overusedEdges += report.overusedEdges;
      ADD_FAILURE() << name << ", plane " << k << ": " << geometry::testing::manifoldOnFloats(piece.mesh).message()
                    << "; case written to "
                    << geometry::testing::dumpCase("float_" + name + "_" + std::to_string(k), mesh,
                                                   glm::dmat4(1.0), planes[k], "piece not manifold on floats");
    }
  }
}

TEST(Corpus, CutsOfClosedCgalMeshesAreManifoldOnTheirFloatPositions) {
  test::TempDir unpacked;
  std::vector<fs::path> files;
  const std::string note = unpackCgal(unpacked.path(), files);
  if (files.empty()) GTEST_SKIP() << note;
  std::sort(files.begin(), files.end());
  FloatTally tally;
  for (const fs::path& file : files) {
    const MeshReadResult read = loadMesh(file.string());
    if (!read.ok() || read.mesh.triangleCount() > kLargeTriangles) continue;
    cutOnFloats(file.filename().string(), read.mesh, tally);
  }
  std::printf("[ floats   ] %zu closed meshes (%zu more not closed on their own float positions, skipped): %zu "
              "cuts (%zu through a vertex), %zu refused; %zu pieces, %zu not manifold on floats (%zu zero-area "
              "triangles, %zu of them with two corners at one point, %zu open edges, %zu edges used twice one way); "
              "%zu cap polygons triangulated again, %zu not cleanly\n",
              tally.meshes, tally.skippedInput, tally.cuts, tally.throughVertex, tally.refused, tally.pieces,
              tally.badPieces, tally.zeroArea, tally.coincident, tally.openEdges, tally.overusedEdges, tally.capPolygons,
              tally.capPolygonsFailed);
  RecordProperty("float_cuts", static_cast<int>(tally.cuts));
  RecordProperty("float_bad_pieces", static_cast<int>(tally.badPieces));
  EXPECT_GT(tally.cuts, 1000u);
}

// Fracture (engine/geometry/fracture.h) of real meshes: every closed mesh of CGAL's data set under
// 20,000 triangles broken into 8 Voronoi cells of seeds in its bounds; every piece manifold on its
// float positions and closed, the pieces' volumes adding up to the mesh's within 1e-6.
TEST(Corpus, FractureOfClosedCgalMeshesKeepsVolumeAndClosedPieces) {
  test::TempDir unpacked;
  std::vector<fs::path> files;
  const std::string note = unpackCgal(unpacked.path(), files);
  if (files.empty()) GTEST_SKIP() << note;
  std::sort(files.begin(), files.end());
  size_t meshes = 0, pieces = 0, refused = 0, bad = 0, cuts = 0, cellCount = 0, bySplits = 0;
  double worst = 0.0;
  for (const fs::path& file : files) {
    const MeshReadResult read = loadMesh(file.string());
    if (!read.ok() || read.mesh.triangleCount() > 20000) continue;
    MeshContainer container;
    if (container.setMesh(read.mesh).code != SplitStatus::Ok || !container.closed()) continue;
    if (!geometry::testing::floatWeldReport(read.mesh).manifold()) continue;
    std::vector<glm::dvec3> scratch;
    const double volume =
        geometry::computeMassProperties(container.cutPositions().doubles(scratch), read.mesh.indices).volume;
    if (!(std::abs(volume) > 0.0)) continue;
    glm::dvec3 lo, hi;
    geometry::testing::bounds(container.cutPositions(), lo, hi);
    const glm::dvec3 margin = 0.01 * (hi - lo);
    const auto cells = geometry::voronoiCells(geometry::fractureSeeds(8, meshes + 1, lo, hi), lo - margin, hi + margin);
    const geometry::FractureResult r = geometry::fracture(container, cells);
    ++meshes;
    if (r.status != SplitStatus::Ok) {
      ++refused;  // a cut the split core refuses (self-intersecting art): the object stays whole
      continue;
    }
    cuts += r.cuts;
    bySplits += r.carvedBySplits;
    for (const geometry::ConvexCell& cell : cells) cellCount += cell.empty ? 0 : 1;
    double sum = 0.0;
    for (const geometry::FracturePiece& piece : r.pieces) {
      ++pieces;
      sum += piece.mass.volume;
      const bool ok = geometry::testing::floatWeldReport(piece.mesh).manifold() && piece.mass.closed;
      bad += ok ? 0 : 1;
      EXPECT_TRUE(ok) << file.filename() << ", cell " << piece.cell;
    }
    const double relative = std::abs(sum - std::abs(volume)) / std::abs(volume);
    worst = std::max(worst, relative);
    EXPECT_LT(relative, 1e-6) << file.filename() << ": pieces " << sum << ", mesh " << volume;
  }
  std::printf("[ fracture ] %zu closed CGAL meshes into 8 cells: %zu of %zu cells carved by the cell clipper, %zu cuts, "
              "%zu pieces, %zu not closed and manifold on floats, %zu refused; worst relative volume difference %.2g\n",
              meshes, cellCount - bySplits, cellCount, cuts, pieces, bad, refused, worst);
  EXPECT_GT(meshes, 20u);
}

}  // namespace
}  // namespace cleave::assets
