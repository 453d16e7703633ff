// MeshContainer: validation, welding by position, cut-space positions, triangle extraction.
//
// Welding. Vertices within 1e-6 of the bounding-box diagonal of each other share a position id (UV,
// normal and skin seams repeat a position with other attributes; the cut must see one point there).
// The method is a uniform grid of cells twice the tolerance wide: every vertex is sorted by (cell,
// index); a vertex can only meet a vertex within the tolerance in its own cell or, per axis, in the
// one neighbouring cell on the side of the cell it is nearest to, so 8 cells are searched. Vertices
// are visited in index order and join the id of the first (lowest-index) earlier vertex within the
// tolerance, so chains merge and the ids, numbered by first vertex, do not depend on sort details.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "engine/geometry/mesh_splitter.h"

namespace cleave::geometry {

namespace {

constexpr double kWeldRelative = 1e-6;
constexpr uint32_t kNone = 0xffffffffu;
constexpr int kCellBits = 21;
constexpr uint64_t kCellMask = (uint64_t(1) << kCellBits) - 1;

bool finite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

template <typename T>
bool sizedLike(const std::vector<T>& attribute, size_t n) {
  return attribute.empty() || attribute.size() == n;
}

void fail(std::string* message, const std::string& text) {
  if (message) *message = text;
}

}  // namespace

SplitStatus MeshContainer::setMesh(const MeshData& mesh, std::string* message) {
  auto reject = [&](const std::string& text) {
    fail(message, "invalid mesh: " + text);
    mesh_.positions.clear();
    mesh_.indices.clear();
    cutPositions_.clear();
    positionIds_.clear();
    representatives_.clear();
    positionIdCount_ = 0;
    boundsDiagonal_ = 0.0;
    closed_ = false;
    return SplitStatus::InvalidInput;
  };
  const size_t n = mesh.positions.size();
  if (mesh.indices.empty()) return reject("no triangle");
  if (mesh.indices.size() % 3 != 0) {
    return reject("index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
  }
  if (n >= kNone) return reject("too many vertices");
  for (size_t k = 0; k < mesh.indices.size(); ++k) {
    if (mesh.indices[k] >= n) {
      return reject("index " + std::to_string(mesh.indices[k]) + " at position " + std::to_string(k) +
                    " is out of range (" + std::to_string(n) + " vertices)");
    }
  }
  for (size_t i = 0; i < n; ++i) {
    if (!finite(mesh.positions[i])) return reject("vertex " + std::to_string(i) + " has a NaN or infinite position");
  }
  auto badSize = [&](const char* name, size_t size) {
    return reject(std::string("attribute '") + name + "' has " + std::to_string(size) + " entries for " +
                  std::to_string(n) + " vertices");
  };
  if (!sizedLike(mesh.normals, n)) return badSize("normals", mesh.normals.size());
  if (!sizedLike(mesh.tangents, n)) return badSize("tangents", mesh.tangents.size());
  if (!sizedLike(mesh.uv0, n)) return badSize("uv0", mesh.uv0.size());
  if (!sizedLike(mesh.uv1, n)) return badSize("uv1", mesh.uv1.size());
  if (!sizedLike(mesh.colors, n)) return badSize("colors", mesh.colors.size());
  if (!sizedLike(mesh.joints, n)) return badSize("joints", mesh.joints.size());
  if (mesh.weights.size() != mesh.joints.size()) return badSize("weights", mesh.weights.size());
  uint32_t covered = 0;
  for (size_t k = 0; k < mesh.submeshes.size(); ++k) {
    const SubMesh& run = mesh.submeshes[k];
    if (run.firstIndex != covered || run.indexCount % 3 != 0) {
      return reject("submesh " + std::to_string(k) + " does not continue the previous run by whole triangles");
    }
    covered += run.indexCount;
  }
  if (!mesh.submeshes.empty() && covered != mesh.indices.size()) {
    return reject("submesh runs cover " + std::to_string(covered) + " of " + std::to_string(mesh.indices.size()) +
                  " indices");
  }

  mesh_ = mesh;  // copy assignment keeps the capacity of our arrays
  model_ = glm::dmat4(1.0);
  jointMatrices_.clear();
  weld();
  cutPositions_.resize(n);
  for (size_t i = 0; i < n; ++i) cutPositions_[i] = glm::dvec3(mesh_.positions[i]);
  mirrored_ = false;
  updateBounds();
  if (message) message->clear();
  return SplitStatus::Ok;
}

void MeshContainer::weld() {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : mesh_.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  const double tolerance = kWeldRelative * glm::length(hi - lo);
  if (!weldHashed(tolerance, lo, hi)) weldSorted(tolerance, lo);
  positionIdCount_ = static_cast<uint32_t>(representatives_.size());
  computeClosed();
}

// The fast weld: a hashed grid of cells about one vertex spacing wide (at least four tolerances),
// each cell's vertices chained in ascending index order. A vertex is compared with the earlier
// vertices of its own cell and, along an axis where it lies within the tolerance of a cell face, of
// the neighbouring cell too; the first one within the tolerance (ascending order) is the lowest.
// Returns false, leaving the ids unset, when the vertices crowd into few cells (more comparisons
// than a fixed budget): the sorted weld below has no such worst case.
bool MeshContainer::weldHashed(double tolerance, const glm::dvec3& lo, const glm::dvec3& hi) {
  const size_t n = mesh_.positions.size();
  const glm::dvec3 extent = hi - lo;
  const double largest = std::max(extent.x, std::max(extent.y, extent.z));
  // About sqrt(n) cells along the largest side: a surface of n vertices puts a few in each cell.
  double cell = largest / std::max(1.0, std::ceil(std::sqrt(double(n))));
  cell = std::max(cell, 4.0 * tolerance);
  if (!(cell > 0.0) || !std::isfinite(cell)) cell = 1.0;  // every vertex at one point
  if (largest / cell > double(kCellMask - 2)) return false;
  size_t capacity = 16;
  while (capacity < 2 * n) capacity *= 2;
  const uint64_t mask = capacity - 1;
  cellKeys_.resize(capacity);
  cellFirst_.assign(capacity, kNone);
  cellLast_.resize(capacity);
  cellNext_.resize(n);
  positionIds_.resize(n);
  representatives_.clear();
  auto slotOf = [&](uint64_t key) {
    uint64_t h = key * 0x9E3779B97F4A7C15ull;
    size_t slot = static_cast<size_t>(h >> 20) & mask;
    while (cellFirst_[slot] != kNone && cellKeys_[slot] != key) slot = (slot + 1) & mask;
    return slot;
  };
  const double tolerance2 = tolerance * tolerance;
  const double reach = tolerance * 1.001;  // generous: the distance test below decides
  uint64_t budget = 64 * uint64_t(n) + 4096;
  for (uint32_t v = 0; v < n; ++v) {
    const glm::dvec3 p(mesh_.positions[v]);
    int64_t c[3];
    int lowSide[3], highSide[3];
    for (int a = 0; a < 3; ++a) {
      const double f = (p[a] - lo[a]) / cell;
      c[a] = static_cast<int64_t>(std::floor(f));
      const double inCell = p[a] - (lo[a] + double(c[a]) * cell);
      lowSide[a] = inCell <= reach && c[a] > 0 ? -1 : 0;
      highSide[a] = cell - inCell <= reach ? 1 : 0;
    }
    uint32_t best = kNone;
    for (int dx = lowSide[0]; dx <= highSide[0]; ++dx) {
      for (int dy = lowSide[1]; dy <= highSide[1]; ++dy) {
        for (int dz = lowSide[2]; dz <= highSide[2]; ++dz) {
          const uint64_t key = (uint64_t(c[0] + dx) << (2 * kCellBits)) | (uint64_t(c[1] + dy) << kCellBits) |
                               uint64_t(c[2] + dz);
          const size_t slot = slotOf(key);
          if (cellFirst_[slot] == kNone) continue;
          for (uint32_t w = cellFirst_[slot]; w != kNone && w < best; w = cellNext_[w]) {
            if (budget-- == 0) return false;
            const glm::dvec3 d = glm::dvec3(mesh_.positions[w]) - p;
            if (glm::dot(d, d) <= tolerance2) {
              best = w;
              break;
            }
          }
        }
      }
    }
    if (best != kNone) {
      positionIds_[v] = positionIds_[best];
    } else {
      positionIds_[v] = static_cast<uint32_t>(representatives_.size());
      representatives_.push_back(v);
    }
    const uint64_t own = (uint64_t(c[0]) << (2 * kCellBits)) | (uint64_t(c[1]) << kCellBits) | uint64_t(c[2]);
    const size_t slot = slotOf(own);
    cellNext_[v] = kNone;
    if (cellFirst_[slot] == kNone) {
      cellKeys_[slot] = own;
      cellFirst_[slot] = v;
    } else {
      cellNext_[cellLast_[slot]] = v;
    }
    cellLast_[slot] = v;
  }
  return true;
}

// The sorted weld: cells twice the tolerance wide; every vertex is sorted by (cell, index); a vertex
// can only meet a vertex within the tolerance in its own cell or, per axis, in the one neighbouring
// cell on the side of the cell it is nearest to, so 8 cells are searched by binary search.
void MeshContainer::weldSorted(double tolerance, const glm::dvec3& lo) {
  const size_t n = mesh_.positions.size();
  const double cell = 2.0 * tolerance;
  auto cellOf = [&](const glm::vec3& p, int axis, double* fraction) -> int64_t {
    if (!(cell > 0.0)) {
      if (fraction) *fraction = 0.5;
      return 0;
    }
    const double f = (double(p[axis]) - lo[axis]) / cell;
    const double c = std::floor(f);
    if (fraction) *fraction = f - c;
    return static_cast<int64_t>(c);
  };
  auto key = [](int64_t x, int64_t y, int64_t z) {
    return (uint64_t(x) << (2 * kCellBits)) | (uint64_t(y) << kCellBits) | uint64_t(z);
  };
  weldScratch_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3& p = mesh_.positions[i];
    weldScratch_[i] = key(cellOf(p, 0, nullptr), cellOf(p, 1, nullptr), cellOf(p, 2, nullptr));
  }
  weldOrder_.resize(n);
  std::iota(weldOrder_.begin(), weldOrder_.end(), 0u);
  std::sort(weldOrder_.begin(), weldOrder_.end(), [&](uint32_t a, uint32_t b) {
    return weldScratch_[a] != weldScratch_[b] ? weldScratch_[a] < weldScratch_[b] : a < b;
  });
  positionIds_.assign(n, kNone);
  representatives_.clear();
  const double tolerance2 = tolerance * tolerance;
  for (uint32_t v = 0; v < n; ++v) {
    const glm::vec3& p = mesh_.positions[v];
    const glm::dvec3 pd(p);
    int64_t c[3], side[3];
    for (int a = 0; a < 3; ++a) {
      double fraction;
      c[a] = cellOf(p, a, &fraction);
      side[a] = fraction < 0.5 ? -1 : 1;
    }
    uint32_t best = kNone;
    for (int combo = 0; combo < 8; ++combo) {
      int64_t q[3];
      bool valid = true;
      for (int a = 0; a < 3; ++a) {
        q[a] = c[a] + (((combo >> a) & 1) ? side[a] : 0);
        valid = valid && q[a] >= 0 && uint64_t(q[a]) <= kCellMask;
      }
      if (!valid || (combo != 0 && !(cell > 0.0))) continue;
      const uint64_t k = key(q[0], q[1], q[2]);
      auto first = std::lower_bound(weldOrder_.begin(), weldOrder_.end(), k,
                                    [&](uint32_t i, uint64_t value) { return weldScratch_[i] < value; });
      for (auto it = first; it != weldOrder_.end() && weldScratch_[*it] == k && *it < v; ++it) {
        if (*it >= best) break;
        const glm::dvec3 d = glm::dvec3(mesh_.positions[*it]) - pd;
        if (glm::dot(d, d) <= tolerance2) {
          best = *it;
          break;
        }
      }
    }
    if (best != kNone) {
      positionIds_[v] = positionIds_[best];
    } else {
      positionIds_[v] = static_cast<uint32_t>(representatives_.size());
      representatives_.push_back(v);
    }
  }
}

// Closedness on position ids: every directed edge of a non-degenerate triangle used once, and its
// reverse used once. The outgoing edges of each id are gathered by a counting sort; an id has few.
void MeshContainer::computeClosed() {
  const uint32_t ids = positionIdCount_;
  edgeStart_.assign(size_t(ids) + 1, 0u);
  const size_t indexCount = mesh_.indices.size();
  auto corners = [&](size_t t, uint32_t (&out)[3]) {
    out[0] = positionIds_[mesh_.indices[t]];
    out[1] = positionIds_[mesh_.indices[t + 1]];
    out[2] = positionIds_[mesh_.indices[t + 2]];
    return out[0] != out[1] && out[1] != out[2] && out[2] != out[0];
  };
  size_t edges = 0;
  for (size_t t = 0; t + 2 < indexCount; t += 3) {
    uint32_t c[3];
    if (!corners(t, c)) continue;
    for (int e = 0; e < 3; ++e) ++edgeStart_[c[e] + 1];
    edges += 3;
  }
  closed_ = edges > 0;
  if (!closed_) return;
  for (uint32_t id = 0; id < ids; ++id) edgeStart_[id + 1] += edgeStart_[id];
  edgeTargets_.resize(edges);
  cellNext_.assign(edgeStart_.begin(), edgeStart_.end() - 1);  // reused: fill cursor per id
  for (size_t t = 0; t + 2 < indexCount; t += 3) {
    uint32_t c[3];
    if (!corners(t, c)) continue;
    for (int e = 0; e < 3; ++e) edgeTargets_[cellNext_[c[e]]++] = c[(e + 1) % 3];
  }
  // Lists longer than kShort are sorted and searched by bisection; short ones are scanned.
  constexpr uint32_t kShort = 16;
  for (uint32_t a = 0; a < ids; ++a) {
    if (edgeStart_[a + 1] - edgeStart_[a] > kShort) {
      std::sort(edgeTargets_.begin() + edgeStart_[a], edgeTargets_.begin() + edgeStart_[a + 1]);
    }
  }
  auto count = [&](uint32_t from, uint32_t to) -> uint32_t {
    const auto first = edgeTargets_.begin() + edgeStart_[from], last = edgeTargets_.begin() + edgeStart_[from + 1];
    if (last - first > kShort) {
      const auto range = std::equal_range(first, last, to);
      return static_cast<uint32_t>(range.second - range.first);
    }
    uint32_t found = 0;
    for (auto it = first; it != last; ++it) found += *it == to;
    return found;
  };
  for (uint32_t a = 0; a < ids && closed_; ++a) {
    for (uint32_t k = edgeStart_[a]; k < edgeStart_[a + 1] && closed_; ++k) {
      const uint32_t b = edgeTargets_[k];
      // Each directed edge once, and its reverse once.
      closed_ = count(a, b) == 1 && count(b, a) == 1;
    }
  }
}

void MeshContainer::updateBounds() {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::dvec3& p : cutPositions_) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  boundsDiagonal_ = cutPositions_.empty() ? 0.0 : glm::length(hi - lo);
}

void MeshContainer::setTransform(const glm::mat4& model) {
  model_ = glm::dmat4(model);
  jointMatrices_.clear();
  cutPositions_.resize(mesh_.positions.size());
  for (size_t i = 0; i < cutPositions_.size(); ++i) {
    cutPositions_[i] = glm::dvec3(model_ * glm::dvec4(glm::dvec3(mesh_.positions[i]), 1.0));
  }
  mirrored_ = glm::determinant(glm::dmat3(model_)) < 0.0;
  updateBounds();
}

SplitStatus MeshContainer::setSkinningPose(std::span<const glm::mat4> jointMatrices, const glm::mat4& model,
                                           std::string* message) {
  if (mesh_.positions.empty()) {
    fail(message, "skinning pose: the container holds no mesh");
    return SplitStatus::InvalidInput;
  }
  if (mesh_.joints.empty() || mesh_.weights.size() != mesh_.joints.size()) {
    fail(message, "skinning pose: the mesh has no joints and weights");
    return SplitStatus::InvalidInput;
  }
  for (size_t j = 0; j < jointMatrices.size(); ++j) {
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) {
        if (!std::isfinite(jointMatrices[j][c][r])) {
          fail(message, "skinning pose: joint matrix " + std::to_string(j) + " is not finite");
          return SplitStatus::InvalidInput;
        }
      }
    }
  }
  const size_t n = mesh_.positions.size();
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 4; ++k) {
      if (mesh_.weights[i][k] != 0.f && mesh_.joints[i][k] >= jointMatrices.size()) {
        fail(message, "skinning pose: vertex " + std::to_string(i) + " uses joint " +
                          std::to_string(mesh_.joints[i][k]) + " of " + std::to_string(jointMatrices.size()));
        return SplitStatus::InvalidInput;
      }
    }
  }
  model_ = glm::dmat4(model);
  jointMatrices_.assign(jointMatrices.begin(), jointMatrices.end());
  cutPositions_.resize(n);
  size_t negative = 0;
  for (size_t i = 0; i < n; ++i) {
    glm::dmat4 blend(0.0);
    double total = 0.0;
    for (int k = 0; k < 4; ++k) {
      const double w = mesh_.weights[i][k];
      if (w == 0.0) continue;
      blend += w * jointMatrices_[mesh_.joints[i][k]];
      total += w;
    }
    blend = total > 0.0 ? blend / total : glm::dmat4(1.0);
    const glm::dmat4 m = model_ * blend;
    cutPositions_[i] = glm::dvec3(m * glm::dvec4(glm::dvec3(mesh_.positions[i]), 1.0));
    if (glm::determinant(glm::dmat3(m)) < 0.0) ++negative;
  }
  mirrored_ = 2 * negative > n;
  updateBounds();
  if (message) message->clear();
  return SplitStatus::Ok;
}

void MeshContainer::extractTriangles(std::span<const uint32_t> triangles, MeshData& out) const {
  out.positions.clear();
  out.normals.clear();
  out.tangents.clear();
  out.uv0.clear();
  out.uv1.clear();
  out.colors.clear();
  out.joints.clear();
  out.weights.clear();
  out.indices.clear();
  out.submeshes.clear();
  const size_t triangleCount = mesh_.indices.size() / 3;
  // Group the triangles by their run (runs in source order), keeping the given order inside a run.
  auto runOf = [&](uint32_t t) -> uint32_t {
    if (mesh_.submeshes.empty()) return 0;
    const uint32_t index = t * 3;
    auto it = std::upper_bound(mesh_.submeshes.begin(), mesh_.submeshes.end(), index,
                               [](uint32_t value, const SubMesh& run) { return value < run.firstIndex; });
    return static_cast<uint32_t>(it - mesh_.submeshes.begin()) - 1;
  };
  std::vector<std::pair<uint64_t, uint32_t>> order;  // (run << 32 | position in list, triangle)
  order.reserve(triangles.size());
  for (size_t k = 0; k < triangles.size(); ++k) {
    if (triangles[k] >= triangleCount) continue;  // precondition; ignored rather than read out of range
    order.push_back({(uint64_t(runOf(triangles[k])) << 32) | uint64_t(k), triangles[k]});
  }
  std::sort(order.begin(), order.end());
  std::vector<uint32_t> remap(mesh_.positions.size(), kNone);
  auto copyVertex = [&](uint32_t v) {
    out.positions.push_back(mesh_.positions[v]);
    if (!mesh_.normals.empty()) out.normals.push_back(mesh_.normals[v]);
    if (!mesh_.tangents.empty()) out.tangents.push_back(mesh_.tangents[v]);
    if (!mesh_.uv0.empty()) out.uv0.push_back(mesh_.uv0[v]);
    if (!mesh_.uv1.empty()) out.uv1.push_back(mesh_.uv1[v]);
    if (!mesh_.colors.empty()) out.colors.push_back(mesh_.colors[v]);
    if (!mesh_.joints.empty()) out.joints.push_back(mesh_.joints[v]);
    if (!mesh_.weights.empty()) out.weights.push_back(mesh_.weights[v]);
  };
  uint32_t currentRun = kNone;
  for (const auto& [runKey, t] : order) {
    const uint32_t run = static_cast<uint32_t>(runKey >> 32);
    if (!mesh_.submeshes.empty() && run != currentRun) {
      out.submeshes.push_back({static_cast<uint32_t>(out.indices.size()), 0u, mesh_.submeshes[run].materialId});
      currentRun = run;
    }
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = mesh_.indices[3 * size_t(t) + c];
      if (remap[v] == kNone) {
        remap[v] = static_cast<uint32_t>(out.positions.size());
        copyVertex(v);
      }
      out.indices.push_back(remap[v]);
    }
    if (!out.submeshes.empty()) out.submeshes.back().indexCount += 3;
  }
}

}  // namespace cleave::geometry
