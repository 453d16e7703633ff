// SPDX-License-Identifier: MIT
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
#include <cstring>
#include <numeric>

#include "cleave/geometry/index_range.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/read_ahead.h"
#include "cleave/geometry/triangle_lanes.h"

namespace cleave::geometry {

namespace {

constexpr double kWeldRelative = 1e-6;
constexpr uint32_t kNone = 0xffffffffu;
constexpr int kCellBits = 21;
constexpr uint64_t kCellMask = (uint64_t(1) << kCellBits) - 1;

// Scratch memory of the weld and the closedness check, which only setMesh needs. It is kept per
// thread rather than per container: the engine builds a container for every object it cuts, and
// fresh arrays of a few megabytes each time would cost more in page faults than the weld itself.
struct WeldScratch {
  std::vector<uint64_t> cellKeys;     // weld hash table: per slot, the cell key and first | last vertex
  std::vector<uint32_t> cellNext;     // per vertex: the next vertex of its cell, ascending
  std::vector<uint64_t> sortKeys;     // sorted weld: cell key per vertex
  std::vector<uint32_t> sortOrder;    // sorted weld: vertices by (cell, index)
  std::vector<uint32_t> rowCount;     // closedness: per position id, the edges filed under it
  std::vector<uint32_t> rows;         // closedness: per position id, a row of the first kRow of them
  std::vector<uint64_t> overflow;     // closedness: id << 32 | edge, the edges past a full row
  std::vector<uint32_t> longList;     // closedness: the edges of one id whose row is full
  std::vector<uint32_t> tally;        // closedness: per position id, entries of one list
  std::vector<uint32_t> parent;       // connectivity: union-find over position ids
};

WeldScratch& weldScratch() {
  thread_local WeldScratch scratch;
  return scratch;
}

bool finite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

template <typename T>
bool sizedLike(const std::vector<T>& attribute, size_t n) {
  return attribute.empty() || attribute.size() == n;
}

MeshStatus invalid(std::string text) { return MeshStatus::failure(SplitStatus::InvalidInput, std::move(text)); }

// Whether a closed mesh is wound inwards: its signed volume (six times, summed about `centre`, the
// centre of its bounds, which keeps the terms small) is negative beyond the rounding of the sum.
// Files come this way (CGAL's beam.off, tetrahedron.off, ellipe0.003.off); cut as they are, their
// sections run clockwise, every loop looks like a hole, and no cap can be made. Triangles are added
// in index order into four running sums (triangle t into sum t % 4, those past the last multiple
// of four into sum 0), so that the additions do not wait on each other; the order is fixed, so is
// the answer. fileRows adds them on its pass over the triangles, four at a time (addFour),
// or eight (addEightAvx2: two fours, the same sums) where the processor runs AVX2.
class InwardsTest {
  typedef double Four __attribute__((vector_size(4 * sizeof(double))));   // lanes: the four sums
  typedef int64_t FourBits __attribute__((vector_size(4 * sizeof(int64_t))));

 public:
  InwardsTest(std::span<const glm::vec3> positions, std::span<const uint32_t> indices, const glm::dvec3& centre)
      : positions_(positions), indices_(indices), centre_(centre), whole_(indices.size() / 3 / 4 * 4) {}
  // Triangles t to t + 3 (t a multiple of four, t + 4 <= the whole groups) at once, each into its
  // own sum with the operations of add() in its order (a four-double vector; the library is built
  // without contraction into fused multiply-adds): the same bits.
  void addFour(size_t t) {
    Four x[3], y[3], z[3];
    for (int c = 0; c < 3; ++c) {
      for (int j = 0; j < 4; ++j) {
        const glm::vec3& p = positions_[indices_[3 * (t + j) + c]];
        x[c][j] = double(p.x) - centre_.x;
        y[c][j] = double(p.y) - centre_.y;
        z[c][j] = double(p.z) - centre_.z;
      }
    }
    addLanes(x, y, z);
  }
#ifdef CLEAVE_AVX2_VARIANTS
  // Triangles t to t + 7 (t a multiple of four, t + 8 <= the whole groups), corner c of triangle
  // t + j at vertex g[c][j]: addFour(t) then addFour(t + 4), the same bits. Vertex indices below
  // 2^29 (gathered at three times the index).
  [[gnu::target("avx2")]] void addEightAvx2(const __m256i (&g)[3]) {
    const float* base = &positions_[0].x;
    __m256 xf[3], yf[3], zf[3];
    for (int c = 0; c < 3; ++c) {
      const __m256i at = _mm256_add_epi32(_mm256_add_epi32(g[c], g[c]), g[c]);
      xf[c] = _mm256_i32gather_ps(base, at, 4);
      yf[c] = _mm256_i32gather_ps(base + 1, at, 4);
      zf[c] = _mm256_i32gather_ps(base + 2, at, 4);
    }
    for (int half = 0; half < 2; ++half) {
      Four x[3], y[3], z[3];
      for (int c = 0; c < 3; ++c) {
        const __m128 hx = half == 0 ? _mm256_castps256_ps128(xf[c]) : _mm256_extractf128_ps(xf[c], 1);
        const __m128 hy = half == 0 ? _mm256_castps256_ps128(yf[c]) : _mm256_extractf128_ps(yf[c], 1);
        const __m128 hz = half == 0 ? _mm256_castps256_ps128(zf[c]) : _mm256_extractf128_ps(zf[c], 1);
        x[c] = (Four)_mm256_cvtps_pd(hx) - centre_.x;
        y[c] = (Four)_mm256_cvtps_pd(hy) - centre_.y;
        z[c] = (Four)_mm256_cvtps_pd(hz) - centre_.z;
      }
      addLanes(x, y, z);
    }
  }
#endif
  void add(size_t t) {
    const glm::dvec3 a = glm::dvec3(positions_[indices_[3 * t]]) - centre_;
    const glm::dvec3 b = glm::dvec3(positions_[indices_[3 * t + 1]]) - centre_;
    const glm::dvec3 c = glm::dvec3(positions_[indices_[3 * t + 2]]) - centre_;
    const double term = glm::dot(a, glm::cross(b, c));
    const size_t lane = t < whole_ ? t & 3 : 0;
    sums_[lane] += term;
    magnitudes_[lane] += std::abs(term);
  }
  size_t whole() const { return whole_; }
  bool inwards() const {
    return (sums_[0] + sums_[1]) + (sums_[2] + sums_[3]) < -1e-9 * ((magnitudes_[0] + magnitudes_[1]) + (magnitudes_[2] + magnitudes_[3]));
  }

 private:
  // Four triangles' terms, corners relative to the centre, into the four sums.
  [[gnu::always_inline]] void addLanes(const Four (&x)[3], const Four (&y)[3], const Four (&z)[3]) {
    const Four kx = y[1] * z[2] - y[2] * z[1];
    const Four ky = z[1] * x[2] - z[2] * x[1];
    const Four kz = x[1] * y[2] - x[2] * y[1];
    const Four term = (x[0] * kx + y[0] * ky) + z[0] * kz;
    sums_ += term;
    magnitudes_ += (Four)((FourBits)term & FourBits{kMagnitude, kMagnitude, kMagnitude, kMagnitude});
  }

  std::span<const glm::vec3> positions_;
  std::span<const uint32_t> indices_;
  glm::dvec3 centre_;
  static constexpr int64_t kMagnitude = INT64_MAX;  // every bit but the sign: std::abs
  size_t whole_;  // triangles in whole groups of four
  Four sums_ = {0.0, 0.0, 0.0, 0.0};
  Four magnitudes_ = {0.0, 0.0, 0.0, 0.0};
};

uint64_t cellKey(int64_t x, int64_t y, int64_t z) {
  return (uint64_t(x) << (2 * kCellBits)) | (uint64_t(y) << kCellBits) | uint64_t(z);
}

// The hashed weld's cell width: twice the median edge length of up to 512 triangles spread over
// the index list, so that a cell holds a few vertices of any surface whatever its bounds look like
// (a cell count set by the bounds alone crowds a flat or thin mesh into few cells). At least four
// tolerances (a vertex then meets at most one neighbouring cell per axis), and wide enough for the
// cell indices to fit their bits. Without a usable edge (every sampled triangle a point): about
// sqrt(n) / 4 cells along the largest side, as for a surface.
double weldCellSize(std::span<const glm::vec3> positions, std::span<const uint32_t> indices, double largest,
                    double tolerance) {
  constexpr size_t kSample = 512;
  const size_t triangles = indices.size() / 3;
  const size_t stride = std::max<size_t>(1, triangles / kSample);
  double lengths[3 * kSample];
  size_t count = 0;
  for (size_t t = 0; t < triangles && count + 3 <= 3 * kSample; t += stride) {
    const glm::dvec3 a(positions[indices[3 * t]]), b(positions[indices[3 * t + 1]]), c(positions[indices[3 * t + 2]]);
    for (const double length : {glm::length(b - a), glm::length(c - b), glm::length(a - c)}) {
      if (length > 0.0) lengths[count++] = length;
    }
  }
  double cell = 0.0;
  if (count > 0) {
    std::nth_element(lengths, lengths + count / 2, lengths + count);
    cell = 2.0 * lengths[count / 2];
  } else {
    cell = largest / std::max(1.0, std::ceil(0.25 * std::sqrt(double(positions.size()))));
  }
  cell = std::max({cell, 4.0 * tolerance, largest / double(kCellMask - 4)});
  return cell > 0.0 && std::isfinite(cell) ? cell : 1.0;  // 1: every vertex at one point
}

// The hashed weld's cell of p (c, per axis) and, per axis, whether p lies within `reach` of the
// cell's lower face (lowSide -1, unless the cell is the first) or of its upper face (highSide 1).
// Returns whether it does of any face: then a neighbouring cell may hold a vertex within reach.
bool cellAndFaces(const glm::dvec3& p, const glm::dvec3& lo, double cell, double inverseCell, double reach,
                  int64_t (&c)[3], int (&lowSide)[3], int (&highSide)[3]) {
  bool near = false;
  for (int a = 0; a < 3; ++a) {
    // p >= lo, so truncation is the floor; the cell index is at most largest / cell + 1.
    c[a] = static_cast<int64_t>((p[a] - lo[a]) * inverseCell);
    const double inCell = p[a] - (lo[a] + double(c[a]) * cell);
    lowSide[a] = inCell <= reach && c[a] > 0 ? -1 : 0;
    highSide[a] = cell - inCell <= reach ? 1 : 0;
    near = near || lowSide[a] != 0 || highSide[a] != 0;
  }
  return near;
}

// The hashed weld's table: open addressing from a cell key to the cell's first and last vertex, one
// 16-byte slot each ([2 s] the key, [2 s + 1] first | last << 32), doubled when three quarters full.
class CellTable {
 public:
  CellTable(std::vector<uint64_t>& slots, size_t expected) : slots_(slots) {
    size_t capacity = 16;
    shift_ = 60;
    while (capacity < expected) {
      capacity *= 2;
      --shift_;
    }
    slots_.assign(2 * capacity, kEmpty);
    mask_ = capacity - 1;
  }
  // Asks the memory for the home slot of `key` ahead of its find().
  void prefetch(uint64_t key) const { __builtin_prefetch(&slots_[2 * home(key)]); }
  // The slot holding `key`, or the empty slot where it would go. Fibonacci hashing: the top bits of
  // the product, which every bit of the key reaches (the low bits of a product never see the key's
  // high bits, where the x cell index is).
  size_t find(uint64_t key) const {
    size_t slot = home(key);
    while (slots_[2 * slot + 1] != kEmpty && slots_[2 * slot] != key) slot = (slot + 1) & mask_;
    return slot;
  }
  // The first vertex of the cell in `slot`; kNone for an empty slot.
  uint32_t first(size_t slot) const {
    const uint64_t record = slots_[2 * slot + 1];
    return record == kEmpty ? kNone : static_cast<uint32_t>(record);
  }
  // Makes v the last vertex of the cell `key`, whose slot find() just gave. Returns the vertex that
  // was last before it, or kNone for a new cell (slots may move then: find() again after).
  uint32_t append(size_t slot, uint64_t key, uint32_t v) {
    uint64_t& record = slots_[2 * slot + 1];
    if (record != kEmpty) {
      const uint32_t last = static_cast<uint32_t>(record >> 32);
      record = (record & 0xffffffffull) | (uint64_t(v) << 32);
      return last;
    }
    slots_[2 * slot] = key;
    record = uint64_t(v) | (uint64_t(v) << 32);
    if (4 * ++occupied_ > 3 * (mask_ + 1)) grow();
    return kNone;
  }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t(0);
  size_t home(uint64_t key) const { return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_); }
  void grow() {
    std::vector<uint64_t> old(slots_.begin(), slots_.end());
    slots_.assign(2 * old.size(), kEmpty);
    mask_ = 2 * mask_ + 1;
    --shift_;
    for (size_t s = 0; s < old.size(); s += 2) {
      if (old[s + 1] == kEmpty) continue;
      const size_t slot = find(old[s]);
      slots_[2 * slot] = old[s];
      slots_[2 * slot + 1] = old[s + 1];
    }
  }
  std::vector<uint64_t>& slots_;
  uint64_t mask_ = 0;
  int shift_ = 60;  // 64 - log2(capacity)
  size_t occupied_ = 0;
};

}  // namespace

void MeshContainer::clear() {
  shared_.reset();
  source_ = &mesh_;
  model_ = glm::dmat4(1.0);
  jointMatrices_.clear();
  mirrored_ = false;
  mesh_.positions.clear();
  mesh_.indices.clear();
  cutPositions_.clear();
  positionIds_.clear();
  representatives_.clear();
  positionIdCount_ = 0;
  boundsDiagonal_ = 0.0;
  boundsMin_ = glm::dvec3(INFINITY);
  boundsMax_ = glm::dvec3(-INFINITY);
  closed_ = false;
  connected_ = false;
  inverted_ = false;
  cutIsSource_ = false;
}

// Checks the mesh; on failure clears the container and gives the reason.
MeshStatus MeshContainer::validate(const MeshData& mesh) {
  auto reject = [&](const std::string& text) {
    clear();
    return invalid("invalid mesh: " + text);
  };
  const size_t n = mesh.positions.size();
  if (mesh.indices.empty()) return reject("no triangle");
  if (mesh.indices.size() % 3 != 0) {
    return reject("index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
  }
  if (n >= kNone) return reject("too many vertices");
  // The common case in one pass each that the compiler can vectorise (index_range.h; exponent bits
  // all set mark an infinity or a NaN), the culprit searched only when there is one.
  if (detail::anyAtOrAbove(mesh.indices, static_cast<uint32_t>(n))) {
    for (size_t k = 0; k < mesh.indices.size(); ++k) {
      if (mesh.indices[k] >= n) {
        return reject("index " + std::to_string(mesh.indices[k]) + " at position " + std::to_string(k) +
                      " is out of range (" + std::to_string(n) + " vertices)");
      }
    }
  }
  // The source-space bounds on the way (take() keeps them).
  glm::vec3 lo, hi;
  if (!detail::finiteBounds(mesh.positions, lo, hi)) {
    for (size_t i = 0; i < n; ++i) {
      if (!finite(mesh.positions[i])) return reject("vertex " + std::to_string(i) + " has a NaN or infinite position");
    }
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
  setSourceBounds(lo, hi);
  return {};
}

MeshStatus MeshContainer::setMesh(const MeshData& mesh) {
  if (MeshStatus valid = validate(mesh); !valid.ok()) return valid;
  mesh_ = mesh;  // copy assignment keeps the capacity of our arrays
  shared_.reset();  // after the copy: `mesh` may be the shared one
  source_ = &mesh_;
  return take(nullptr);
}

MeshStatus MeshContainer::setMesh(const MeshData& mesh, const MeshWeld& weld) {
  MeshStatus valid = validate(mesh);
  if (valid.ok()) valid = adoptWeld(mesh, weld);
  if (!valid.ok()) return valid;
  mesh_ = mesh;
  shared_.reset();
  source_ = &mesh_;
  return take(&weld);
}

MeshStatus MeshContainer::setMesh(std::shared_ptr<const MeshData> mesh, const MeshWeld* weld) {
  if (!mesh) {
    clear();
    return invalid("invalid mesh: no mesh given");
  }
  MeshStatus valid = validate(*mesh);
  if (valid.ok() && weld) valid = adoptWeld(*mesh, *weld);
  if (!valid.ok()) return valid;
  shared_ = std::move(mesh);
  source_ = shared_.get();
  return take(weld);
}

// Takes a weld worked out before when it fits the mesh: one id per vertex, each below the count,
// each representative a vertex carrying its own id, representatives ascending (ids numbered by first
// vertex). Copied and checked in passes the compiler vectorises (index_range.h); on failure the
// container is cleared.
MeshStatus MeshContainer::adoptWeld(const MeshData& mesh, const MeshWeld& weld) {
  const size_t n = mesh.positions.size();
  const size_t ids = weld.representatives.size();
  bool ok = weld.positionIds.size() == n && ids > 0 && ids <= n;
  if (ok) {
    positionIds_.resize(n);
    ok = detail::copyBelow(weld.positionIds, positionIds_.data(), static_cast<uint32_t>(ids));
  }
  // Ascending with the last one below n: every representative is a vertex, and pointBack may read
  // the ids at them.
  ok = ok && detail::strictlyAscending(weld.representatives) && weld.representatives.back() < n &&
       detail::pointBack(weld.representatives, positionIds_.data());
  if (ok) {
    representatives_.assign(weld.representatives.begin(), weld.representatives.end());
    return {};
  }
  clear();
  return invalid("invalid weld: it does not belong to this mesh (" + std::to_string(weld.positionIds.size()) +
                 " ids for " + std::to_string(n) + " vertices, or ids and representatives disagree)");
}

// The rest of setMesh once source_ points at a valid mesh: the weld (taken or worked out), the cut
// space (the source space for now) and its bounds.
MeshStatus MeshContainer::take(const MeshWeld* weld) {
  model_ = glm::dmat4(1.0);
  jointMatrices_.clear();
  // The cut space is the source space until a transform is set (setTransform updates the bounds):
  // cutPositions() reads the source floats, no copy is made.
  cutPositions_.clear();  // the bounds are the source's, from validate()
  if (weld) {  // ids and representatives adopted by adoptWeld()
    positionIdCount_ = static_cast<uint32_t>(representatives_.size());
    closed_ = weld->closed;
    connected_ = weld->connected;
  } else {
    this->weld();
  }
  // A closed mesh wound inwards is cut as if mirrored: the splitter's loops and caps then follow
  // its own winding, its pieces keep that winding and their volumes come out positive. (Worked out
  // by computeClosed when welding.)
  if (weld) inverted_ = closed_ && weld->inverted;
  mirrored_ = inverted_;
  cutIsSource_ = true;
  return {};
}

void MeshContainer::copyWeld(MeshWeld& out) const {
  out.positionIds.assign(positionIds_.begin(), positionIds_.end());
  out.representatives.assign(representatives_.begin(), representatives_.end());
  out.closed = closed_;
  out.inverted = inverted_;
  out.connected = connected_;
}

// Position ids by the weld tolerance, then closedness and connectivity. Needs the source-space
// bounds (take() sets them).
void MeshContainer::weld() {
  const double tolerance = kWeldRelative * boundsDiagonal_;
  if (!weldHashed(tolerance, boundsMin_, boundsMax_)) weldSorted(tolerance, boundsMin_);
  positionIdCount_ = static_cast<uint32_t>(representatives_.size());
  computeClosed();  // also sets connected_ and inverted_
}

// The fast weld: a hashed grid of cells about twice the median edge length wide (weldCellSize), each
// cell's vertices chained in ascending index order. A vertex is compared with the earlier vertices
// of its own cell and, along an axis where it lies within the tolerance of a cell face, of the
// neighbouring cell too; the first one within the tolerance (ascending order) is the lowest, so the
// ids do not depend on the cell size. Cells sized by the edges hold a few vertices each on any surface
// (a flat comb or a sphere's crowded poles as much as a ball), and consecutive vertices (meshes list
// them with spatial coherence) share cells, so the table stays in cache. Returns false, leaving the
// ids unset, when the vertices crowd into few cells anyway (more comparisons than a fixed budget):
// the sorted weld below has no such worst case.
bool MeshContainer::weldHashed(double tolerance, const glm::dvec3& lo, const glm::dvec3& hi) {
  std::vector<uint32_t>& cellNext = weldScratch().cellNext;
  const std::span<const glm::vec3> positions = source_->positions;
  const size_t n = positions.size();
  const glm::dvec3 extent = hi - lo;
  const double largest = std::max(extent.x, std::max(extent.y, extent.z));
  const double cell = weldCellSize(positions, source_->indices, largest, tolerance);
  const double inverseCell = 1.0 / cell;
  CellTable table(weldScratch().cellKeys, n / 2);
  cellNext.resize(n);
  positionIds_.resize(n);
  representatives_.clear();
  representatives_.reserve(n);
  const double tolerance2 = tolerance * tolerance;
  const double reach = tolerance * 1.001;  // generous: the distance test below decides
  const float wide = static_cast<float>(2.0 * reach);
  uint64_t budget = 64 * uint64_t(n) + 4096;
  // The home slot of the cell a few dozen vertices ahead is asked for early when the table outgrows
  // the caches (read_ahead.h): a new cell's slot is a miss to memory there.
  constexpr uint32_t kAhead = 32;
  const bool ahead = n >= detail::kFarCount;
  auto cellOf = [&](uint32_t v) {
    const glm::dvec3 q(positions[v]);
    return cellKey(static_cast<int64_t>((q.x - lo.x) * inverseCell), static_cast<int64_t>((q.y - lo.y) * inverseCell),
                   static_cast<int64_t>((q.z - lo.z) * inverseCell));
  };
  for (uint32_t v = 0; v < n; ++v) {
    if (ahead && v + kAhead < n) table.prefetch(cellOf(v + kAhead));
    const glm::dvec3 p(positions[v]);
    int64_t c[3];
    int lowSide[3], highSide[3];
    const bool near = cellAndFaces(p, lo, cell, inverseCell, reach, c, lowSide, highSide);
    uint32_t best = kNone;
    // The lowest earlier vertex of one cell within the tolerance (into best); false when over budget.
    // A vertex whose x differs by more than `wide` in float arithmetic is farther than the
    // tolerance (the float difference is within 2^-24 of the true one, and wide is twice the
    // tolerance): skipped without the distance in double. A sphere's crowded poles hold hundreds of
    // vertices in a cell (the 1M sphere: 3.5M comparisons for 500k vertices), so this is most of
    // them.
    const float x = positions[v].x;
    auto scan = [&](uint32_t first) {
      for (uint32_t w = first; w != kNone && w < best; w = cellNext[w]) {
        if (budget-- == 0) return false;
        if (std::abs(positions[w].x - x) > wide) continue;
        const glm::dvec3 d = glm::dvec3(positions[w]) - p;
        if (glm::dot(d, d) <= tolerance2) {
          best = w;
          break;
        }
      }
      return true;
    };
    const uint64_t own = cellKey(c[0], c[1], c[2]);
    const size_t ownSlot = table.find(own);
    if (!scan(table.first(ownSlot))) return false;
    for (int dx = lowSide[0]; near && dx <= highSide[0]; ++dx) {
      for (int dy = lowSide[1]; dy <= highSide[1]; ++dy) {
        for (int dz = lowSide[2]; dz <= highSide[2]; ++dz) {
          if (dx == 0 && dy == 0 && dz == 0) continue;
          if (!scan(table.first(table.find(cellKey(c[0] + dx, c[1] + dy, c[2] + dz))))) return false;
        }
      }
    }
    if (best != kNone) {
      positionIds_[v] = positionIds_[best];
    } else {
      positionIds_[v] = static_cast<uint32_t>(representatives_.size());
      representatives_.push_back(v);
    }
    cellNext[v] = kNone;
    const uint32_t previous = table.append(ownSlot, own, v);
    if (previous != kNone) cellNext[previous] = v;
  }
  return true;
}

// The sorted weld: cells twice the tolerance wide; every vertex is sorted by (cell, index); a vertex
// can only meet a vertex within the tolerance in its own cell or, per axis, in the one neighbouring
// cell on the side of the cell it is nearest to, so 8 cells are searched by binary search.
void MeshContainer::weldSorted(double tolerance, const glm::dvec3& lo) {
  std::vector<uint64_t>& weldScratch_ = weldScratch().sortKeys;
  std::vector<uint32_t>& weldOrder_ = weldScratch().sortOrder;
  const size_t n = source_->positions.size();
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
  weldScratch_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3& p = source_->positions[i];
    weldScratch_[i] = cellKey(cellOf(p, 0, nullptr), cellOf(p, 1, nullptr), cellOf(p, 2, nullptr));
  }
  weldOrder_.resize(n);
  std::iota(weldOrder_.begin(), weldOrder_.end(), 0u);
  std::sort(weldOrder_.begin(), weldOrder_.end(), [&](uint32_t a, uint32_t b) {
    return weldScratch_[a] != weldScratch_[b] ? weldScratch_[a] < weldScratch_[b] : a < b;
  });
  positionIds_.assign(n, kNone);
  representatives_.clear();
  representatives_.reserve(n);
  const double tolerance2 = tolerance * tolerance;
  for (uint32_t v = 0; v < n; ++v) {
    const glm::vec3& p = source_->positions[v];
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
      const uint64_t k = cellKey(q[0], q[1], q[2]);
      auto first = std::lower_bound(weldOrder_.begin(), weldOrder_.end(), k,
                                    [&](uint32_t i, uint64_t value) { return weldScratch_[i] < value; });
      for (auto it = first; it != weldOrder_.end() && weldScratch_[*it] == k && *it < v; ++it) {
        if (*it >= best) break;
        const glm::dvec3 d = glm::dvec3(source_->positions[*it]) - pd;
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

namespace {
constexpr uint32_t kRow = 8;  // edges kept per position id in its row; the rest overflow

// Where computeClosed files edges: per position id a row of kRow entries, then the overflow.
struct EdgeRows {
  uint32_t* count;
  uint32_t* rows;
  std::vector<uint64_t>* overflow;

  void put(uint32_t a, uint32_t slot, uint32_t edge) {
    if (slot < kRow) rows[size_t(kRow) * a + slot] = edge;
    else overflow->push_back(uint64_t(a) << 32 | edge);
  }
  // The edges of a triangle of three distinct ids c (winding order). Its two edges at its lowest id
  // go under that id at once (one count update, not two that wait on each other), as 2 b for the
  // one leaving it (to b) and 2 b + 1 for the one arriving (from b); the opposite edge goes under
  // the lower of the other two ids.
  [[gnu::always_inline]] void triangle(const uint32_t (&c)[3]) {
    const int lowest = c[0] < c[1] ? (c[0] < c[2] ? 0 : 2) : (c[1] < c[2] ? 1 : 2);
    const uint32_t next = c[lowest == 2 ? 0 : lowest + 1], previous = c[lowest == 0 ? 2 : lowest - 1];
    lowestTwo(c[lowest], 2 * next, 2 * previous + 1);
    opposite(std::min(next, previous), next < previous ? 2 * previous : 2 * next + 1);
  }
  // The edge opposite a triangle's lowest id, under the lower of its two ids `a`.
  void opposite(uint32_t a, uint32_t edge) { put(a, count[a]++, edge); }
  [[gnu::always_inline]] void lowestTwo(uint32_t a, uint32_t leaving, uint32_t arriving) {
    const uint32_t slot = count[a];
    count[a] = slot + 2;
    if (slot + 2 <= kRow) {
      uint32_t* row = rows + size_t(kRow) * a + slot;
      row[0] = leaving;
      row[1] = arriving;
    } else {
      put(a, slot, leaving);
      put(a, slot + 1, arriving);
    }
  }
};

#ifdef CLEAVE_AVX2_VARIANTS
// fileRows' pass eight triangles at a time over the whole groups of eight below `triangles`: the
// winding test's sums (two fours, the same bits), and each triangle of three distinct position ids
// filed as EdgeRows::triangle files it (`degenerate` set for any other). Returns the triangles done.
// With `ahead`, the corners 64 triangles on are asked for early (read_ahead.h). Vertex indices
// below 2^29.
[[gnu::target("avx2")]] size_t fileEightsAvx2(const uint32_t* index, const uint32_t* ids, const glm::vec3* positions,
                                              size_t triangles, bool ahead, InwardsTest& winding, EdgeRows& rows,
                                              size_t& edges, bool& degenerate) {
  const __m256i one = _mm256_set1_epi32(1);
  size_t t = 0;
  for (; t + 8 <= triangles; t += 8) {
    if (ahead && t + 72 <= triangles) {
      __builtin_prefetch(&positions[index[3 * (t + 64)]]);
      __builtin_prefetch(&positions[index[3 * (t + 64) + 23]]);
      __builtin_prefetch(&ids[index[3 * (t + 64)]]);
      __builtin_prefetch(&ids[index[3 * (t + 64) + 23]]);
    }
    __m256i g[3];
    detail::triangleCornersAvx2(index, t, g[0], g[1], g[2]);
    winding.addEightAvx2(g);
    const __m256i c0 = _mm256_i32gather_epi32(reinterpret_cast<const int*>(ids), g[0], 4);
    const __m256i c1 = _mm256_i32gather_epi32(reinterpret_cast<const int*>(ids), g[1], 4);
    const __m256i c2 = _mm256_i32gather_epi32(reinterpret_cast<const int*>(ids), g[2], 4);
    const __m256i repeated = _mm256_or_si256(_mm256_or_si256(_mm256_cmpeq_epi32(c0, c1), _mm256_cmpeq_epi32(c1, c2)),
                                             _mm256_cmpeq_epi32(c2, c0));
    // EdgeRows::triangle in lanes: the lowest corner, the corners after and before it.
    const __m256i lowest = _mm256_min_epu32(_mm256_min_epu32(c0, c1), c2);
    const __m256i atFirst = _mm256_cmpeq_epi32(lowest, c0), atSecond = _mm256_cmpeq_epi32(lowest, c1);
    const __m256i next = _mm256_blendv_epi8(_mm256_blendv_epi8(c0, c2, atSecond), c1, atFirst);
    const __m256i previous = _mm256_blendv_epi8(_mm256_blendv_epi8(c1, c0, atSecond), c2, atFirst);
    const __m256i twiceNext = _mm256_add_epi32(next, next), twicePrevious = _mm256_add_epi32(previous, previous);
    const __m256i nextLower = _mm256_cmpeq_epi32(_mm256_min_epu32(next, previous), next);
    alignas(32) uint32_t at[8], leaving[8], arriving[8], oppositeAt[8], opposite[8];
    _mm256_store_si256(reinterpret_cast<__m256i*>(at), lowest);
    _mm256_store_si256(reinterpret_cast<__m256i*>(leaving), twiceNext);
    _mm256_store_si256(reinterpret_cast<__m256i*>(arriving), _mm256_add_epi32(twicePrevious, one));
    _mm256_store_si256(reinterpret_cast<__m256i*>(oppositeAt), _mm256_min_epu32(next, previous));
    _mm256_store_si256(reinterpret_cast<__m256i*>(opposite),
                       _mm256_blendv_epi8(_mm256_add_epi32(twiceNext, one), twicePrevious, nextLower));
    const uint32_t skip = static_cast<uint32_t>(_mm256_movemask_ps(_mm256_castsi256_ps(repeated)));
    for (int j = 0; j < 8; ++j) {
      if ((skip >> j) & 1u) {
        degenerate = true;
        continue;
      }
      rows.lowestTwo(at[j], leaving[j], arriving[j]);
      rows.opposite(oppositeAt[j], opposite[j]);
      edges += 3;
    }
  }
  return t;
}
#endif
}  // namespace

// Closedness on position ids: every directed edge of a non-degenerate triangle used once, and its
// reverse used once. Each edge is filed under the lower of its two ids, as the higher id and a
// direction bit, in a row per id (fileRows); the surface is closed when every id's edges hold each
// higher id exactly once in each direction (pairedRows). The connectivity of a closed mesh comes
// from the same edges, unless degenerate triangles (which are not filed) join ids too.
void MeshContainer::computeClosed() {
  bool degenerate = false, inwards = false;
  const size_t edges = fileRows(degenerate, inwards);
  closed_ = edges > 0 && edges % 2 == 0 && positionIdCount_ < 0x80000000u;
  connected_ = false;
  inverted_ = false;
  if (!closed_) return;
  uint32_t parts = 0;
  closed_ = pairedRows(degenerate ? nullptr : &parts);
  if (closed_ && degenerate) computeConnected();
  else connected_ = closed_ && parts == 1;
  inverted_ = closed_ && inwards;
}

// The filing of computeClosed, one pass over the triangles: per position id a, in
// weldScratch().rows from kRow a, the first kRow edges whose lower id is a, each as 2 b (a to b) or
// 2 b + 1 (b to a), their count in rowCount[a] and the rest in the overflow (an id of high valence:
// a pole, a cone's tip). Returns the number of edges filed; `degenerate` tells whether some
// triangle was left out for a repeated id; `inwards`, InwardsTest over every triangle (its position
// gathers share the pass and its misses). On a big mesh the pass asks for the corners' positions
// and ids 64 triangles ahead: read behind the indices, they came from memory about one at a time.
// Where the processor runs AVX2 it takes eight triangles at a time (fileEightsAvx2).
size_t MeshContainer::fileRows(bool& degenerate, bool& inwards) {
  WeldScratch& scratch = weldScratch();
  const uint32_t ids = positionIdCount_;
  scratch.rowCount.assign(ids, 0u);
  scratch.rows.resize(size_t(kRow) * ids);
  scratch.overflow.clear();
  EdgeRows rows{scratch.rowCount.data(), scratch.rows.data(), &scratch.overflow};
  const uint32_t* index = source_->indices.data();
  const size_t indexCount = source_->indices.size() / 3 * 3;
  InwardsTest winding(source_->positions, source_->indices, 0.5 * (boundsMin_ + boundsMax_));
  size_t edges = 0;
  auto file = [&](size_t t) {
    const uint32_t c[3] = {positionIds_[index[t]], positionIds_[index[t + 1]], positionIds_[index[t + 2]]};
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) {
      degenerate = true;
      return;
    }
    rows.triangle(c);
    edges += 3;
  };
  size_t t = 0;
  const size_t ahead = indexCount >= 3 * detail::kFarCount ? 3 * 64 : 0;  // read_ahead.h
#ifdef CLEAVE_AVX2_VARIANTS
  if (detail::runsAvx2() && source_->positions.size() < (size_t(1) << 29)) {
    t = 3 * fileEightsAvx2(index, positionIds_.data(), source_->positions.data(), winding.whole(), ahead != 0,
                           winding, rows, edges, degenerate);
  }
#endif
  for (; t < 3 * winding.whole(); t += 12) {
    if (ahead != 0 && t + ahead + 12 <= indexCount) {
      __builtin_prefetch(&source_->positions[index[t + ahead]]);
      __builtin_prefetch(&source_->positions[index[t + ahead + 11]]);
      __builtin_prefetch(&positionIds_[index[t + ahead]]);
      __builtin_prefetch(&positionIds_[index[t + ahead + 11]]);
    }
    winding.addFour(t / 3);
    for (size_t k = t; k < t + 12; k += 3) file(k);
  }
  for (; t < indexCount; t += 3) {
    winding.add(t / 3);
    file(t);
  }
  inwards = winding.inwards();
  std::sort(scratch.overflow.begin(), scratch.overflow.end());
  return edges;
}

namespace {
typedef uint32_t EightIds __attribute__((vector_size(8 * sizeof(uint32_t))));
typedef int32_t EightFlags __attribute__((vector_size(8 * sizeof(int32_t))));

// How many entries of v rotated by r lanes (lane j takes lane j + r, mod 8) equal `reverse`, added
// to `count` (-1 a match). __builtin_shufflevector: clang, and GCC from 12 (as the mass kernels).
// Vectors go by reference: one returned by value changes the ABI where AVX is off.
template <int r>
[[gnu::always_inline]] inline void countRotated(const EightIds& v, const EightIds& reverse, EightFlags& count) {
  const EightIds other = __builtin_shufflevector(v, v, r % 8, (r + 1) % 8, (r + 2) % 8, (r + 3) % 8, (r + 4) % 8,
                                                 (r + 5) % 8, (r + 6) % 8, (r + 7) % 8);
  count -= other == reverse;
}

// pairedRows for a row of 1 to 8 edges in one vector: each entry must meet its reverse (entry ^ 1)
// exactly once among the others. (An entry twice would give its reverse two, or itself none.)
// Seven rotations compare every entry with every other; the lanes past the count are set to ~0,
// which no entry or reverse equals (ids are below 2^31).
[[gnu::always_inline]] inline bool pairedEight(const uint32_t* row, uint32_t count) {
  EightIds loaded;
  std::memcpy(&loaded, row, sizeof loaded);
  const EightIds lane = {0, 1, 2, 3, 4, 5, 6, 7};
  const EightFlags inRow = lane < count - EightIds{};
  const EightIds v = inRow ? loaded : ~EightIds{};
  const EightIds reverse = v ^ 1u;
  EightFlags reverses = {};
  countRotated<1>(v, reverse, reverses);
  countRotated<2>(v, reverse, reverses);
  countRotated<3>(v, reverse, reverses);
  countRotated<4>(v, reverse, reverses);
  countRotated<5>(v, reverse, reverses);
  countRotated<6>(v, reverse, reverses);
  countRotated<7>(v, reverse, reverses);
  const EightFlags bad = inRow & (reverses != 1);
  uint64_t words[4];
  std::memcpy(words, &bad, sizeof words);
  return (words[0] | words[1] | words[2] | words[3]) == 0;
}

// pairedRows for one id's edges past a row: a tally per higher id (one for a forward entry, 1 << 16
// for a reverse one) must read exactly 0x10001 at its first entry (then it is cleared); no branch
// depends on the entries until the verdict. A list of 65536 entries or more (whose tally could
// carry) is sorted and read in pairs instead.
bool pairedLong(uint32_t* first, uint32_t* last, uint32_t* tally) {
  if (last - first >= 0x10000) {
    std::sort(first, last);
    for (uint32_t* i = first; i < last; i += 2) {
      if (last - i < 2 || (i[0] & 1u) != 0 || i[1] != i[0] + 1 || (i + 2 < last && (i[2] >> 1) == (i[0] >> 1))) {
        return false;
      }
    }
    return true;
  }
  for (const uint32_t* i = first; i < last; ++i) tally[*i >> 1] += (*i & 1u) ? 0x10000u : 1u;
  // Read and cleared in one pass: the first entry of a higher id finds its whole tally, a later one
  // finds it cleared (0).
  uint32_t wrong = 0;
  for (const uint32_t* i = first; i < last; ++i) {
    const uint32_t count = tally[*i >> 1];
    wrong |= uint32_t(count != 0x10001u && count != 0);
    tally[*i >> 1] = 0;
  }
  return wrong == 0;
}

// The body of pairedRows (see there), written once: compiled for AVX2 and without.
[[gnu::always_inline]] inline bool pairedRowsIn(WeldScratch& scratch, uint32_t ids, uint32_t* parts) {
  const uint32_t* count = scratch.rowCount.data();
  uint32_t* rows = scratch.rows.data();
  const std::vector<uint64_t>& overflow = scratch.overflow;
  std::vector<uint32_t>& longList = scratch.longList;
  std::vector<uint32_t>& parent = scratch.parent;
  if (!overflow.empty()) scratch.tally.assign(ids, 0u);
  if (parts) parent.assign(ids, kNone);
  auto find = [&](uint32_t x) {
    if (parent[x] == kNone) return parent[x] = x;
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  size_t spilled = 0;  // into the overflow, sorted by id
  const bool ahead = ids >= detail::kFarCount;
  for (uint32_t a = 0; a < ids; ++a) {
    // Rows written in a scattered order in fileRows are read in order here: on a big mesh, asked for
    // 64 rows ahead (read_ahead.h; the 1M sphere's set-up 1.5-2 ms less).
    if (ahead && a + 64 < ids) __builtin_prefetch(rows + size_t(kRow) * (a + 64));
    const uint32_t n = count[a];
    if (n == 0) continue;
    uint32_t* first = rows + size_t(kRow) * a;
    uint32_t* last = first + n;
    if (n <= kRow) {
      if (!pairedEight(first, n)) return false;
    } else {
      longList.assign(first, first + kRow);
      for (; spilled < overflow.size() && (overflow[spilled] >> 32) == a; ++spilled) {
        longList.push_back(static_cast<uint32_t>(overflow[spilled]));
      }
      first = longList.data();
      last = first + longList.size();
      if (!pairedLong(first, last, scratch.tally.data())) return false;
    }
    if (!parts) continue;
    uint32_t root = find(a);
    for (const uint32_t* i = first; i < last; ++i) {
      if ((*i & 1u) != 0) continue;
      const uint32_t other = find(*i >> 1);
      if (other == root) continue;
      parent[std::max(root, other)] = std::min(root, other);
      root = std::min(root, other);
    }
  }
  if (parts) {
    *parts = 0;
    for (uint32_t id = 0; id < ids && *parts < 2; ++id) *parts += parent[id] == id ? 1u : 0u;
  }
  return true;
}

bool pairedRowsPlain(WeldScratch& scratch, uint32_t ids, uint32_t* parts) { return pairedRowsIn(scratch, ids, parts); }

#ifdef CLEAVE_AVX2_VARIANTS  // index_range.h
[[gnu::target("avx2")]] bool pairedRowsAvx2(WeldScratch& scratch, uint32_t ids, uint32_t* parts) {
  return pairedRowsIn(scratch, ids, parts);
}
#endif
}  // namespace

// Whether every id's filed edges hold each higher id once in each direction: a row of up to kRow in
// one vector (pairedEight), more with a tally (pairedLong). With `parts`, the parts of the id graph
// the edges make (a union-find over the forward entries; ids with no edge are in none).
bool MeshContainer::pairedRows(uint32_t* parts) {
#ifdef CLEAVE_AVX2_VARIANTS
  if (detail::runsAvx2()) return pairedRowsAvx2(weldScratch(), positionIdCount_, parts);
#endif
  return pairedRowsPlain(weldScratch(), positionIdCount_, parts);
}

// One part or several: a union-find over the position ids of every triangle's corners (degenerate
// triangles too: the splitter's islands join them the same way), the lower id always the parent,
// then the roots among the ids a triangle uses are counted (up to two).
void MeshContainer::computeConnected() {
  std::vector<uint32_t>& parent = weldScratch().cellNext;  // reused: the union-find
  std::vector<uint32_t>& used = weldScratch().rowCount;    // reused: per id, used by a triangle
  const uint32_t ids = positionIdCount_;
  parent.resize(ids);
  std::iota(parent.begin(), parent.end(), 0u);
  used.assign(ids, 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  };
  const std::vector<uint32_t>& indices = source_->indices;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const uint32_t c[3] = {positionIds_[indices[t]], positionIds_[indices[t + 1]], positionIds_[indices[t + 2]]};
    used[c[0]] = used[c[1]] = used[c[2]] = 1;
    uint32_t root = find(c[0]);
    for (int k = 1; k < 3; ++k) {
      const uint32_t other = find(c[k]);
      if (other == root) continue;
      parent[std::max(root, other)] = std::min(root, other);
      root = std::min(root, other);
    }
  }
  uint32_t parts = 0;
  for (uint32_t id = 0; id < ids && parts < 2; ++id) parts += used[id] && parent[id] == id ? 1u : 0u;
  connected_ = parts == 1;
}

// updateBounds for cut positions that are the source's: from the floats (a float widens to a double
// exactly, so their bounds are the same). validate() works them out on its way over the positions;
// this is for setTransform's return to the source space.
void MeshContainer::sourceBounds() {
  glm::vec3 lo, hi;
  detail::finiteBounds(source_->positions, lo, hi);  // finite: validate() checked them
  setSourceBounds(lo, hi);
}

void MeshContainer::setSourceBounds(const glm::vec3& lo, const glm::vec3& hi) {
  const bool any = lo.x <= hi.x;
  boundsMin_ = any ? glm::dvec3(lo) : glm::dvec3(INFINITY);
  boundsMax_ = any ? glm::dvec3(hi) : glm::dvec3(-INFINITY);
  boundsDiagonal_ = any ? glm::length(boundsMax_ - boundsMin_) : 0.0;
}

void MeshContainer::updateBounds() {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::dvec3& p : cutPositions_) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  boundsDiagonal_ = cutPositions_.empty() ? 0.0 : glm::length(hi - lo);
  boundsMin_ = lo;
  boundsMax_ = hi;
}

void MeshContainer::setTransform(const glm::mat4& model) {
  model_ = glm::dmat4(model);
  jointMatrices_.clear();
  const bool identity = model == glm::mat4(1.f);
  if (identity && cutIsSource_) return;  // the cut positions, bounds and winding are those already set
  cutIsSource_ = identity;
  if (identity) {  // back to the source floats (after another transform or a pose)
    cutPositions_.clear();
    mirrored_ = inverted_;
    sourceBounds();
    return;
  }
  cutPositions_.resize(source_->positions.size());
  for (size_t i = 0; i < cutPositions_.size(); ++i) {
    cutPositions_[i] = glm::dvec3(model_ * glm::dvec4(glm::dvec3(source_->positions[i]), 1.0));
  }
  mirrored_ = (glm::determinant(glm::dmat3(model_)) < 0.0) != inverted_;
  updateBounds();
}

MeshStatus MeshContainer::setSkinningPose(std::span<const glm::mat4> jointMatrices, const glm::mat4& model) {
  if (source_->positions.empty()) {
    return invalid("skinning pose: the container holds no mesh");
  }
  if (source_->joints.empty() || source_->weights.size() != source_->joints.size()) {
    return invalid("skinning pose: the mesh has no joints and weights");
  }
  for (size_t j = 0; j < jointMatrices.size(); ++j) {
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) {
        if (!std::isfinite(jointMatrices[j][c][r])) {
          return invalid("skinning pose: joint matrix " + std::to_string(j) + " is not finite");
        }
      }
    }
  }
  const size_t n = source_->positions.size();
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 4; ++k) {
      if (source_->weights[i][k] != 0.f && source_->joints[i][k] >= jointMatrices.size()) {
        return invalid("skinning pose: vertex " + std::to_string(i) + " uses joint " +
                          std::to_string(source_->joints[i][k]) + " of " + std::to_string(jointMatrices.size()));
      }
    }
  }
  model_ = glm::dmat4(model);
  jointMatrices_.assign(jointMatrices.begin(), jointMatrices.end());
  cutIsSource_ = false;
  // Once per pose: model x joint matrix as an affine 3 x 4 (the bottom row of a skinning matrix is
  // (0, 0, 0, 1)); its 3 x 3 part, and whether every one is a similarity (rotation, uniform scale)
  // with a determinant of one sign. A blend of such matrices keeps that sign wherever it is not
  // singular (a blend of rotations has det >= 0), so the winding flip is known for the whole pose
  // and no per-vertex determinant is needed; otherwise each vertex's blend is tested as before.
  const size_t joints = jointMatrices.size();
  poseAffine_.resize(joints + 1);
  int poseSign = 0;
  bool uniformSign = true;
  for (size_t j = 0; j <= joints; ++j) {
    // The last entry is the model alone, for vertices without weight.
    const glm::dmat4 m = j < joints ? model_ * glm::dmat4(jointMatrices[j]) : model_;
    poseAffine_[j] = glm::dmat4x3(m);
    const glm::dmat3 linear(m);
    const double det = glm::determinant(linear);
    const int sign = det > 0.0 ? 1 : (det < 0.0 ? -1 : 0);
    const glm::dmat3 gram = glm::transpose(linear) * linear;
    const double scale2 = (gram[0][0] + gram[1][1] + gram[2][2]) / 3.0;
    double offDiagonal = 0.0;
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) offDiagonal = std::max(offDiagonal, std::abs(gram[c][r] - (c == r ? scale2 : 0.0)));
    }
    const bool similarity = scale2 > 0.0 && offDiagonal <= 1e-6 * scale2;
    if (poseSign == 0) poseSign = sign;
    uniformSign = uniformSign && similarity && sign != 0 && sign == poseSign;
  }
  cutPositions_.resize(n);
  size_t negative = 0;
  for (size_t i = 0; i < n; ++i) {
    const glm::vec4& w = source_->weights[i];
    const glm::u16vec4& jt = source_->joints[i];
    const double total = double(w[0]) + double(w[1]) + double(w[2]) + double(w[3]);
    const glm::dvec4 p(glm::dvec3(source_->positions[i]), 1.0);
    glm::dmat4x3 blend;
    if (total > 0.0) {
      blend = glm::dmat4x3(0.0);
      for (int k = 0; k < 4; ++k) {
        if (w[k] == 0.f) continue;
        blend += (double(w[k]) / total) * poseAffine_[jt[k]];
      }
    } else {
      blend = poseAffine_[joints];
    }
    cutPositions_[i] = blend * p;
    if (!uniformSign && glm::determinant(glm::dmat3(blend)) < 0.0) ++negative;
  }
  mirrored_ = (uniformSign ? poseSign < 0 : 2 * negative > n) != inverted_;
  updateBounds();
  return {};
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
  const size_t triangleCount = source_->indices.size() / 3;
  // Group the triangles by their run (runs in source order), keeping the given order inside a run.
  auto runOf = [&](uint32_t t) -> uint32_t {
    if (source_->submeshes.empty()) return 0;
    const uint32_t index = t * 3;
    auto it = std::upper_bound(source_->submeshes.begin(), source_->submeshes.end(), index,
                               [](uint32_t value, const SubMesh& run) { return value < run.firstIndex; });
    return static_cast<uint32_t>(it - source_->submeshes.begin()) - 1;
  };
  std::vector<std::pair<uint64_t, uint32_t>> order;  // (run << 32 | position in list, triangle)
  order.reserve(triangles.size());
  for (size_t k = 0; k < triangles.size(); ++k) {
    if (triangles[k] >= triangleCount) continue;  // precondition; ignored rather than read out of range
    order.push_back({(uint64_t(runOf(triangles[k])) << 32) | uint64_t(k), triangles[k]});
  }
  std::sort(order.begin(), order.end());
  std::vector<uint32_t> remap(source_->positions.size(), kNone);
  auto copyVertex = [&](uint32_t v) {
    out.positions.push_back(source_->positions[v]);
    if (!source_->normals.empty()) out.normals.push_back(source_->normals[v]);
    if (!source_->tangents.empty()) out.tangents.push_back(source_->tangents[v]);
    if (!source_->uv0.empty()) out.uv0.push_back(source_->uv0[v]);
    if (!source_->uv1.empty()) out.uv1.push_back(source_->uv1[v]);
    if (!source_->colors.empty()) out.colors.push_back(source_->colors[v]);
    if (!source_->joints.empty()) out.joints.push_back(source_->joints[v]);
    if (!source_->weights.empty()) out.weights.push_back(source_->weights[v]);
  };
  uint32_t currentRun = kNone;
  for (const auto& [runKey, t] : order) {
    const uint32_t run = static_cast<uint32_t>(runKey >> 32);
    if (!source_->submeshes.empty() && run != currentRun) {
      out.submeshes.push_back({static_cast<uint32_t>(out.indices.size()), 0u, source_->submeshes[run].materialId});
      currentRun = run;
    }
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = source_->indices[3 * size_t(t) + c];
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
