// SPDX-License-Identifier: MIT
// Mass properties by the divergence theorem.
//
// Each triangle (a, b, c), taken relative to a reference point r, spans a signed tetrahedron with r.
// With det = a . (b x c), the tetrahedron contributes (Tonon 2004; Blow and Binstock, "How to find
// the inertia tensor (or other mass properties) of a 3D solid body represented by a triangle mesh"):
//   volume           det / 6
//   first moment     det / 24  * (a + b + c)
//   second moment    det / 120 * (a a^T + b b^T + c c^T + (a+b+c)(a+b+c)^T)
// which is the canonical-tetrahedron covariance mapped by the matrix [a b c]. Summed over a closed,
// consistently wound surface the contributions outside the solid cancel. Using the bounding-box
// centre as r keeps every product small, so the sums lose little precision in double.
#include "cleave/geometry/mass_properties.h"

#include <algorithm>
#include <numeric>
#include <cmath>
#include <vector>

#include "cleave/geometry/convex_hull.h"
#include "cleave/geometry/index_range.h"
#include "cleave/geometry/mass_kernel.h"

namespace cleave::geometry {
namespace {

template <class Vec>
bool validInput(std::span<const Vec> positions, std::span<const uint32_t> indices) {
  if (indices.empty() || indices.size() % 3 != 0) return false;
  for (uint32_t index : indices) {
    if (index >= positions.size()) return false;
  }
  for (const Vec& p : positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  }
  return true;
}

// Ids such that two vertices share an id exactly when their coordinates compare equal.
template <class Vec>
std::vector<uint32_t> weldExactly(std::span<const Vec> positions) {
  const uint32_t n = static_cast<uint32_t>(positions.size());
  std::vector<uint32_t> order(n);
  for (uint32_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    const Vec &pa = positions[a], &pb = positions[b];
    if (pa.x != pb.x) return pa.x < pb.x;
    if (pa.y != pb.y) return pa.y < pb.y;
    if (pa.z != pb.z) return pa.z < pb.z;
    return a < b;
  });
  std::vector<uint32_t> id(n);
  uint32_t next = 0;
  for (uint32_t k = 0; k < n; ++k) {
    if (k > 0 && positions[order[k]] != positions[order[k - 1]]) ++next;
    id[order[k]] = next;
  }
  return id;
}

// Whether, on the ids, every directed edge of a non-degenerate triangle is used once and its reverse
// once. The directed edges go into an open-addressing set (a repeat is an edge used twice the same
// way), then each one's reverse is looked up: linear in the edges, where a sort was not (the open
// pieces of multi-part art ask this of every piece and of every part of it).
bool closedOnIds(std::span<const uint32_t> id, std::span<const uint32_t> indices) {
  std::vector<uint64_t> edges;
  edges.reserve(indices.size());
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    uint32_t a = id[indices[t]], b = id[indices[t + 1]], c = id[indices[t + 2]];
    if (a == b || b == c || c == a) continue;
    edges.push_back((uint64_t(a) << 32) | b);
    edges.push_back((uint64_t(b) << 32) | c);
    edges.push_back((uint64_t(c) << 32) | a);
  }
  if (edges.empty()) return false;
  constexpr uint64_t kEmpty = ~uint64_t(0);  // never an edge: its two ids would be equal
  int shift = 63;
  size_t capacity = 2;
  while (capacity < 2 * edges.size()) {
    capacity *= 2;
    --shift;
  }
  std::vector<uint64_t> set(capacity, kEmpty);
  const size_t mask = capacity - 1;
  auto slotOf = [&](uint64_t key) {  // Fibonacci hashing: the top bits of the product
    size_t slot = static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> shift);
    while (set[slot] != kEmpty && set[slot] != key) slot = (slot + 1) & mask;
    return slot;
  };
  for (uint64_t e : edges) {
    const size_t slot = slotOf(e);
    if (set[slot] == e) return false;  // an edge used twice in the same direction
    set[slot] = e;
  }
  for (uint64_t e : edges) {
    const uint64_t reverse = (e << 32) | (e >> 32);
    if (set[slotOf(reverse)] != reverse) return false;
  }
  return true;
}

struct Moments {
  double volume = 0.0;
  glm::dvec3 first{0.0};   // integral of (x - r) dV
  glm::dmat3 second{0.0};  // integral of (x - r)(x - r)^T dV
};

Moments integrate(std::span<const glm::dvec3> p, std::span<const uint32_t> indices,
                  const glm::dvec3& ref, bool flip) {
  Moments m;
  const detail::MomentSums sums = detail::sumMoments(p, indices, ref, flip);
  const double xx = sums.xx, yy = sums.yy, zz = sums.zz, xy = sums.xy, yz = sums.yz, zx = sums.zx;
  m.volume = sums.sixV / 6.0;
  m.first = glm::dvec3(sums.fx, sums.fy, sums.fz) / 24.0;
  glm::dmat3 second(0.0);
  second[0][0] = xx;
  second[1][1] = yy;
  second[2][2] = zz;
  second[0][1] = second[1][0] = xy;
  second[1][2] = second[2][1] = yz;
  second[2][0] = second[0][2] = zx;
  m.second = second / 120.0;
  return m;
}

glm::dvec3 vertexCentroid(std::span<const glm::dvec3> p, std::span<const uint32_t> indices) {
  glm::dvec3 sum(0.0);
  for (uint32_t index : indices) sum += p[index];
  return sum / double(indices.size());
}

// Properties of the surface (p, indices), which the caller knows to be closed, whose referenced
// points lie within [lo, hi] (their bounds: the centre is the reference point of the sums).
MassProperties fromSurfaceWithin(std::span<const glm::dvec3> p, std::span<const uint32_t> indices, bool flip,
                                 const glm::dvec3& lo, const glm::dvec3& hi) {
  MassProperties out;
  const glm::dvec3 ref = 0.5 * (lo + hi);
  Moments m = integrate(p, indices, ref, flip);
  out.volume = m.volume;
  // Scale for "zero": the volume of a tetrahedron whose edges are 1e-12 of the mesh size.
  const double size = glm::length(hi - lo);
  if (!(std::abs(m.volume) > 1e-36 * size * size * size) || size == 0.0) {
    out.volume = 0.0;
    out.centerOfMass = vertexCentroid(p, indices);
    return out;
  }
  glm::dvec3 c = m.first / m.volume;
  glm::dmat3 central = m.second - m.volume * glm::outerProduct(c, c);
  double trace = central[0][0] + central[1][1] + central[2][2];
  glm::dmat3 inertia = trace * glm::dmat3(1.0) - central;
  // Symmetrise against rounding so consumers can rely on it.
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      double v = 0.5 * (inertia[i][j] + inertia[j][i]);
      inertia[i][j] = v;
      inertia[j][i] = v;
    }
  }
  out.centerOfMass = ref + c;
  out.inertia = inertia;
  return out;
}

// The same, the bounds taken first. With `everyPointUsed`, the caller knows every point is a corner
// of some triangle, and the bounds are taken over the points (a sixth of the reads, in order).
MassProperties fromSurface(std::span<const glm::dvec3> p, std::span<const uint32_t> indices,
                           bool flip, bool everyPointUsed = false) {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  if (everyPointUsed) {
    for (const glm::dvec3& q : p) {
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
  } else {
    for (uint32_t index : indices) {
      lo = glm::min(lo, p[index]);
      hi = glm::max(hi, p[index]);
    }
  }
  return fromSurfaceWithin(p, indices, flip, lo, hi);
}

// The convex hull of the referenced points stands in for an open surface.
MassProperties fromHull(std::span<const glm::dvec3> p, std::span<const uint32_t> indices) {
  std::vector<uint8_t> used(p.size(), 0);
  std::vector<glm::dvec3> referenced;
  for (uint32_t index : indices) {
    if (!used[index]) {
      used[index] = 1;
      referenced.push_back(p[index]);
    }
  }
  MassProperties out;
  ConvexHull hull = computeConvexHull(std::span<const glm::dvec3>(referenced));
  if (hull.status == HullStatus::Ok) {
    out = fromSurface(hull.positions, hull.indices, false);
  } else {
    out.centerOfMass = vertexCentroid(p, indices);
  }
  out.closed = false;
  out.fromConvexHull = true;
  return out;
}

// An open surface made of several parts (multi-part art: plates, bolts and limbs modelled apart) is
// the sum of its parts, each closed part integrated exactly and each open one by its hull; one part
// is its hull. Parts that pass into one another count their common volume twice.
MassProperties openSurface(std::span<const glm::dvec3> p, std::span<const uint32_t> id,
                           std::span<const uint32_t> indices, bool flip) {
  std::vector<uint32_t> parent(p.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    for (int c = 1; c < 3; ++c) {
      const uint32_t a = find(id[indices[t]]), b = find(id[indices[t + c]]);
      parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<std::pair<uint32_t, uint32_t>> byPart;  // (part root, triangle)
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    byPart.push_back({find(id[indices[t]]), static_cast<uint32_t>(t / 3)});
  }
  std::sort(byPart.begin(), byPart.end());
  if (byPart.empty() || byPart.front().first == byPart.back().first) return fromHull(p, indices);
  MassProperties sum;
  bool first = true;
  std::vector<uint32_t> part;
  for (size_t k = 0; k < byPart.size();) {
    part.clear();
    size_t j = k;
    for (; j < byPart.size() && byPart[j].first == byPart[k].first; ++j) {
      const uint32_t t = byPart[j].second;
      part.insert(part.end(), {indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]});
    }
    k = j;
    MassProperties one;
    if (closedOnIds(id, part)) {
      one = fromSurface(p, part, flip);
      one.closed = true;
    } else {
      one = fromHull(p, part);
    }
    sum = first ? one : combineMassProperties(sum, one);  // fromConvexHull when any part's is
    first = false;
  }
  sum.closed = false;
  return sum;
}

template <class Vec>
MassProperties compute(std::span<const Vec> positions, std::span<const uint32_t> indices,
                       const glm::dmat4& transform) {
  MassProperties out;
  if (!validInput(positions, indices)) return out;
  std::vector<glm::dvec3> p(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    p[i] = glm::dvec3(transform * glm::dvec4(glm::dvec3(positions[i]), 1.0));
  }
  // Exact weld on the given coordinates: an injective transform cannot change closedness.
  std::vector<uint32_t> id = weldExactly(positions);
  const bool closed = closedOnIds(id, indices);
  // A mirroring transform reverses the winding in the transformed space.
  const bool flip = glm::determinant(glm::dmat3(transform)) < 0.0;
  if (closed) {
    out = fromSurface(p, indices, flip);
    out.closed = true;
    return out;
  }
  return openSurface(p, id, indices, flip);
}

}  // namespace

MassProperties computeMassProperties(std::span<const glm::vec3> positions,
                                     std::span<const uint32_t> indices,
                                     const glm::dmat4& transform) {
  return compute(positions, indices, transform);
}

MassProperties computeMassProperties(std::span<const glm::dvec3> positions,
                                     std::span<const uint32_t> indices,
                                     const glm::dmat4& transform) {
  return compute(positions, indices, transform);
}

MassProperties computeMassProperties(const MeshData& mesh, const glm::dmat4& transform) {
  return computeMassProperties(std::span<const glm::vec3>(mesh.positions),
                               std::span<const uint32_t>(mesh.indices), transform);
}

MassProperties integrateClosedSurface(std::span<const glm::dvec3> positions,
                                      std::span<const uint32_t> indices, bool flipWinding,
                                      bool everyPointUsed) {
  if (indices.empty() || indices.size() % 3 != 0) return {};
  if (positions.size() <= UINT32_MAX && detail::anyAtOrAbove(indices, static_cast<uint32_t>(positions.size())))
    return {};
  MassProperties out = fromSurface(positions, indices, flipWinding, everyPointUsed);
  out.closed = true;
  return out;
}

namespace detail {
MassProperties integrateWrittenSurface(std::span<const glm::dvec3> positions, std::span<const uint32_t> indices,
                                       bool flipWinding, const glm::dvec3& lo, const glm::dvec3& hi) {
  MassProperties out = fromSurfaceWithin(positions, indices, flipWinding, lo, hi);
  out.closed = true;
  return out;
}
}  // namespace detail

MassProperties combineMassProperties(const MassProperties& a, const MassProperties& b) {
  MassProperties out;
  out.closed = a.closed && b.closed;
  out.fromConvexHull = a.fromConvexHull || b.fromConvexHull;
  out.volume = a.volume + b.volume;
  if (!(out.volume > 0.0)) {
    out.centerOfMass = 0.5 * (a.centerOfMass + b.centerOfMass);
    return out;
  }
  out.centerOfMass = (a.volume * a.centerOfMass + b.volume * b.centerOfMass) / out.volume;
  // Parallel axis theorem: each part's tensor moved from its centre to the common one.
  auto shifted = [&](const MassProperties& m) {
    const glm::dvec3 d = m.centerOfMass - out.centerOfMass;
    return m.inertia + m.volume * (glm::dot(d, d) * glm::dmat3(1.0) - glm::outerProduct(d, d));
  };
  out.inertia = shifted(a) + shifted(b);
  return out;
}

bool isClosedAndOriented(std::span<const glm::vec3> positions, std::span<const uint32_t> indices) {
  if (!validInput(positions, indices)) return false;
  std::vector<uint32_t> id = weldExactly(positions);
  return closedOnIds(id, indices);
}

PrincipalInertia principalInertia(const glm::dmat3& inertia) {
  // Cyclic Jacobi: rotate away the largest-remaining off-diagonal terms until they vanish. A 3x3
  // symmetric matrix converges quadratically; 50 sweeps is a generous bound.
  double a[3][3];
  double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a[r][c] = 0.5 * (inertia[c][r] + inertia[r][c]);
  }
  double scale = 0.0;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) scale = std::max(scale, std::abs(a[r][c]));
  }
  for (int sweep = 0; sweep < 50 && scale > 0.0; ++sweep) {
    double off = std::abs(a[0][1]) + std::abs(a[0][2]) + std::abs(a[1][2]);
    if (off <= 1e-15 * scale) break;
    static constexpr int kPairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    for (const auto& pair : kPairs) {
      const int p = pair[0], q = pair[1];
      if (std::abs(a[p][q]) <= 1e-300) continue;
      double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
      double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
      double c = 1.0 / std::sqrt(t * t + 1.0);
      double s = t * c;
      for (int k = 0; k < 3; ++k) {  // A <- A J
        double akp = a[k][p], akq = a[k][q];
        a[k][p] = c * akp - s * akq;
        a[k][q] = s * akp + c * akq;
      }
      for (int k = 0; k < 3; ++k) {  // A <- J^T A
        double apk = a[p][k], aqk = a[q][k];
        a[p][k] = c * apk - s * aqk;
        a[q][k] = s * apk + c * aqk;
      }
      for (int k = 0; k < 3; ++k) {  // V <- V J
        double vkp = v[k][p], vkq = v[k][q];
        v[k][p] = c * vkp - s * vkq;
        v[k][q] = s * vkp + c * vkq;
      }
    }
  }
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int x, int y) { return a[x][x] < a[y][y]; });
  PrincipalInertia out;
  for (int k = 0; k < 3; ++k) {
    const int src = order[k];
    out.moments[k] = a[src][src];
    out.axes[k] = glm::dvec3(v[0][src], v[1][src], v[2][src]);
  }
  if (glm::determinant(out.axes) < 0.0) out.axes[2] = -out.axes[2];
  return out;
}

}  // namespace cleave::geometry
