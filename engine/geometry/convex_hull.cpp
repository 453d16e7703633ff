// SPDX-License-Identifier: MIT
// Quickhull in double precision (Barber, Dobkin, Huhdanpaa, "The Quickhull Algorithm for Convex
// Hulls", ACM TOMS 1996).
//
// Every face keeps the list of points above it (its outside set). Faces are processed in creation
// order; the furthest point of a face's outside set becomes an apex, the faces it sees are found by
// a walk over face adjacency, and the horizon (edges between seen and unseen faces) is joined to the
// apex. Points of removed faces are handed to the new faces or dropped when inside. A point within
// the tolerance of a face is "on" it and never creates a face, which is what makes duplicate and
// coplanar points harmless. Adjacency is a directed-edge table (open addressing) used for look-ups
// only, so no hash order leaks into the output.
#include "cleave/geometry/convex_hull.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace cleave::geometry {

const char* toString(HullStatus status) {
  switch (status) {
    case HullStatus::Ok: return "Ok";
    case HullStatus::TooFewPoints: return "TooFewPoints";
    case HullStatus::Collinear: return "Collinear";
    case HullStatus::Coplanar: return "Coplanar";
    case HullStatus::InvalidInput: return "InvalidInput";
    case HullStatus::NumericalFailure: return "NumericalFailure";
  }
  return "Unknown";
}

namespace {

constexpr uint32_t kNone = 0xffffffffu;

uint64_t edgeKey(uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | uint64_t(b); }

// Directed edge -> face: linear probing in one array, erase by shifting the run back (no
// tombstones), so a hull of a few dozen points allocates once instead of once per edge.
class EdgeTable {
 public:
  // False when the edge is there already.
  bool insert(uint64_t key, uint32_t face) {
    if (2 * (count_ + 1) > keys_.size()) grow(std::max<size_t>(64, 2 * keys_.size()));
    size_t i = slot(key);
    while (keys_[i] != kEmpty) {
      if (keys_[i] == key) return false;
      i = (i + 1) & mask_;
    }
    keys_[i] = key;
    faces_[i] = face;
    ++count_;
    return true;
  }
  uint32_t find(uint64_t key) const {
    if (keys_.empty()) return kNone;
    for (size_t i = slot(key); keys_[i] != kEmpty; i = (i + 1) & mask_)
      if (keys_[i] == key) return faces_[i];
    return kNone;
  }
  void erase(uint64_t key) {
    if (keys_.empty()) return;
    size_t i = slot(key);
    while (keys_[i] != key) {
      if (keys_[i] == kEmpty) return;
      i = (i + 1) & mask_;
    }
    // Move back each later entry of the run that may sit in the hole (its home is not in (i, j]).
    for (size_t j = (i + 1) & mask_; keys_[j] != kEmpty; j = (j + 1) & mask_) {
      const size_t home = slot(keys_[j]);
      const bool between = i <= j ? (home > i && home <= j) : (home > i || home <= j);
      if (between) continue;
      keys_[i] = keys_[j];
      faces_[i] = faces_[j];
      i = j;
    }
    keys_[i] = kEmpty;
    --count_;
  }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t(0);
  size_t slot(uint64_t key) const { return size_t((key * 0x9e3779b97f4a7c15ull) >> 32) & mask_; }
  void grow(size_t capacity) {
    std::vector<uint64_t> keys(capacity, kEmpty);
    std::vector<uint32_t> faces(capacity, kNone);
    keys.swap(keys_);
    faces.swap(faces_);
    mask_ = capacity - 1;
    count_ = 0;
    for (size_t i = 0; i < keys.size(); ++i)
      if (keys[i] != kEmpty) insert(keys[i], faces[i]);
  }
  std::vector<uint64_t> keys_;
  std::vector<uint32_t> faces_;
  size_t mask_ = 0;
  size_t count_ = 0;
};

struct Face {
  uint32_t v[3] = {0, 0, 0};
  glm::dvec3 normal{0.0};
  double offset = 0.0;
  std::vector<uint32_t> outside;
  bool alive = true;
  uint32_t mark = 0;
};

class QuickHull {
 public:
  QuickHull(std::span<const glm::dvec3> input, double relativeTolerance) : input_(input) {
    tolerance_ = std::max(relativeTolerance, 1e-15);
  }

  ConvexHull run() {
    ConvexHull hull;
    if (input_.size() < 4) {
      return fail(hull, HullStatus::TooFewPoints,
                  "a convex hull needs at least four points, got " + std::to_string(input_.size()));
    }
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (size_t i = 0; i < input_.size(); ++i) {
      const glm::dvec3& p = input_[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        return fail(hull, HullStatus::InvalidInput,
                    "point " + std::to_string(i) + " has a NaN or infinite coordinate");
      }
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    // Work relative to the box centre so plane offsets stay small.
    const glm::dvec3 centre = 0.5 * (lo + hi);
    points_.resize(input_.size());
    for (size_t i = 0; i < input_.size(); ++i) points_[i] = input_[i] - centre;
    const double diagonal = glm::length(hi - lo);
    eps_ = tolerance_ * diagonal;
    if (!(diagonal > 0.0)) {
      return fail(hull, HullStatus::TooFewPoints, "all points coincide");
    }

    HullStatus status = buildInitialSimplex(hull);
    if (status != HullStatus::Ok) return hull;

    for (size_t f = 0; f < faces_.size(); ++f) {
      if (!faces_[f].alive || faces_[f].outside.empty()) continue;
      if (!addApex(static_cast<uint32_t>(f))) {
        return fail(hull, HullStatus::NumericalFailure,
                    "the horizon seen from a point was not a simple loop; the input is numerically "
                    "degenerate at tolerance " + std::to_string(eps_));
      }
    }
    if (!checkClosed()) {
      return fail(hull, HullStatus::NumericalFailure, "the hull surface did not close");
    }

    std::vector<uint32_t> remap(points_.size(), kNone);
    for (const Face& face : faces_) {
      if (!face.alive) continue;
      for (uint32_t k = 0; k < 3; ++k) {
        uint32_t v = face.v[k];
        if (remap[v] == kNone) {
          remap[v] = static_cast<uint32_t>(hull.positions.size());
          hull.positions.push_back(input_[v]);
          hull.sourceIndices.push_back(v);
        }
        hull.indices.push_back(remap[v]);
      }
    }
    return hull;
  }

 private:
  static ConvexHull& fail(ConvexHull& hull, HullStatus status, std::string message) {
    hull.status = status;
    hull.message = std::move(message);
    hull.positions.clear();
    hull.sourceIndices.clear();
    hull.indices.clear();
    return hull;
  }

  double distance(const Face& face, uint32_t p) const {
    return glm::dot(face.normal, points_[p]) - face.offset;
  }

  // Makes face (a, b, c), flipped if needed so that `below` is under it.
  uint32_t makeFace(uint32_t a, uint32_t b, uint32_t c) {
    Face face;
    face.v[0] = a;
    face.v[1] = b;
    face.v[2] = c;
    glm::dvec3 n = glm::cross(points_[b] - points_[a], points_[c] - points_[a]);
    double len = glm::length(n);
    face.normal = len > 0.0 ? n / len : glm::dvec3(0.0);
    face.offset = glm::dot(face.normal, points_[a]);
    faces_.push_back(std::move(face));
    return static_cast<uint32_t>(faces_.size() - 1);
  }

  bool linkFace(uint32_t f) {
    const Face& face = faces_[f];
    for (uint32_t k = 0; k < 3; ++k) {
      if (!edges_.insert(edgeKey(face.v[k], face.v[(k + 1) % 3]), f)) return false;
    }
    return true;
  }

  HullStatus buildInitialSimplex(ConvexHull& hull) {
    const size_t n = points_.size();
    // Extreme points along the axes; the farthest pair of them seeds the simplex.
    uint32_t extremes[6] = {0, 0, 0, 0, 0, 0};
    for (uint32_t i = 0; i < n; ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        if (points_[i][axis] < points_[extremes[2 * axis]][axis]) extremes[2 * axis] = i;
        if (points_[i][axis] > points_[extremes[2 * axis + 1]][axis]) extremes[2 * axis + 1] = i;
      }
    }
    uint32_t i0 = extremes[0], i1 = extremes[1];
    double best = -1.0;
    for (int a = 0; a < 6; ++a) {
      for (int b = a + 1; b < 6; ++b) {
        double d = glm::length(points_[extremes[a]] - points_[extremes[b]]);
        if (d > best) {
          best = d;
          i0 = extremes[a];
          i1 = extremes[b];
        }
      }
    }
    if (best <= eps_) {
      fail(hull, HullStatus::TooFewPoints, "all points lie within the tolerance of one point");
      return hull.status;
    }
    const glm::dvec3 axis = (points_[i1] - points_[i0]) / best;
    uint32_t i2 = kNone;
    best = eps_;
    for (uint32_t i = 0; i < n; ++i) {
      glm::dvec3 d = points_[i] - points_[i0];
      double off = glm::length(d - glm::dot(d, axis) * axis);
      if (off > best) {
        best = off;
        i2 = i;
      }
    }
    if (i2 == kNone) {
      fail(hull, HullStatus::Collinear, "all points lie on one line: the hull has no volume");
      return hull.status;
    }
    glm::dvec3 planeNormal =
        glm::normalize(glm::cross(points_[i1] - points_[i0], points_[i2] - points_[i0]));
    uint32_t i3 = kNone;
    best = eps_;
    for (uint32_t i = 0; i < n; ++i) {
      double off = std::abs(glm::dot(planeNormal, points_[i] - points_[i0]));
      if (off > best) {
        best = off;
        i3 = i;
      }
    }
    if (i3 == kNone) {
      fail(hull, HullStatus::Coplanar, "all points lie in one plane: the hull has no volume");
      return hull.status;
    }

    const uint32_t tetra[4][4] = {{i0, i1, i2, i3}, {i0, i1, i3, i2}, {i0, i2, i3, i1}, {i1, i2, i3, i0}};
    for (const auto& t : tetra) {
      uint32_t f = makeFace(t[0], t[1], t[2]);
      if (distance(faces_[f], t[3]) > 0.0) {
        faces_.pop_back();
        f = makeFace(t[0], t[2], t[1]);
      }
      if (!linkFace(f)) {
        fail(hull, HullStatus::NumericalFailure, "could not orient the initial simplex");
        return hull.status;
      }
    }
    for (uint32_t i = 0; i < n; ++i) {
      if (i == i0 || i == i1 || i == i2 || i == i3) continue;
      assignToFaces(i, 0);
    }
    return HullStatus::Ok;
  }

  // Puts point p in the outside set of the face (from `firstFace` on) it is farthest above.
  void assignToFaces(uint32_t p, size_t firstFace) {
    uint32_t bestFace = kNone;
    double best = eps_;
    for (size_t f = firstFace; f < faces_.size(); ++f) {
      if (!faces_[f].alive) continue;
      double d = distance(faces_[f], p);
      if (d > best) {
        best = d;
        bestFace = static_cast<uint32_t>(f);
      }
    }
    if (bestFace != kNone) faces_[bestFace].outside.push_back(p);
  }

  bool addApex(uint32_t seed) {
    Face& seedFace = faces_[seed];
    uint32_t apex = seedFace.outside.front();
    double best = distance(seedFace, apex);
    for (uint32_t p : seedFace.outside) {
      double d = distance(seedFace, p);
      if (d > best) {
        best = d;
        apex = p;
      }
    }

    // Walk the faces that see the apex; collect the horizon in walk order.
    ++markCounter_;
    visible_.clear();
    horizon_.clear();
    stack_.clear();
    stack_.push_back(seed);
    faces_[seed].mark = markCounter_;
    while (!stack_.empty()) {
      uint32_t f = stack_.back();
      stack_.pop_back();
      visible_.push_back(f);
      for (uint32_t k = 0; k < 3; ++k) {
        uint32_t a = faces_[f].v[k], b = faces_[f].v[(k + 1) % 3];
        const uint32_t g = edges_.find(edgeKey(b, a));
        if (g == kNone) return false;
        if (faces_[g].mark == markCounter_) continue;
        if (distance(faces_[g], apex) > eps_) {
          faces_[g].mark = markCounter_;
          stack_.push_back(g);
        } else {
          horizon_.push_back({a, b});
        }
      }
    }
    orphans_.clear();
    for (uint32_t f : visible_) {
      Face& face = faces_[f];
      face.alive = false;
      for (uint32_t k = 0; k < 3; ++k) edges_.erase(edgeKey(face.v[k], face.v[(k + 1) % 3]));
      for (uint32_t p : face.outside) {
        if (p != apex) orphans_.push_back(p);
      }
      face.outside.clear();
      face.outside.shrink_to_fit();
    }

    const size_t firstNew = faces_.size();
    for (const auto& e : horizon_) {
      uint32_t f = makeFace(e[0], e[1], apex);
      if (!linkFace(f)) return false;
    }
    // Every new edge to the apex must meet its partner: the horizon is one simple loop.
    for (size_t f = firstNew; f < faces_.size(); ++f) {
      const Face& face = faces_[f];
      for (uint32_t k = 0; k < 3; ++k) {
        if (edges_.find(edgeKey(face.v[(k + 1) % 3], face.v[k])) == kNone) return false;
      }
    }
    for (uint32_t p : orphans_) assignToFaces(p, firstNew);
    return true;
  }

  bool checkClosed() const {
    for (const Face& face : faces_) {
      if (!face.alive) continue;
      for (uint32_t k = 0; k < 3; ++k) {
        if (edges_.find(edgeKey(face.v[(k + 1) % 3], face.v[k])) == kNone) return false;
      }
    }
    return true;
  }

  std::span<const glm::dvec3> input_;
  std::vector<glm::dvec3> points_;
  double tolerance_ = 1e-9;
  double eps_ = 0.0;
  std::vector<Face> faces_;
  EdgeTable edges_;  // directed edge -> face; look-ups only
  uint32_t markCounter_ = 0;
  std::vector<uint32_t> visible_;
  std::vector<uint32_t> stack_;
  std::vector<std::array<uint32_t, 2>> horizon_;
  std::vector<uint32_t> orphans_;
};

double signedVolume(std::span<const glm::dvec3> p, std::span<const uint32_t> indices,
                    const glm::dvec3& ref) {
  double sixV = 0.0;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    glm::dvec3 a = p[indices[t]] - ref, b = p[indices[t + 1]] - ref, c = p[indices[t + 2]] - ref;
    sixV += glm::dot(a, glm::cross(b, c));
  }
  return sixV / 6.0;
}

}  // namespace

ConvexHull computeConvexHull(std::span<const glm::dvec3> points, double relativeTolerance) {
  QuickHull builder(points, relativeTolerance);
  return builder.run();
}

ConvexHull computeConvexHull(std::span<const glm::vec3> points, double relativeTolerance) {
  std::vector<glm::dvec3> copy(points.begin(), points.end());
  return computeConvexHull(std::span<const glm::dvec3>(copy), relativeTolerance);
}

MeshData toMeshData(const ConvexHull& hull) {
  MeshData mesh;
  mesh.positions.reserve(hull.positions.size());
  for (const glm::dvec3& p : hull.positions) mesh.positions.emplace_back(p);
  mesh.indices = hull.indices;
  return mesh;
}

std::vector<uint32_t> extremePoints(std::span<const glm::dvec3> points, uint32_t count) {
  std::vector<char> keep(points.size(), 0);
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  for (uint32_t i = 0; i < count && !points.empty(); ++i) {
    const double z = 1.0 - 2.0 * (double(i) + 0.5) / double(count);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden * double(i);
    const glm::dvec3 dir(r * std::cos(phi), r * std::sin(phi), z);
    size_t best = 0;
    double bestDot = -std::numeric_limits<double>::infinity();
    for (size_t v = 0; v < points.size(); ++v) {
      const double d = dir.x * points[v].x + dir.y * points[v].y + dir.z * points[v].z;
      if (d > bestDot) {  // strict: ties keep the lowest index
        bestDot = d;
        best = v;
      }
    }
    keep[best] = 1;
  }
  std::vector<uint32_t> out;
  for (uint32_t v = 0; v < points.size(); ++v)
    if (keep[v]) out.push_back(v);
  return out;
}

bool isConvex(const MeshData& mesh, double relativeTolerance) {
  const size_t n = mesh.positions.size();
  if (mesh.indices.empty() || mesh.indices.size() % 3 != 0 || n < 4) return false;
  std::vector<glm::dvec3> p(n);
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (size_t i = 0; i < n; ++i) {
    p[i] = glm::dvec3(mesh.positions[i]);
    if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y) || !std::isfinite(p[i].z)) return false;
    lo = glm::min(lo, p[i]);
    hi = glm::max(hi, p[i]);
  }
  for (uint32_t index : mesh.indices) {
    if (index >= n) return false;
  }
  const double diagonal = glm::length(hi - lo);
  const double tol = relativeTolerance * diagonal;
  const glm::dvec3 centre = 0.5 * (lo + hi);

  // Exact weld: equal coordinates share an id (value comparison, so -0 and +0 weld).
  std::vector<uint32_t> order(n);
  for (uint32_t i = 0; i < n; ++i) order[i] = i;
  auto less = [&](uint32_t a, uint32_t b) {
    const glm::vec3 &pa = mesh.positions[a], &pb = mesh.positions[b];
    if (pa.x != pb.x) return pa.x < pb.x;
    if (pa.y != pb.y) return pa.y < pb.y;
    if (pa.z != pb.z) return pa.z < pb.z;
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<uint32_t> id(n);
  uint32_t next = 0;
  for (size_t k = 0; k < n; ++k) {
    if (k > 0 && mesh.positions[order[k]] != mesh.positions[order[k - 1]]) ++next;
    id[order[k]] = next;
  }

  struct Edge {
    uint64_t key;
    uint32_t triangle;
    uint32_t opposite;  // vertex index (not id) opposite the edge
  };
  std::vector<Edge> edges;
  edges.reserve(mesh.indices.size());
  for (uint32_t t = 0; t < mesh.indices.size() / 3; ++t) {
    const uint32_t* v = &mesh.indices[3 * t];
    if (id[v[0]] == id[v[1]] || id[v[1]] == id[v[2]] || id[v[2]] == id[v[0]]) continue;
    for (uint32_t k = 0; k < 3; ++k) {
      edges.push_back({edgeKey(id[v[k]], id[v[(k + 1) % 3]]), t, v[(k + 2) % 3]});
    }
  }
  if (edges.empty()) return false;
  std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) { return a.key < b.key; });
  for (size_t k = 1; k < edges.size(); ++k) {
    if (edges[k].key == edges[k - 1].key) return false;  // non-manifold or misoriented
  }
  for (const Edge& e : edges) {
    uint64_t reverse = (e.key << 32) | (e.key >> 32);
    auto it = std::lower_bound(edges.begin(), edges.end(), reverse,
                               [](const Edge& a, uint64_t key) { return a.key < key; });
    if (it == edges.end() || it->key != reverse) return false;  // open
    const uint32_t* v = &mesh.indices[3 * e.triangle];
    glm::dvec3 normal = glm::cross(p[v[1]] - p[v[0]], p[v[2]] - p[v[0]]);
    double len = glm::length(normal);
    if (!(len > 1e-300)) continue;  // a sliver has no plane to test against
    if (glm::dot(normal / len, p[it->opposite] - p[v[0]]) > tol) return false;  // reflex edge
  }

  const double meshVolume = signedVolume(p, mesh.indices, centre);
  if (!(meshVolume > 0.0)) return false;
  ConvexHull hull = computeConvexHull(std::span<const glm::dvec3>(p), 1e-12);
  if (hull.status != HullStatus::Ok) return false;
  const double hullVolume = signedVolume(hull.positions, hull.indices, centre);
  double hullArea = 0.0;
  for (size_t t = 0; t < hull.indices.size(); t += 3) {
    const glm::dvec3& a = hull.positions[hull.indices[t]];
    hullArea += 0.5 * glm::length(glm::cross(hull.positions[hull.indices[t + 1]] - a,
                                             hull.positions[hull.indices[t + 2]] - a));
  }
  return hullVolume - meshVolume <= tol * hullArea + 1e-12 * hullVolume;
}

}  // namespace cleave::geometry
