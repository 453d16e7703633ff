// SPDX-License-Identifier: MIT
// Invariants of the split over generated meshes and many seeded planes, for the concave splitter
// (every mesh) and the convex splitter (convex meshes):
//   - the status is Ok when the plane crosses the mesh beyond the tolerance, PlaneMissesMesh when it
//     does not; a failed split holds no pieces;
//   - every piece is closed and consistently wound, with valid arrays, submesh runs and cap counts,
//     and a positive volume;
//   - the volumes of the pieces (as reported, and recomputed from the piece meshes) sum to the
//     volume of the original within 1e-6 relative;
//   - the cap area on each side equals the section area computed independently of the splitter;
//   - no vertex lies on the wrong side of the plane beyond the tolerance;
//   - island counts where they are known (meshes made of disjoint convex parts; special planes).
// A failing plane is reported with its index and values, and dumped as a corpus-ready text file.
// Re-cuts: a recorded piece whose cap once failed (tests/geometry/data), and pieces cut again and
// again, five generations deep under random rigid motions, with the same invariants.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"
#include "tests/geometry/test_meshes.h"

namespace cleave::geometry {
namespace {

namespace prim = primitives;
using testing::SeededRandom;
constexpr double kPi = std::numbers::pi;

struct InvariantCase {
  std::string name;
  MeshData mesh;
  glm::mat4 model{1.f};
  std::vector<glm::mat4> jointMatrices;  // non-empty: cut space is this skinning pose
  bool convex = false;
  // Vertex ranges [first, second) of disjoint convex parts: islands per side are then predictable.
  std::vector<std::pair<uint32_t, uint32_t>> convexParts;
  uint32_t planeCount = 100;
  uint64_t seed = 1;
  const MeshWeld* weld = nullptr;  // set: the container takes this weld instead of welding
  bool recut = false;              // a piece of an earlier split (see SplitRecutStress)
};

std::vector<std::pair<uint32_t, uint32_t>> whole(const MeshData& m) {
  return {{0u, static_cast<uint32_t>(m.positions.size())}};
}

// A bent limb: an elongated ellipsoid with two joints, the upper one rotated 35 degrees about z
// around the origin, with a smooth weight ramp over y in [-0.25, 0.25].
InvariantCase bentSkinCase() {
  InvariantCase c;
  c.name = "skinnedBentLimb";
  c.mesh = prim::ellipsoid(glm::vec3(0.3f, 1.f, 0.3f), 24, 32);
  for (const glm::vec3& p : c.mesh.positions) {
    float t = glm::clamp((p.y + 0.25f) / 0.5f, 0.f, 1.f);
    float w = t * t * (3.f - 2.f * t);
    c.mesh.joints.emplace_back(0, 1, 0, 0);
    c.mesh.weights.emplace_back(1.f - w, w, 0.f, 0.f);
  }
  c.jointMatrices = {glm::mat4(1.f), glm::rotate(glm::mat4(1.f), glm::radians(35.f), glm::vec3(0, 0, 1))};
  c.model = glm::translate(glm::mat4(1.f), glm::vec3(0.2f, 1.f, -0.3f)) *
            glm::rotate(glm::mat4(1.f), 0.3f, glm::vec3(0, 1, 0));
  c.planeCount = 100;
  c.seed = 16;
  return c;
}

InvariantCase makeCase(const std::string& name) {
  InvariantCase c;
  c.name = name;
  const glm::mat4 turn = glm::rotate(glm::mat4(1.f), 0.6f, glm::normalize(glm::vec3(1, 2, -1)));
  const glm::mat4 shift = glm::translate(glm::mat4(1.f), glm::vec3(0.4f, -1.2f, 2.f));
  if (name == "sphere") {
    c.mesh = prim::uvSphere(1.f, 32, 16);
    c.convex = true;
    c.planeCount = 150;
    c.seed = 1;
  } else if (name == "sphereFine") {
    c.mesh = prim::uvSphere(0.5f, 64, 32);
    c.convex = true;
    c.planeCount = 50;
    c.seed = 2;
  } else if (name == "ellipsoidNonUniform") {
    c.mesh = prim::ellipsoid(glm::vec3(1.f, 0.5f, 0.8f), 24, 12);
    c.model = shift * turn * glm::scale(glm::mat4(1.f), glm::vec3(2.f, 0.5f, 1.3f));
    c.convex = true;
    c.seed = 3;
  } else if (name == "boxSeams") {
    c.mesh = prim::box(glm::vec3(0.5f, 1.f, 0.25f));
    c.convex = true;
    c.planeCount = 150;
    c.seed = 4;
  } else if (name == "boxMirrored") {
    c.mesh = prim::box(glm::vec3(0.5f, 1.f, 0.25f));
    c.model = shift * turn * glm::scale(glm::mat4(1.f), glm::vec3(-1.5f, 1.f, 0.7f));
    c.convex = true;
    c.seed = 5;
  } else if (name == "cylinder") {
    c.mesh = prim::cylinder(0.5f, 2.f, 24);
    c.convex = true;
    c.seed = 6;
  } else if (name == "capsule") {
    c.mesh = prim::capsule(0.4f, 1.f, 20, 10);
    c.convex = true;
    c.seed = 7;
  } else if (name == "tetrahedron") {
    c.mesh = prim::tetrahedron(1.f);
    c.convex = true;
    c.seed = 8;
  } else if (name == "torus") {
    c.mesh = prim::torus(1.f, 0.3f, 48, 16);
    c.planeCount = 150;
    c.seed = 9;
  } else if (name == "torusMirroredSheared") {
    c.mesh = prim::torus(1.f, 0.3f, 32, 12);
    glm::mat4 shear(1.f);
    shear[1][0] = 0.4f;  // x += 0.4 y
    c.model = shift * turn * shear * glm::scale(glm::mat4(1.f), glm::vec3(1.5f, -0.8f, 1.f));
    c.seed = 10;
  } else if (name == "hollowSphere") {
    c.mesh = prim::hollowSphere(1.f, 0.6f, 32, 16);
    c.seed = 11;
  } else if (name == "nestedShells3") {
    c.mesh = prim::nestedShells(3, 1.f, 32, 16);
    c.seed = 12;
  } else if (name == "comb16") {
    c.mesh = prim::combPrism(16);
    c.planeCount = 150;
    c.seed = 13;
  } else if (name == "star7") {
    c.mesh = prim::starPrism(7);
    c.planeCount = 150;
    c.seed = 14;
  } else if (name == "twoDisjointSpheres") {
    c.mesh = prim::twoDisjointSpheres(0.5f, 0.3f, 24, 12);
    const uint32_t half = static_cast<uint32_t>(c.mesh.positions.size() / 2);
    c.convexParts = {{0u, half}, {half, 2 * half}};
    c.planeCount = 150;
    c.seed = 15;
  } else if (name == "skinnedBentLimb") {
    return bentSkinCase();
  } else {
    ADD_FAILURE() << "unknown case " << name;
  }
  if (c.convex && c.convexParts.empty()) c.convexParts = whole(c.mesh);
  return c;
}

const std::vector<std::string> kAllCases = {
    "sphere",  "sphereFine",   "ellipsoidNonUniform", "boxSeams",      "boxMirrored",
    "cylinder", "capsule",     "tetrahedron",         "torus",         "torusMirroredSheared",
    "hollowSphere", "nestedShells3", "comb16",        "star7",         "twoDisjointSpheres",
    "skinnedBentLimb"};
const std::vector<std::string> kConvexCases = {"sphere",   "sphereFine", "ellipsoidNonUniform", "boxSeams",
                                               "boxMirrored", "cylinder", "capsule",            "tetrahedron"};

struct Expected {
  int above = -1;  // pieces expected above, -1 when unknown
  int below = -1;
  int loopsPerPiece = -1;  // cap loops expected on every piece, -1 when unknown
};

bool prepare(MeshContainer& container, const InvariantCase& c, std::string& why) {
  MeshStatus set = c.weld ? container.setMesh(c.mesh, *c.weld) : container.setMesh(c.mesh);
  if (set.ok() && c.jointMatrices.empty()) container.setTransform(c.model);
  else if (set.ok()) set = container.setSkinningPose(c.jointMatrices, c.model);
  why = set.message;
  return set.ok();
}

// The largest relative difference between cap area and section area over every checked split, and
// how many splits it covers: printed when the binary ends, as the figure the slack below allows for.
struct CapAreaRecord {
  double worst = 0.0;
  size_t splits = 0;
};
CapAreaRecord gCapArea[2];  // [0] generated meshes, [1] re-cut pieces

class CapAreaReport : public ::testing::Environment {
 public:
  void TearDown() override {
    std::printf("[ checked  ] cap area vs section area, worst relative difference: %.3g over %zu splits of "
                "generated meshes, %.3g over %zu splits of re-cut pieces\n",
                gCapArea[0].worst, gCapArea[0].splits, gCapArea[1].worst, gCapArea[1].splits);
  }
};
const ::testing::Environment* const kCapAreaReport = ::testing::AddGlobalTestEnvironment(new CapAreaReport);

double maxCoordinate(const MeshData& m) {
  double largest = 0.0;
  for (const glm::vec3& p : m.positions) largest = std::max({largest, double(std::abs(p.x)), double(std::abs(p.y)), double(std::abs(p.z))});
  return largest;
}

bool inCapRun(const MeshData& m, size_t triangle, uint32_t capMaterialId) {
  for (const SubMesh& run : m.submeshes) {
    if (3 * triangle >= run.firstIndex && 3 * triangle < run.firstIndex + run.indexCount) return run.materialId == capMaterialId;
  }
  return false;
}

// Whether the corners of triangle t of m lie within `slack` of the plane of triangle `from` of the
// source (both in source space).
bool onSourcePlane(const MeshData& m, size_t t, const MeshData& source, uint32_t from, double slack) {
  const glm::dvec3 a(source.positions[source.indices[3 * from]]), b(source.positions[source.indices[3 * from + 1]]),
      c(source.positions[source.indices[3 * from + 2]]);
  const glm::dvec3 n = glm::cross(b - a, c - a);
  if (!(glm::length(n) > 0.0)) return true;  // a degenerate source triangle has no plane to check
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 p(m.positions[m.indices[3 * t + k]]);
    if (std::abs(glm::dot(p - a, n)) / glm::length(n) > slack) return false;
  }
  return true;
}

// Checks one split; returns the problems found (empty when every invariant holds).
std::vector<std::string> checkSplit(IMeshSplitter& splitter, const MeshContainer& container,
                                    const InvariantCase& c, const Plane& plane, const Expected& expected,
                                    SplitResult& result) {
  std::vector<std::string> problems;
  auto problem = [&](const std::string& text) { problems.push_back(text); };
  SplitOptions options;
  options.capMaterialId = 1;
  const bool skinned = !c.jointMatrices.empty();
  const glm::dmat4 model(c.model);
  const bool mirrored = glm::determinant(glm::dmat3(model)) < 0.0;
  std::vector<glm::dvec3> cutScratch;
  const std::span<const glm::dvec3> cut = container.cutPositions().doubles(cutScratch);
  const MeshData& source = c.mesh;
  const double diagonal = testing::boundsDiagonal(cut);
  const double tol = options.relativeTolerance * container.boundsDiagonal();
  const glm::dvec3 n = plane.normal / glm::length(plane.normal);
  const double offset = plane.offset / glm::length(plane.normal);

  double minD = INFINITY, maxD = -INFINITY;
  for (const glm::dvec3& p : cut) {
    const double d = glm::dot(n, p) - offset;
    minD = std::min(minD, d);
    maxD = std::max(maxD, d);
  }
  const bool misses = maxD <= tol || minD >= -tol;
  const bool ambiguous = std::abs(maxD - tol) < 0.5 * tol || std::abs(minD + tol) < 0.5 * tol;

  const SplitStatus status = splitter.split(container, plane, options, result);
  if (status != result.status) problem("returned status differs from result.status");
  if (!ambiguous && misses && status != SplitStatus::PlaneMissesMesh) {
    problem(std::string("plane misses the mesh (signed distances ") + std::to_string(minD) + " .. " +
            std::to_string(maxD) + ") but status is " + toString(status));
  }
  if (!ambiguous && !misses && status != SplitStatus::Ok) {
    problem(std::string("plane crosses the mesh but status is ") + toString(status) + ": " + result.message);
  }
  if (status != SplitStatus::Ok) {
    if (!result.pieces.empty()) problem("a failed split returned pieces");
    if (result.message.empty()) problem("a failed split gave no reason");
    return problems;
  }

  const std::vector<glm::dvec3> cutCopy(cut.begin(), cut.end());
  // The source winding is outward in source space; a mirroring cut space turns it inside out.
  const double orientation = mirrored ? -1.0 : 1.0;
  const double originalVolume =
      orientation * computeMassProperties(std::span<const glm::dvec3>(cutCopy), source.indices).volume;
  const double section = orientation * testing::sectionArea(cut, source.indices, plane);
  double reportedVolume = 0.0, recomputedVolume = 0.0, capAbove = 0.0, capBelow = 0.0;
  int above = 0, below = 0;
  bool seenBelow = false;
  for (size_t k = 0; k < result.pieces.size(); ++k) {
    const SplitPiece& piece = result.pieces[k];
    const MeshData& m = piece.mesh;
    const std::string at = "piece " + std::to_string(k) + " (side " + std::to_string(piece.side) + "): ";
    if (piece.side == 1) {
      ++above;
      if (seenBelow) problem(at + "an above piece after a below piece");
    } else if (piece.side == -1) {
      ++below;
      seenBelow = true;
    } else {
      problem(at + "side is neither +1 nor -1");
    }
    if (m.empty() || m.indices.size() % 3 != 0) {
      problem(at + "empty or ragged index list");
      continue;
    }
    const size_t nv = m.positions.size();
    auto sized = [&](size_t s) { return s == 0 || s == nv; };
    if (!sized(m.normals.size()) || !sized(m.tangents.size()) || !sized(m.uv0.size()) ||
        !sized(m.uv1.size()) || !sized(m.colors.size()) || !sized(m.joints.size()) ||
        m.weights.size() != m.joints.size()) {
      problem(at + "an attribute array does not match the vertex count");
    }
    if (m.normals.empty() != source.normals.empty() || m.tangents.empty() != source.tangents.empty() ||
        m.uv0.empty() != source.uv0.empty() || m.joints.empty() != source.joints.empty()) {
      problem(at + "an attribute of the source was dropped or invented");
    }
    bool inRange = true;
    for (uint32_t i : m.indices) inRange = inRange && i < nv;
    if (!inRange) {
      problem(at + "index out of range");
      continue;
    }
    uint32_t covered = 0;
    for (const SubMesh& run : m.submeshes) {
      if (run.firstIndex != covered) problem(at + "submesh runs have a gap or overlap");
      covered = run.firstIndex + run.indexCount;
    }
    if (!m.submeshes.empty() && covered != m.indices.size()) problem(at + "submesh runs do not cover the indices");

    std::vector<glm::dvec3> src = testing::toCutSpace(m, glm::dmat4(1.0));
    ::testing::AssertionResult closed = testing::closedAndOriented(src, m.indices, 1e-7 * testing::boundsDiagonal(src));
    if (!closed) problem(at + "not closed and oriented: " + closed.message());
    // As a file written from it is read back: welded by exact float position, closed, consistently
    // wound and without zero-area triangles (cut points that round to one float are one point).
    ::testing::AssertionResult onFloats = testing::manifoldOnFloats(m);
    if (!onFloats) problem(at + onFloats.message());
    // Provenance: each triangle names the source triangle whose plane it lies in, or a cap loop of
    // this split (and then it is in the cap's run).
    if (piece.sourceTriangles.size() != m.triangleCount()) {
      problem(at + "provenance has " + std::to_string(piece.sourceTriangles.size()) + " entries for " +
              std::to_string(m.triangleCount()) + " triangles");
    } else {
      const double slack = 1e-6 * testing::boundsDiagonal(src) + 4.0 * 0x1.0p-24 * maxCoordinate(m);
      for (size_t t = 0; t < piece.sourceTriangles.size(); ++t) {
        const uint32_t from = piece.sourceTriangles[t];
        if (from & kFromCap) {
          if ((from & ~kFromCap) >= result.sectionLoops + result.bridgedChains || !inCapRun(m, t, options.capMaterialId)) {
            problem(at + "triangle " + std::to_string(t) + " names cap loop " + std::to_string(from & ~kFromCap));
            break;
          }
          continue;
        }
        if (from >= source.triangleCount() || !onSourcePlane(m, t, source, from, slack)) {
          problem(at + "triangle " + std::to_string(t) + " does not lie in its source triangle " + std::to_string(from));
          break;
        }
      }
    }
    if (!piece.mass.closed) problem(at + "mass properties say the piece is open");
    // The piece's own weld (empty means unknown, allowed): accepted by a container, vertices of one
    // id at one position, and closed on its ids (each directed edge once, and its reverse once).
    if (!piece.weld.positionIds.empty()) {
      MeshContainer again;
      if (const MeshStatus set = again.setMesh(m, piece.weld); !set.ok()) {
        problem(at + "the container refuses the piece's weld: " + set.message);
      } else {
        if (!again.closed()) problem(at + "the piece's weld says it is open");
        if (again.inverted() != container.inverted()) problem(at + "the piece's weld has the wrong winding flag");
        for (size_t v = 0; v < nv; ++v) {
          if (m.positions[v] != m.positions[piece.weld.representatives[piece.weld.positionIds[v]]]) {
            problem(at + "vertex " + std::to_string(v) + " shares a position id with a vertex elsewhere");
            break;
          }
        }
        std::vector<uint64_t> edges;
        const std::vector<uint32_t>& id = piece.weld.positionIds;
        for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
          const uint32_t c[3] = {id[m.indices[t]], id[m.indices[t + 1]], id[m.indices[t + 2]]};
          if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) continue;
          for (int e = 0; e < 3; ++e) edges.push_back((uint64_t(c[e]) << 32) | c[(e + 1) % 3]);
        }
        std::sort(edges.begin(), edges.end());
        bool closedOnIds = std::adjacent_find(edges.begin(), edges.end()) == edges.end();
        for (size_t k = 0; closedOnIds && k < edges.size(); ++k) {
          const uint64_t reverse = (edges[k] << 32) | (edges[k] >> 32);
          closedOnIds = std::binary_search(edges.begin(), edges.end(), reverse);
        }
        if (!closedOnIds) problem(at + "not closed on the ids of its weld");
      }
    }
    if (!(piece.mass.volume > 0.0)) problem(at + "volume " + std::to_string(piece.mass.volume) + " is not positive");
    reportedVolume += piece.mass.volume;

    uint32_t capTriangles = 0;
    const double capArea = testing::capArea(m, options.capMaterialId, model, &capTriangles);
    if (capTriangles != piece.capTriangles) {
      problem(at + "capTriangles " + std::to_string(piece.capTriangles) + " but " + std::to_string(capTriangles) +
              " triangles carry the cap material");
    }
    if (expected.loopsPerPiece >= 0 && int(piece.capLoops) != expected.loopsPerPiece) {
      problem(at + std::to_string(piece.capLoops) + " cap loops, expected " + std::to_string(expected.loopsPerPiece));
    }
    if (skinned) continue;  // source-space pieces cannot be re-posed exactly (skinning is not linear along an edge)

    (piece.side > 0 ? capAbove : capBelow) += capArea;
    const std::vector<glm::dvec3> inCut = testing::toCutSpace(m, model);
    const double v = testing::signedVolume(inCut, m.indices);
    recomputedVolume += mirrored ? -v : v;
    // Positions are stored in float: allow their rounding on top of the on-plane tolerance.
    const double slack = tol + 1e-6 * diagonal;
    double worst = 0.0;
    for (const glm::dvec3& p : inCut) worst = std::max(worst, -double(piece.side) * (glm::dot(n, p) - offset));
    if (worst > slack) {
      problem(at + "a vertex lies " + std::to_string(worst) + " on the wrong side (allowed " + std::to_string(slack) + ")");
    }
  }

  auto relative = [](double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); };
  if (relative(reportedVolume, originalVolume) > 1e-6) {
    problem("reported piece volumes sum to " + std::to_string(reportedVolume) + ", original " +
            std::to_string(originalVolume));
  }
  if (!skinned) {
    // New vertices are stored as float source positions: each may move by half an ulp of the largest
    // source coordinate (times the model's largest stretch). That changes the volume by up to about
    // that much times the surface area, and the cap area by that much times the section perimeter
    // (bounded here by four bounding-box diagonals). It matters for small pieces far from their
    // source origin, as re-cut pieces are.
    double largest = 0.0;
    for (const glm::vec3& p : source.positions) largest = std::max({largest, double(std::abs(p.x)), double(std::abs(p.y)), double(std::abs(p.z))});
    const double stretch = std::max({glm::length(model[0]), glm::length(model[1]), glm::length(model[2])});
    const double ulp = 0x1.0p-24 * largest * stretch;
    double surface = 2.0 * std::abs(section);
    for (size_t k = 0; k + 2 < source.indices.size(); k += 3) {
      surface += testing::triangleArea(cut[source.indices[k]], cut[source.indices[k + 1]], cut[source.indices[k + 2]]);
    }
    if (std::abs(recomputedVolume - originalVolume) > 1e-6 * std::abs(originalVolume) + ulp * surface) {
      problem("piece meshes enclose " + std::to_string(recomputedVolume) + " in total, original " +
              std::to_string(originalVolume));
    }
    const double rounding = ulp * 4.0 * diagonal;
    // Cut points closer than the on-plane tolerance (SplitOptions::relativeTolerance, 1e-6 of the
    // diagonal) are merged into one, which moves each by at most that much: the cap then differs from
    // the exact section by at most the tolerance times twice the perimeter (bounded by 4 diagonals).
    const double merging = 1e-6 * diagonal * 2.0 * 4.0 * diagonal;
    const double areaSlack = 1e-6 * std::abs(section) + 1e-10 * diagonal * diagonal + rounding + merging;
    if (std::abs(section) > 0.0) {
      const double worst = std::max(std::abs(capAbove - section), std::abs(capBelow - section)) / std::abs(section);
      CapAreaRecord& record = gCapArea[c.recut ? 1 : 0];
      record.worst = std::max(record.worst, worst);
      ++record.splits;
    }
    if (std::abs(capAbove - section) > areaSlack || std::abs(capBelow - section) > areaSlack) {
      char text[200];
      std::snprintf(text, sizeof text, "cap areas above %.12g and below %.12g, section area %.12g", capAbove,
                    capBelow, section);
      problem(text);
    }
  }

  Expected want = expected;
  if (want.above < 0 && !c.convexParts.empty()) {
    // Each convex part yields one island on every side it reaches beyond the tolerance; skip planes
    // that graze a part within a few tolerances, where either answer is right. The parts are
    // apart, so (IslandMode::Touching) a part wholly on one side goes with a piece there that the
    // plane cut, when there is one: a side has one piece per cut part, or else one per part.
    want.above = want.below = 0;
    int cutParts = 0;
    for (const auto& [first, last] : c.convexParts) {
      double lo = INFINITY, hi = -INFINITY;
      for (uint32_t i = first; i < last; ++i) {
        const double d = glm::dot(n, cut[i]) - offset;
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
      if (std::abs(hi) < 4 * tol || std::abs(lo) < 4 * tol) want.above = want.below = -1;
      if (want.above < 0) break;
      want.above += hi > tol ? 1 : 0;
      want.below += lo < -tol ? 1 : 0;
      cutParts += hi > tol && lo < -tol ? 1 : 0;
    }
    if (want.above >= 0 && cutParts > 0) want.above = want.below = cutParts;
  }
  if (want.above >= 0 && (above != want.above || below != want.below)) {
    problem(std::to_string(above) + " pieces above and " + std::to_string(below) + " below, expected " +
            std::to_string(want.above) + " and " + std::to_string(want.below));
  }
  return problems;
}

std::string describePlane(const Plane& p) {
  char text[160];
  std::snprintf(text, sizeof text, "normal (%.17g, %.17g, %.17g) offset %.17g", p.normal.x, p.normal.y,
                p.normal.z, p.offset);
  return text;
}

// Runs the case over its plane set; reports every failing plane (dumping the first few) and
// returns how many splits were checked.
size_t runCase(IMeshSplitter& splitter, const InvariantCase& c, const std::string& label,
               const std::vector<std::pair<Plane, Expected>>& extraPlanes = {}) {
  MeshContainer container;
  std::string why;
  if (!prepare(container, c, why)) {
    ADD_FAILURE() << c.name << ": the container rejected the mesh: " << why;
    return 0;
  }
  std::vector<std::pair<Plane, Expected>> planes = extraPlanes;
  glm::dvec3 lo, hi;
  testing::bounds(container.cutPositions(), lo, hi);
  if (extraPlanes.empty()) {
    const glm::dvec3 centre = 0.5 * (lo + hi);
    for (int a = 0; a < 3; ++a) {  // axis planes through the centre: on-plane vertices are likely
      Plane p;
      p.normal = glm::dvec3(0.0);
      p.normal[a] = 1.0;
      p.offset = centre[a];
      planes.push_back({p, Expected{}});
    }
    for (const Plane& p : testing::randomPlanes(c.seed, c.planeCount, lo, hi)) planes.push_back({p, Expected{}});
  }
  SplitResult result;  // reused, as the engine does
  size_t failures = 0;
  for (size_t k = 0; k < planes.size(); ++k) {
    std::vector<std::string> problems = checkSplit(splitter, container, c, planes[k].first, planes[k].second, result);
    if (problems.empty()) continue;
    std::ostringstream text;
    text << label << " / " << c.name << " plane #" << k << " (" << describePlane(planes[k].first) << "):";
    for (const std::string& s : problems) text << "\n  - " << s;
    if (failures < 5) {
      std::string path = testing::dumpCase(label + "_" + c.name + "_plane" + std::to_string(k), c.mesh,
                                           glm::dmat4(c.model), planes[k].first, problems.front(), c.jointMatrices);
      text << "\n  case written to " << path;
    }
    ADD_FAILURE() << text.str();
    ++failures;
  }
  std::cout << "[ checked  ] " << label << " / " << c.name << ": " << planes.size() << " split cases, "
            << failures << " failing\n";
  ::testing::Test::RecordProperty("splitCases", static_cast<int>(planes.size()));
  return planes.size();
}

class ConcaveSplitInvariants : public ::testing::TestWithParam<std::string> {};
class ConvexSplitInvariants : public ::testing::TestWithParam<std::string> {};

TEST_P(ConcaveSplitInvariants, PiecesAreClosedAndKeepVolumeAndSectionArea) {
  auto splitter = makeConcaveSplitter();
  ASSERT_NE(splitter, nullptr);
  EXPECT_GT(runCase(*splitter, makeCase(GetParam()), "concave"), 0u);
}

TEST_P(ConvexSplitInvariants, PiecesAreClosedAndKeepVolumeAndSectionArea) {
  auto splitter = makeConvexSplitter();
  ASSERT_NE(splitter, nullptr);
  EXPECT_GT(runCase(*splitter, makeCase(GetParam()), "convex"), 0u);
}

std::string caseName(const ::testing::TestParamInfo<std::string>& info) { return info.param; }

INSTANTIATE_TEST_SUITE_P(Generated, ConcaveSplitInvariants, ::testing::ValuesIn(kAllCases), caseName);
INSTANTIATE_TEST_SUITE_P(Generated, ConvexSplitInvariants, ::testing::ValuesIn(kConvexCases), caseName);

Plane planeOf(glm::dvec3 normal, double offset) {
  Plane p;
  p.normal = normal;
  p.offset = offset;
  return p;
}

// ---- Islands settled by the section: the same pieces as the island search. ----

std::vector<std::string> samePieces(const SplitResult& a, const SplitResult& b) {
  std::vector<std::string> problems;
  if (a.status != b.status) problems.push_back("status differs");
  if (a.pieces.size() != b.pieces.size()) problems.push_back("piece count differs");
  for (size_t k = 0; problems.empty() && k < a.pieces.size(); ++k) {
    const SplitPiece& p = a.pieces[k];
    const SplitPiece& q = b.pieces[k];
    const std::string at = "piece " + std::to_string(k) + ": ";
    if (p.mesh.positions != q.mesh.positions || p.mesh.normals != q.mesh.normals || p.mesh.uv0 != q.mesh.uv0 ||
        p.mesh.indices != q.mesh.indices || p.mesh.joints != q.mesh.joints || p.mesh.weights != q.mesh.weights ||
        p.mesh.tangents != q.mesh.tangents || p.mesh.uv1 != q.mesh.uv1 || p.mesh.colors != q.mesh.colors) {
      problems.push_back(at + "mesh differs");
    }
    bool sameRuns = p.mesh.submeshes.size() == q.mesh.submeshes.size();
    for (size_t r = 0; sameRuns && r < p.mesh.submeshes.size(); ++r) {
      const SubMesh& x = p.mesh.submeshes[r];
      const SubMesh& y = q.mesh.submeshes[r];
      sameRuns = x.firstIndex == y.firstIndex && x.indexCount == y.indexCount && x.materialId == y.materialId;
    }
    if (!sameRuns) problems.push_back(at + "submesh runs differ");
    if (p.sourceTriangles != q.sourceTriangles || p.side != q.side || p.capLoops != q.capLoops ||
        p.capTriangles != q.capTriangles || p.reached != q.reached) {
      problems.push_back(at + "provenance, side or caps differ");
    }
    if (p.weld.positionIds != q.weld.positionIds || p.weld.representatives != q.weld.representatives ||
        p.weld.closed != q.weld.closed || p.weld.inverted != q.weld.inverted || p.weld.connected != q.weld.connected) {
      problems.push_back(at + "weld differs");
    }
    if (p.mass.volume != q.mass.volume || p.mass.centerOfMass != q.mass.centerOfMass ||
        p.mass.inertia != q.mass.inertia) {
      problems.push_back(at + "mass differs");
    }
  }
  return problems;
}

// A closed mesh known to be one part needs no island search when its section settles the islands
// (every cut point and on-plane vertex on a loop; one loop, or loops one cap joins). Every mesh is
// cut with its weld as worked out and with the same weld not known to be one part (always the
// search): random planes, axis planes and planes through vertices, the pieces compared byte for byte.
TEST(SplitIslands, SettledByTheSectionTheyAreWhatTheSearchFinds) {
  auto splitter = makeConcaveSplitter();
  size_t compared = 0, skipped = 0, fromLoops = 0;
  for (const std::string& name : kAllCases) {
    InvariantCase c = makeCase(name);
    MeshContainer welded;
    std::string why;
    ASSERT_TRUE(prepare(welded, c, why)) << name << ": " << why;
    MeshWeld weld;
    welded.copyWeld(weld);
    const bool onePart = name != "hollowSphere" && name != "nestedShells3" && name != "twoDisjointSpheres";
    EXPECT_EQ(weld.connected, onePart) << name;
    MeshWeld unknown = weld;
    unknown.connected = false;
    MeshContainer known, searched;
    c.weld = &weld;
    ASSERT_TRUE(prepare(known, c, why)) << name << ": " << why;
    c.weld = &unknown;
    ASSERT_TRUE(prepare(searched, c, why)) << name << ": " << why;
    glm::dvec3 lo, hi;
    testing::bounds(known.cutPositions(), lo, hi);
    std::vector<Plane> planes = testing::randomPlanes(c.seed + 100, 40, lo, hi);
    for (int a = 0; a < 3; ++a) planes.push_back(planeOf(glm::dvec3(a == 0, a == 1, a == 2), 0.5 * (lo[a] + hi[a])));
    testing::SeededRandom rng(c.seed + 200);
    const CutPositions cut = known.cutPositions();
    for (size_t k = 0; k < 10; ++k) {  // through a vertex
      const glm::dvec3 normal = rng.unitVector();
      planes.push_back(planeOf(normal, glm::dot(normal, cut[(k * 7919) % cut.size()])));
    }
    // Default options, then without caps, one side kept, strict islands (a plane in four each).
    std::vector<SplitOptions> variants(4);
    variants[1].cap = false;
    variants[2].keepSide = 1;
    variants[3].islands = IslandMode::Connected;
    SplitResult a, b;
    for (size_t k = 0; k < planes.size(); ++k) {
      const SplitOptions& options = variants[k % 4 == 0 ? 1 + (k / 4) % 3 : 0];
      splitter->split(known, planes[k], options, a);
      splitter->split(searched, planes[k], options, b);
      const std::vector<std::string> problems = samePieces(a, b);
      EXPECT_TRUE(problems.empty()) << name << " plane #" << k << " (" << describePlane(planes[k])
                                    << "): " << problems.front();
      EXPECT_FALSE(b.islandsFromSection) << name << " plane #" << k << ": not known to be one part";
      EXPECT_FALSE(b.islandFromLoops) << name << " plane #" << k << ": not known to be one part";
      skipped += a.islandsFromSection ? 1 : 0;
      fromLoops += a.islandFromLoops ? 1 : 0;
      ++compared;
    }
  }
  std::cout << "[ checked  ] islands settled by the section: " << skipped << " of " << compared
            << " split pairs without a search, and " << fromLoops
            << " with one side's search saved by the other's; the same pieces as the search\n";
  EXPECT_GT(skipped, compared / 4);  // the shortcut is taken often enough to be tested
  EXPECT_LT(skipped, compared);      // and refused where it must be (several caps, several parts)
  EXPECT_GT(fromLoops, 0u);          // a comb or a star cut across its teeth
}

// Outward-wound tetrahedron a, b, c, d appended to m (positions and indices only).
void appendTetrahedron(MeshData& m, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
  const uint32_t first = static_cast<uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), {a, b, c, d});
  const glm::vec3 centre = 0.25f * (a + b + c + d);
  const uint32_t faces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  for (const auto& f : faces) {
    const glm::vec3 p = m.positions[first + f[0]], q = m.positions[first + f[1]], r = m.positions[first + f[2]];
    const bool outward = glm::dot(glm::cross(q - p, r - p), p - centre) > 0.f;
    m.indices.insert(m.indices.end(), {first + f[0], first + (outward ? f[1] : f[2]), first + (outward ? f[2] : f[1])});
  }
}

// Cuts `m` set up twice: with the weld found for it (closed and one part) and with that weld saying
// it is not known to be one part, which takes the island search with nothing settled or put off.
// Both must give the same pieces; returns the first result.
SplitResult cutKnownAndSearched(const MeshData& m, const Plane& plane, IslandMode mode) {
  MeshContainer welded;
  EXPECT_TRUE(welded.setMesh(m).ok());
  EXPECT_TRUE(welded.closed());
  EXPECT_TRUE(welded.connected());
  MeshWeld weld, unknown;
  welded.copyWeld(weld);
  unknown = weld;
  unknown.connected = false;
  MeshContainer known, searched;
  EXPECT_TRUE(known.setMesh(m, weld).ok());
  EXPECT_TRUE(searched.setMesh(m, unknown).ok());
  auto splitter = makeConcaveSplitter();
  SplitOptions options;
  options.islands = mode;
  SplitResult a, b;
  EXPECT_EQ(splitter->split(known, plane, options, a), SplitStatus::Ok) << a.message;
  EXPECT_EQ(splitter->split(searched, plane, options, b), SplitStatus::Ok) << b.message;
  const std::vector<std::string> problems = samePieces(a, b);
  EXPECT_TRUE(problems.empty()) << problems.front();
  return a;
}

// A comb cut across its teeth near the tips: the tips (the smaller side) are one island per loop,
// which proves the other side one island, so it is not searched; the pieces are the search's.
TEST(SplitIslands, ASideJoinedByEveryLoopIsOneIslandWithoutASearch) {
  const MeshData comb = primitives::combPrism(16);
  const SplitResult a = cutKnownAndSearched(comb, planeOf({0, 1, 0}, 0.7), IslandMode::Touching);
  EXPECT_TRUE(a.islandFromLoops);
  EXPECT_FALSE(a.islandsFromSection);
  ASSERT_EQ(a.pieces.size(), 17u);
  EXPECT_EQ(a.pieces.back().capLoops, 16u);  // the spine below holds every loop
  // Across the spine the section is one loop: settled by the section, no search on either side.
  const SplitResult b = cutKnownAndSearched(comb, planeOf({0, 1, 0}, 0.1), IslandMode::Touching);
  EXPECT_TRUE(b.islandsFromSection);
  EXPECT_FALSE(b.islandFromLoops);
}

// One part whose two sides also meet at a vertex on the plane that no loop passes: a cube cut
// through its middle (one loop) and, joined to it at a lower corner, a tetrahedron below the plane
// touching at one vertex the tip of another above it. Above, the cube's half and the upper
// tetrahedron are two islands (made one piece by Touching, or two with IslandMode::Connected): the
// section alone must not settle them.
TEST(SplitIslands, AVertexOnThePlaneOffTheLoopsTakesTheSearch) {
  MeshData m = prim::box(glm::vec3(1.f));
  m.normals.clear();
  m.tangents.clear();
  m.uv0.clear();
  m.submeshes.clear();
  const glm::vec3 touch(3.f, 3.f, 0.f);
  appendTetrahedron(m, glm::vec3(1.f, 1.f, -1.f), touch, glm::vec3(3.f, 1.5f, -0.6f), glm::vec3(1.5f, 3.f, -0.6f));
  appendTetrahedron(m, touch, glm::vec3(4.f, 3.f, 1.f), glm::vec3(3.f, 4.f, 1.f), glm::vec3(4.f, 4.f, 0.3f));
  for (IslandMode mode : {IslandMode::Touching, IslandMode::Connected}) {
    const SplitResult a = cutKnownAndSearched(m, planeOf({0, 0, 1}, 0.0), mode);
    size_t above = 0;
    bool aboveOnePart = true;
    for (const SplitPiece& piece : a.pieces) {
      if (piece.side < 0) continue;
      ++above;
      aboveOnePart = aboveOnePart && piece.weld.connected;
    }
    EXPECT_EQ(above, mode == IslandMode::Touching ? 1u : 2u);
    EXPECT_EQ(aboveOnePart, mode == IslandMode::Connected);
  }
}

// One part whose pieces above the plane pass into one another: a comb of two teeth, the right tooth
// leaning over so that its top passes into the left one, cut below where they meet. The section
// rules out cavities, so the touching parts are joined after the pieces are written, and the side
// is written again as one piece: the same pieces as the search that joins them first (the weld
// saying the mesh is not known to be one part), and the pieces below moved down to follow.
TEST(SplitIslands, PartsJoinedAfterWritingGiveThePiecesOfJoiningFirst) {
  MeshData m = prim::combPrism(2);
  for (glm::vec3& q : m.positions) {
    if (q.y > 0.7f && q.x > 0.f) q.x -= 0.15f;  // the right tooth's top, over the left one's
  }
  for (IslandMode mode : {IslandMode::Touching, IslandMode::Connected}) {
    const SplitResult a = cutKnownAndSearched(m, planeOf({0, 1, 0}, 0.5), mode);
    ASSERT_EQ(a.pieces.size(), mode == IslandMode::Touching ? 2u : 3u);
    EXPECT_GT(a.pieces.front().side, 0);
    EXPECT_LT(a.pieces.back().side, 0);
    EXPECT_EQ(a.pieces.front().capLoops, mode == IslandMode::Touching ? 2u : 1u);
    EXPECT_EQ(a.pieces.back().capLoops, 2u);
    EXPECT_FALSE(a.islandsFromSection);
  }
}

// A piece's weld says it is one part only when it is: the sphere the plane misses goes with the
// half on its side (two parts), the other half is one.
TEST(SplitIslands, PieceWeldsKnowWhetherTheyAreOnePart) {
  InvariantCase c = makeCase("twoDisjointSpheres");
  MeshContainer container;
  std::string why;
  ASSERT_TRUE(prepare(container, c, why)) << why;
  EXPECT_FALSE(container.connected());
  SplitResult result;
  ASSERT_EQ(makeConcaveSplitter()->split(container, planeOf({1, 0, 0}, 0.5), SplitOptions{}, result),
            SplitStatus::Ok);
  ASSERT_EQ(result.pieces.size(), 2u);
  int joined = 0;
  for (const SplitPiece& piece : result.pieces) {
    bool twoParts = false;  // holds the sphere at negative x, which the plane misses
    for (const glm::vec3& p : piece.mesh.positions) twoParts = twoParts || p.x < 0.f;
    joined += twoParts ? 1 : 0;
    EXPECT_EQ(piece.weld.connected, !twoParts);
    MeshContainer again;
    ASSERT_TRUE(again.setMesh(piece.mesh).ok());
    EXPECT_EQ(again.connected(), !twoParts);  // the weld from nothing agrees
  }
  EXPECT_EQ(joined, 1);
}

// ---- Special planes with known island counts (both splitters where the input is convex). ----

void runSpecial(const std::string& caseName, const Plane& plane, const Expected& expected) {
  auto splitter = makeConcaveSplitter();
  ASSERT_NE(splitter, nullptr);
  EXPECT_EQ(runCase(*splitter, makeCase(caseName), "special", {{plane, expected}}), 1u);
}

// A vertical plane through the axis crosses the tube twice: the section is two discs, and each side
// is one C-shaped half (the core circle splits into one arc per side) carrying both discs as caps.
TEST(SplitInvariants, TorusVerticalCutThroughAxisGivesOneHalfWithTwoCapsPerSide) {
  runSpecial("torus", planeOf({1, 0, 0}, 0.0), Expected{1, 1, 2});
  runSpecial("torus", planeOf({0.3, 0, 1}, 0.01), Expected{1, 1, 2});
}

// A vertical plane through the tube only (between R - r and R + r from the axis): one loop.
TEST(SplitInvariants, TorusCutThroughOneSideOfTheTubeGivesOneLoop) {
  runSpecial("torus", planeOf({1, 0, 0}, 1.1), Expected{1, 1, 1});
}

TEST(SplitInvariants, TorusHorizontalCutGivesAnnulusOnEachSide) {
  runSpecial("torus", planeOf({0, 1, 0}, 0.05), Expected{1, 1, 2});
}

TEST(SplitInvariants, TwoDisjointSpheresCutThroughBothGiveTwoPlusTwo) {
  runSpecial("twoDisjointSpheres", planeOf({0, 1, 0}, 0.1), Expected{2, 2, 1});
}

TEST(SplitInvariants, PlaneThroughOneOfTwoSpheresKeepsTheOtherWithTheHalfOnItsSide) {
  // The sphere the plane does not reach goes with the half of the other on its side (Touching).
  runSpecial("twoDisjointSpheres", planeOf({1, 0, 0}, 0.5), Expected{1, 1, -1});
}

TEST(SplitInvariants, HollowSphereCutThroughCentreGivesOneBowlPerSide) {
  runSpecial("hollowSphere", planeOf({0, 1, 0}, 0.05), Expected{1, 1, 2});
}

TEST(SplitInvariants, NestedShellsCutThroughCentreGiveTwoPiecesPerSide) {
  runSpecial("nestedShells3", planeOf({0, 1, 0}, 0.03), Expected{2, 2, -1});
}

TEST(SplitInvariants, CombCutAcrossTeethGivesOnePiecePerTooth) {
  runSpecial("comb16", planeOf({0, 1, 0}, 0.5), Expected{16, 1, -1});
}

TEST(SplitInvariants, CombCutAlongExtrusionCapsTheWholeOutline) {
  runSpecial("comb16", planeOf({0, 0, 1}, 0.02), Expected{1, 1, 1});
}

TEST(SplitInvariants, StarCutAcrossAxisCapsTheStar) {
  runSpecial("star7", planeOf({0, 1, 0}, 0.1), Expected{1, 1, 1});
}

TEST(SplitInvariants, ConvexSplitterGivesOnePiecePerSideOnTheBox) {
  auto splitter = makeConvexSplitter();
  ASSERT_NE(splitter, nullptr);
  EXPECT_EQ(runCase(*splitter, makeCase("boxSeams"), "special", {{planeOf({1, 1, 1}, 0.1), Expected{1, 1, 1}}}), 1u);
}

// ---- Re-cut pieces: sections of earlier caps, rounded floats. ----

// Reads the v and f lines of a small OBJ file (faces fanned; v/vt/vn forms take the position index)
// and the "# model" (16 floats, column-major) and "# plane" header lines of a recorded failure.
bool readRecordedCase(const std::filesystem::path& path, MeshData& mesh, glm::mat4& model, Plane& plane) {
  std::ifstream in(path);
  if (!in) return false;
  std::string line;
  bool hasPlane = false;
  while (std::getline(in, line)) {
    std::istringstream ss(line);
    std::string tag;
    ss >> tag;
    if (tag == "v") {
      glm::vec3 p;
      ss >> p.x >> p.y >> p.z;
      mesh.positions.push_back(p);
    } else if (tag == "f") {
      std::vector<uint32_t> face;
      std::string corner;
      while (ss >> corner) face.push_back(static_cast<uint32_t>(std::stoul(corner.substr(0, corner.find('/'))) - 1));
      for (size_t k = 1; k + 1 < face.size(); ++k) mesh.indices.insert(mesh.indices.end(), {face[0], face[k], face[k + 1]});
    } else if (tag == "#" && line.rfind("# model ", 0) == 0) {
      std::istringstream values(line.substr(8));
      for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) values >> model[c][r];
      }
    } else if (tag == "#" && line.rfind("# plane", 0) == 0) {
      const size_t at = line.find("normal ");
      if (at == std::string::npos) continue;
      std::istringstream values(line.substr(at + 7));
      std::string word;
      values >> plane.normal.x >> plane.normal.y >> plane.normal.z >> word >> plane.offset;
      hasPlane = word == "offset" && !values.fail();
    }
  }
  return hasPlane && !mesh.positions.empty() && !mesh.indices.empty();
}

// A piece of a cylinder cut three times, recorded from the demo: its earlier caps are fan and ear
// triangulated, so the new plane crosses many cap edges and the section has long runs of nearly
// collinear points, two of them 2e-8 apart in reversed order (the exact ring overlaps itself). Both
// splitters used to fail with TriangulationFailed ("the section polygon overlaps itself").
TEST(SplitRegression, RecutCylinderPieceCapsWithItsModelMatrix) {
  const std::filesystem::path path =
      std::filesystem::path(CLEAVE_SOURCE_DIR) / "tests" / "geometry" / "data" / "recut_cylinder_piece.obj";
  InvariantCase c;
  c.name = "recutCylinderPiece";
  Plane plane;
  ASSERT_TRUE(readRecordedCase(path, c.mesh, c.model, plane)) << "cannot read " << path;
  ASSERT_EQ(c.mesh.triangleCount(), 478u);
  MeshContainer container;
  std::string why;
  ASSERT_TRUE(prepare(container, c, why)) << why;
  for (int convex = 0; convex < 2; ++convex) {
    auto splitter = convex ? makeConvexSplitter() : makeConcaveSplitter();
    SplitResult result;
    const std::vector<std::string> problems = checkSplit(*splitter, container, c, plane, Expected{1, 1, 1}, result);
    std::string text;
    for (const std::string& p : problems) text += "\n  - " + p;
    EXPECT_TRUE(problems.empty()) << (convex ? "convex" : "concave") << " splitter:" << text;
    EXPECT_EQ(result.status, SplitStatus::Ok) << result.message;
  }
}

// A random rigid motion (rotation by a random unit quaternion, translation within +-2 m).
glm::mat4 randomRigid(SeededRandom& rng) {
  glm::dquat q(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
  q = glm::length(q) > 1e-3 ? glm::normalize(q) : glm::dquat(1, 0, 0, 0);
  glm::dmat4 m = glm::mat4_cast(q);
  m[3] = glm::dvec4(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2), 1.0);
  return glm::mat4(m);
}

// Every piece is cut again, five generations deep, by random planes through its middle, each time
// under a new random rigid model matrix; about half of the pieces are first baked into float
// positions in the cut space of their parent (as a physics step would leave them), so earlier caps
// carry rounding.
// Every split must succeed with all the invariants (closed pieces, volume kept, cap area equal to
// the section area), with the concave and the convex splitter alternately.
struct RecutTotals {
  size_t splits = 0, failures = 0, misses = 0;
};

RecutTotals runRecutGenerations(const std::string& name, const MeshData& base, uint64_t seed) {
  constexpr int kGenerations = 5;
  constexpr size_t kPiecesPerGeneration = 16;
  SeededRandom rng(seed);
  auto concave = makeConcaveSplitter();
  auto convex = makeConvexSplitter();
  RecutTotals totals;
  // Pieces are cut again with the weld the split gave them (as the engine does), the base mesh with
  // a weld of its own.
  std::vector<MeshData> generation{base};
  std::vector<MeshWeld> welds(1);
  SplitResult result;
  for (int g = 0; g < kGenerations && !generation.empty(); ++g) {
    std::vector<MeshData> next;
    std::vector<MeshWeld> nextWelds;
    for (size_t k = 0; k < generation.size(); ++k) {
      InvariantCase c;
      c.name = name + "_g" + std::to_string(g) + "_p" + std::to_string(k);
      c.mesh = std::move(generation[k]);
      c.model = randomRigid(rng);
      c.weld = g > 0 ? &welds[k] : nullptr;
      c.recut = g > 0;
      MeshContainer container;
      std::string why;
      if (!prepare(container, c, why)) {
        ADD_FAILURE() << c.name << ": the container rejected the piece: " << why;
        ++totals.failures;
        continue;
      }
      glm::dvec3 lo, hi;
      testing::bounds(container.cutPositions(), lo, hi);
      glm::dvec3 point;
      for (int a = 0; a < 3; ++a) point[a] = lo[a] + (hi[a] - lo[a]) * rng.uniform(0.3, 0.7);
      Plane plane;
      plane.normal = rng.unitVector();
      plane.offset = glm::dot(plane.normal, point);
      const bool useConvex = (totals.splits & 1) != 0;
      const std::vector<std::string> problems =
          checkSplit(useConvex ? *convex : *concave, container, c, plane, Expected{}, result);
      ++totals.splits;
      if (!problems.empty()) {
        ++totals.failures;
        std::ostringstream text;
        text << c.name << (useConvex ? " (convex)" : " (concave)") << " " << describePlane(plane) << ":";
        for (const std::string& p : problems) text << "\n  - " << p;
        if (totals.failures <= 3) {
          text << "\n  case written to "
               << testing::dumpCase("recut_" + c.name, c.mesh, glm::dmat4(c.model), plane, problems.front());
        }
        ADD_FAILURE() << text.str();
        continue;
      }
      if (result.status != SplitStatus::Ok) {
        ++totals.misses;
        continue;
      }
      for (SplitPiece& piece : result.pieces) {
        if (next.size() >= kPiecesPerGeneration) break;
        MeshData m = std::move(piece.mesh);
        m.submeshes.clear();  // one material again: the next cap area is then that of the new cut alone
        if (rng.uniform() < 0.5) {
          const glm::dmat4 model(c.model);
          const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(model)));
          for (glm::vec3& p : m.positions) p = glm::vec3(model * glm::dvec4(glm::dvec3(p), 1.0));
          for (glm::vec3& n : m.normals) n = glm::vec3(glm::normalize(normalMatrix * glm::dvec3(n)));
          for (glm::vec4& t : m.tangents) t = glm::vec4(glm::vec3(glm::normalize(glm::dmat3(model) * glm::dvec3(t))), t.w);
        }
        next.push_back(std::move(m));
        nextWelds.push_back(std::move(piece.weld));
      }
    }
    generation = std::move(next);
    welds = std::move(nextWelds);
  }
  std::cout << "[ checked  ] recut / " << name << ": " << totals.splits << " splits over " << kGenerations
            << " generations, " << totals.misses << " planes missing a thin piece, " << totals.failures
            << " failing\n";
  return totals;
}

TEST(SplitRecutStress, FiveGenerationsOfRandomCutsUnderRandomRigidMotions) {
  const std::vector<std::pair<std::string, MeshData>> shapes = {
      {"cylinder", prim::cylinder(0.4f, 1.2f, 40)},
      {"sphere", prim::uvSphere(0.5f, 32, 17)},
      {"box", prim::box(glm::vec3(0.5f, 0.3f, 0.2f))},
      {"capsule", prim::capsule(0.3f, 0.6f, 24, 12)},
  };
  size_t splits = 0, failures = 0;
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    for (const auto& [name, mesh] : shapes) {
      const RecutTotals t = runRecutGenerations(name + "_seed" + std::to_string(seed), mesh, 1000 + seed);
      splits += t.splits;
      failures += t.failures;
    }
  }
  ::testing::Test::RecordProperty("recutSplits", static_cast<int>(splits));
  EXPECT_GE(splits, 300u);
  EXPECT_EQ(failures, 0u);
}

// ---- The independent section area, checked on its own so the invariants above can trust it. ----

TEST(SectionArea, AxisCutOfABoxIsTheFaceArea) {
  MeshData box = prim::box(glm::vec3(0.5f, 1.f, 0.25f));
  std::vector<glm::dvec3> p = testing::toCutSpace(box, glm::dmat4(1.0));
  EXPECT_NEAR(testing::sectionArea(p, box.indices, planeOf({0, 1, 0}, 0.3)), 1.0 * 0.5, 1e-15);
  EXPECT_NEAR(testing::sectionArea(p, box.indices, planeOf({0, -2, 0}, 0.6)), 1.0 * 0.5, 1e-15);
  EXPECT_NEAR(testing::sectionArea(p, box.indices, planeOf({1, 0, 0}, 0.0)), 2.0 * 0.5, 1e-15);
  EXPECT_EQ(testing::sectionArea(p, box.indices, planeOf({0, 1, 0}, 5.0)), 0.0);
}

TEST(SectionArea, TiltedCutOfACubeFollowsTheSlope) {
  MeshData box = prim::box(glm::vec3(1.f));
  std::vector<glm::dvec3> p = testing::toCutSpace(box, glm::dmat4(1.0));
  // y + z/2 = 0 crosses the cube as a 2 x 2 sqrt(1.25) rectangle.
  EXPECT_NEAR(testing::sectionArea(p, box.indices, planeOf({0, 1, 0.5}, 0.0)), 4.0 * std::sqrt(1.25), 1e-12);
}

TEST(SectionArea, HoleOfAHollowSphereCountsNegative) {
  MeshData outer = prim::uvSphere(1.f, 64, 33);  // odd ring count: no vertex on the equator
  MeshData shell = prim::hollowSphere(1.f, 0.5f, 64, 33);
  MeshData inner = prim::uvSphere(0.5f, 64, 33);
  auto area = [](const MeshData& m) {
    std::vector<glm::dvec3> p = testing::toCutSpace(m, glm::dmat4(1.0));
    return testing::sectionArea(p, m.indices, planeOf({0, 1, 0}, 0.0));
  };
  EXPECT_NEAR(area(shell), area(outer) - area(inner), 1e-12);
  EXPECT_NEAR(area(shell) / (kPi * 0.75), 1.0, 5e-3);
}

TEST(SectionArea, VerticalCutOfATorusIsTwoDiscs) {
  MeshData torus = prim::torus(1.f, 0.25f, 128, 64);
  std::vector<glm::dvec3> p = testing::toCutSpace(torus, glm::dmat4(1.0));
  EXPECT_NEAR(testing::sectionArea(p, torus.indices, planeOf({0, 0, 1}, 0.0)) / (2 * kPi * 0.0625), 1.0, 5e-3);
}

TEST(SectionArea, AgreesForThePlaneAndItsOpposite) {
  MeshData comb = prim::combPrism(5);
  std::vector<glm::dvec3> p = testing::toCutSpace(comb, glm::dmat4(1.0));
  SeededRandom rng(3);
  for (int k = 0; k < 20; ++k) {
    glm::dvec3 n = rng.unitVector();
    double d = rng.uniform(-0.2, 0.2);
    EXPECT_NEAR(testing::sectionArea(p, comb.indices, planeOf(n, d)),
                testing::sectionArea(p, comb.indices, planeOf(-n, -d)), 1e-12);
  }
}

}  // namespace
}  // namespace cleave::geometry
