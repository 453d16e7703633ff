// SPDX-License-Identifier: MIT
#include "cleave/geometry/island_contacts.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace cleave::geometry {

namespace {

constexpr uint32_t kNone = 0xffffffffu;
constexpr double kPi = 3.14159265358979323846;
// Pairs with at most this many candidate triangle pairs are tested directly, without a grid.
constexpr size_t kDirectPairs = 4096;
// A triangle of B over more grid cells than this is tested against every triangle of A instead.
constexpr size_t kMaxCellsPerTriangle = 64;

double orient(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) {
  return glm::dot(a - d, glm::cross(b - d, c - d));
}

int sign(double v) { return (v > 0.0) - (v < 0.0); }

struct Box {
  glm::dvec3 lo, hi;
};

Box triangleBox(const glm::dvec3* t, double grow) {
  return {glm::min(glm::min(t[0], t[1]), t[2]) - grow, glm::max(glm::max(t[0], t[1]), t[2]) + grow};
}

bool overlaps(const Box& a, const Box& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
         b.lo.z <= a.hi.z;
}

// Triangles a and b cross, or a corner of one lies within the tolerance of the other.
bool trianglesTouch(const glm::dvec3* a, const glm::dvec3* b, double tolerance) {
  if (!overlaps(triangleBox(a, tolerance), triangleBox(b, 0.0))) return false;
  for (int e = 0; e < 3; ++e) {
    if (segmentCrossesTriangle(a[e], a[(e + 1) % 3], b[0], b[1], b[2])) return true;
    if (segmentCrossesTriangle(b[e], b[(e + 1) % 3], a[0], a[1], a[2])) return true;
  }
  const double tolerance2 = tolerance * tolerance;
  for (int k = 0; k < 3; ++k) {
    if (pointTriangleDistance2(a[k], b[0], b[1], b[2]) <= tolerance2) return true;
    if (pointTriangleDistance2(b[k], a[0], a[1], a[2]) <= tolerance2) return true;
  }
  return false;
}

// Generalised winding number of the triangles of component `of` at q (1 inside a closed outward
// surface, 0 outside).
double windingAt(std::span<const glm::dvec3> corners, const ContactScratch& s, uint32_t of, const glm::dvec3& q) {
  double solidAngle = 0.0;
  for (uint32_t t = s.first[of]; t != kNone; t = s.next[t]) {
    const glm::dvec3 a = corners[3 * t] - q, b = corners[3 * t + 1] - q, c = corners[3 * t + 2] - q;
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double numerator = glm::dot(a, glm::cross(b, c));
    const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(b, c) * la + glm::dot(c, a) * lb;
    solidAngle += 2.0 * std::atan2(numerator, denominator);
  }
  return solidAngle / (4.0 * kPi);
}

// The triangles of component c whose boxes meet `region`.
void trianglesIn(std::span<const glm::dvec3> corners, const ContactScratch& s, uint32_t c, const Box& region,
                 std::vector<uint32_t>& out) {
  out.clear();
  for (uint32_t t = s.first[c]; t != kNone; t = s.next[t]) {
    if (overlaps(triangleBox(&corners[3 * t], 0.0), region)) out.push_back(t);
  }
}

class GridTest {
 public:
  GridTest(std::span<const glm::dvec3> corners, ContactScratch& s, const Box& region, double tolerance)
      : corners_(corners), s_(s), region_(region), tolerance_(tolerance) {}

  // Whether a triangle of trianglesA touches one of trianglesB.
  bool run() {
    const std::vector<uint32_t>& a = s_.trianglesA;
    const std::vector<uint32_t>& b = s_.trianglesB;
    if (a.size() * b.size() <= kDirectPairs) {
      for (uint32_t ta : a) {
        for (uint32_t tb : b) {
          if (trianglesTouch(&corners_[3 * ta], &corners_[3 * tb], tolerance_)) return true;
        }
      }
      return false;
    }
    const glm::dvec3 size = region_.hi - region_.lo;
    const double longest = std::max({size.x, size.y, size.z});
    const int n = std::clamp(static_cast<int>(std::cbrt(double(b.size()))) + 1, 1, 256);
    cell_ = longest > 0.0 ? longest / n : 1.0;
    for (int k = 0; k < 3; ++k) cells_[k] = std::max(1, static_cast<int>(std::ceil(size[k] / cell_)));
    s_.cells.clear();
    s_.big.clear();
    for (uint32_t tb : b) {
      int lo[3], hi[3];
      cellRange(triangleBox(&corners_[3 * tb], tolerance_), lo, hi);
      const size_t covered = size_t(hi[0] - lo[0] + 1) * size_t(hi[1] - lo[1] + 1) * size_t(hi[2] - lo[2] + 1);
      if (covered > kMaxCellsPerTriangle) {
        s_.big.push_back(tb);
        continue;
      }
      forCells(lo, hi, [&](uint32_t cell) { s_.cells.push_back((uint64_t(cell) << 32) | tb); });
    }
    std::sort(s_.cells.begin(), s_.cells.end());
    for (uint32_t ta : a) {
      const glm::dvec3* ca = &corners_[3 * ta];
      for (uint32_t tb : s_.big) {
        if (trianglesTouch(ca, &corners_[3 * tb], tolerance_)) return true;
      }
      int lo[3], hi[3];
      cellRange(triangleBox(ca, 0.0), lo, hi);
      bool touched = false;
      forCells(lo, hi, [&](uint32_t cell) {
        if (touched) return;
        auto it = std::lower_bound(s_.cells.begin(), s_.cells.end(), uint64_t(cell) << 32);
        for (; it != s_.cells.end() && (*it >> 32) == cell && !touched; ++it) {
          touched = trianglesTouch(ca, &corners_[3 * (*it & 0xffffffffu)], tolerance_);
        }
      });
      if (touched) return true;
    }
    return false;
  }

 private:
  void cellRange(const Box& box, int* lo, int* hi) const {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::clamp(static_cast<int>(std::floor((box.lo[k] - region_.lo[k]) / cell_)), 0, cells_[k] - 1);
      hi[k] = std::clamp(static_cast<int>(std::floor((box.hi[k] - region_.lo[k]) / cell_)), 0, cells_[k] - 1);
    }
  }
  template <class F>
  void forCells(const int* lo, const int* hi, F&& f) const {
    for (int z = lo[2]; z <= hi[2]; ++z) {
      for (int y = lo[1]; y <= hi[1]; ++y) {
        for (int x = lo[0]; x <= hi[0]; ++x) f(static_cast<uint32_t>((z * cells_[1] + y) * cells_[0] + x));
      }
    }
  }

  std::span<const glm::dvec3> corners_;
  ContactScratch& s_;
  Box region_;
  double tolerance_;
  double cell_ = 1.0;
  int cells_[3] = {1, 1, 1};
};

bool inside(const Box& inner, const Box& outer) {
  return glm::all(glm::greaterThanEqual(inner.lo, outer.lo)) && glm::all(glm::lessThanEqual(inner.hi, outer.hi));
}

// Whether components a and b touch, overlap, or one holds the other.
bool componentsMeet(std::span<const glm::dvec3> corners, ContactScratch& s, uint32_t a, uint32_t b,
                    double tolerance) {
  const Box boxA{s.lo[a], s.hi[a]}, boxB{s.lo[b], s.hi[b]};
  const Box region{glm::max(boxA.lo, boxB.lo) - tolerance, glm::min(boxA.hi, boxB.hi) + tolerance};
  trianglesIn(corners, s, a, region, s.trianglesA);
  trianglesIn(corners, s, b, region, s.trianglesB);
  if (!s.trianglesA.empty() && !s.trianglesB.empty() && GridTest(corners, s, region, tolerance).run()) return true;
  const Box grownB{boxB.lo - tolerance, boxB.hi + tolerance}, grownA{boxA.lo - tolerance, boxA.hi + tolerance};
  if (inside(boxA, grownB) && std::abs(windingAt(corners, s, b, corners[3 * s.first[a]])) > 0.5) return true;
  if (inside(boxB, grownA) && std::abs(windingAt(corners, s, a, corners[3 * s.first[b]])) > 0.5) return true;
  return false;
}

uint32_t findRoot(std::vector<uint32_t>& parent, uint32_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace

bool segmentCrossesTriangle(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& a, const glm::dvec3& b,
                            const glm::dvec3& c) {
  const int sp = sign(orient(a, b, c, p)), sq = sign(orient(a, b, c, q));
  if (sp == sq) return false;  // both on one side, or both in the plane (left to the distance test)
  const int s0 = sign(orient(p, q, a, b)), s1 = sign(orient(p, q, b, c)), s2 = sign(orient(p, q, c, a));
  return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

// Closest point on a triangle by its Voronoi regions (Ericson, Real-Time Collision Detection 5.1.5).
double pointTriangleDistance2(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  auto at = [&](const glm::dvec3& x) { return glm::dot(p - x, p - x); };
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return at(a);
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return at(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return at(a + ab * (d1 / (d1 - d3)));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return at(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return at(a + ac * (d2 / (d2 - d6)));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) return at(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) return std::min({at(a), at(b), at(c)});  // degenerate triangle
  return at(a + ab * (vb / sum) + ac * (vc / sum));
}

void overlappingBoxes(std::span<const glm::dvec3> lo, std::span<const glm::dvec3> hi, double tolerance,
                      std::vector<std::pair<uint32_t, uint32_t>>& pairs, std::vector<uint32_t>& byX) {
  const uint32_t count = static_cast<uint32_t>(lo.size());
  byX.resize(count);
  std::iota(byX.begin(), byX.end(), 0u);
  std::sort(byX.begin(), byX.end(), [&](uint32_t a, uint32_t b) { return lo[a].x != lo[b].x ? lo[a].x < lo[b].x : a < b; });
  pairs.clear();
  auto empty = [&](uint32_t c) { return lo[c].x > hi[c].x; };
  for (size_t i = 0; i < count; ++i) {
    const uint32_t a = byX[i];
    if (empty(a)) continue;
    const Box grown{lo[a] - tolerance, hi[a] + tolerance};
    for (size_t j = i + 1; j < count && lo[byX[j]].x <= hi[a].x + tolerance; ++j) {
      const uint32_t b = byX[j];
      if (!empty(b) && overlaps(grown, Box{lo[b], hi[b]})) pairs.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(pairs.begin(), pairs.end());
}

uint32_t joinTouchingComponents(std::span<const glm::dvec3> corners, std::span<const uint32_t> component,
                                uint32_t count, double tolerance, std::vector<uint32_t>& root,
                                ContactScratch& s) {
  root.resize(count);
  std::iota(root.begin(), root.end(), 0u);
  if (count < 2) return 0;
  const size_t triangles = component.size();
  s.lo.assign(count, glm::dvec3(INFINITY));
  s.hi.assign(count, glm::dvec3(-INFINITY));
  s.first.assign(count, kNone);
  s.next.resize(triangles);
  for (size_t t = triangles; t-- > 0;) {  // lists in ascending triangle order
    const uint32_t c = component[t];
    const Box box = triangleBox(&corners[3 * t], 0.0);
    s.lo[c] = glm::min(s.lo[c], box.lo);
    s.hi[c] = glm::max(s.hi[c], box.hi);
    s.next[t] = s.first[c];
    s.first[c] = static_cast<uint32_t>(t);
  }
  overlappingBoxes(s.lo, s.hi, tolerance, s.pairs, s.byX);
  s.parent.resize(count);
  std::iota(s.parent.begin(), s.parent.end(), 0u);
  uint32_t joins = 0;
  for (const auto& [a, b] : s.pairs) {
    const uint32_t ra = findRoot(s.parent, a), rb = findRoot(s.parent, b);
    if (ra == rb || !componentsMeet(corners, s, a, b, tolerance)) continue;
    s.parent[std::max(ra, rb)] = std::min(ra, rb);
    ++joins;
  }
  for (uint32_t c = 0; c < count; ++c) root[c] = findRoot(s.parent, c);
  return joins;
}

}  // namespace cleave::geometry
