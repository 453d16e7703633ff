// SPDX-License-Identifier: MIT
#include "cleave/geometry/cell_clipper.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numeric>

#include "cleave/geometry/cap_triangulator.h"

namespace cleave::geometry {

namespace {

constexpr uint32_t kNone = 0xffffffffu;
constexpr uint32_t kMaxCorners = 64;  // a polygon with more (never seen: a triangle gains one per plane) falls back

uint64_t pairKey(uint32_t a, uint32_t b) { return (uint64_t(std::min(a, b)) << 32) | std::max(a, b); }
uint64_t directedKey(uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; }
uint32_t keyFrom(uint64_t k) { return static_cast<uint32_t>(k >> 32); }
uint32_t keyTo(uint64_t k) { return static_cast<uint32_t>(k & 0xffffffffu); }

// Open addressing from 64-bit keys to indices; emptied in O(1) by a new epoch.
class PairTable {
 public:
  void reset() {
    if (keys_.empty()) grow(64);
    ++epoch_;
    count_ = 0;
  }
  uint32_t get(uint64_t key) const {
    for (size_t i = slot(key);; i = (i + 1) & mask_) {
      if (stamps_[i] != epoch_) return kNone;
      if (keys_[i] == key) return values_[i];
    }
  }
  // The value of `key`, or kNone after giving it `value` (one probe for both).
  uint32_t putIfAbsent(uint64_t key, uint32_t value) {
    if (2 * (count_ + 1) > keys_.size()) grow(2 * keys_.size());
    size_t i = slot(key);
    for (; stamps_[i] == epoch_; i = (i + 1) & mask_)
      if (keys_[i] == key) return values_[i];
    keys_[i] = key;
    values_[i] = value;
    stamps_[i] = epoch_;
    ++count_;
    return kNone;
  }

 private:
  size_t slot(uint64_t key) const { return size_t((key * 0x9e3779b97f4a7c15ull) >> 32) & mask_; }
  void grow(size_t size) {
    std::vector<uint64_t> keys = std::move(keys_);
    std::vector<uint32_t> values = std::move(values_), stamps = std::move(stamps_);
    const uint32_t old = epoch_;
    keys_.assign(size, 0);
    values_.assign(size, 0);
    stamps_.assign(size, 0);
    mask_ = size - 1;
    epoch_ = 1;
    count_ = 0;
    for (size_t i = 0; i < keys.size(); ++i) {
      if (stamps[i] == old && old != 0) putIfAbsent(keys[i], values[i]);
    }
  }
  std::vector<uint64_t> keys_;
  std::vector<uint32_t> values_, stamps_;
  size_t mask_ = 0, count_ = 0;
  uint32_t epoch_ = 0;
};

struct Corner {
  uint32_t point;   // a position id of the container, or a cut point
  uint32_t vertex;  // a vertex of the container's mesh, or of State::extra (from vertexCount on)
};

struct Poly {
  uint32_t first, count;  // corners, counter-clockwise seen from outside
  uint32_t source;        // the container's triangle, or kFromCap | plane
  uint32_t run;           // output material run
  uint32_t last;          // the last plane (clipping order) it is not below: settled once past it
  uint32_t touch;         // bit r: a corner of its mesh triangle may not be below the plane of rank r
                          // (clear: the triangle is below it, so every part of it is)
};

constexpr uint32_t kMayTouchAll = 0xffffffffu;  // caps, and cells past the masks: classified at every plane

// Whether the plane of `rank` may reach the polygon (ranks past the mask's bits always may).
inline bool mayTouch(const Poly& poly, uint32_t rank) { return rank >= 32 || (poly.touch >> rank & 1); }

glm::vec3 normalizedOr(const glm::dvec3& v, const glm::vec3& fallback) {
  const double len = glm::length(v);
  return len > 0.0 && std::isfinite(len) ? glm::vec3(v / len) : fallback;
}

}  // namespace

struct CellClipper::State {
  // The container, set up once per fracture (begin).
  const MeshContainer* container = nullptr;
  const MeshData* mesh = nullptr;
  uint32_t vertexCount = 0, idCount = 0;
  std::vector<uint32_t> runMaterials;  // output runs: the mesh's materials in order, then the cap's if new
  std::vector<uint32_t> triangleRun;   // per triangle of the mesh
  uint32_t capRun = 0;
  glm::dmat3 capLinear{1.0}, capInverse{1.0};  // source to cut space (the model's linear part), and back
  static constexpr uint32_t kMaskedPlanes = 32;  // cells with more planes take 16-bit ranks (startWideCell)
  std::vector<uint32_t> notBelow;  // per position id: bit r set when it is not below the plane of rank r
  std::vector<uint32_t> aboveAt;   // per position id: bit r set when it is above the plane of rank r
  static constexpr uint16_t kNever = 0xffff;
  std::vector<uint16_t> firstMet, lastMet;  // wide cells, per id: the first and last rank it is not below
  std::vector<double> idX, idY, idZ;  // the position ids' cut-space coordinates, one array each
  std::vector<uint32_t> triangleIds;  // per triangle of the mesh, its corners' position ids
  std::vector<uint32_t> aboveCount, order;  // per cell plane: points above it; the planes in clipping order
  std::vector<int8_t> planeSign;  // per cell plane, per position id: -1 below, 0 on, +1 above
  // The signs of every plane classified since begin, kept for the neighbour cell: the bisector of two
  // seeds is, bit for bit, the negated plane of the other seed's cell, so its signs are the negated
  // ones (d is negated exactly: IEEE rounding is symmetric). Keyed by the bits of the plane.
  struct KnownPlane {
    Plane plane;
    double tolerance;
    uint32_t at;  // into knownSigns, idCount each
  };
  std::vector<KnownPlane> knownPlanes;
  std::vector<int8_t> knownSigns;
  PairTable knownByBits;

  // Points (position ids first, then the cell's cut points) and their classification for one plane.
  std::vector<glm::dvec3> pos, src;  // cut space, source space
  std::vector<uint32_t> donor;       // a vertex at the point (cap colours), or kNone
  std::vector<uint32_t> cutFrom;     // a cut point: the lower id of the two it lies between
  struct PointClass {
    double dist = 0.0;    // to the plane (0 within the tolerance)
    uint32_t stamp = 0;   // the plane (epoch) it was classified for
    int8_t sign = 0;      // -1 below, 0 on, +1 above
  };
  std::vector<PointClass> cls;
  uint32_t epoch = 0;
  MeshData extra;  // vertices the cell adds

  std::vector<Corner> fixedCorners;    // of the settled polygons (below every plane: never clipped)
  std::vector<Corner> corners;       // of the active ones (a pool: clipped polygons append theirs)
  std::vector<Poly> settled, active;
  uint32_t activeKept = 0;  // during a plane's clip: the active polygons kept so far (compacted in place)
  PairTable pointCuts, vertexCuts;

  // The caps: per plane that made one, its border as directed point pairs (sorted), clipped by
  // every later plane and ear-clipped at the end; caps[0, capCount) are this cell's.
  struct Cap {
    uint32_t plane = 0;
    std::vector<uint64_t> edges;
  };
  struct End {
    double at;       // along the line of the two planes
    uint32_t point;
    bool arrives;    // the border arrives at the line here (else it leaves)
  };
  std::vector<Cap> caps;
  uint32_t capCount = 0;
  std::vector<uint64_t> keptEdges;
  std::vector<End> ends;

  // One cap.
  std::vector<uint64_t> segments, live;
  std::vector<uint8_t> visited;
  std::vector<uint32_t> loopPoints, outerOf, capTris, capVertex;
  std::vector<CapRing> rings, polygon;
  std::vector<double> area;
  std::vector<glm::dvec2> flat;
  CapTriangulator triangulator;

  // The piece.
  std::vector<uint32_t> vertexOut, pointOut, parent, runCount;
  std::vector<uint64_t> edges;
  std::vector<glm::dvec3> cutOut;

  bool begin(const MeshContainer& c, const SplitOptions& options);
  void startCell(const ConvexCell& cell, double tolerance);
  void startWideCell();
  void classifyIds(const ConvexCell& cell, double tolerance);
  uint32_t planeSigns(const Plane& plane, double tolerance, int8_t* signs);
  void pushTriangle(uint32_t t, bool isActive, uint32_t last, uint32_t touch);
  void keep(const Poly& poly, uint32_t rank);
  int8_t classify(uint32_t point, const Plane& plane, double tolerance);
  uint32_t cutPoint(uint32_t a, uint32_t b);
  uint32_t cutVertex(const Corner& a, const Corner& b, uint32_t point);
  bool clipPlane(const Plane& plane, uint32_t rank, double tolerance, bool& crossed);
  bool clipPolygon(const Poly& poly, const Plane& plane, uint32_t rank, double tolerance, bool& crossed);
  void keepOnPlaneEdges(uint32_t first, uint32_t count);
  bool cancelSegments();
  bool traceRings(const std::vector<uint64_t>& edgesOfCap);
  bool clipCap(Cap& c, const glm::dvec3& capNormal, const Plane& plane, double tolerance);
  bool capPlane(const ConvexCell& cell, uint32_t k, double tolerance);
  bool emitCap(const Cap& c, const Plane& plane, const SplitOptions& options);
  bool triangulateLoops(const glm::dvec3& u, const glm::dvec3& v);
  struct CapFrame {
    glm::vec3 normal, tangent;  // in the source space
    float handedness;           // the tangent's w
  };
  CapFrame capFrame(const glm::dvec3& n, const glm::dvec3& u, const glm::dvec3& v) const;
  uint32_t capVertexOf(uint32_t point, const CapFrame& frame, const glm::dvec2& uv, const SplitOptions& options);
  bool oneIsland();
  bool closedOnPoints();
  uint32_t vertexOf(const Corner& c, FracturePiece& piece);
  void reserveVertices(FracturePiece& piece, size_t vertices, size_t points) const;
  void writePiece(FracturePiece& piece);
  bool finishPiece(FracturePiece& piece);
  bool floatClean(const FracturePiece& piece) const;

  // Every polygon of the part with its corners: the settled ones, then the active ones.
  template <class F>
  void forEachPoly(F&& f) const {
    for (const Poly& poly : settled) f(poly, fixedCorners.data() + poly.first);
    for (const Poly& poly : active) f(poly, corners.data() + poly.first);
  }

  template <class T>
  const T& attribute(const std::vector<T>& source, const std::vector<T>& added, uint32_t v) const {
    return v < vertexCount ? source[v] : added[v - vertexCount];
  }
};

CellClipper::CellClipper() : s_(std::make_unique<State>()) {}
CellClipper::~CellClipper() = default;

bool CellClipper::begin(const MeshContainer& container, const SplitOptions& options) {
  return s_->begin(container, options);
}

bool CellClipper::State::begin(const MeshContainer& c, const SplitOptions& options) {
  container = nullptr;
  const MeshData& m = c.mesh();
  if (!c.closed() || c.mirrored() || !c.jointMatrices().empty() || !m.joints.empty() || !options.cap ||
      (options.uvMode == CapUvMode::NormalizedBounds && options.uvPerBorder)) {
    return false;
  }
  container = &c;
  mesh = &m;
  vertexCount = static_cast<uint32_t>(m.positions.size());
  idCount = c.positionIdCount();
  runMaterials.clear();
  triangleRun.assign(m.indices.size() / 3, 0);
  auto runOf = [&](uint32_t material) {
    const auto it = std::find(runMaterials.begin(), runMaterials.end(), material);
    if (it != runMaterials.end()) return static_cast<uint32_t>(it - runMaterials.begin());
    runMaterials.push_back(material);
    return static_cast<uint32_t>(runMaterials.size() - 1);
  };
  if (m.submeshes.empty()) runOf(0);
  for (const SubMesh& sub : m.submeshes) {
    const uint32_t run = runOf(sub.materialId);
    for (uint32_t t = sub.firstIndex / 3; t < (sub.firstIndex + sub.indexCount) / 3; ++t) triangleRun[t] = run;
  }
  capRun = runOf(options.capMaterialId);
  capLinear = glm::dmat3(c.model());
  capInverse = glm::inverse(capLinear);
  pos.resize(idCount);
  src.resize(idCount);
  donor.assign(idCount, kNone);
  const std::span<const uint32_t> ids = c.positionIds();
  for (uint32_t v = 0; v < vertexCount; ++v) {
    if (donor[ids[v]] != kNone) continue;
    donor[ids[v]] = v;
    pos[ids[v]] = c.cutPositions()[v];
    src[ids[v]] = glm::dvec3(m.positions[v]);
  }
  idX.resize(idCount);
  idY.resize(idCount);
  idZ.resize(idCount);
  for (uint32_t p = 0; p < idCount; ++p) idX[p] = pos[p].x, idY[p] = pos[p].y, idZ[p] = pos[p].z;
  triangleIds.resize(m.indices.size());
  for (size_t i = 0; i < m.indices.size(); ++i) triangleIds[i] = ids[m.indices[i]];
  knownPlanes.clear();
  knownSigns.clear();
  knownByBits.reset();
  return true;
}

namespace {

uint64_t planeBits(const Plane& plane) {
  const double parts[4] = {plane.normal.x, plane.normal.y, plane.normal.z, plane.offset};
  uint64_t h = 0x243f6a8885a308d3ull;
  for (double part : parts) {
    uint64_t bits;
    std::memcpy(&bits, &part, sizeof bits);
    h = (h ^ bits) * 0x100000001b3ull;
    h ^= h >> 29;
  }
  return h;
}

bool samePlane(const Plane& a, const Plane& b) {
  return a.normal.x == b.normal.x && a.normal.y == b.normal.y && a.normal.z == b.normal.z && a.offset == b.offset;
}

}  // namespace

// The signs of every position id against `plane` into `signs`: the negated signs of its opposite
// plane when a neighbour cell classified that one, else computed and kept. Returns how many are above.
uint32_t CellClipper::State::planeSigns(const Plane& plane, double tolerance, int8_t* signs) {
  const uint32_t n = idCount;  // a local: the byte stores below could alias a member
  const Plane opposite{-plane.normal, -plane.offset};
  const uint32_t known = knownByBits.get(planeBits(opposite));
  uint32_t above = 0;
  if (known != kNone && samePlane(knownPlanes[known].plane, opposite) && knownPlanes[known].tolerance == tolerance) {
    const int8_t* from = knownSigns.data() + knownPlanes[known].at;
    for (uint32_t p = 0; p < n; ++p) signs[p] = int8_t(-from[p]);
    for (uint32_t p = 0; p < n; ++p) above += uint32_t(signs[p] > 0);
    return above;
  }
  // One array per coordinate, the products summed as glm::dot does: the same bits, in vector lanes.
  const double* x = idX.data();
  const double* y = idY.data();
  const double* z = idZ.data();
  const double nx = plane.normal.x, ny = plane.normal.y, nz = plane.normal.z;
  const double offset = plane.offset;
  for (uint32_t p = 0; p < n; ++p) {
    const double d = ((nx * x[p] + ny * y[p]) + nz * z[p]) - offset;
    signs[p] = int8_t(int(d > tolerance) - int(d < -tolerance));  // as classify() decides
  }
  for (uint32_t p = 0; p < n; ++p) above += uint32_t(signs[p] > 0);
  if (knownByBits.putIfAbsent(planeBits(plane), static_cast<uint32_t>(knownPlanes.size())) == kNone) {
    knownPlanes.push_back({plane, tolerance, static_cast<uint32_t>(knownSigns.size())});
    knownSigns.insert(knownSigns.end(), signs, signs + n);
  }
  return above;
}

inline int8_t CellClipper::State::classify(uint32_t point, const Plane& plane, double tolerance) {
  PointClass& c = cls[point];
  if (c.stamp == epoch) return c.sign;
  const double d = glm::dot(plane.normal, pos[point]) - plane.offset;
  c.stamp = epoch;
  c.dist = std::abs(d) <= tolerance ? 0.0 : d;
  c.sign = std::abs(d) <= tolerance ? 0 : (d > 0.0 ? 1 : -1);
  return c.sign;
}

// Every position id against every plane of the cell (planeSign); `order`, the planes by how many
// points lie above them, most first, so that the active polygons become few soonest; and per id,
// as bits by rank in that order, the planes it is not below and those it is above (for cells of at
// most kMaskedPlanes planes).
void CellClipper::State::classifyIds(const ConvexCell& cell, double tolerance) {
  const uint32_t planes = static_cast<uint32_t>(cell.planes.size());
  const uint32_t n = idCount;
  aboveCount.assign(planes, 0);
  planeSign.resize(size_t(planes) * n);
  for (uint32_t k = 0; k < planes; ++k)
    aboveCount[k] = planeSigns(cell.planes[k], tolerance, planeSign.data() + size_t(k) * n);
  order.resize(planes);
  for (uint32_t k = 0; k < planes; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return aboveCount[a] > aboveCount[b]; });
  if (planes > kMaskedPlanes) return;
  notBelow.assign(n, 0);
  aboveAt.assign(n, 0);
  uint32_t* met = notBelow.data();
  uint32_t* above = aboveAt.data();
  for (uint32_t r = 0; r < planes; ++r) {
    const int8_t* signs = planeSign.data() + size_t(order[r]) * n;
    for (uint32_t p = 0; p < n; ++p) {
      met[p] |= uint32_t(signs[p] >= 0) << r;
      above[p] |= uint32_t(signs[p] > 0) << r;
    }
  }
}

// The cell's polygons to clip (active) and those below every plane (settled: no plane touches
// them). A triangle is left out when the clip would drop it without a trace: at the first plane (in
// clipping order) that any of its corners is not below, all three are above. It never crosses nor
// touches a plane before, so no section point, edge or cut comes of it, and leaving it out gives
// the same piece, the same bits, with far fewer polygons to clip (most of the mesh, for a small
// cell). (A triangle above only a later plane cannot be dropped before that plane comes: the
// sections of the planes before it need it to close their loops.)
void CellClipper::State::startCell(const ConvexCell& cell, double tolerance) {
  pos.resize(idCount);
  src.resize(idCount);
  donor.resize(idCount);
  cutFrom.assign(idCount, kNone);
  extra.positions.clear();
  extra.normals.clear();
  extra.tangents.clear();
  extra.uv0.clear();
  extra.uv1.clear();
  extra.colors.clear();
  fixedCorners.clear();
  corners.clear();
  settled.clear();
  active.clear();
  classifyIds(cell, tolerance);
  if (cell.planes.size() > kMaskedPlanes) {
    startWideCell();
    return;
  }
  const uint32_t triangles = static_cast<uint32_t>(mesh->indices.size() / 3);
  const uint32_t* met = notBelow.data();
  const uint32_t* above = aboveAt.data();
  for (uint32_t t = 0; t < triangles; ++t) {
    const uint32_t a = triangleIds[3 * t], b = triangleIds[3 * t + 1], c = triangleIds[3 * t + 2];
    const uint32_t any = met[a] | met[b] | met[c];
    if (any == 0) {
      pushTriangle(t, false, 0, 0);
      continue;
    }
    const int first = std::countr_zero(any);  // the first plane any corner is not below
    if ((above[a] & above[b] & above[c]) >> first & 1) continue;
    pushTriangle(t, true, uint32_t(31 - std::countl_zero(any)), any);  // the last such plane
  }
}

// startCell for a cell of more planes than the masks hold: the first and last rank each id is not
// below as 16-bit ranks leave out and settle the same triangles; every plane classifies the active
// ones (no touch bits). Past 65534 planes nothing is left out.
void CellClipper::State::startWideCell() {
  const uint32_t planes = static_cast<uint32_t>(order.size());
  const uint32_t n = idCount;
  const uint32_t triangles = static_cast<uint32_t>(mesh->indices.size() / 3);
  if (planes >= kNever) {
    for (uint32_t t = 0; t < triangles; ++t) pushTriangle(t, true, kNone, kMayTouchAll);
    return;
  }
  firstMet.assign(n, kNever);
  lastMet.assign(n, 0);
  uint16_t* met = firstMet.data();
  uint16_t* last = lastMet.data();
  for (uint32_t r = 0; r < planes; ++r) {
    const int8_t* signs = planeSign.data() + size_t(order[r]) * n;
    for (uint32_t p = 0; p < n; ++p) {
      met[p] = met[p] == kNever && signs[p] >= 0 ? uint16_t(r) : met[p];
      last[p] = signs[p] >= 0 ? uint16_t(r) : last[p];
    }
  }
  for (uint32_t t = 0; t < triangles; ++t) {
    const uint32_t a = triangleIds[3 * t], b = triangleIds[3 * t + 1], c = triangleIds[3 * t + 2];
    const uint16_t first = std::min({met[a], met[b], met[c]});
    if (first != kNever) {
      const int8_t* signs = planeSign.data() + size_t(order[first]) * n;
      if (signs[a] > 0 && signs[b] > 0 && signs[c] > 0) continue;
    }
    pushTriangle(t, first != kNever, std::max({last[a], last[b], last[c]}), kMayTouchAll);
  }
}

void CellClipper::State::pushTriangle(uint32_t t, bool isActive, uint32_t last, uint32_t touch) {
  std::vector<Corner>& into = isActive ? corners : fixedCorners;
  (isActive ? active : settled)
      .push_back(Poly{static_cast<uint32_t>(into.size()), 3, t, triangleRun[t], last, touch});
  for (int i = 0; i < 3; ++i) into.push_back(Corner{triangleIds[3 * t + i], mesh->indices[3 * t + i]});
}

// The point where plane cuts the segment of points a and b (one per pair and plane: interpolated
// from the lower id, so both polygons of an edge get the same bits).
inline uint32_t CellClipper::State::cutPoint(uint32_t a, uint32_t b) {
  const uint32_t point = static_cast<uint32_t>(pos.size());
  const uint32_t known = pointCuts.putIfAbsent(pairKey(a, b), point);
  if (known != kNone) return known;
  const uint32_t lo = std::min(a, b), hi = std::max(a, b);
  const double t = cls[lo].dist / (cls[lo].dist - cls[hi].dist);
  pos.push_back(pos[lo] + t * (pos[hi] - pos[lo]));
  src.push_back(src[lo] + t * (src[hi] - src[lo]));
  donor.push_back(kNone);
  cutFrom.push_back(lo);
  cls.push_back(PointClass{0.0, epoch, 0});
  return point;
}

// The vertex at cut point `point` between corners a and b: every attribute interpolated from the
// corner at the lower point id (one vertex per vertex pair and plane: seams keep their sides).
uint32_t CellClipper::State::cutVertex(const Corner& a, const Corner& b, uint32_t point) {
  const uint32_t vertex = vertexCount + static_cast<uint32_t>(extra.positions.size());
  const uint32_t known = vertexCuts.putIfAbsent(pairKey(a.vertex, b.vertex), vertex);
  if (known != kNone) return known;
  const Corner& lo = a.point < b.point ? a : b;
  const Corner& hi = a.point < b.point ? b : a;
  const double t = cls[lo.point].dist / (cls[lo.point].dist - cls[hi.point].dist);
  const float tf = static_cast<float>(t);
  const MeshData& m = *mesh;
  extra.positions.push_back(glm::vec3(src[point]));
  if (!m.normals.empty()) {
    const glm::vec3 na = attribute(m.normals, extra.normals, lo.vertex), nb = attribute(m.normals, extra.normals, hi.vertex);
    extra.normals.push_back(normalizedOr(glm::mix(glm::dvec3(na), glm::dvec3(nb), t), t < 0.5 ? na : nb));
  }
  if (!m.tangents.empty()) {
    const glm::vec4 ta = attribute(m.tangents, extra.tangents, lo.vertex), tb = attribute(m.tangents, extra.tangents, hi.vertex);
    const glm::vec4& nearest = t < 0.5 ? ta : tb;
    extra.tangents.push_back(glm::vec4(normalizedOr(glm::mix(glm::dvec3(ta), glm::dvec3(tb), t), glm::vec3(nearest)), nearest.w));
  }
  if (!m.uv0.empty()) extra.uv0.push_back(glm::mix(attribute(m.uv0, extra.uv0, lo.vertex), attribute(m.uv0, extra.uv0, hi.vertex), tf));
  if (!m.uv1.empty()) extra.uv1.push_back(glm::mix(attribute(m.uv1, extra.uv1, lo.vertex), attribute(m.uv1, extra.uv1, hi.vertex), tf));
  if (!m.colors.empty()) {
    extra.colors.push_back(glm::mix(attribute(m.colors, extra.colors, lo.vertex), attribute(m.colors, extra.colors, hi.vertex), tf));
  }
  if (donor[point] == kNone) donor[point] = vertex;
  return vertex;
}

// The on-plane edges of the polygon just written (both ends on the plane), reversed: the cap's border.
inline void CellClipper::State::keepOnPlaneEdges(uint32_t first, uint32_t count) {
  for (uint32_t i = 0; i < count; ++i) {
    const Corner& a = corners[first + i];
    const Corner& b = corners[first + (i + 1 == count ? 0 : i + 1)];
    if (cls[a.point].sign == 0 && cls[b.point].sign == 0) segments.push_back(directedKey(b.point, a.point));
  }
}

// A polygon kept by the plane of `rank`: active for the planes after, or settled when it is below
// all of them (its corners are, so every part of it is: no later plane visits it).
void CellClipper::State::keep(const Poly& poly, uint32_t rank) {
  if (poly.last > rank) {
    active[activeKept++] = poly;  // never past the one being clipped
    return;
  }
  settled.push_back(
      Poly{static_cast<uint32_t>(fixedCorners.size()), poly.count, poly.source, poly.run, poly.last, poly.touch});
  fixedCorners.insert(fixedCorners.end(), corners.begin() + poly.first, corners.begin() + poly.first + poly.count);
}

// One polygon against the plane: dropped (above), kept as it is, or clipped (its new corners
// appended to the corner pool). False: it lies in the plane.
bool CellClipper::State::clipPolygon(const Poly& poly, const Plane& plane, uint32_t rank, double tolerance,
                                     bool& crossed) {
  int8_t s[kMaxCorners];
  bool anyAbove = false, anyBelow = false, anyOn = false;
  for (uint32_t i = 0; i < poly.count; ++i) {
    s[i] = classify(corners[poly.first + i].point, plane, tolerance);
    anyAbove = anyAbove || s[i] > 0;
    anyBelow = anyBelow || s[i] < 0;
    anyOn = anyOn || s[i] == 0;
  }
  if (!anyBelow) return anyAbove;  // above (or touching it): dropped; wholly in the plane: refused
  if (!anyAbove) {
    if (anyOn) keepOnPlaneEdges(poly.first, poly.count);
    keep(poly, rank);
    return true;
  }
  crossed = true;
  const uint32_t first = static_cast<uint32_t>(corners.size());
  for (uint32_t i = 0; i < poly.count; ++i) {
    const uint32_t j = i + 1 == poly.count ? 0 : i + 1;
    const Corner a = corners[poly.first + i];
    const Corner b = corners[poly.first + j];
    if (s[i] <= 0) corners.push_back(a);
    if ((s[i] < 0 && s[j] > 0) || (s[i] > 0 && s[j] < 0)) {
      const uint32_t point = cutPoint(a.point, b.point);
      const uint32_t vertex = cutVertex(a, b, point);
      corners.push_back(Corner{point, vertex});
    }
  }
  const uint32_t count = static_cast<uint32_t>(corners.size()) - first;
  if (count > kMaxCorners) return false;
  keepOnPlaneEdges(first, count);
  keep(Poly{first, count, poly.source, poly.run, poly.last, poly.touch}, rank);  // part of its triangle
  return true;
}

// All active polygons against one plane; the kept ones become the active set. False: fall back.
bool CellClipper::State::clipPlane(const Plane& plane, uint32_t rank, double tolerance, bool& crossed) {
  ++epoch;
  cls.resize(pos.size());
  pointCuts.reset();
  vertexCuts.reset();
  activeKept = 0;
  segments.clear();
  crossed = false;
  const size_t count = active.size();
  for (size_t i = 0; i < count; ++i) {
    const Poly poly = active[i];  // a copy: keep() writes the kept ones over the front of `active`
    if (!mayTouch(poly, rank)) {  // a triangle of the mesh wholly below this plane (its ids' signs say so)
      keep(poly, rank);
      continue;
    }
    if (poly.count > kMaxCorners || !clipPolygon(poly, plane, rank, tolerance, crossed)) return false;
  }
  active.resize(activeKept);
  return true;
}

// The section's border from the on-plane edges of one plane: opposite pairs (kept on both sides)
// cancelled, the rest in `live`, sorted. False when an edge or a point is met twice.
bool CellClipper::State::cancelSegments() {
  std::sort(segments.begin(), segments.end());
  live.clear();
  for (size_t i = 0; i < segments.size(); ++i) {
    const uint64_t reverse = directedKey(keyTo(segments[i]), keyFrom(segments[i]));
    if (std::binary_search(segments.begin(), segments.end(), reverse)) continue;  // kept on both sides
    if (i > 0 && segments[i] == segments[i - 1]) return false;                    // an edge met twice
    live.push_back(segments[i]);
  }
  for (size_t i = 1; i < live.size(); ++i) {
    if (keyFrom(live[i]) == keyFrom(live[i - 1])) return false;  // a point met twice: loops touch
  }
  return true;
}

// The loops of sorted directed edges (each point left by one edge), as rings of loopPoints.
// False on an open chain or a loop of fewer than three points.
bool CellClipper::State::traceRings(const std::vector<uint64_t>& edgesOfCap) {
  visited.assign(edgesOfCap.size(), 0);
  loopPoints.clear();
  rings.clear();
  for (size_t start = 0; start < edgesOfCap.size(); ++start) {
    if (visited[start]) continue;
    const uint32_t begin = static_cast<uint32_t>(loopPoints.size());
    size_t at = start;
    while (!visited[at]) {
      visited[at] = 1;
      loopPoints.push_back(keyFrom(edgesOfCap[at]));
      const auto next = std::lower_bound(edgesOfCap.begin(), edgesOfCap.end(), uint64_t(keyTo(edgesOfCap[at])) << 32);
      if (next == edgesOfCap.end() || keyFrom(*next) != keyTo(edgesOfCap[at])) return false;  // an open chain
      at = static_cast<size_t>(next - edgesOfCap.begin());
    }
    if (at != start || loopPoints.size() - begin < 3) return false;
    rings.push_back(CapRing{begin, static_cast<uint32_t>(loopPoints.size())});
  }
  return true;
}

// An earlier cap's border against plane j: edges above dropped, crossing ones cut, and the border
// closed along the line where the two planes meet. Walking that line in direction n_cap x n_j, the
// cap's inside below j is on the left: each point where the border arrives at the line (from below)
// is followed by one where it leaves again, and the cap gains the edge between them. Plane j's cap
// gains the same edge the other way (segments). False when the border lies along the line or the
// points on it do not alternate (a degenerate meeting: the splits handle it).
bool CellClipper::State::clipCap(Cap& c, const glm::dvec3& capNormal, const Plane& plane, double tolerance) {
  keptEdges.clear();
  ends.clear();
  for (uint64_t e : c.edges) {
    const uint32_t a = keyFrom(e), b = keyTo(e);
    const int8_t sa = classify(a, plane, tolerance), sb = classify(b, plane, tolerance);
    if (sa == 0 && sb == 0) return false;
    if (sa <= 0 && sb <= 0) {
      keptEdges.push_back(e);
    } else if (sa < 0 || sb < 0) {
      const uint32_t cut = cutPoint(a, b);
      keptEdges.push_back(sa < 0 ? directedKey(a, cut) : directedKey(cut, b));
    } else {
      continue;
    }
    const uint64_t kept = keptEdges.back();
    if (cls[keyTo(kept)].sign == 0) ends.push_back(End{0.0, keyTo(kept), true});
    if (cls[keyFrom(kept)].sign == 0) ends.push_back(End{0.0, keyFrom(kept), false});
  }
  if (ends.empty()) {
    c.edges.swap(keptEdges);
    return true;
  }
  const glm::dvec3 along = glm::cross(capNormal, plane.normal);
  for (End& end : ends) end.at = glm::dot(pos[end.point], along);
  std::sort(ends.begin(), ends.end(), [](const End& x, const End& y) {
    return x.at != y.at ? x.at < y.at : (x.point != y.point ? x.point < y.point : x.arrives > y.arrives);
  });
  // A point the border passes through on the line (arrives and leaves) is no end.
  size_t n = 0;
  for (size_t i = 0; i < ends.size(); ++i) {
    if (i + 1 < ends.size() && ends[i].point == ends[i + 1].point && ends[i].arrives != ends[i + 1].arrives) {
      ++i;
      continue;
    }
    ends[n++] = ends[i];
  }
  if (n % 2 != 0) return false;
  for (size_t i = 0; i < n; i += 2) {
    if (!ends[i].arrives || ends[i + 1].arrives || !(ends[i].at < ends[i + 1].at)) return false;
    keptEdges.push_back(directedKey(ends[i].point, ends[i + 1].point));
    segments.push_back(directedKey(ends[i + 1].point, ends[i].point));
  }
  std::sort(keptEdges.begin(), keptEdges.end());
  c.edges.swap(keptEdges);
  return true;
}

// Plane k after its clip: the earlier caps clipped by it, then its own cap from the section.
bool CellClipper::State::capPlane(const ConvexCell& cell, uint32_t k, double tolerance) {
  const Plane& plane = cell.planes[k];
  for (uint32_t i = 0; i < capCount; ++i) {
    if (!clipCap(caps[i], glm::normalize(cell.planes[caps[i].plane].normal), plane, tolerance)) return false;
  }
  if (segments.empty()) return true;
  if (!cancelSegments()) return false;
  if (live.empty()) return true;
  if (capCount == caps.size()) caps.emplace_back();
  caps[capCount].plane = k;
  caps[capCount].edges.assign(live.begin(), live.end());
  ++capCount;
  return true;
}

// The loops in plane coordinates, holes given to the smallest border holding them, ear-clipped.
// capTris: indices into loopPoints, counter-clockwise seen from above the plane.
bool CellClipper::State::triangulateLoops(const glm::dvec3& u, const glm::dvec3& v) {
  const glm::dvec3 origin = pos[loopPoints.front()];
  flat.resize(loopPoints.size());
  double largest = 0.0;
  for (size_t i = 0; i < loopPoints.size(); ++i) {
    const glm::dvec3 p = pos[loopPoints[i]];
    flat[i] = glm::dvec2(glm::dot(p - origin, u), glm::dot(p - origin, v));
    largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  }
  area.resize(rings.size());
  for (size_t r = 0; r < rings.size(); ++r) {
    area[r] = CapTriangulator::twiceSignedArea(flat, rings[r]);
    if (area[r] == 0.0) return false;
  }
  outerOf.assign(rings.size(), kNone);
  for (size_t h = 0; h < rings.size(); ++h) {
    if (area[h] > 0.0) continue;
    for (size_t o = 0; o < rings.size(); ++o) {
      if (area[o] > 0.0 && CapTriangulator::ringContains(flat, rings[o], flat[rings[h].begin]) &&
          (outerOf[h] == kNone || area[o] < area[outerOf[h]])) {
        outerOf[h] = static_cast<uint32_t>(o);
      }
    }
    if (outerOf[h] == kNone) return false;
  }
  capTris.clear();
  const double tolerance = std::max(4.0 * 0x1.0p-24 * largest, 1e-12 * container->boundsDiagonal());
  for (size_t o = 0; o < rings.size(); ++o) {
    if (!(area[o] > 0.0)) continue;
    polygon.assign(1, rings[o]);
    for (size_t h = 0; h < rings.size(); ++h) {
      if (outerOf[h] == o) polygon.push_back(rings[h]);
    }
    // Most cell faces are convex without holes: fanned at once, ear-clipped only when not.
    if (polygon.size() == 1 && triangulator.triangulateConvex(flat, polygon[0], capTris, tolerance)) continue;
    if (!triangulator.triangulate(flat, polygon, capTris, tolerance)) return false;
  }
  return true;
}

// A cap's normal and tangent taken back to the source space (one per cap: every vertex shares them).
CellClipper::State::CapFrame CellClipper::State::capFrame(const glm::dvec3& n, const glm::dvec3& u,
                                                          const glm::dvec3& v) const {
  const glm::dvec3 normal = glm::normalize(glm::transpose(capLinear) * n);
  const glm::dvec3 tangent = glm::normalize(capInverse * u);
  const float w = glm::dot(glm::cross(normal, tangent), capInverse * v) < 0.0 ? -1.f : 1.f;
  return CapFrame{glm::vec3(normal), glm::vec3(tangent), w};
}

// A cap vertex at a loop point: the point's position, the cap's frame, the UV in the atlas, the
// colour of a vertex at the point.
uint32_t CellClipper::State::capVertexOf(uint32_t point, const CapFrame& frame, const glm::dvec2& uv,
                                         const SplitOptions& options) {
  const MeshData& m = *mesh;
  const uint32_t vertex = vertexCount + static_cast<uint32_t>(extra.positions.size());
  extra.positions.push_back(glm::vec3(src[point]));
  if (!m.normals.empty()) extra.normals.push_back(frame.normal);
  if (!m.tangents.empty()) extra.tangents.push_back(glm::vec4(frame.tangent, frame.handedness));
  const glm::vec2 mapped(glm::dvec2(options.atlasRect.x, options.atlasRect.y) +
                         uv * glm::dvec2(options.atlasRect.z, options.atlasRect.w));
  if (!m.uv0.empty()) extra.uv0.push_back(mapped);
  if (!m.uv1.empty()) extra.uv1.push_back(mapped);
  if (!m.colors.empty()) {
    uint32_t at = point;  // a point where only caps meet (on three planes) has no vertex: one it was cut from
    while (donor[at] == kNone) at = cutFrom[at];
    extra.colors.push_back(attribute(m.colors, extra.colors, donor[at]));
  }
  return vertex;
}

// A cap's border, once every plane has clipped it, ear-clipped into triangles added to the active
// polygons (with a vertex per border point).
bool CellClipper::State::emitCap(const Cap& c, const Plane& plane, const SplitOptions& options) {
  if (c.edges.empty()) return true;
  if (!traceRings(c.edges)) return false;
  const uint32_t k = c.plane;
  const glm::dvec3 n = glm::normalize(plane.normal);
  glm::dvec3 u, v;
  capPlaneBasis(n, u, v);
  if (!triangulateLoops(u, v)) return false;
  glm::dvec2 lo(INFINITY), hi(-INFINITY);
  for (uint32_t p : loopPoints) {
    const glm::dvec2 planar(glm::dot(pos[p], u), glm::dot(pos[p], v));
    lo = glm::min(lo, planar);
    hi = glm::max(hi, planar);
  }
  capVertex.resize(loopPoints.size());
  const CapFrame frame = capFrame(n, u, v);
  for (size_t i = 0; i < loopPoints.size(); ++i) {
    const glm::dvec3& p = pos[loopPoints[i]];
    const glm::dvec2 planar(glm::dot(p, u), glm::dot(p, v));
    glm::dvec2 uv = planar * options.uvPerMetre;
    if (options.uvMode == CapUvMode::NormalizedBounds) {
      const glm::dvec2 size = hi - lo;
      uv = glm::dvec2(size.x > 0.0 ? (planar.x - lo.x) / size.x : 0.0, size.y > 0.0 ? (planar.y - lo.y) / size.y : 0.0);
    }
    capVertex[i] = capVertexOf(loopPoints[i], frame, uv, options);
  }
  for (size_t t = 0; t + 2 < capTris.size(); t += 3) {
    active.push_back(Poly{static_cast<uint32_t>(corners.size()), 3, kFromCap | k, capRun, kNone, kMayTouchAll});
    for (int c = 0; c < 3; ++c) corners.push_back(Corner{loopPoints[capTris[t + c]], capVertex[capTris[t + c]]});
  }
  return true;
}

bool CellClipper::State::oneIsland() {
  parent.resize(pos.size());
  for (uint32_t p = 0; p < parent.size(); ++p) parent[p] = p;
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  uint32_t root = kNone;
  forEachPoly([&](const Poly& poly, const Corner* c) {
    const uint32_t a = find(c[0].point);
    for (uint32_t i = 1; i < poly.count; ++i) parent[find(c[i].point)] = a;
    if (root == kNone) root = a;
  });
  for (uint32_t i = 0; i < capCount; ++i) {
    for (uint64_t e : caps[i].edges) parent[find(keyFrom(e))] = find(keyTo(e));
  }
  bool one = true;
  forEachPoly([&](const Poly&, const Corner* c) { one = one && find(c[0].point) == find(root); });
  return one;
}

// Every edge of the polygons met once each way (on points): no directed edge twice, and each one's
// reverse met too (counted when the second of the two comes).
bool CellClipper::State::closedOnPoints() {
  pointCuts.reset();
  bool closed = true;
  uint32_t count = 0, paired = 0;
  forEachPoly([&](const Poly& poly, const Corner* c) {
    for (uint32_t i = 0; i < poly.count && closed; ++i) {
      const uint32_t a = c[i].point, b = c[i + 1 == poly.count ? 0 : i + 1].point;
      closed = a != b && pointCuts.putIfAbsent(directedKey(a, b), 0) == kNone;
      paired += pointCuts.get(directedKey(b, a)) != kNone ? 2 : 0;
      ++count;
    }
  });
  return closed && paired == count;
}

CellClipper::Outcome CellClipper::clip(const ConvexCell& cell, uint32_t cellIndex, const SplitOptions& options,
                                       double tolerance, FracturePiece& piece, uint32_t& cuts) {
  State& s = *s_;
  if (!s.container || cell.empty) return Outcome::Fallback;
  s.startCell(cell, tolerance);
  s.capCount = 0;
  uint32_t made = 0;
  for (uint32_t i = 0; i < cell.planes.size() && (!s.active.empty() || s.capCount > 0); ++i) {
    const uint32_t k = s.order[i];
    bool crossed = false;
    if (!s.clipPlane(cell.planes[k], i, tolerance, crossed)) return Outcome::Fallback;
    made += crossed ? 1 : 0;
    if (!s.capPlane(cell, k, tolerance)) return Outcome::Fallback;
  }
  // (A cell wholly inside the solid keeps no polygon of the mesh, only caps.)
  while (s.capCount > 0 && s.caps[s.capCount - 1].edges.empty()) --s.capCount;
  bool anyCap = false;
  for (uint32_t i = 0; i < s.capCount; ++i) anyCap = anyCap || !s.caps[i].edges.empty();
  if (s.settled.empty() && s.active.empty() && !anyCap) {
    cuts += made;
    return Outcome::Nothing;
  }
  // Untouched by every plane (the whole mesh, or whole parts of it): carved by splits, which copy it.
  if (made == 0) return Outcome::Fallback;
  if (options.separateIslands && !s.oneIsland()) return Outcome::Fallback;
  for (uint32_t i = 0; i < s.capCount; ++i) {
    if (!s.emitCap(s.caps[i], cell.planes[s.caps[i].plane], options)) return Outcome::Fallback;
  }
  if (!s.closedOnPoints()) return Outcome::Fallback;
  FracturePiece out;
  out.cell = cellIndex;
  s.writePiece(out);
  if (!s.finishPiece(out)) return Outcome::Fallback;
  piece = std::move(out);
  cuts += made;
  return Outcome::Piece;
}

// The output vertex of a corner: its attributes copied on first use, its position id likewise.
inline uint32_t CellClipper::State::vertexOf(const Corner& c, FracturePiece& piece) {
  if (vertexOut[c.vertex] != kNone) return vertexOut[c.vertex];
  const MeshData& m = *mesh;
  MeshData& out = piece.mesh;
  const uint32_t v = static_cast<uint32_t>(out.positions.size());
  vertexOut[c.vertex] = v;
  out.positions.push_back(attribute(m.positions, extra.positions, c.vertex));
  if (!m.normals.empty()) out.normals.push_back(attribute(m.normals, extra.normals, c.vertex));
  if (!m.tangents.empty()) out.tangents.push_back(attribute(m.tangents, extra.tangents, c.vertex));
  if (!m.uv0.empty()) out.uv0.push_back(attribute(m.uv0, extra.uv0, c.vertex));
  if (!m.uv1.empty()) out.uv1.push_back(attribute(m.uv1, extra.uv1, c.vertex));
  if (!m.colors.empty()) out.colors.push_back(attribute(m.colors, extra.colors, c.vertex));
  if (pointOut[c.point] == kNone) {
    pointOut[c.point] = static_cast<uint32_t>(piece.weld.representatives.size());
    piece.weld.representatives.push_back(v);
  }
  piece.weld.positionIds.push_back(pointOut[c.point]);
  return v;
}

// Room for `vertices` output vertices (each attribute the mesh has) and `points` welded points:
// the piece's arrays grow once.
void CellClipper::State::reserveVertices(FracturePiece& piece, size_t vertices, size_t points) const {
  const MeshData& m = *mesh;
  MeshData& out = piece.mesh;
  out.positions.reserve(vertices);
  if (!m.normals.empty()) out.normals.reserve(vertices);
  if (!m.tangents.empty()) out.tangents.reserve(vertices);
  if (!m.uv0.empty()) out.uv0.reserve(vertices);
  if (!m.uv1.empty()) out.uv1.reserve(vertices);
  if (!m.colors.empty()) out.colors.reserve(vertices);
  piece.weld.positionIds.reserve(vertices);
  piece.weld.representatives.reserve(points);
}

// The polygons fanned into triangles, run by run (the mesh's materials in order, then the cap's).
void CellClipper::State::writePiece(FracturePiece& piece) {
  runCount.assign(runMaterials.size(), 0);
  size_t cornerCount = 0;
  forEachPoly([&](const Poly& poly, const Corner*) {
    runCount[poly.run] += poly.count - 2;
    cornerCount += poly.count;
  });
  const size_t triangles = std::accumulate(runCount.begin(), runCount.end(), size_t(0));
  vertexOut.assign(vertexCount + extra.positions.size(), kNone);
  pointOut.assign(pos.size(), kNone);
  MeshData& out = piece.mesh;
  reserveVertices(piece, std::min(cornerCount, vertexOut.size()), std::min(cornerCount, pointOut.size()));
  out.indices.reserve(3 * triangles);
  piece.sourceTriangles.reserve(triangles);
  for (uint32_t run = 0; run < runMaterials.size(); ++run) {
    if (runCount[run] == 0) continue;
    out.submeshes.push_back(SubMesh{static_cast<uint32_t>(out.indices.size()), 3 * runCount[run], runMaterials[run]});
    forEachPoly([&](const Poly& poly, const Corner* c) {
      if (poly.run != run) return;
      for (uint32_t i = 1; i + 1 < poly.count; ++i) {
        out.indices.push_back(vertexOf(c[0], piece));
        out.indices.push_back(vertexOf(c[i], piece));
        out.indices.push_back(vertexOf(c[i + 1], piece));
        piece.sourceTriangles.push_back(poly.source);
      }
    });
  }
  piece.capTriangles = runCount[capRun];
  piece.weld.closed = true;
}

// The float checks and the mass properties. False: fall back.
bool CellClipper::State::finishPiece(FracturePiece& piece) {
  if (!floatClean(piece)) return false;
  const glm::dmat4& model = container->model();
  cutOut.resize(piece.mesh.positions.size());
  for (size_t v = 0; v < cutOut.size(); ++v) cutOut[v] = glm::dvec3(model * glm::dvec4(glm::dvec3(piece.mesh.positions[v]), 1.0));
  piece.mass = integrateClosedSurface(cutOut, piece.mesh.indices, false, false);
  return true;
}

// Distinct float positions for distinct points, and no triangle of zero area in float.
bool CellClipper::State::floatClean(const FracturePiece& piece) const {
  const MeshData& m = piece.mesh;
  std::vector<glm::vec3> at;
  at.reserve(piece.weld.representatives.size());
  for (uint32_t v : piece.weld.representatives) at.push_back(m.positions[v]);
  std::sort(at.begin(), at.end(), [](const glm::vec3& a, const glm::vec3& b) {
    return a.x != b.x ? a.x < b.x : (a.y != b.y ? a.y < b.y : a.z < b.z);
  });
  if (std::adjacent_find(at.begin(), at.end()) != at.end()) return false;
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]), c(m.positions[m.indices[t + 2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    if (!(glm::dot(n, n) > 0.0)) return false;
  }
  return true;
}

}  // namespace cleave::geometry
