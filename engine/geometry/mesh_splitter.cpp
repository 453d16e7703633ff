// SPDX-License-Identifier: MIT
// The split core: classification, shared-edge cutting, boundary loops, caps, islands, mass.
//
// Method, in the order of split():
//  1. Classify every position id (welded vertex) by its signed distance to the plane in cut space:
//     above, below, or on the plane within relativeTolerance * boundsDiagonal. All vertices of an id
//     share the class of its first vertex, so a seam can never be on two sides at once.
//  2. Collect the crossing edges (one end above, one below) twice: by welded id pair, which fixes the
//     edge parameter t and the new position once for every triangle that uses the edge (watertight
//     pieces), and by source vertex pair, which gives each seam side its own interpolated attributes.
//  3. Cut the triangles: a triangle with an on-plane vertex and the two others on opposite sides is
//     split in two through that vertex (never at it: no zero-area sliver); a triangle with one lone
//     vertex gives a triangle and a quad (two triangles, shorter diagonal). A face lying in the plane
//     goes to the side its normal points away from, where the solid is.
//  4. The boundary of each side's surface is the set of its on-plane edges without a reverse twin on
//     the same side. Reversed, the boundary of the below side is the section, counter-clockwise seen
//     from the plane normal; it must equal the boundary of the above side, or the input is
//     non-manifold at the cut. The segments are chained into loops on welded ids (at a vertex with
//     several ways on, the sharpest left turn keeps touching loops apart); a chain that does not
//     close is an open section.
//  5. Caps: runs of loop points within float rounding of each other (a plane crossing the sliver
//     fans of an earlier cap leaves them, in an order scrambled by rounding) are merged into one
//     point, their cut vertices moved onto it on both sides so the pieces stay watertight. The
//     loops are projected on a fixed orthonormal basis of the plane, split by signed area
//     into outer borders and holes, each hole given to the smallest border containing it (any nesting
//     depth), and each border with its holes triangulated by CapTriangulator. The convex splitter
//     first tries the thesis's fast path: one loop, in angular order around its centroid, strictly
//     convex once collinear points are removed, fanned; anything else takes the general path.
//     Cap triangles flat on the float positions they are written with are flipped with their
//     neighbour across their longest edge.
//  6. Exact float output: the parts of cut triangles (and caps) whose corners round to one float
//     position are dropped and those corners welded into one id, so the pieces are closed on their
//     float positions as on their ids; a side with nothing left is a miss.
//     Islands: union-find over welded ids (cap triangles included) on each side; with
//     IslandMode::Touching, parts that touch, pass into or hold one another are then joined, and a
//     part the plane did not reach goes with the nearest piece it did (island_contacts.h); pieces are ordered
//     by their smallest source triangle. When the section rules out cavities (a closed mesh of one
//     part), the joins are looked for once the pieces are written, from the bounds and reach the
//     writing works out anyway; a side is written again only if parts were joined. Each piece is written in source space with its own vertex
//     remap, submesh runs in input order (cap triangles join an existing run of the cap material).
//  7. Mass properties per piece on the cut-space positions.
// Every scratch array lives in the splitter and every output array in the reused SplitResult, so a
// warmed-up split of a same-size mesh performs no heap allocation.
#include "cleave/geometry/mesh_splitter.h"

#include <algorithm>
#include <cassert>
#include <bit>
#include <cmath>
#include <compare>
#include <cstring>
#include <iterator>
#include <memory>
#include <numeric>
#include <type_traits>

#include "cleave/geometry/cap_triangulator.h"
#include "cleave/geometry/island_contacts.h"
#include "cleave/geometry/mass_kernel.h"
#include "cleave/geometry/offset_list.h"
#include "cleave/geometry/pass_threads.h"
#include "cleave/geometry/read_ahead.h"
#include "cleave/geometry/side_lanes.h"
#include "cleave/geometry/whole_blocks.h"

namespace cleave::geometry {

void capPlaneBasis(const glm::dvec3& unitNormal, glm::dvec3& u, glm::dvec3& v) {
  const glm::dvec3 an = glm::abs(unitNormal);
  int axis = 0;
  if (an.y < an[axis]) axis = 1;
  if (an.z < an[axis]) axis = 2;
  glm::dvec3 e(0.0);
  e[axis] = 1.0;
  u = glm::normalize(glm::cross(unitNormal, e));
  v = glm::cross(unitNormal, u);
}

const char* toString(SplitStatus status) {
  switch (status) {
    case SplitStatus::Ok: return "Ok";
    case SplitStatus::PlaneMissesMesh: return "PlaneMissesMesh";
    case SplitStatus::InvalidInput: return "InvalidInput";
    case SplitStatus::OpenSection: return "OpenSection";
    case SplitStatus::TriangulationFailed: return "TriangulationFailed";
  }
  return "Unknown";
}

namespace {

constexpr uint32_t kNone = 0xffffffffu;
constexpr uint32_t kReachedBit = 0x80000000u;  // SideTriangle::source of a triangle the plane reached
constexpr uint32_t kCapBit = 0x40000000u;      // SideTriangle::source of a cap triangle: | its loop
constexpr uint32_t kSourceMask = kCapBit - 1;   // the source triangle (or loop) of SideTriangle::source
// SplitOptions::threads: below this many side triangles a second thread costs more than it saves.
constexpr size_t kParallelTriangles = 50000;
// From detail::kFarCount position ids on (read_ahead.h), the classification asks for the positions
// of the representatives kIdsAhead ids early (CutPositions::prefetch).
constexpr uint32_t kIdsAhead = 64;
constexpr double kPi = 3.14159265358979323846;

uint64_t pairKey(uint32_t a, uint32_t b) { return (uint64_t(std::min(a, b)) << 32) | std::max(a, b); }
uint64_t directedKey(uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; }
uint32_t keyFrom(uint64_t k) { return static_cast<uint32_t>(k >> 32); }
uint32_t keyTo(uint64_t k) { return static_cast<uint32_t>(k & 0xffffffffu); }

// Skin influences of a point at t along a -> b: joints merged by id, the four largest weights kept
// (ties: lower joint id first), renormalised to sum 1; unused slots are joint 0 with weight 0.
void mergeSkin(const glm::u16vec4& ja, const glm::vec4& wa, const glm::u16vec4& jb, const glm::vec4& wb, double t,
               glm::u16vec4& joints, glm::vec4& weights) {
  uint16_t id[8];
  double w[8];
  int count = 0;
  auto add = [&](uint16_t joint, double weight) {
    if (!(weight > 0.0)) return;
    for (int k = 0; k < count; ++k) {
      if (id[k] == joint) {
        w[k] += weight;
        return;
      }
    }
    id[count] = joint;
    w[count] = weight;
    ++count;
  };
  for (int k = 0; k < 4; ++k) add(ja[k], (1.0 - t) * double(wa[k]));
  for (int k = 0; k < 4; ++k) add(jb[k], t * double(wb[k]));
  for (int i = 1; i < count; ++i) {  // insertion sort: weight descending, joint ascending
    for (int k = i; k > 0 && (w[k] > w[k - 1] || (w[k] == w[k - 1] && id[k] < id[k - 1])); --k) {
      std::swap(w[k], w[k - 1]);
      std::swap(id[k], id[k - 1]);
    }
  }
  count = std::min(count, 4);
  double total = 0.0;
  for (int k = 0; k < count; ++k) total += w[k];
  joints = glm::u16vec4(0);
  weights = glm::vec4(0.f);
  if (!(total > 0.0)) {
    joints = ja;
    weights = wa;
    return;
  }
  for (int k = 0; k < count; ++k) {
    joints[k] = id[k];
    weights[k] = static_cast<float>(w[k] / total);
  }
}

// The joints a piece still uses (a weight above zero), ascending; the others are dropped from it.
// A bit set over the joint ids keeps this linear in the vertex count and free of allocation once
// `used` has grown to its largest size.
void collectUsedJoints(const MeshData& piece, std::vector<uint16_t>& used) {
  used.clear();
  if (piece.joints.empty()) return;
  uint32_t highest = 0;
  for (const glm::u16vec4& j : piece.joints) {
    highest = std::max({highest, uint32_t(j.x), uint32_t(j.y), uint32_t(j.z), uint32_t(j.w)});
  }
  uint64_t bits[1024];  // 65536 joint ids; only the words up to the highest id are used
  std::fill(bits, bits + (highest >> 6) + 1, uint64_t(0));
  for (size_t v = 0; v < piece.joints.size(); ++v) {
    for (int k = 0; k < 4; ++k) {
      if (!(piece.weights[v][k] > 0.f)) continue;
      const uint32_t j = piece.joints[v][k];
      bits[j >> 6] |= uint64_t(1) << (j & 63);
    }
  }
  for (uint32_t word = 0; word <= (highest >> 6); ++word) {
    for (uint64_t b = bits[word]; b != 0; b &= b - 1) {
      used.push_back(static_cast<uint16_t>(word * 64 + static_cast<uint32_t>(std::countr_zero(b))));
    }
  }
}

glm::vec3 normalizedOr(const glm::dvec3& v, const glm::vec3& fallback) {
  const double len = glm::length(v);
  return len > 0.0 && std::isfinite(len) ? glm::vec3(v / len) : fallback;
}

// The values f(0), f(1), ... as an iterator with random-access moves (its reference is a value, as
// for a proxy), so that a vector is assigned them in one pass (resize-then-write would first fill
// it with zeros).
template <typename F>
class MappedIterator {
 public:
  using iterator_category = std::random_access_iterator_tag;
  using value_type = std::invoke_result_t<const F&, size_t>;
  using difference_type = std::ptrdiff_t;
  using pointer = void;
  using reference = value_type;
  MappedIterator(const F* f, size_t i) : f_(f), i_(i) {}
  value_type operator*() const { return (*f_)(i_); }
  value_type operator[](difference_type d) const { return (*f_)(i_ + static_cast<size_t>(d)); }
  MappedIterator& operator++() { ++i_; return *this; }
  MappedIterator operator++(int) { MappedIterator old = *this; ++i_; return old; }
  MappedIterator& operator--() { --i_; return *this; }
  MappedIterator operator--(int) { MappedIterator old = *this; --i_; return old; }
  MappedIterator& operator+=(difference_type d) { i_ += static_cast<size_t>(d); return *this; }
  MappedIterator& operator-=(difference_type d) { i_ -= static_cast<size_t>(d); return *this; }
  MappedIterator operator+(difference_type d) const { return {f_, i_ + static_cast<size_t>(d)}; }
  MappedIterator operator-(difference_type d) const { return {f_, i_ - static_cast<size_t>(d)}; }
  friend MappedIterator operator+(difference_type d, const MappedIterator& it) { return it + d; }
  difference_type operator-(const MappedIterator& o) const { return static_cast<difference_type>(i_ - o.i_); }
  bool operator==(const MappedIterator& o) const { return i_ == o.i_; }
  auto operator<=>(const MappedIterator& o) const { return i_ <=> o.i_; }

 private:
  const F* f_;
  size_t i_;
};

// out = {f(0), ..., f(count - 1)}, written once (the capacity is kept when it suffices).
template <typename T, typename F>
void assignMapped(std::vector<T>& out, size_t count, const F& f) {
  out.assign(MappedIterator<F>(&f, 0), MappedIterator<F>(&f, count));
}

// The index of the first of `sorted` not less than `key`, as std::lower_bound, with a conditional
// move in place of its branch: the comparisons of the cut's edge lookups follow no pattern, so the
// branch was mispredicted about every other step.
size_t lowerBound(const std::vector<uint64_t>& sorted, uint64_t key) {
  if (sorted.empty()) return 0;
  const uint64_t* base = sorted.data();
  size_t n = sorted.size();
  while (n > 1) {
    const size_t half = n / 2;
    base = base[half] < key ? base + half : base;
    n -= half;
  }
  return static_cast<size_t>(base - sorted.data()) + (*base < key ? 1 : 0);
}

// 16 bytes: every pass over a side reads them (the output run slot is worked out from `source`:
// Splitter::slotOf).
struct SideTriangle {
  uint32_t v[3];    // vertex references (see Splitter::kinds), cut-space outward winding
  uint32_t source;  // source triangle | kReachedBit when the plane reached it; a cap: kReachedBit | kCapBit | loop
};
static_assert(sizeof(SideTriangle) == 16);
constexpr uint32_t kDroppedSource = kNone;  // SideTriangle::source of a triangle about to be erased

// A side's triangles: filled by up to two threads with nothing to copy after (OffsetList), grown by
// places that are filled before they are read (a crossing triangle's parts).
using SideList = detail::OffsetList<SideTriangle>;

struct LoopInfo {
  uint32_t begin = 0, end = 0;  // into loopIds_ / points_
  double twiceArea = 0.0;
  glm::dvec2 lo{0.0}, hi{0.0};
  uint32_t outer = kNone;  // for a hole: its border loop
  bool capped = false;
};

class Splitter final : public IMeshSplitter {
 public:
  explicit Splitter(bool convexFastPath) : convexFastPath_(convexFastPath) {}
  Splitter(const Splitter&) = delete;  // planeTris_ and friends point into the splitter itself
  Splitter& operator=(const Splitter&) = delete;

  SplitStatus split(const MeshContainer& container, const Plane& plane, const SplitOptions& options,
                    SplitResult& result) override;

 private:
  SplitStatus fail(SplitResult& result, SplitStatus status, const std::string& message);
  void preparePieces(SplitResult& result, size_t count);

  // Vertex references: [0, sourceCount_) source vertices, then one new vertex per crossing source
  // vertex pair, then cap vertices (below, then above). extra_ holds everything past the source.
  uint32_t weldedOf(uint32_t ref) const;
  bool onPlane(uint32_t ref) const;
  glm::dvec3 cutOf(uint32_t ref) const;
  glm::dvec3 sectionCut(uint32_t welded) const;
  uint32_t pairVertex(uint32_t a, uint32_t b) const;
  glm::dvec2 project(const glm::dvec3& p) const { return {glm::dot(p - origin_, u_), glm::dot(p - origin_, v_)}; }

  SplitStatus begin(const MeshContainer& container, const Plane& plane, const SplitOptions& options,
                    SplitResult& result);
  void cutEdges();
  void makeCutVertices();
  void assignSlots(const SplitOptions& options);
  SplitStatus traceSection(const SplitOptions& options, SplitResult& result);
  void chooseBasis();
  SplitStatus capAll(const SplitOptions& options, SplitResult& result);
  void classify(double tolerance);
  struct CutOutput;
  void cutCrossing(uint32_t t, const uint32_t (&g)[3], const int (&s)[3], uint32_t (&next)[2]);
  [[gnu::always_inline]] bool wholeSide(const uint32_t (&g)[3], const int (&s)[3], int& index, bool& planar) const;
  [[gnu::noinline]] int inPlaneSide(const uint32_t (&g)[3]) const;
  void cutWholeAndCollect(bool unite);
  template <bool kBackwards>
  void collectRange(uint32_t begin, uint32_t end, bool unite, SideTriangle* const (&lists)[2], CutOutput& out);
  void cutVertices(const SplitOptions& options);
  void joinChunks(uint32_t chunks);
  void cutPending();
  // How many chunks (threads) a pass over `count` items uses: threads_ for big passes, else 1.
  uint32_t chunkCount(size_t count) const {
    return threads_ > 1 && count >= kParallelTriangles ? std::min<uint32_t>(threads_, 8) : 1;
  }
  // Runs job(chunk, begin, end) over [0, count) cut into `chunks` equal ranges: chunk 0 on the
  // calling thread, the others on the splitter's parked threads (all here if none can be started).
  template <class Job>
  void inChunks(uint32_t chunks, uint32_t count, Job&& job) {
    auto range = [&](uint32_t c) { return uint32_t(uint64_t(count) * c / chunks); };
    passThreads_.run(chunks, [&](uint32_t c) { job(c, range(c), range(c + 1)); });
  }
  void collectBoundary(int side, std::vector<uint64_t>& boundary);
  void buildLoops();
  void measureLoops();
  void sortSegmentEnds();
  bool startsChain(uint64_t segment) const {
    return !std::binary_search(segmentEnds_.begin(), segmentEnds_.end(), keyFrom(segment));
  }
  void walkChains();
  void bridgeChains();
  bool chordClear(uint32_t begin, uint32_t end, bool alone);
  void mergeNearPoints();
  uint32_t nextSegment(uint32_t at, uint32_t incoming) const;
  bool capSection(const SplitOptions& options, std::string& why);
  bool tryConvexCap();
  void makeCapVertices(const SplitOptions& options);
  uint32_t capUvGroup(const SplitOptions& options, uint32_t loopIndex) const;
  glm::dvec2 capPlanar(uint32_t k) const;
  void capUvBounds(const SplitOptions& options);
  glm::dvec2 capUv(const SplitOptions& options, uint32_t k, uint32_t g) const;
  glm::dmat3 capLinear(bool fromExtra, uint32_t donor) const;
  // The linear part of a cap vertex's cut-space transform and its inverse (the cap's normal and
  // tangent taken back to the source's space): the same on both sides of the cap.
  struct CapFrame {
    glm::dmat3 linear{1.0}, inverse{1.0};
  };
  void writeCapVertex(const SplitOptions& options, uint32_t k, int s, size_t at, const glm::dvec2& uv,
                      const CapFrame& frame);
  void linkWelded(uint32_t a, uint32_t b);
  glm::vec3 outputPosition(uint32_t ref) const {
    return ref < sourceCount_ ? mesh_->positions[ref] : extra_.positions[ref - sourceCount_];
  }
  void dropCollapsedTriangles();
  void flipFlatCapTriangles();
  void pushCapTriangles();
  bool flatCapTriangle(size_t t) const;
  bool flipCapTriangle(uint32_t t);
  uint32_t weldedOfAny(uint32_t ref) const;
  // The cut-space position of any vertex reference: source vertices inline, the rest by a call.
  glm::dvec3 cutOfAny(uint32_t ref) const { return ref < sourceCount_ ? cut_[ref] : cutOfAdded(ref); }
  glm::dvec3 cutOfAdded(uint32_t ref) const;
  // The signed distance of position id `id` from the plane (classify's sides come from it).
  double distanceOf(uint32_t id) const { return glm::dot(normal_, cut_[reps_[id]]) - offset_; }
  uint32_t weldedRef(uint32_t ref) const {  // writePieces: the welded id of a vertex reference
    return ref < sourceCount_ ? ids_[ref] : extraWelded_[ref - sourceCount_];
  }

  // Scratch of one side's islands and pieces: each side has its own, so the two can be written at
  // once (SplitOptions::threads).
  // (Aligned to cache lines so that one side's writes never share a line with the other's.)
  struct alignas(64) SideWork {
    std::vector<uint32_t> parent, label, pieceOf, pieceMap, order, bucket, pieceSize;
    detail::OffsetList<SideTriangle> ordered;  // orderSide: the side's triangles in output order (unless identity)
    std::vector<uint32_t> partsOf;  // per piece: the islands it is made of (0: not known)
    uint32_t islands = 0;           // labelSide: the islands found (0 when not searched)
    bool searched = false;          // labelSide searched for islands
    bool oneIsland = false;         // searched, and one island: no labels (w.label, w.pieceOf)
    bool joinAfterWrite = false;    // touching parts are joined once the pieces are written
    detail::OffsetList<uint32_t> vertexRefs;  // the piece being written: its vertices' references, in order
    size_t vertexCount = 0;          // how many of vertexRefs
    bool identity = false;  // orderSide: the output order is the side list's (ordered is not filled)
    // Per vertex reference: its index in the piece being written, or kNone (every entry, between
    // pieces: gatherVertices sets back those writeTriangles set).
    std::vector<uint32_t> localOf;
    std::vector<uint32_t> weldRemap;   // per welded id: its position id in the piece, or kNone (all, between pieces)
    detail::OffsetList<uint32_t> weldedOfId;  // pieceWeld: per position id of the piece, its welded id
    detail::OffsetList<glm::dvec3> pieceCut;  // cut-space positions of the piece being written (vertexCount)
    glm::dvec3 pieceLo{INFINITY}, pieceHi{-INFINITY};  // and their bounds
    std::vector<uint32_t> flipped;
    std::vector<double> volume;
    std::vector<double> solidAngle;  // mergeCavities: per piece, seen from one cavity
    std::vector<uint32_t> firstTriangle, groupNumber;
    std::vector<glm::dvec3> contactCorners;  // joinTouching: 3 cut-space corners per side triangle
    std::vector<uint32_t> contactRoot;
    std::vector<uint8_t> contactReached;
    std::vector<glm::dvec3> contactLo, contactHi;  // joinTouching: bounds per piece, then per group
    ContactScratch contactScratch;
  };
  static uint32_t find(SideWork& w, uint32_t x);
  static void uniteCorners(SideWork& w, uint32_t a, uint32_t b, uint32_t c);
  static void unite(uint32_t* parent, uint32_t x, uint32_t y);
  uint32_t labelSide(int side, SideWork& w, const SplitOptions& options, bool noCavities, bool knownOne);
  bool loopsBoundIslands() const;
  void assignLoops(int side, SideWork& w, uint32_t pieces);
  uint32_t writeAndJoin(int side, uint32_t pieces, uint32_t firstPiece, bool weldKnown, const SplitOptions& options,
                        SplitResult& result);
  bool everyJoinOnALoop();
  bool sectionSettlesIslands();
  bool sectionRulesOutCavities(const SplitOptions& options) const;
  void uniteSide(int side, SideWork& w, uint32_t weldedCount);
  void islandStats(int side, SideWork& w, uint32_t pieces, bool volumes, bool bounds) const;
  uint32_t mergeCavities(int side, SideWork& w, uint32_t pieces) const;
  uint32_t joinTouching(int side, SideWork& w, uint32_t pieces, const SplitOptions& options) const;
  static uint32_t regroup(SideWork& w, std::span<const uint32_t> root, uint32_t pieces);
  void writePieces(const SplitOptions& options, SplitResult& result);
  void orderSide(int side, SideWork& w, uint32_t pieces) const;
  void writeSide(int side, SideWork& w, uint32_t pieces, uint32_t firstPiece, bool weldKnown,
                 const SplitOptions& options, SplitResult& result);
  static void beginPiece(SideWork& w, int side, SplitPiece& out);
  size_t writeTriangles(int side, SideWork& w, size_t k, uint32_t p, const SplitOptions& options, SplitPiece& out);
  void gatherVertices(SideWork& w, MeshData& m) const;
  void gatherPositions(SideWork& w, std::vector<glm::vec3>& positions) const;
  void pieceWeld(SideWork& w, MeshWeld& weld, bool closed) const;
  void pieceMass(SideWork& w, SplitPiece& out) const;
  // Runs job(0) and job(1): at once when `parallel` (job(1) on the calling thread, job(0) on a
  // parked thread, or after job(1) if none can be started), else one after the other.
  template <class Job>
  void bothSides(bool parallel, Job&& job) {
    if (parallel) {
      passThreads_.run(2, [&](uint32_t i) { job(1 - static_cast<int>(i)); });
    } else {
      job(0);
      job(1);
    }
  }
  // The output run slot of a side triangle: the cap slot for a cap, else its source triangle's run.
  uint32_t slotOf(const SideTriangle& tri) const {
    if (tri.source & kCapBit) return capSlot_;
    if (runFirst_.size() <= 1) return 0;
    const uint32_t t = tri.source & kSourceMask;
    return static_cast<uint32_t>(std::upper_bound(runFirst_.begin(), runFirst_.end(), t) - runFirst_.begin()) - 1;
  }
  uint32_t aliasRoot(uint32_t welded) const {
    while (welded >= idCount_ && welded - idCount_ < alias_.size() && alias_[welded - idCount_] != welded)
      welded = alias_[welded - idCount_];
    return welded;
  }

  bool convexFastPath_;
  CapTriangulator triangulator_;

  // Per call.
  const MeshContainer* container_ = nullptr;
  const MeshData* mesh_ = nullptr;
  CutPositions cut_;  // the source floats or the container's doubles (cut_positions.h)
  std::span<const uint32_t> ids_;
  std::span<const uint32_t> reps_;
  uint32_t idCount_ = 0;
  uint32_t sourceCount_ = 0;
  bool mirrored_ = false;
  glm::dvec3 normal_{0.0};
  double offset_ = 0.0;
  glm::dvec3 u_{0.0}, v_{0.0}, origin_{0.0};
  double capTolerance_ = 0.0;
  double mergeTolerance_ = 0.0;
  double onPlaneTolerance_ = 0.0;
  double diagonal_ = 0.0;  // the container's cut-space bounds diagonal

  std::vector<int8_t> side_;       // per position id: +1, -1, 0; then detail::kSidePadding bytes
  bool laneSides_ = false;  // classify takes ids four at a time (side_lanes.h)
  bool wholeBlocks_ = false;  // cutWholeAndCollect takes whole triangles eight at a time (whole_blocks.h)
  std::vector<int8_t> vertexSide_;  // wholeBlocks_: per source vertex its id's side; padded as side_
  struct Pending {  // cutWholeAndCollect: a crossing triangle and where its parts go
    uint32_t triangle;
    uint32_t first[2];
  };
  // Steps 2 and 3's output per chunk of source triangles, beside the side triangles it writes into
  // the side lists' storage; chunk 0's lists are the split's (below). Aligned to cache lines: chunks
  // write their own lists' ends, and a line shared with another chunk's lists or with what the
  // passes read (side_, ids_) goes back and forth.
  struct alignas(64) CutOutput {
    std::vector<uint32_t> planeTris[2];  // per side: the triangles that may have an on-plane edge
    std::vector<uint64_t> crossing, crossingPairs;  // step 2's crossing edges (by id, by vertex)
    std::vector<Pending> pending;                   // the crossing triangles, in source order
    size_t first[2] = {0, 0}, end[2] = {0, 0};      // per side: the storage range it wrote
  };
  CutOutput cutMain_;
  std::vector<CutOutput> cutChunks_;  // chunks 1, 2, ... (cutChunks_[c - 1])
  SideList sideTris_[2];              // [0] above, [1] below
  std::vector<uint32_t>* const planeTris_ = cutMain_.planeTris;
  std::vector<Pending>& pending_ = cutMain_.pending;
  alignas(64) std::vector<uint32_t> cutTris_[2];  // per side: the triangles made by cutting one (not whole ones)
  std::vector<uint64_t>& weldedEdges_ = cutMain_.crossing;  // sorted unique (cutVertices) crossing edges by position id pair
  std::vector<double> edgeT_;          // per welded edge: parameter from its lower id
  std::vector<glm::dvec3> edgeCut_;    // per welded edge: cut-space point
  std::vector<glm::vec3> edgeSource_;  // per welded edge: source-space point
  std::vector<uint32_t> edgeFirstPair_;  // per welded edge: first source pair (attribute donor for caps)
  std::vector<uint64_t>& pairs_ = cutMain_.crossingPairs;  // the same by source vertex pair
  std::vector<uint32_t> pairEdge_;     // per pair: welded edge
  MeshData extra_;                     // attributes of new and cap vertices
  uint32_t capBase_ = 0;               // first cap vertex reference
  bool united_ = false;        // cutWholeAndCollect united the whole triangles' islands
  // One island per side without a search (see sectionSettlesIslands): islandCandidate_ after the
  // classification (a closed mesh of one part), cutsOnLoops_ after the
  // loops are traced, oneIslandEach_ once the caps are made.
  bool islandCandidate_ = false, cutsOnLoops_ = false, oneIslandEach_ = false;
  bool sidesAgree_ = false;           // traceSection: both sides have the same on-plane boundary
  std::vector<uint8_t> cutOnLoop_;    // per welded cut edge: its point is on a loop
  std::vector<uint32_t> onPlaneIds_;  // islandCandidate_: the position ids on the plane, ascending
  std::vector<uint32_t> loopSourceIds_;  // everyJoinOnALoop: the position ids on loops, sorted
  std::vector<uint32_t> loopOfPoint_, loopParent_;  // sectionSettlesIslands: loops joined by caps
  bool dropped_[2] = {false, false};  // dropCollapsedTriangles removed triangles of that side
  size_t capStart_[2] = {0, 0};            // per side: the first cap triangle
  std::vector<uint64_t> boundary_[2];
  std::vector<uint64_t> segments_;     // section segments, sorted, counter-clockwise seen from +normal
  std::vector<uint64_t> reversed_;
  std::vector<uint8_t> segmentUsed_;
  std::vector<uint32_t> segmentEnds_;  // sortSegmentEnds: where the section's segments end, sorted
  std::vector<uint32_t> loopIds_;      // welded ids of the loop vertices, loop after loop
  std::vector<uint32_t> mergedIds_;    // loopIds_ after merging near-coincident points
  std::vector<glm::dvec2> points_;     // their projection on the plane
  std::vector<LoopInfo> loops_;
  std::vector<CapRing> rings_;
  std::vector<uint32_t> capTriangles_;  // into loopIds_, counter-clockwise seen from +normal
  std::vector<uint32_t> capLoopOf_;     // per cap triangle: the outer loop of its cap
  std::vector<std::pair<double, uint32_t>> angular_;
  std::vector<uint32_t> flatCaps_;                     // cap triangles flat on their float positions
  uint32_t openChains_ = 0;
  bool bridge_ = false;          // OpenSectionMode::Bridge
  double bridgeGap_ = 0.0;       // in cut space
  uint32_t bridgedChains_ = 0;
  std::vector<uint32_t> chainIds_;                      // Bridge: welded ids of the open chains
  std::vector<std::pair<uint32_t, uint32_t>> chains_;   // [begin, end) into chainIds_
  std::vector<glm::dvec2> chainPoints_, otherPoints_;   // Bridge: a chain and a loop on the plane
  bool piecesClosed_ = false;  // this split's pieces are closed on their weld ids
  uint32_t uncappedLoops_ = 0;  // closed loops of open art left open (they could not be capped)
  uint32_t closedLoops_ = 0;
  uint32_t slotCount_ = 0;  // output runs of the input
  uint32_t capSlot_ = 0;
  std::vector<uint32_t> runFirst_;  // per input run: its first triangle (runs follow one another)
  std::vector<uint32_t> alias_;       // per welded cut edge: the welded id it was merged into
  std::vector<uint32_t> extraWelded_;  // per vertex reference past the source: its welded id
  std::vector<uint32_t> loopPiece_;
  std::vector<glm::dvec3> capBounds_;  // makeCapVertices: per cap group, [2 g] = lo, [2 g + 1] = hi
  SideWork work_[2];
  uint32_t threads_ = 1;  // SplitOptions::threads of the call
  detail::PassThreads passThreads_;  // runs the passes' chunks when threads_ > 1
  std::vector<SplitPiece> spare_;
};

SplitStatus Splitter::fail(SplitResult& result, SplitStatus status, const std::string& message) {
  preparePieces(result, 0);
  result.status = status;
  result.message = message;
  return status;
}

// Resizes the piece list keeping the buffers of pieces that are not needed now for later calls.
void Splitter::preparePieces(SplitResult& result, size_t count) {
  while (result.pieces.size() > count) {
    spare_.push_back(std::move(result.pieces.back()));
    result.pieces.pop_back();
  }
  while (result.pieces.size() < count) {
    if (!spare_.empty()) {
      result.pieces.push_back(std::move(spare_.back()));
      spare_.pop_back();
    } else {
      result.pieces.emplace_back();
    }
  }
}

uint32_t Splitter::weldedOf(uint32_t ref) const {
  if (ref < sourceCount_) return ids_[ref];
  const uint32_t k = ref - sourceCount_;
  if (k < pairs_.size()) return idCount_ + pairEdge_[k];
  return kNone;  // cap vertices are mapped by the caller
}

bool Splitter::onPlane(uint32_t ref) const { return ref >= sourceCount_ || side_[ids_[ref]] == 0; }

glm::dvec3 Splitter::cutOf(uint32_t ref) const {
  if (ref < sourceCount_) return cut_[ref];
  return edgeCut_[pairEdge_[ref - sourceCount_]];
}

glm::dvec3 Splitter::sectionCut(uint32_t welded) const {
  return welded < idCount_ ? cut_[reps_[welded]] : edgeCut_[welded - idCount_];
}

uint32_t Splitter::pairVertex(uint32_t a, uint32_t b) const {
  return sourceCount_ + static_cast<uint32_t>(lowerBound(pairs_, pairKey(a, b)));
}

// A split in stages: bind the container and check the call; classify and find the crossing edges;
// the cut points and the new vertices; cut the triangles; trace the section; cap it; write the
// pieces. Each stage that can refuse the split returns its status (result has the message).
SplitStatus Splitter::split(const MeshContainer& container, const Plane& plane, const SplitOptions& options,
                            SplitResult& result) {
  // The passes of one split follow each other closely (the longest stretch between two, the section
  // and caps of the 1M-triangle sphere, takes about a millisecond): the pass threads spin between
  // them rather than sleep (a wake costs tens of microseconds or more), and sleep once it returns.
  const detail::PassThreads::Hold hold(passThreads_);
  const SplitStatus checked = begin(container, plane, options, result);
  if (checked != SplitStatus::Ok) return checked;
  // 1, 2. Classification per position id, then the crossing edges.
  classify(onPlaneTolerance_);
  // A closed mesh known to be one part: its section may settle the islands (sectionSettlesIslands),
  // so the whole triangles are not united on the way. The ids on the plane are kept for the check.
  islandCandidate_ = options.separateIslands && container.closed() && container.connected();
  onPlaneIds_.clear();
  if (islandCandidate_) {  // memchr: a vector search over the bytes, where std::find goes one by one
    const int8_t* sides = side_.data();
    for (size_t from = 0; from < idCount_;) {
      const void* hit = std::memchr(sides + from, 0, idCount_ - from);
      if (hit == nullptr) break;
      const size_t at = static_cast<size_t>(static_cast<const int8_t*>(hit) - sides);
      onPlaneIds_.push_back(static_cast<uint32_t>(at));
      from = at + 1;
    }
  }
  // Steps 2 and 3 share a pass over the source: the crossing triangles are cut once their edges are
  // known.
  cutWholeAndCollect(options.separateIslands && !islandCandidate_);
  cutVertices(options);
  // 3. Cut the crossing triangles.
  cutPending();
  if (sideTris_[0].empty() || sideTris_[1].empty()) {
    return fail(result, SplitStatus::PlaneMissesMesh,
                "the plane does not cross the mesh: every vertex lies on one side or within the tolerance of it");
  }
  // 4. Section: boundaries of both sides, compared, then chained.
  const SplitStatus traced = traceSection(options, result);
  if (traced != SplitStatus::Ok) return traced;
  // 5. Caps.
  capStart_[0] = sideTris_[0].size();
  capStart_[1] = sideTris_[1].size();
  const SplitStatus capped = capAll(options, result);
  if (capped != SplitStatus::Ok) return capped;
  // 6, 7. Islands, piece meshes, mass.
  dropCollapsedTriangles();
  if (sideTris_[0].empty() || sideTris_[1].empty()) {
    return fail(result, SplitStatus::PlaneMissesMesh,
                "the plane cuts off nothing that float positions can hold: every triangle on one side collapses "
                "to zero area");
  }
  writePieces(options, result);
  return SplitStatus::Ok;
}

// Resets the result, binds the container and checks the call: a set-up container, a finite plane
// with a non-zero normal, finite options and cut space. Sets the unit normal, offset and tolerance.
SplitStatus Splitter::begin(const MeshContainer& container, const Plane& plane, const SplitOptions& options,
                            SplitResult& result) {
  result.status = SplitStatus::Ok;
  result.message.clear();
  result.sectionLoops = 0;
  result.openChains = 0;
  result.bridgedChains = 0;
  result.uncappedLoops = 0;
  result.sidesDisagree = false;
  result.islandsFromSection = false;
  result.islandFromLoops = false;
  container_ = &container;
  threads_ = options.threads;
  mesh_ = &container.mesh();
  const MeshData& mesh = *mesh_;
  cut_ = container.cutPositions();
  ids_ = container.positionIds();
  reps_ = container.positionRepresentatives();
  idCount_ = container.positionIdCount();
  sourceCount_ = static_cast<uint32_t>(mesh.positions.size());
  mirrored_ = container.mirrored();
  wholeBlocks_ = detail::wholeBlocksRun(sourceCount_, idCount_);
  laneSides_ = detail::runsAvx2() && sourceCount_ < (uint32_t(1) << 29);
  if (mesh.indices.empty() || mesh.positions.empty() || cut_.size() != mesh.positions.size() ||
      ids_.size() != mesh.positions.size()) {
    return fail(result, SplitStatus::InvalidInput, "the container holds no valid mesh (setMesh failed or was not called)");
  }
  const double length = glm::length(plane.normal);
  if (!(length > 0.0) || !std::isfinite(length) || !std::isfinite(plane.offset)) {
    return fail(result, SplitStatus::InvalidInput, "the plane normal is zero or not finite, or the offset is not finite");
  }
  if (!(options.relativeTolerance >= 0.0) || !std::isfinite(options.relativeTolerance) ||
      !std::isfinite(options.uvPerMetre)) {
    return fail(result, SplitStatus::InvalidInput, "relativeTolerance must be finite and >= 0, uvPerMetre finite");
  }
  diagonal_ = container.boundsDiagonal();
  if (!std::isfinite(diagonal_)) {
    return fail(result, SplitStatus::InvalidInput, "cut-space positions are not finite (check the transform or pose)");
  }
  normal_ = plane.normal / length;
  offset_ = plane.offset / length;
  onPlaneTolerance_ = options.relativeTolerance * diagonal_;
  return SplitStatus::Ok;
}

// Per welded crossing edge: where the plane crosses it (t from its lower id), in cut space and in
// the source's space.
void Splitter::cutEdges() {
  const MeshData& mesh = *mesh_;
  const size_t edgeCount = weldedEdges_.size();
  edgeT_.resize(edgeCount);
  edgeCut_.resize(edgeCount);
  edgeSource_.resize(edgeCount);
  edgeFirstPair_.assign(edgeCount, kNone);
  for (size_t e = 0; e < edgeCount; ++e) {
    const uint32_t lo = keyFrom(weldedEdges_[e]), hi = keyTo(weldedEdges_[e]);
    const double dLo = distanceOf(lo), dHi = distanceOf(hi);
    const double t = dLo / (dLo - dHi);
    edgeT_[e] = t;
    const uint32_t a = reps_[lo], b = reps_[hi];
    edgeCut_[e] = cut_[a] + t * (cut_[b] - cut_[a]);
    const glm::dvec3 pa(mesh.positions[a]), pb(mesh.positions[b]);
    edgeSource_[e] = glm::vec3(pa + t * (pb - pa));
  }
}

// New vertices, one per source pair, with every attribute interpolated at the welded edge's t.
void Splitter::makeCutVertices() {
  const MeshData& mesh = *mesh_;
  const size_t pairCount = pairs_.size();
  pairEdge_.resize(pairCount);
  extra_.positions.clear();
  extra_.normals.clear();
  extra_.tangents.clear();
  extra_.uv0.clear();
  extra_.uv1.clear();
  extra_.colors.clear();
  extra_.joints.clear();
  extra_.weights.clear();
  for (size_t k = 0; k < pairCount; ++k) {
    uint32_t a = keyFrom(pairs_[k]), b = keyTo(pairs_[k]);
    const uint64_t welded = pairKey(ids_[a], ids_[b]);
    const uint32_t e = static_cast<uint32_t>(lowerBound(weldedEdges_, welded));
    pairEdge_[k] = e;
    if (edgeFirstPair_[e] == kNone) edgeFirstPair_[e] = static_cast<uint32_t>(k);
    if (ids_[a] != keyFrom(welded)) std::swap(a, b);  // a: the end with the lower id, where t = 0
    const double t = edgeT_[e];
    const float tf = static_cast<float>(t);
    extra_.positions.push_back(edgeSource_[e]);
    if (!mesh.normals.empty()) {
      const glm::dvec3 n = glm::mix(glm::dvec3(mesh.normals[a]), glm::dvec3(mesh.normals[b]), t);
      extra_.normals.push_back(normalizedOr(n, mesh.normals[t < 0.5 ? a : b]));
    }
    if (!mesh.tangents.empty()) {
      const glm::vec4 ta = mesh.tangents[a], tb = mesh.tangents[b];
      const glm::dvec3 d = glm::mix(glm::dvec3(ta), glm::dvec3(tb), t);
      const glm::vec4& nearest = t < 0.5 ? ta : tb;
      extra_.tangents.push_back(glm::vec4(normalizedOr(d, glm::vec3(nearest)), nearest.w));
    }
    if (!mesh.uv0.empty()) extra_.uv0.push_back(glm::mix(mesh.uv0[a], mesh.uv0[b], tf));
    if (!mesh.uv1.empty()) extra_.uv1.push_back(glm::mix(mesh.uv1[a], mesh.uv1[b], tf));
    if (!mesh.colors.empty()) extra_.colors.push_back(glm::mix(mesh.colors[a], mesh.colors[b], tf));
    if (!mesh.joints.empty()) {
      glm::u16vec4 j;
      glm::vec4 w;
      mergeSkin(mesh.joints[a], mesh.weights[a], mesh.joints[b], mesh.weights[b], t, j, w);
      extra_.joints.push_back(j);
      extra_.weights.push_back(w);
    }
  }
  capBase_ = sourceCount_ + static_cast<uint32_t>(pairCount);
}

// Output run slots: the input runs in order, then the cap run unless an input run has its material.
void Splitter::assignSlots(const SplitOptions& options) {
  const MeshData& mesh = *mesh_;
  slotCount_ = mesh.submeshes.empty() ? 1u : static_cast<uint32_t>(mesh.submeshes.size());
  runFirst_.clear();
  for (const SubMesh& run : mesh.submeshes) runFirst_.push_back(run.firstIndex / 3);
  capSlot_ = slotCount_;
  for (uint32_t r = 0; r < slotCount_; ++r) {
    const uint32_t material = mesh.submeshes.empty() ? 0u : mesh.submeshes[r].materialId;
    if (material == options.capMaterialId) {
      capSlot_ = r;
      break;
    }
  }
}

// Step 4: the on-plane boundaries of both sides, compared (they differ on art that is not watertight
// where it is cut), the projection basis, then the loops and chains of the section.
SplitStatus Splitter::traceSection(const SplitOptions& options, SplitResult& result) {
  collectBoundary(1, boundary_[1]);
  collectBoundary(0, boundary_[0]);
  segments_.clear();
  for (uint64_t k : boundary_[1]) segments_.push_back(directedKey(keyTo(k), keyFrom(k)));
  std::sort(segments_.begin(), segments_.end());
  const bool sidesAgree = segments_ == boundary_[0];
  const bool refuseOpen = options.openSections == OpenSectionMode::Refuse;
  if (options.cap && !sidesAgree && refuseOpen) {
    return fail(result, SplitStatus::OpenSection,
                "the section differs between the two sides of the plane: the mesh is non-manifold or "
                "self-intersecting where it is cut");
  }
  result.sidesDisagree = !sidesAgree;
  sidesAgree_ = sidesAgree;
  chooseBasis();
  bridge_ = options.cap && options.openSections == OpenSectionMode::Bridge;
  bridgeGap_ = std::max(options.bridgeGap, 0.0) * diagonal_;
  buildLoops();
  result.sectionLoops = closedLoops_;
  result.openChains = options.cap ? openChains_ : 0;
  result.bridgedChains = bridgedChains_;
  // Pieces are closed on their ids only when the source is and every section loop closes.
  piecesClosed_ = options.cap && container_->closed() && openChains_ + bridgedChains_ == 0 && sidesAgree;
  if (options.cap && openChains_ > 0 && refuseOpen) {
    return fail(result, SplitStatus::OpenSection,
                "the section has " + std::to_string(openChains_) +
                    " open chain(s): the mesh is open or non-manifold where it is cut");
  }
  return SplitStatus::Ok;
}

// The projection basis depends on the normal only, so world-planar cap UVs line up across cuts.
void Splitter::chooseBasis() {
  capPlaneBasis(normal_, u_, v_);
  origin_ = segments_.empty() ? glm::dvec3(0.0) : sectionCut(keyFrom(segments_.front()));
}

// Step 5: the caps of the section's loops (with options.cap), their vertices and triangles.
SplitStatus Splitter::capAll(const SplitOptions& options, SplitResult& result) {
  capTriangles_.clear();
  for (LoopInfo& loop : loops_) loop.capped = false;
  if (!options.cap) return SplitStatus::Ok;
  std::string why;
  if (!capSection(options, why)) return fail(result, SplitStatus::TriangulationFailed, why);
  result.uncappedLoops = uncappedLoops_;
  makeCapVertices(options);
  flipFlatCapTriangles();
  pushCapTriangles();
  return SplitStatus::Ok;
}

// The parts of crossing triangle t (corners g in cut-space winding, corner sides s),
// written to the side lists at next[0] (above) and next[1] (below), which advance; out's plane and
// cut lists get their indices.
void Splitter::cutCrossing(uint32_t t, const uint32_t (&g)[3], const int (&s)[3], uint32_t (&next)[2]) {
  auto pushCut = [&](bool planar, int side, uint32_t a, uint32_t b, uint32_t c) {
    const int index = side > 0 ? 0 : 1;
    cutTris_[index].push_back(next[index]);
    if (planar) planeTris_[index].push_back(next[index]);  // may have an on-plane edge
    sideTris_[index][next[index]++] = {{a, b, c}, t | kReachedBit};
  };
  int zero = -1;
  for (int k = 0; k < 3; ++k) {
    if (s[k] == 0) zero = k;
  }
  if (zero >= 0) {
    // Through the on-plane vertex: two triangles, one per side.
    const uint32_t o = g[zero], x = g[(zero + 1) % 3], y = g[(zero + 2) % 3];
    const uint32_t c = pairVertex(x, y);
    pushCut(true, s[(zero + 1) % 3], o, x, c);
    pushCut(true, s[(zero + 2) % 3], o, c, y);
    return;
  }
  int lone = 0;
  for (int k = 0; k < 3; ++k) {
    if (s[k] != s[(k + 1) % 3] && s[k] != s[(k + 2) % 3]) lone = k;
  }
  const uint32_t l = g[lone], a = g[(lone + 1) % 3], b = g[(lone + 2) % 3];
  const uint32_t ca = pairVertex(l, a), cb = pairVertex(l, b);
  const int loneSide = s[lone], otherSide = -s[lone];
  pushCut(true, loneSide, l, ca, cb);
  const glm::dvec3 d1 = cutOf(ca) - cutOf(b), d2 = cutOf(a) - cutOf(cb);
  if (glm::dot(d1, d1) <= glm::dot(d2, d2)) {
    pushCut(false, otherSide, ca, a, b);
    pushCut(true, otherSide, ca, b, cb);
  } else {
    pushCut(true, otherSide, ca, a, cb);
    pushCut(false, otherSide, a, b, cb);
  }
}

// Where a source triangle that is not cut goes: side index 0 (above) or 1 (below), and whether it
// may have an edge on the plane (two or more on-plane corners). Corners g in cut-space winding.
// False when the plane cuts it.
// (Inlined into every pass over the triangles; the rare face in the plane is a call.)
inline bool Splitter::wholeSide(const uint32_t (&g)[3], const int (&s)[3], int& index, bool& planar) const {
  const bool anyAbove = s[0] > 0 || s[1] > 0 || s[2] > 0;
  const bool anyBelow = s[0] < 0 || s[1] < 0 || s[2] < 0;
  if (anyAbove != anyBelow) {
    index = anyAbove ? 0 : 1;
    planar = (s[0] == 0) + (s[1] == 0) + (s[2] == 0) >= 2;
    return true;
  }
  if (anyAbove) return false;
  index = inPlaneSide(g);
  planar = true;
  return true;
}

// The side of a face in the plane: the solid lies behind it, on the side its normal points away from.
int Splitter::inPlaneSide(const uint32_t (&g)[3]) const {
  const glm::dvec3 p0 = cut_[reps_[ids_[g[0]]]], p1 = cut_[reps_[ids_[g[1]]]], p2 = cut_[reps_[ids_[g[2]]]];
  return glm::dot(glm::cross(p1 - p0, p2 - p0), normal_) > 0.0 ? 1 : 0;
}

// Steps 2 and 3 in one pass over the source, in chunks on threads when big (SplitOptions::threads).
// A triangle the plane does not cut goes to its side at once, and with `unite` (one chunk only) its
// corners' islands are united on the way (SideWork::parent over the source's position ids;
// uniteSide adds the rest). A crossing triangle gives its crossing edges and keeps its places in the
// side lists (as many as it will have parts), to be cut by cutPending once cutVertices has made the
// edges' new vertices. A triangle gives a side at most two parts, so chunk c's triangles fit below
// twice its end in the side lists' storage: it writes forwards from twice its beginning, except
// chunk 0 of several, which writes backwards down from twice its end, where chunk 1 begins. The
// two then meet with nothing to move, and joinChunks moves only chunks 2, 3, ... up to them: the
// same lists as one chunk gives.
void Splitter::cutWholeAndCollect(bool unite) {
  const uint32_t triangleCount = static_cast<uint32_t>(mesh_->indices.size() / 3);
  const uint32_t chunks = chunkCount(triangleCount);
  unite = unite && chunks == 1;
  if (cutChunks_.size() < chunks - 1) cutChunks_.resize(chunks - 1);
  for (int side = 0; side < 2 && unite; ++side) {
    work_[side].parent.resize(idCount_);
    std::iota(work_[side].parent.begin(), work_[side].parent.end(), 0u);
  }
  united_ = unite;
#ifdef CLEAVE_AVX2_VARIANTS
  if (wholeBlocks_ && !unite) {
    vertexSide_.resize(size_t(sourceCount_) + detail::kSidePadding);
    inChunks(chunkCount(sourceCount_), sourceCount_, [&](uint32_t, uint32_t begin, uint32_t end) {
      detail::vertexSidesAvx2(ids_.data(), side_.data(), begin, end, vertexSide_.data());
    });
  }
#endif
  SideTriangle* const lists[2] = {sideTris_[0].place(2 * size_t(triangleCount)),
                                  sideTris_[1].place(2 * size_t(triangleCount))};
  inChunks(chunks, triangleCount, [&](uint32_t chunk, uint32_t begin, uint32_t end) {
    if (chunk == 0 && chunks > 1) collectRange<true>(begin, end, unite, lists, cutMain_);
    else collectRange<false>(begin, end, unite, lists, chunk == 0 ? cutMain_ : cutChunks_[chunk - 1]);
  });
  joinChunks(chunks);
}

// The crossing edges (sorted already: collectRange sorts each chunk's, joinChunks merges them) made
// unique, their cut points, the new vertices and the output run slots.
void Splitter::cutVertices(const SplitOptions& options) {
  weldedEdges_.erase(std::unique(weldedEdges_.begin(), weldedEdges_.end()), weldedEdges_.end());
  pairs_.erase(std::unique(pairs_.begin(), pairs_.end()), pairs_.end());
  cutEdges();
  makeCutVertices();
  assignSlots(options);
}

// cutWholeAndCollect over the source triangles [begin, end): side triangles into `lists` (the side
// lists' storage) forwards from 2 begin, or with kBackwards, last triangle first, backwards down from
// 2 end; the rest into out's lists (cleared first), with storage positions. out.first and out.end get
// the range written per side.
template <bool kBackwards>
void Splitter::collectRange(uint32_t begin, uint32_t end, bool unite, SideTriangle* const (&lists)[2],
                            CutOutput& out) {
  const MeshData& mesh = *mesh_;
  out.crossing.clear();
  out.crossingPairs.clear();
  out.pending.clear();
  out.planeTris[0].clear();
  out.planeTris[1].clear();
  uint32_t at[2] = {2 * (kBackwards ? end : begin), 2 * (kBackwards ? end : begin)};
  // Local copies: the stores into the lists could alias the members, which were read again each time.
  const uint32_t* const indices = mesh.indices.data();
  const uint32_t* const ids = ids_.data();
  const int8_t* const sides = side_.data();
  const bool mirrored = mirrored_;
  [[maybe_unused]] const bool blocks = wholeBlocks_ && !unite;
  for (uint32_t k = begin; k < end; ++k) {
#ifdef CLEAVE_AVX2_VARIANTS
    // Every eighth triangle, the whole ones from there on eight at a time (whole_blocks.h); the
    // triangles of a block they stop at go through the loop here.
    if (blocks && (k - begin) % 8 == 0) {
      const int8_t* const vertexSides = vertexSide_.data();
      if (kBackwards) {  // the triangles left are [begin, end - (k - begin)), last first
        const uint32_t hi = detail::wholeBlocksAvx2<true>(indices, vertexSides, mirrored, begin, end - (k - begin), lists, at);
        k = begin + (end - hi);
      } else {
        k = detail::wholeBlocksAvx2<false>(indices, vertexSides, mirrored, k, end, lists, at);
      }
      if (k == end) break;
    }
#endif
    const uint32_t t = kBackwards ? end - 1 - (k - begin) : k;
    uint32_t g[3] = {indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]};
    if (mirrored) std::swap(g[1], g[2]);  // cut-space outward winding
    const uint32_t id[3] = {ids[g[0]], ids[g[1]], ids[g[2]]};
    const int s[3] = {sides[id[0]], sides[id[1]], sides[id[2]]};
    int index = 0;
    bool planar = false;
    if (wholeSide(g, s, index, planar)) {
      const uint32_t place = kBackwards ? --at[index] : at[index]++;
      if (planar) out.planeTris[index].push_back(place);
      lists[index][place] = {{g[0], g[1], g[2]}, planar ? t | kReachedBit : t};
      if (unite) uniteCorners(work_[index], id[0], id[1], id[2]);
      continue;
    }
    for (int e = 0; e < 3; ++e) {
      const int f = e == 2 ? 0 : e + 1;
      if (s[e] * s[f] < 0) {
        out.crossing.push_back(pairKey(id[e], id[f]));
        out.crossingPairs.push_back(pairKey(g[e], g[f]));
      }
    }
    // Its parts per side: through an on-plane vertex one each; else the lone corner's triangle and
    // the quad's two on the other side (see cutCrossing).
    uint32_t count[2] = {1, 1};
    if (s[0] != 0 && s[1] != 0 && s[2] != 0) {
      const int lone = s[0] != s[1] && s[0] != s[2] ? 0 : (s[1] != s[0] && s[1] != s[2] ? 1 : 2);
      count[s[lone] > 0 ? 1 : 0] = 2;
    }
    if (kBackwards) at[0] -= count[0], at[1] -= count[1];
    out.pending.push_back({t, {at[0], at[1]}});
    if (!kBackwards) at[0] += count[0], at[1] += count[1];
  }
  std::sort(out.crossing.begin(), out.crossing.end());  // on the chunk's thread; joinChunks merges them
  std::sort(out.crossingPairs.begin(), out.crossingPairs.end());
  for (int side = 0; side < 2; ++side) {
    out.first[side] = kBackwards ? at[side] : 2 * size_t(begin);
    out.end[side] = kBackwards ? 2 * size_t(end) : at[side];
  }
}

// The chunks' side triangles made one list per side, and their other lists joined into chunk 0's,
// with storage positions made list indices. Chunk 0 of several wrote last to first: its lists are
// turned round. Chunk 1 begins where chunk 0 ends; chunks 2, 3, ... are moved down to the end of the
// one before (std::copy: the target starts below the source).
void Splitter::joinChunks(uint32_t chunks) {
  const size_t offset[2] = {cutMain_.first[0], cutMain_.first[1]};
  size_t total[2] = {cutMain_.end[0] - offset[0], cutMain_.end[1] - offset[1]};
  if (chunks > 1) {
    std::reverse(pending_.begin(), pending_.end());
    for (Pending& p : pending_) p.first[0] -= uint32_t(offset[0]), p.first[1] -= uint32_t(offset[1]);
    for (int side = 0; side < 2; ++side) {
      std::reverse(planeTris_[side].begin(), planeTris_[side].end());
      for (uint32_t& index : planeTris_[side]) index -= uint32_t(offset[side]);
    }
  }
  for (uint32_t chunk = 1; chunk < chunks; ++chunk) {
    CutOutput& part = cutChunks_[chunk - 1];
    uint32_t shift[2];  // from a storage position of the chunk's to a list index
    for (int side = 0; side < 2; ++side) {
      SideTriangle* const storage = sideTris_[side].data();  // the list starts there until adopt()
      const size_t target = offset[side] + total[side];
      if (target != part.first[side]) std::copy(storage + part.first[side], storage + part.end[side], storage + target);
      shift[side] = uint32_t(part.first[side] - total[side]);
      total[side] += part.end[side] - part.first[side];
      for (uint32_t index : part.planeTris[side]) planeTris_[side].push_back(index - shift[side]);
    }
    for (Pending p : part.pending) {
      p.first[0] -= shift[0];
      p.first[1] -= shift[1];
      pending_.push_back(p);
    }
    for (auto [to, from] : {std::pair{&weldedEdges_, &part.crossing}, std::pair{&pairs_, &part.crossingPairs}}) {
      const auto middle = static_cast<std::ptrdiff_t>(to->size());
      to->insert(to->end(), from->begin(), from->end());
      std::inplace_merge(to->begin(), to->begin() + middle, to->end());
    }
  }
  sideTris_[0].adopt(offset[0], total[0]);
  sideTris_[1].adopt(offset[1], total[1]);
}

// The crossing triangles cutWholeAndCollect kept places for, cut into them; the plane and cut lists
// sorted back into side-list order.
void Splitter::cutPending() {
  const MeshData& mesh = *mesh_;
  const size_t planeWhole[2] = {planeTris_[0].size(), planeTris_[1].size()};
  cutTris_[0].clear();
  cutTris_[1].clear();
  for (const Pending& p : pending_) {
    uint32_t g[3] = {mesh.indices[3 * p.triangle], mesh.indices[3 * p.triangle + 1], mesh.indices[3 * p.triangle + 2]};
    if (mirrored_) std::swap(g[1], g[2]);
    const int s[3] = {side_[ids_[g[0]]], side_[ids_[g[1]]], side_[ids_[g[2]]]};
    uint32_t next[2] = {p.first[0], p.first[1]};
    cutCrossing(p.triangle, g, s, next);
  }
  if (pending_.empty()) return;
  // cutTris_ is ascending already (only cutPending writes it); planeTris_ is the whole triangles'
  // ascending run followed by the cut parts' one.
  for (int side = 0; side < 2; ++side) {
    std::vector<uint32_t>& plane = planeTris_[side];
    std::inplace_merge(plane.begin(), plane.begin() + static_cast<std::ptrdiff_t>(planeWhole[side]), plane.end());
  }
}

// Unites the islands of position ids a, b and c of one side. A parent always has a lower id than
// its child, so a root is the lowest id of its island (as labelSide's one-pass flattening needs).
void Splitter::uniteCorners(SideWork& w, uint32_t a, uint32_t b, uint32_t c) {
  uint32_t* parent = w.parent.data();
  unite(parent, a, b);
  unite(parent, a, c);
}

// Rem's union with splicing: the two paths are climbed together, the one whose parent is higher
// moving up; each node left behind is pointed at the other path's lower parent on the way, so the
// paths shorten as they are walked and no separate find runs. Stops where the paths meet or at a
// root, which is linked below the other path.
void Splitter::unite(uint32_t* parent, uint32_t x, uint32_t y) {
  while (parent[x] != parent[y]) {
    if (parent[x] < parent[y]) std::swap(x, y);  // x: the path with the higher parent
    const uint32_t up = parent[x];
    parent[x] = parent[y];
    if (up == x) return;  // x was a root: now linked below y's parent
    x = up;
  }
}

// Step 1: the side of every position id (in chunks on threads when big). The distances are not
// kept: cutEdges works out again the few it needs (distanceOf, the same bits).
void Splitter::classify(double tolerance) {
  side_.resize(size_t(idCount_) + detail::kSidePadding);  // the padding is never read as a side
  const uint32_t ahead = idCount_ >= detail::kFarCount ? kIdsAhead : 0;
  inChunks(chunkCount(idCount_), idCount_, [&](uint32_t, uint32_t begin, uint32_t end) {
    int8_t* const sides = side_.data();  // a local pointer: a byte store would make every load again
    uint32_t id = begin;
#ifdef CLEAVE_AVX2_VARIANTS
    if (laneSides_) {  // side_lanes.h: four ids at a time, the same sides; the last few below
      id = detail::classifyAvx2(cut_.source().data(), cut_.moved().data(), reps_.data(), begin, end, normal_, offset_,
                                tolerance, ahead, sides);
    }
#endif
    for (; id < end; ++id) {
      if (ahead != 0 && id + ahead < end) cut_.prefetch(reps_[id + ahead]);
      const double d = distanceOf(id);
      sides[id] = d > tolerance ? 1 : (d < -tolerance ? -1 : 0);
    }
  });
}

// On-plane edges of one side without a reverse twin on that side, sorted (directed, welded ids).
void Splitter::collectBoundary(int sideIndex, std::vector<uint64_t>& boundary) {
  std::vector<uint64_t>& edges = reversed_;
  edges.clear();
  for (uint32_t index : planeTris_[sideIndex]) {
    const SideTriangle& tri = sideTris_[sideIndex][index];
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = tri.v[e], b = tri.v[(e + 1) % 3];
      if (!onPlane(a) || !onPlane(b)) continue;
      const uint32_t wa = weldedOf(a), wb = weldedOf(b);
      if (wa == wb) continue;
      edges.push_back(directedKey(wa, wb));
    }
  }
  std::sort(edges.begin(), edges.end());
  boundary.clear();
  for (size_t k = 0; k < edges.size();) {
    size_t j = k;
    while (j < edges.size() && edges[j] == edges[k]) ++j;
    const uint64_t reverse = directedKey(keyTo(edges[k]), keyFrom(edges[k]));
    size_t twins = 0;  // the search without a branch (lowerBound): a twin is rare, its place random
    for (size_t at = lowerBound(edges, reverse); at < edges.size() && edges[at] == reverse; ++at) ++twins;
    for (size_t c = twins; c < j - k; ++c) boundary.push_back(edges[k]);
    k = j;
  }
}

// The unused segment leaving `at` that turns most to the left coming in along `incoming`.
uint32_t Splitter::nextSegment(uint32_t at, uint32_t incoming) const {
  const auto first = segments_.begin() + static_cast<std::ptrdiff_t>(lowerBound(segments_, directedKey(at, 0)));
  uint32_t best = kNone;
  double bestTurn = -INFINITY;
  const glm::dvec2 here = project(sectionCut(at));
  const glm::dvec2 in = here - project(sectionCut(keyFrom(segments_[incoming])));
  for (auto it = first; it != segments_.end() && keyFrom(*it) == at; ++it) {
    const uint32_t s = static_cast<uint32_t>(it - segments_.begin());
    if (segmentUsed_[s]) continue;
    if (best == kNone) best = s;
    const glm::dvec2 out = project(sectionCut(keyTo(*it))) - here;
    const double turn = std::atan2(in.x * out.y - in.y * out.x, glm::dot(in, out));
    if (turn > bestTurn) {
      bestTurn = turn;
      best = s;
    }
  }
  return best;
}

void Splitter::buildLoops() {
  segmentUsed_.assign(segments_.size(), 0);
  loopIds_.clear();
  points_.clear();
  loops_.clear();
  openChains_ = 0;
  closedLoops_ = 0;
  bridgedChains_ = 0;
  chainIds_.clear();
  chains_.clear();
  if (bridge_) {  // the chains first, from their starts, so that none is broken into fragments
    sortSegmentEnds();
    walkChains();
  }
  for (uint32_t s0 = 0; s0 < segments_.size(); ++s0) {
    if (segmentUsed_[s0]) continue;
    const uint32_t start = keyFrom(segments_[s0]);
    const uint32_t begin = static_cast<uint32_t>(loopIds_.size());
    loopIds_.push_back(start);
    segmentUsed_[s0] = 1;
    uint32_t current = s0;
    bool closed = true;
    for (uint32_t at = keyTo(segments_[s0]); at != start;) {
      const uint32_t next = nextSegment(at, current);
      if (next == kNone) {
        closed = false;
        break;
      }
      loopIds_.push_back(at);
      segmentUsed_[next] = 1;
      current = next;
      at = keyTo(segments_[next]);
    }
    if (!closed) {
      ++openChains_;  // a fragment; the chains are counted by their starts below
      loopIds_.resize(begin);
      continue;
    }
    ++closedLoops_;
    LoopInfo loop;
    loop.begin = begin;
    loop.end = static_cast<uint32_t>(loopIds_.size());
    loops_.push_back(loop);
  }
  if (openChains_ > 0 || !chains_.empty()) {
    // A walk that starts inside an open chain stops at its end and leaves the part before it as a
    // fragment of its own: count the chains by their starts (a segment no other segment leads to).
    if (!bridge_) sortSegmentEnds();
    openChains_ = 0;
    for (uint64_t k : segments_) openChains_ += startsChain(k) ? 1 : 0;
    openChains_ = std::max<uint32_t>(openChains_, 1);
  }
  if (bridge_) bridgeChains();
  measureLoops();
}

// The loops as traced, made ready for the caps: the cap and merge tolerances, near points merged,
// the points projected into the cap plane, each loop's area and bounds there.
void Splitter::measureLoops() {
  // The scale of float rounding at the section: cut points are computed from float source positions,
  // so re-cut sections carry zig-zag runs and near-coincident points a few ulps of the coordinates
  // apart. Four ulps of the largest coordinate on the section is the cap tolerance: points that
  // close to the segment joining their neighbouring corners are not corners (see CapTriangulator),
  // which leaves the cap area exact up to slivers of that width. Runs of near-coincident points are
  // merged within the on-plane tolerance (points that close are one point to the classification
  // too), never less than the cap tolerance: merging moves cut vertices by at most a few of those.
  double largest = 0.0;
  for (uint32_t welded : loopIds_) {
    const glm::dvec3 p = glm::abs(sectionCut(welded));
    largest = std::max({largest, p.x, p.y, p.z});
  }
  capTolerance_ = std::max(4.0 * 0x1.0p-24 * largest, 1e-12 * container_->boundsDiagonal());
  mergeTolerance_ = std::max(capTolerance_, onPlaneTolerance_);
  cutsOnLoops_ = islandCandidate_ && everyJoinOnALoop();  // before the merge renames loop points
  mergeNearPoints();
  points_.resize(loopIds_.size());
  for (size_t k = 0; k < loopIds_.size(); ++k) points_[k] = project(sectionCut(loopIds_[k]));
  for (LoopInfo& loop : loops_) {
    const CapRing ring{loop.begin, loop.end};
    loop.twiceArea = loop.end - loop.begin >= 3 ? CapTriangulator::twiceSignedArea(points_, ring) : 0.0;
    loop.lo = glm::dvec2(INFINITY);
    loop.hi = glm::dvec2(-INFINITY);
    for (uint32_t k = loop.begin; k < loop.end; ++k) {
      loop.lo = glm::min(loop.lo, points_[k]);
      loop.hi = glm::max(loop.hi, points_[k]);
    }
  }
}

void Splitter::sortSegmentEnds() {
  segmentEnds_.clear();
  for (uint64_t k : segments_) segmentEnds_.push_back(keyTo(k));
  std::sort(segmentEnds_.begin(), segmentEnds_.end());
}

// Bridge: each open chain of the section, walked from its start (a segment no other segment leads
// to) until it stops; its segments are used up.
void Splitter::walkChains() {
  for (uint32_t s0 = 0; s0 < segments_.size(); ++s0) {
    if (segmentUsed_[s0] || !startsChain(segments_[s0])) continue;
    const uint32_t begin = static_cast<uint32_t>(chainIds_.size());
    chainIds_.push_back(keyFrom(segments_[s0]));
    segmentUsed_[s0] = 1;
    uint32_t current = s0;
    for (;;) {
      const uint32_t at = keyTo(segments_[current]);
      chainIds_.push_back(at);
      const uint32_t next = nextSegment(at, current);
      if (next == kNone) break;
      segmentUsed_[next] = 1;
      current = next;
    }
    chains_.push_back({begin, static_cast<uint32_t>(chainIds_.size())});
  }
}

// Bridge: closes the open chains whose ends lie within the gap, or whose chord is clear (see
// chordClear), into loops to be capped; the others stay open (openChains_, counted by their starts
// as without Bridge, less the bridged ones).
void Splitter::bridgeChains() {
  for (const auto& [begin, end] : chains_) {
    if (end - begin < 3) continue;  // one segment: nothing to cap
    const double gap = glm::length(sectionCut(chainIds_[end - 1]) - sectionCut(chainIds_[begin]));
    // Ends within the gap close a seam: loops inside are then its holes. A long chord must close a
    // cap of its own.
    if (!chordClear(begin, end, !(gap <= bridgeGap_))) continue;
    LoopInfo loop;
    loop.begin = static_cast<uint32_t>(loopIds_.size());
    loopIds_.insert(loopIds_.end(), chainIds_.begin() + begin, chainIds_.begin() + end);
    loop.end = static_cast<uint32_t>(loopIds_.size());
    loops_.push_back(loop);
    ++bridgedChains_;
    if (openChains_ > 0) --openChains_;
  }
}

// Whether the chord closing the chain [begin, end) of chainIds_ crosses no segment of the section
// (other than at the chain's ends), and, when it must stand `alone`, the polygon it closes neither
// holds a point of another loop nor has its first point inside one: a cap of its own.
bool Splitter::chordClear(uint32_t begin, uint32_t end, bool alone) {
  const uint32_t first = chainIds_[begin], last = chainIds_[end - 1];
  const glm::dvec2 a = project(sectionCut(last)), b = project(sectionCut(first));
  auto turn = [](const glm::dvec2& p, const glm::dvec2& q, const glm::dvec2& r) {
    const glm::dvec2 u = q - p, v = r - p;
    const double cross = u.x * v.y - u.y * v.x;
    return (cross > 0.0) - (cross < 0.0);
  };
  for (uint64_t k : segments_) {
    const uint32_t u = keyFrom(k), v = keyTo(k);
    if (u == first || u == last || v == first || v == last) continue;
    const glm::dvec2 p = project(sectionCut(u)), q = project(sectionCut(v));
    if (turn(a, b, p) * turn(a, b, q) < 0 && turn(p, q, a) * turn(p, q, b) < 0) return false;
  }
  if (!alone) return true;
  chainPoints_.clear();
  for (uint32_t k = begin; k < end; ++k) chainPoints_.push_back(project(sectionCut(chainIds_[k])));
  for (const LoopInfo& loop : loops_) {
    otherPoints_.clear();
    for (uint32_t k = loop.begin; k < loop.end; ++k) otherPoints_.push_back(project(sectionCut(loopIds_[k])));
    if (CapTriangulator::ringContains(chainPoints_, CapRing{0, static_cast<uint32_t>(chainPoints_.size())}, otherPoints_[0])) return false;
    const glm::dvec2 probe = 0.5 * (chainPoints_[0] + chainPoints_[1]);
    if (CapTriangulator::ringContains(otherPoints_, CapRing{0, static_cast<uint32_t>(otherPoints_.size())}, probe)) return false;
  }
  return true;
}

// Merges runs of consecutive loop points into one: each point of a run lies within the merge
// tolerance of the one before it and within four merge tolerances of the run's first point.
// Such runs come from planes that cross many edges next to one another, typically the sliver fans
// of an earlier cap: rounding leaves their order along the section scrambled by a few ulps, so the
// exact loop folds over itself. The cut vertices of a run are moved onto its representative (the
// on-plane source vertex of the run if it has one, else its first point), for both sides, in cut
// and source space alike, so the side triangles and the cap still meet edge to edge (the side
// triangles between merged points become degenerate) and the loop keeps the representative only.
// A run never holds two source vertices: those cannot move.
void Splitter::mergeNearPoints() {
  const double tolerance2 = mergeTolerance_ * mergeTolerance_;
  // Every cut point starts as its own alias (sized on every call, so that a warm splitter does not
  // allocate when a later split of the same size merges points and an earlier one did not).
  alias_.resize(weldedEdges_.size());
  std::iota(alias_.begin(), alias_.end(), idCount_);
  if (!(tolerance2 > 0.0)) return;
  auto distance2 = [&](uint32_t a, uint32_t b) {
    const glm::dvec3 d = sectionCut(a) - sectionCut(b);
    return glm::dot(d, d);
  };
  bool moved = false;
  mergedIds_.clear();
  for (LoopInfo& loop : loops_) {
    const uint32_t n = loop.end - loop.begin;
    const uint32_t begin = static_cast<uint32_t>(mergedIds_.size());
    uint32_t start = kNone;
    if (n >= 4) {
      for (uint32_t i = 0; i < n && start == kNone; ++i) {
        const uint32_t prev = loopIds_[loop.begin + (i + n - 1) % n];
        if (distance2(loopIds_[loop.begin + i], prev) > tolerance2) start = i;
      }
    }
    if (start == kNone) {
      mergedIds_.insert(mergedIds_.end(), loopIds_.begin() + loop.begin, loopIds_.begin() + loop.end);
    } else {
      for (uint32_t i = 0; i < n;) {
        const uint32_t first = loopIds_[loop.begin + (start + i) % n];
        uint32_t rep = first;
        uint32_t j = i + 1;
        for (; j < n; ++j) {
          const uint32_t id = loopIds_[loop.begin + (start + j) % n];
          const uint32_t previous = loopIds_[loop.begin + (start + j - 1) % n];
          if (distance2(id, previous) > tolerance2 || distance2(id, first) > 16.0 * tolerance2) break;
          if (id < idCount_) {
            if (rep < idCount_) break;
            rep = id;
          }
        }
        if (j > i + 1) {
          const glm::dvec3 cut = sectionCut(rep);
          const glm::vec3 source = rep < idCount_ ? mesh_->positions[reps_[rep]] : edgeSource_[rep - idCount_];
          for (uint32_t m = i; m < j; ++m) {
            const uint32_t id = loopIds_[loop.begin + (start + m) % n];
            if (id == rep) continue;
            // The aliases form a forest: the root of the point is linked to the root of the run's
            // representative (a point can sit in two loops where the section touches itself, so
            // either may have been merged already). A source vertex is always a root.
            linkWelded(id, rep);
            edgeCut_[id - idCount_] = cut;
            edgeSource_[id - idCount_] = source;
            moved = true;
          }
        }
        mergedIds_.push_back(rep);
        i = j;
      }
    }
    loop.begin = begin;
    loop.end = static_cast<uint32_t>(mergedIds_.size());
  }
  loopIds_.swap(mergedIds_);
  if (moved) {
    for (size_t k = 0; k < pairs_.size(); ++k) extra_.positions[k] = edgeSource_[pairEdge_[k]];
  }
}

// Links the alias roots of two welded ids: a cut point's root is linked to the other root; two
// source vertices stay apart (they cannot move).
void Splitter::linkWelded(uint32_t a, uint32_t b) {
  const uint32_t from = aliasRoot(a), to = aliasRoot(b);
  if (from == to) return;
  if (from >= idCount_) {
    alias_[from - idCount_] = to;
  } else if (to >= idCount_) {
    alias_[to - idCount_] = from;
  }
}

// Where a cut point rounds to the same float position as another cut point or a vertex next to it
// (points closer than float precision but farther apart than the merge tolerance, as on meshes
// with many small handles or where the plane passes through a vertex of a flat region), the part
// of a cut triangle between them has zero area in the written mesh, and the pieces would be closed
// on their ids but not on their float positions. Such triangles (of the cut and of the caps) are
// dropped and their coinciding corners welded into one id: their edges cancel in pairs, so the
// pieces stay closed on both. Whole source triangles are never dropped.
void Splitter::dropCollapsedTriangles() {
  for (int side = 0; side < 2; ++side) {
    SideList& tris = sideTris_[side];
    bool dropped = false;
    auto check = [&](SideTriangle& tri) {
      const glm::vec3 p[3] = {outputPosition(tri.v[0]), outputPosition(tri.v[1]), outputPosition(tri.v[2])};
      bool collapsed = false;
      for (int e = 0; e < 3; ++e) {
        if (p[e] != p[(e + 1) % 3]) continue;
        const uint32_t a = weldedOfAny(tri.v[e]), b = weldedOfAny(tri.v[(e + 1) % 3]);
        linkWelded(a, b);
        collapsed = collapsed || aliasRoot(a) == aliasRoot(b);
      }
      if (!collapsed) return;
      tri.source = kDroppedSource;
      dropped = true;
    };
    for (uint32_t index : cutTris_[side]) check(tris[index]);
    for (size_t index = capStart_[side]; index < tris.size(); ++index) check(tris[index]);
    dropped_[side] = dropped;
    if (dropped) {
      tris.truncate(std::remove_if(tris.begin(), tris.end(), [](const SideTriangle& t) { return t.source == kDroppedSource; }));
    }
  }
}

// Whether cap triangle t (into capTriangles_) has collinear corners on the float positions it is
// written with (exact: see the float weld check of the tests).
bool Splitter::flatCapTriangle(size_t t) const {
  const size_t base = capBase_ - sourceCount_;  // extra_ index of the below cap vertex of loop point 0
  const glm::dvec3 a(extra_.positions[base + capTriangles_[3 * t]]);
  const glm::dvec3 b(extra_.positions[base + capTriangles_[3 * t + 1]]);
  const glm::dvec3 c(extra_.positions[base + capTriangles_[3 * t + 2]]);
  return glm::cross(b - a, c - a) == glm::dvec3(0.0);
}

// A cap triangle can be thin enough in double to pass the triangulator and still be flat once its
// corners are written as float: three points of one straight edge of the section (as where a plane
// runs along a flat face), whose rounding in double kept them apart. Such a triangle is flipped with
// its neighbour across its longest edge (p, q, m) + (q, p, d) -> (p, d, m) + (d, q, m): the middle
// point m lies on p-q, so both new triangles have the area of the old pair. A longest edge on the
// section's border has no neighbour in the cap and stays (the side triangles there are as flat).
void Splitter::flipFlatCapTriangles() {
  flatCaps_.clear();
  const size_t count = capTriangles_.size() / 3;
  for (size_t t = 0; t < count; ++t) {
    if (flatCapTriangle(t)) flatCaps_.push_back(static_cast<uint32_t>(t));
  }
  if (flatCaps_.empty()) return;
  // A flat neighbour cannot take the flip; once it is flipped away, the next pass can.
  bool flipped = true;
  for (int pass = 0; pass < 4 && flipped; ++pass) {
    flipped = false;
    for (uint32_t t : flatCaps_) flipped = flipCapTriangle(t) || flipped;
  }
}

// Flips cap triangle t if it is flat on floats; flips are rare, so the neighbour is found by a scan.
bool Splitter::flipCapTriangle(uint32_t t) {
  if (!flatCapTriangle(t)) return false;  // not flat, or fixed by an earlier flip
  const size_t base = capBase_ - sourceCount_;
  auto twice = [&](uint32_t a, uint32_t b, uint32_t c) {
    const glm::dvec2 u = points_[b] - points_[a], v = points_[c] - points_[a];
    return u.x * v.y - u.y * v.x;
  };
  uint32_t* tri = &capTriangles_[3 * size_t(t)];
  int longest = 0;
  double best = -1.0;
  for (int e = 0; e < 3; ++e) {
    const glm::dvec3 d =
        glm::dvec3(extra_.positions[base + tri[(e + 1) % 3]]) - glm::dvec3(extra_.positions[base + tri[e]]);
    if (glm::dot(d, d) > best) {
      best = glm::dot(d, d);
      longest = e;
    }
  }
  const uint32_t p = tri[longest], q = tri[(longest + 1) % 3], m = tri[(longest + 2) % 3];
  for (size_t k = 0; k < capTriangles_.size(); k += 3) {
    uint32_t* other = &capTriangles_[k];
    int at = -1;  // the corner of `other` where its edge q -> p starts
    for (int c = 0; c < 3; ++c) {
      if (other[c] == q && other[(c + 1) % 3] == p) at = c;
    }
    if (at < 0) continue;
    const uint32_t d = other[(at + 2) % 3];
    if (!(twice(p, d, m) > 0.0) || !(twice(d, q, m) > 0.0)) return false;
    tri[0] = p, tri[1] = d, tri[2] = m;
    other[0] = d, other[1] = q, other[2] = m;
    return true;
  }
  return false;
}

// The cap triangles onto both sides: below with outward normal +n, counter-clockwise as
// triangulated; above reversed.
void Splitter::pushCapTriangles() {
  const uint32_t loopVertices = static_cast<uint32_t>(loopIds_.size());
  for (size_t k = 0; k < capTriangles_.size(); k += 3) {
    const uint32_t a = capTriangles_[k], b = capTriangles_[k + 1], c = capTriangles_[k + 2];
    const uint32_t source = kReachedBit | kCapBit | capLoopOf_[k / 3];
    sideTris_[1].push_back({{capBase_ + a, capBase_ + b, capBase_ + c}, source});
    sideTris_[0].push_back(
        {{capBase_ + loopVertices + a, capBase_ + loopVertices + c, capBase_ + loopVertices + b}, source});
  }
}

// The thesis's fast path: one loop whose angular order around its centroid is the loop order, strictly
// convex once collinear points are removed, fanned.
bool Splitter::tryConvexCap() {
  if (loops_.size() != 1) return false;
  const LoopInfo& loop = loops_[0];
  const uint32_t count = loop.end - loop.begin;
  if (count < 3 || !(loop.twiceArea > 0.0)) return false;
  glm::dvec2 centroid(0.0);
  for (uint32_t k = loop.begin; k < loop.end; ++k) centroid += points_[k];
  centroid /= double(count);
  angular_.clear();
  for (uint32_t k = loop.begin; k < loop.end; ++k) {
    const glm::dvec2 d = points_[k] - centroid;
    angular_.push_back({std::atan2(d.y, d.x), k});
  }
  std::sort(angular_.begin(), angular_.end());
  // The sorted order must be the loop order, rotated.
  uint32_t at = 0;
  while (angular_[at].second != loop.begin) ++at;
  for (uint32_t k = 0; k < count; ++k) {
    if (angular_[(at + k) % count].second != loop.begin + k) return false;
  }
  return triangulator_.triangulateConvex(points_, CapRing{loop.begin, loop.end}, capTriangles_, capTolerance_);
}

bool Splitter::capSection(const SplitOptions& options, std::string& why) {
  // Pieces that are open anyway (open art) keep what cannot be capped open instead of failing.
  const bool lenient = options.openSections != OpenSectionMode::Refuse && !piecesClosed_;
  uncappedLoops_ = 0;
  capLoopOf_.clear();
  if (convexFastPath_ && tryConvexCap()) {
    loops_[0].capped = true;
    capLoopOf_.assign(capTriangles_.size() / 3, 0u);
    return true;
  }
  capTriangles_.clear();
  // Outer borders (positive area) and holes (negative); loops without area are left uncapped.
  for (LoopInfo& loop : loops_) {
    const glm::dvec2 size = loop.hi - loop.lo;
    const double scale = std::max(size.x, size.y);
    loop.outer = kNone;
    loop.capped = loop.end - loop.begin >= 3 && std::abs(loop.twiceArea) > 1e-12 * scale * scale;
  }
  for (size_t h = 0; h < loops_.size(); ++h) {
    LoopInfo& hole = loops_[h];
    if (!hole.capped || hole.twiceArea > 0.0) continue;
    const glm::dvec2 q = 0.5 * (points_[hole.begin] + points_[hole.begin + 1]);
    double bestArea = INFINITY;
    for (size_t o = 0; o < loops_.size(); ++o) {
      const LoopInfo& outer = loops_[o];
      if (!outer.capped || outer.twiceArea < 0.0 || outer.twiceArea >= bestArea) continue;
      if (q.x < outer.lo.x || q.x > outer.hi.x || q.y < outer.lo.y || q.y > outer.hi.y) continue;
      if (!CapTriangulator::ringContains(points_, CapRing{outer.begin, outer.end}, q)) continue;
      bestArea = outer.twiceArea;
      hole.outer = static_cast<uint32_t>(o);
    }
    if (hole.outer == kNone) {
      if (lenient) {  // open art wound both ways: this loop stays open, the rest is capped
        hole.capped = false;
        ++uncappedLoops_;
        continue;
      }
      why = "cap triangulation failed: a hole loop of the section lies outside every outer loop "
            "(inconsistent winding of the input)";
      return false;
    }
  }
  for (size_t o = 0; o < loops_.size(); ++o) {
    const LoopInfo& outer = loops_[o];
    if (!outer.capped || outer.twiceArea < 0.0) continue;
    rings_.clear();
    rings_.push_back({outer.begin, outer.end});
    for (const LoopInfo& hole : loops_) {
      if (hole.capped && hole.outer == o) rings_.push_back({hole.begin, hole.end});
    }
    const size_t before = capTriangles_.size();
    if (!triangulator_.triangulate(points_, rings_, capTriangles_, capTolerance_)) {
      if (lenient) {  // open art that overlaps itself here: this border and its holes stay open
        capTriangles_.resize(before);
        for (LoopInfo& loop : loops_) {
          if (&loop != &outer && loop.outer != o) continue;
          loop.capped = false;
          ++uncappedLoops_;
        }
        continue;
      }
      why = "cap triangulation failed for a border of " + std::to_string(outer.end - outer.begin) + " points with " +
            std::to_string(rings_.size() - 1) + " hole(s): the section polygon overlaps itself";
      return false;
    }
    capLoopOf_.resize(capTriangles_.size() / 3, static_cast<uint32_t>(o));
  }
  return true;
}

// Cap vertices, one per loop vertex and side: the cut position, the plane normal (out of the
// piece), a tangent along the cap U axis, cap UVs, and the colour and skin of the cut vertex.
void Splitter::makeCapVertices(const SplitOptions& options) {
  const MeshData& mesh = *mesh_;
  const uint32_t count = static_cast<uint32_t>(loopIds_.size());
  capUvBounds(options);
  const size_t base = extra_.positions.size();
  const size_t total = base + 2 * size_t(count);
  extra_.positions.resize(total);
  if (!mesh.normals.empty()) extra_.normals.resize(total);
  if (!mesh.tangents.empty()) extra_.tangents.resize(total);
  if (!mesh.uv0.empty()) extra_.uv0.resize(total);
  if (!mesh.uv1.empty()) extra_.uv1.resize(total);
  if (!mesh.colors.empty()) extra_.colors.resize(total);
  if (!mesh.joints.empty()) {
    extra_.joints.resize(total);
    extra_.weights.resize(total);
  }
  uint32_t loopIndex = 0;
  for (uint32_t k = 0; k < count; ++k) {
    while (k >= loops_[loopIndex].end) ++loopIndex;
    const glm::dvec2 uv = capUv(options, k, capUvGroup(options, loopIndex));
    CapFrame frame;
    if (!mesh.normals.empty() || !mesh.tangents.empty()) {  // else neither is written
      const uint32_t welded = loopIds_[k];
      const bool fromExtra = welded >= idCount_;
      frame.linear = capLinear(fromExtra, fromExtra ? edgeFirstPair_[welded - idCount_] : reps_[welded]);
      frame.inverse = glm::inverse(frame.linear);
    }
    for (int s = 0; s < 2; ++s) writeCapVertex(options, k, s, base + size_t(s) * count + k, uv, frame);
  }
}

// The cap UV bounds group of a loop: per border (an outer loop with its holes) or one for the cap.
uint32_t Splitter::capUvGroup(const SplitOptions& options, uint32_t loopIndex) const {
  const LoopInfo& loop = loops_[loopIndex];
  if (!options.uvPerBorder) return 0u;
  return loop.twiceArea > 0.0 || loop.outer == kNone ? loopIndex : loop.outer;
}

// Plane coordinates of loop point k: absolute, so world-planar UVs line up across cuts.
glm::dvec2 Splitter::capPlanar(uint32_t k) const {
  const glm::dvec3 p = sectionCut(loopIds_[k]);
  return glm::dvec2(glm::dot(p, u_), glm::dot(p, v_));
}

// capBounds_: per UV group, [2 g] = lo and [2 g + 1] = hi of its capped loops' plane coordinates.
void Splitter::capUvBounds(const SplitOptions& options) {
  capBounds_.clear();
  capBounds_.resize(2 * std::max<size_t>(loops_.size(), 1), glm::dvec3(0.0));
  for (size_t g = 0; g < capBounds_.size(); g += 2) {
    capBounds_[g] = glm::dvec3(INFINITY);
    capBounds_[g + 1] = glm::dvec3(-INFINITY);
  }
  for (uint32_t l = 0; l < loops_.size(); ++l) {
    if (!loops_[l].capped) continue;
    const uint32_t g = capUvGroup(options, l);
    for (uint32_t k = loops_[l].begin; k < loops_[l].end; ++k) {
      const glm::dvec2 p = capPlanar(k);
      capBounds_[2 * g] = glm::min(capBounds_[2 * g], glm::dvec3(p, 0.0));
      capBounds_[2 * g + 1] = glm::max(capBounds_[2 * g + 1], glm::dvec3(p, 0.0));
    }
  }
}

// The cap UV of loop point k in UV group g (before the atlas and the above side's mirroring).
glm::dvec2 Splitter::capUv(const SplitOptions& options, uint32_t k, uint32_t g) const {
  const glm::dvec2 p = capPlanar(k);
  if (options.uvMode == CapUvMode::WorldPlanar) return p * options.uvPerMetre;
  const glm::dvec2 lo(capBounds_[2 * g]), hi(capBounds_[2 * g + 1]);
  const glm::dvec2 size = hi - lo;
  return glm::dvec2(size.x > 0.0 ? (p.x - lo.x) / size.x : 0.0, size.y > 0.0 ? (p.y - lo.y) / size.y : 0.0);
}

// The linear part of the map from source to cut space at the donor vertex of a cap vertex: the
// model matrix, times the donor's skinning blend when the container is posed.
glm::dmat3 Splitter::capLinear(bool fromExtra, uint32_t donor) const {
  const MeshData& mesh = *mesh_;
  const glm::dmat3 model3(container_->model());
  const bool skinned = !container_->jointMatrices().empty() && !mesh.joints.empty();
  if (!skinned) return model3;
  const glm::u16vec4 j = fromExtra ? extra_.joints[donor] : mesh.joints[donor];
  const glm::vec4 w = fromExtra ? extra_.weights[donor] : mesh.weights[donor];
  glm::dmat4 blend(0.0);
  double sum = 0.0;
  for (int c = 0; c < 4; ++c) {
    if (w[c] == 0.f || j[c] >= container_->jointMatrices().size()) continue;
    blend += double(w[c]) * container_->jointMatrices()[j[c]];
    sum += w[c];
  }
  return model3 * (sum > 0.0 ? glm::dmat3(blend / sum) : glm::dmat3(1.0));
}

// Cap vertex `at` of loop point k on cap side s (0: the below cap, normal +n; 1: the above cap,
// normal -n, U mirrored): the donor's position, colour and skin, the cap's normal and tangent
// taken back to the source's space, the UV in the atlas.
void Splitter::writeCapVertex(const SplitOptions& options, uint32_t k, int s, size_t at, const glm::dvec2& uv,
                              const CapFrame& frame) {
  const MeshData& mesh = *mesh_;
  const uint32_t welded = loopIds_[k];
  const bool fromExtra = welded >= idCount_;
  const uint32_t donor = fromExtra ? edgeFirstPair_[welded - idCount_] : reps_[welded];
  const glm::dvec3 outward = s == 0 ? normal_ : -normal_;
  const glm::dvec3 tangentCut = s == 0 ? u_ : -u_;
  glm::dvec2 capUv = uv;
  if (s == 1) capUv.x = options.uvMode == CapUvMode::WorldPlanar ? -uv.x : 1.0 - uv.x;
  const glm::dvec2 atlasOrigin(options.atlasRect.x, options.atlasRect.y);
  const glm::dvec2 atlasSize(options.atlasRect.z, options.atlasRect.w);
  const glm::vec2 mapped(atlasOrigin + capUv * atlasSize);
  extra_.positions[at] = fromExtra ? edgeSource_[welded - idCount_] : mesh.positions[donor];
  if (!mesh.normals.empty() || !mesh.tangents.empty()) {
    const glm::dvec3 n = glm::normalize(glm::transpose(frame.linear) * outward);
    if (!mesh.normals.empty()) extra_.normals[at] = glm::vec3(n);
    if (!mesh.tangents.empty()) {
      const glm::dvec3 t = glm::normalize(frame.inverse * tangentCut);
      const glm::dvec3 b = frame.inverse * v_;  // the bitangent: cross(outward, tangentCut) = v on both sides
      const float w = glm::dot(glm::cross(n, t), b) < 0.0 ? -1.f : 1.f;
      extra_.tangents[at] = glm::vec4(glm::vec3(t), w);
    }
  }
  if (!mesh.uv0.empty()) extra_.uv0[at] = mapped;
  if (!mesh.uv1.empty()) extra_.uv1[at] = mapped;
  if (!mesh.colors.empty()) extra_.colors[at] = fromExtra ? extra_.colors[donor] : mesh.colors[donor];
  if (!mesh.joints.empty()) {
    extra_.joints[at] = fromExtra ? extra_.joints[donor] : mesh.joints[donor];
    extra_.weights[at] = fromExtra ? extra_.weights[donor] : mesh.weights[donor];
  }
}

uint32_t Splitter::weldedOfAny(uint32_t ref) const {
  if (ref < capBase_) return weldedOf(ref);
  const uint32_t k = ref - capBase_;
  const uint32_t loopVertices = static_cast<uint32_t>(loopIds_.size());
  return loopIds_[k < loopVertices ? k : k - loopVertices];
}

glm::dvec3 Splitter::cutOfAdded(uint32_t ref) const {
  return ref < capBase_ ? cutOf(ref) : sectionCut(weldedOfAny(ref));
}

// A closed surface component wound inwards (negative volume) is a cavity: it belongs to the
// smallest outward component that encloses it, found by the generalised winding number (the sum of
// the solid angles of that component's triangles, Van Oosterom and Strackee 1983) at one of its
// points. Pieces are renumbered in order of their first triangle. Returns the new piece count.
uint32_t Splitter::mergeCavities(int side, SideWork& w, uint32_t pieces) const {
  const SideList& tris = sideTris_[side];
  bool anyCavity = false;
  for (uint32_t p = 0; p < pieces; ++p) anyCavity = anyCavity || w.volume[p] < 0.0;
  if (!anyCavity) return pieces;
  // Per cavity, one pass over the side: the solid angle of every outward piece at once (each sum in
  // triangle order, as piece by piece), then the smallest enclosing one (the first of equals).
  for (uint32_t p = 0; p < pieces; ++p) {
    if (!(w.volume[p] < 0.0)) continue;
    const glm::dvec3 q = cutOfAny(tris[w.firstTriangle[p]].v[0]);
    w.solidAngle.assign(pieces, 0.0);
    for (size_t k = 0; k < tris.size(); ++k) {
      const uint32_t o = w.pieceOf[k];
      if (!(w.volume[o] > 0.0)) continue;
      const glm::dvec3 a = cutOfAny(tris[k].v[0]) - q, b = cutOfAny(tris[k].v[1]) - q, c = cutOfAny(tris[k].v[2]) - q;
      const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
      const double numerator = glm::dot(a, glm::cross(b, c));
      const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(b, c) * la + glm::dot(c, a) * lb;
      w.solidAngle[o] += 2.0 * std::atan2(numerator, denominator);
    }
    uint32_t best = kNone;
    for (uint32_t o = 0; o < pieces; ++o) {
      const bool encloses = w.volume[o] > 0.0 && w.solidAngle[o] > 2.0 * kPi;  // winding number above 1/2
      if (encloses && (best == kNone || w.volume[o] < w.volume[best])) best = o;
    }
    if (best != kNone) w.pieceMap[p] = best;
  }
  // Resolve chains, then renumber; the reach and bounds of islandStats go with their new groups.
  for (uint32_t p = 0; p < pieces; ++p) {
    uint32_t target = p;
    while (w.pieceMap[target] != target) target = w.pieceMap[target];
    w.firstTriangle[p] = target;  // reused: the surviving piece
  }
  const uint32_t groups = regroup(w, w.firstTriangle, pieces);
  if (w.contactLo.size() == pieces) {
    for (uint32_t p = 0; p < pieces; ++p) {
      const uint32_t root = w.firstTriangle[p];
      if (root == p) continue;
      w.contactReached[root] = w.contactReached[root] || w.contactReached[p];
      w.contactLo[root] = glm::min(w.contactLo[root], w.contactLo[p]);
      w.contactHi[root] = glm::max(w.contactHi[root], w.contactHi[p]);
    }
    // Groups are numbered in order of their root piece: move each root's entry to its number.
    for (uint32_t p = 0; p < pieces; ++p) {
      if (w.firstTriangle[p] != p) continue;
      const uint32_t g = w.groupNumber[p];
      w.contactReached[g] = w.contactReached[p];
      w.contactLo[g] = w.contactLo[p];
      w.contactHi[g] = w.contactHi[p];
    }
    w.contactReached.resize(groups);
    w.contactLo.resize(groups);
    w.contactHi.resize(groups);
  }
  return groups;
}

// One pass over a side's triangles for the passes after labelling: per piece, its signed volume
// (six times, about origin_) and first triangle for mergeCavities (`volumes`), and whether the plane
// reached it and its cut-space bounds for joinTouching (`bounds`; otherwise contactLo is left empty).
void Splitter::islandStats(int side, SideWork& w, uint32_t pieces, bool volumes, bool bounds) const {
  const SideList& tris = sideTris_[side];
  w.volume.assign(pieces, 0.0);
  w.firstTriangle.assign(pieces, kNone);
  w.contactReached.assign(bounds ? pieces : 0, 0);
  w.contactLo.assign(bounds ? pieces : 0, glm::dvec3(INFINITY));
  w.contactHi.assign(bounds ? pieces : 0, glm::dvec3(-INFINITY));
  for (size_t k = 0; k < tris.size(); ++k) {
    const uint32_t p = w.pieceOf[k];
    const glm::dvec3 a = cutOfAny(tris[k].v[0]), b = cutOfAny(tris[k].v[1]), c = cutOfAny(tris[k].v[2]);
    if (volumes) w.volume[p] += glm::dot(a - origin_, glm::cross(b - origin_, c - origin_));
    if (w.firstTriangle[p] == kNone) w.firstTriangle[p] = static_cast<uint32_t>(k);
    if (!bounds) continue;
    w.contactReached[p] = w.contactReached[p] || (tris[k].source & kReachedBit) != 0;
    w.contactLo[p] = glm::min(w.contactLo[p], glm::min(a, glm::min(b, c)));
    w.contactHi[p] = glm::max(w.contactHi[p], glm::max(a, glm::max(b, c)));
  }
}

// Gives every piece of the side being written the number of its group: root[p] is the piece that
// stands for p's group (root[root[p]] == root[p]). Groups are numbered in order of their first
// piece, which keeps the order of first triangle. Updates pieceOf and pieceMap (whose entries
// are pieces of one group each); returns the group count.
uint32_t Splitter::regroup(SideWork& w, std::span<const uint32_t> root, uint32_t pieces) {
  w.groupNumber.assign(pieces, kNone);
  uint32_t count = 0;
  for (uint32_t p = 0; p < pieces; ++p) {
    if (w.groupNumber[root[p]] == kNone) w.groupNumber[root[p]] = count++;
  }
  for (uint32_t& p : w.pieceMap) p = w.groupNumber[root[p]];
  for (uint32_t& p : w.pieceOf) p = w.groupNumber[root[p]];
  return count;
}

// Parts of one side that touch, pass into or hold one another become one piece (island_contacts.h),
// and a part the plane did not reach that touches nothing goes with the piece of its side the plane
// did reach nearest to it (bounding boxes), so that only what the cut separates falls apart. Pieces
// are renumbered in order of first triangle, as before. Returns the new piece count.
uint32_t Splitter::joinTouching(int side, SideWork& w, uint32_t pieces, const SplitOptions& options) const {
  const SideList& tris = sideTris_[side];
  const double tolerance = std::max(options.touchTolerance, 0.0) * container_->boundsDiagonal();
  // Bounds and reach per piece first: pieces whose boxes meet nothing, all reached by the plane (the
  // teeth of a comb cut across), are apart without a look at their triangles.
  // (islandStats and mergeCavities, or writeSide, worked them out, per piece as numbered now.)
  std::vector<uint8_t>& reached = w.contactReached;
  std::vector<glm::dvec3>& lo = w.contactLo;
  std::vector<glm::dvec3>& hi = w.contactHi;
  overlappingBoxes(lo, hi, tolerance, w.contactScratch.pairs, w.contactScratch.byX);
  const bool allReached = std::find(reached.begin(), reached.end(), uint8_t(0)) == reached.end();
  if (w.contactScratch.pairs.empty() && allReached) return pieces;
  w.contactCorners.resize(3 * tris.size());
  for (size_t k = 0; k < tris.size(); ++k) {
    for (int c = 0; c < 3; ++c) w.contactCorners[3 * k + c] = cutOfAny(tris[k].v[c]);
  }
  joinTouchingComponents(w.contactCorners, w.pieceOf, pieces, tolerance, w.contactRoot, w.contactScratch);
  // Per joined group (its root): reached by the plane, and its bounds.
  for (uint32_t p = 0; p < pieces; ++p) {
    const uint32_t g = w.contactRoot[p];
    if (g == p) continue;
    reached[g] = reached[g] || reached[p];
    lo[g] = glm::min(lo[g], lo[p]);
    hi[g] = glm::max(hi[g], hi[p]);
  }
  for (uint32_t g = 0; g < pieces; ++g) {
    if (w.contactRoot[g] != g || reached[g]) continue;
    uint32_t best = kNone;
    double bestGap = INFINITY;
    for (uint32_t r = 0; r < pieces; ++r) {
      if (w.contactRoot[r] != r || !reached[r]) continue;
      const glm::dvec3 gap = glm::max(glm::max(lo[r] - hi[g], lo[g] - hi[r]), glm::dvec3(0.0));
      if (glm::dot(gap, gap) < bestGap) {
        bestGap = glm::dot(gap, gap);
        best = r;
      }
    }
    if (best != kNone) w.contactRoot[g] = best;  // roots stay roots: the reached one is never moved
  }
  bool joined = false;
  for (uint32_t p = 0; p < pieces; ++p) {
    w.contactRoot[p] = w.contactRoot[w.contactRoot[p]];  // through a moved group to its reached piece
    joined = joined || w.contactRoot[p] != p;
  }
  return joined ? regroup(w, w.contactRoot, pieces) : pieces;
}

uint32_t Splitter::find(SideWork& w, uint32_t x) {
  std::vector<uint32_t>& parent = w.parent;
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

// The vertices of a piece, one attribute array at a time, from the source arrays or extra_; and
// their cut-space positions (pieceCut) and its bounds for the mass properties.
void Splitter::gatherVertices(SideWork& w, MeshData& m) const {
  const MeshData& mesh = *mesh_;
  const size_t count = w.vertexCount;
  const uint32_t* refs = w.vertexRefs.data();
  const uint32_t sourceCount = sourceCount_;
  auto gather = [&](auto& out, const auto& source, const auto& extra) {
    if (source.empty()) return;
    assignMapped(out, count, [&](size_t i) {
      const uint32_t ref = refs[i];
      return ref < sourceCount ? source[ref] : extra[ref - sourceCount];
    });
  };
  gatherPositions(w, m.positions);
  gather(m.normals, mesh.normals, extra_.normals);
  gather(m.tangents, mesh.tangents, extra_.tangents);
  gather(m.uv0, mesh.uv0, extra_.uv0);
  gather(m.uv1, mesh.uv1, extra_.uv1);
  gather(m.colors, mesh.colors, extra_.colors);
  gather(m.joints, mesh.joints, extra_.joints);
  gather(m.weights, mesh.weights, extra_.weights);
}

// The piece's float positions and, on the same pass, their cut-space positions (w.pieceCut) and
// bounds. While the cut space is the source space a source vertex's cut position is its float
// position widened, so it is not read twice. The piece's entries of localOf are set back to kNone
// on the way, ready for the next piece.
void Splitter::gatherPositions(SideWork& w, std::vector<glm::vec3>& positions) const {
  const size_t count = w.vertexCount;
  const uint32_t* refs = w.vertexRefs.data();
  const uint32_t sourceCount = sourceCount_;
  const glm::vec3* source = mesh_->positions.data();
  const glm::vec3* extra = extra_.positions.data();
  const bool sourceSpace = cut_.isSource();
  uint32_t* const localOf = w.localOf.data();
  glm::dvec3* const cut = w.pieceCut.place(count);
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  assignMapped(positions, count, [&](size_t i) {
    const uint32_t ref = refs[i];
    localOf[ref] = kNone;
    const glm::vec3 p = ref < sourceCount ? source[ref] : extra[ref - sourceCount];
    const glm::dvec3 q = sourceSpace && ref < sourceCount ? glm::dvec3(p) : cutOfAny(ref);
    cut[i] = q;
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
    return p;
  });
  w.pieceLo = lo;
  w.pieceHi = hi;
}

// The weld of the piece being written: its vertices' welded ids (merged cut points taken to the point
// they were merged into) numbered in order of first vertex. A capped piece of a closed mesh is closed
// on these ids: its side triangles and its cap meet along the section's welded ids.
void Splitter::pieceWeld(SideWork& w, MeshWeld& weld, bool closed) const {
  const size_t count = w.vertexCount;
  const uint32_t* refs = w.vertexRefs.data();
  const uint32_t weldedCount = idCount_ + static_cast<uint32_t>(weldedEdges_.size());
  if (w.weldRemap.size() < weldedCount) w.weldRemap.resize(weldedCount, kNone);
  weld.positionIds.resize(count);
  weld.representatives.clear();
  weld.representatives.reserve(count);  // at most one per vertex
  weld.closed = closed;
  weld.inverted = closed && container_->inverted();  // pieces keep the winding of the mesh
  auto weldedOfPiece = [&](uint32_t i) {
    const uint32_t ref = refs[i];
    return aliasRoot(ref < sourceCount_ ? ids_[ref] : extraWelded_[ref - sourceCount_]);
  };
  uint32_t* const remap = w.weldRemap.data();
  uint32_t* const ids = weld.positionIds.data();
  uint32_t* const weldedOfId = w.weldedOfId.place(count);  // per piece id: its welded id
  std::vector<uint32_t>& representatives = weld.representatives;
  for (uint32_t i = 0; i < count; ++i) {
    const uint32_t welded = weldedOfPiece(i);
    uint32_t& entry = remap[welded];
    if (entry == kNone) {
      entry = static_cast<uint32_t>(representatives.size());
      weldedOfId[entry] = welded;
      representatives.push_back(i);
    }
    ids[i] = entry;
  }
  for (size_t id = 0; id < representatives.size(); ++id) remap[weldedOfId[id]] = kNone;  // ready for the next piece
}

// The union-find of one side's islands over welded ids: every triangle's corners united, or, after
// cutWholeAndCollect united the whole source triangles', only the parts of cut triangles and the
// caps (all triangles the plane reached when some were dropped and the places moved).
void Splitter::uniteSide(int side, SideWork& w, uint32_t weldedCount) {
  const SideList& tris = sideTris_[side];
  const uint32_t first = united_ ? idCount_ : 0;
  w.parent.resize(weldedCount);
  std::iota(w.parent.begin() + first, w.parent.end(), first);
  auto unite = [&](const SideTriangle& tri) {
    uniteCorners(w, weldedRef(tri.v[0]), weldedRef(tri.v[1]), weldedRef(tri.v[2]));
  };
  if (!united_) {
    for (const SideTriangle& tri : tris) unite(tri);
  } else if (dropped_[side]) {
    for (const SideTriangle& tri : tris) {
      if (tri.source & kReachedBit) unite(tri);
    }
  } else {
    for (uint32_t index : cutTris_[side]) unite(tris[index]);
    for (size_t index = capStart_[side]; index < tris.size(); ++index) unite(tris[index]);
  }
}

// Whether every point where the two sides can meet, each cut point (welded crossing edge) and each
// position id on the plane, is a point of some traced loop, on the loops as traced (before near
// points are merged).
bool Splitter::everyJoinOnALoop() {
  const size_t cuts = weldedEdges_.size();
  cutOnLoop_.assign(cuts, 0);
  loopSourceIds_.clear();
  size_t marked = 0;
  for (uint32_t id : loopIds_) {
    if (id < idCount_) {
      loopSourceIds_.push_back(id);
    } else if (!cutOnLoop_[id - idCount_]) {
      cutOnLoop_[id - idCount_] = 1;
      ++marked;
    }
  }
  if (marked != cuts) return false;
  std::sort(loopSourceIds_.begin(), loopSourceIds_.end());
  for (uint32_t id : onPlaneIds_) {
    if (!std::binary_search(loopSourceIds_.begin(), loopSourceIds_.end(), id)) return false;
  }
  return true;
}

// True when the section proves that each side is one island, so that no union-find is needed.
// The mesh is closed and one part (islands are triangles joined through shared welded ids). Then:
//  - the triangles of both sides together are still one part: the parts of a cut triangle share its
//    cut points (and its corner on the plane), and two triangles that shared an id still share it
//    through the parts holding it;
//  - an id used on both sides is a cut point or a position id on the plane (an above triangle has
//    no corner below, nor a below one a corner above), so every island of a side, which must meet
//    the rest through some id, holds one of those;
//  - each of those lies on a loop (everyJoinOnALoop), and each loop is one island of each side:
//    its consecutive points are joined by a boundary edge, which is an edge of a triangle of both
//    sides when the two boundaries agree;
//  - the loops are one island when there is one loop, or when the cap triangles join them all (one
//    border and its holes).
// Nothing may have been dropped as collapsed (a dropped triangle may have joined two parts), and the
// section has no open or bridged chain. The islands found this way are what the union-find finds.
bool Splitter::sectionSettlesIslands() {
  if (!loopsBoundIslands()) return false;
  if (loops_.size() == 1) return true;
  // Loops joined through the cap triangles (points into loopIds_, loop after loop).
  loopOfPoint_.resize(loopIds_.size());
  for (uint32_t l = 0; l < loops_.size(); ++l) {
    std::fill(loopOfPoint_.begin() + loops_[l].begin, loopOfPoint_.begin() + loops_[l].end, l);
  }
  loopParent_.resize(loops_.size());
  std::iota(loopParent_.begin(), loopParent_.end(), 0u);
  auto root = [&](uint32_t l) {
    while (loopParent_[l] != l) l = loopParent_[l] = loopParent_[loopParent_[l]];
    return l;
  };
  uint32_t groups = static_cast<uint32_t>(loops_.size());
  for (size_t k = 0; k + 2 < capTriangles_.size(); k += 3) {
    for (int c = 1; c < 3; ++c) {
      const uint32_t a = root(loopOfPoint_[capTriangles_[k]]), b = root(loopOfPoint_[capTriangles_[k + c]]);
      if (a == b) continue;
      loopParent_[std::max(a, b)] = std::min(a, b);
      --groups;
    }
  }
  return groups == 1;
}

// The conditions under which every island of either side holds a whole loop, and a loop is one
// island of each side (see sectionSettlesIslands): a closed mesh of one part, every point where the
// sides meet on a traced loop, nothing dropped, both sides with the same boundary, closed loops only.
bool Splitter::loopsBoundIslands() const {
  return islandCandidate_ && cutsOnLoops_ && !dropped_[0] && !dropped_[1] && sidesAgree_ && openChains_ == 0 &&
         bridgedChains_ == 0 && chains_.empty() && !loops_.empty();
}

// True when no island of a side can be a cavity (a closed shell wound inwards, inside another one):
// the conditions of sectionSettlesIslands but for the loop count, and every loop capped. Then every
// island holds a loop, whole, and a hole's cap triangles join it to the border around it, so each
// island is the whole surface of a part of the solid, wound outwards.
bool Splitter::sectionRulesOutCavities(const SplitOptions& options) const {
  if (!options.cap || !loopsBoundIslands()) return false;
  return std::all_of(loops_.begin(), loops_.end(), [](const LoopInfo& loop) { return loop.capped; });
}

// Islands of one side: union-find over welded ids (only roots are linked, a parent always has a
// lower id than its child), then cavities into what encloses them (unless `noCavities`: the
// section rules them out) and, with IslandMode::Touching, touching parts joined: here, or after
// the pieces are written when there are no cavities to merge first (w.joinAfterWrite: the writing
// works out each piece's bounds and reach anyway). Fills w.pieceOf (per side triangle; left as it
// was when the side is one piece), w.pieceMap and this side's entries of loopPiece_; returns the
// piece count.
uint32_t Splitter::labelSide(int side, SideWork& w, const SplitOptions& options, bool noCavities, bool knownOne) {
  const SideList& tris = sideTris_[side];
  const uint32_t weldedCount = idCount_ + static_cast<uint32_t>(weldedEdges_.size());
  uint32_t pieces = 0;
  w.searched = options.separateIslands && !oneIslandEach_;
  w.oneIsland = false;
  if (!w.searched) {
    pieces = tris.empty() ? 0 : 1;  // w.pieceOf is not filled: every triangle is in piece 0
  } else if (knownOne && !tris.empty()) {
    w.oneIsland = true;  // the other side's islands prove it (see writePieces)
    pieces = 1;
  } else {
    uniteSide(side, w, weldedCount);
    // One ascending pass points every id at its root, and counts the roots among the ids this side
    // can use (those on its side or on the plane, and the cut points).
    const int8_t otherSide = side == 0 ? -1 : 1;
    uint32_t roots = 0;
    for (uint32_t x = 0; x < weldedCount; ++x) {
      if (x < idCount_ && side_[x] == otherSide) continue;  // not this side's: no triangle of it uses x
      const uint32_t root = w.parent[x] = w.parent[w.parent[x]];
      roots += root == x ? 1u : 0u;
    }
    if (roots == 1 && !tris.empty()) {
      // Every id this side can use is in one island: so is every triangle, and no label is needed.
      w.oneIsland = true;
      pieces = 1;
    } else {
      w.label.assign(weldedCount, kNone);
      w.pieceOf.resize(tris.size());
      for (size_t k = 0; k < tris.size(); ++k) {
        const uint32_t root = w.parent[weldedRef(tris[k].v[0])];
        if (w.label[root] == kNone) w.label[root] = pieces++;
        w.pieceOf[k] = w.label[root];
      }
    }
  }
  w.islands = pieces;
  w.pieceMap.resize(pieces);
  std::iota(w.pieceMap.begin(), w.pieceMap.end(), 0u);
  const bool cavities = options.cap && options.separateIslands && pieces > 1 && !noCavities;
  const bool touching = options.separateIslands && options.islands == IslandMode::Touching && pieces > 1;
  w.joinAfterWrite = touching && !cavities;
  if (cavities || (touching && !w.joinAfterWrite)) islandStats(side, w, pieces, cavities, touching);
  if (cavities) pieces = mergeCavities(side, w, pieces);
  if (touching && !w.joinAfterWrite && pieces > 1) pieces = joinTouching(side, w, pieces, options);
  assignLoops(side, w, pieces);
  return pieces;
}

// This side's entries of loopPiece_ (a loop's cap belongs to the piece of its first vertex) and
// w.partsOf, the islands of each piece for its weld: one where the section settled them, counted
// after a search, not known without one.
void Splitter::assignLoops(int side, SideWork& w, uint32_t pieces) {
  const bool labelled = w.searched && !w.oneIsland;
  for (size_t l = 0; l < loops_.size(); ++l) {
    if (!loops_[l].capped) continue;
    loopPiece_[2 * l + side] = labelled ? w.pieceMap[w.label[find(w, loopIds_[loops_[l].begin])]] : 0;
  }
  w.partsOf.assign(pieces, oneIslandEach_ ? 1u : 0u);
  if (w.searched) {
    for (uint32_t i = 0; i < w.islands; ++i) ++w.partsOf[w.pieceMap[i]];
  }
}

// Output order of one side's triangles: by piece, then output run slot, then as generated (source
// order, then caps). A stable counting sort on (piece, slot); the plain sort only for an extreme
// bucket count; no order at all (w.identity) when the triangles are in that order already (one
// piece of one run, caps last). w.pieceSize gets each piece's triangle count.
void Splitter::orderSide(int side, SideWork& w, uint32_t pieces) const {
  const SideList& tris = sideTris_[side];
  const size_t slots = size_t(std::max(slotCount_, capSlot_)) + 1;
  const size_t buckets = size_t(pieces) * slots;
  w.pieceSize.assign(pieces, 0u);
  // One piece, and the slots ascend along the side list (source runs in order, then the caps in a
  // slot of their own or in the last run's): in order already, no pass needed.
  if (pieces == 1 && capSlot_ + 1 >= slotCount_) {
    w.pieceSize[0] = static_cast<uint32_t>(tris.size());
    w.identity = true;
    return;
  }
  // w.pieceOf is not filled for a side of one piece (labelSide).
  const uint32_t* piece = pieces == 1 ? nullptr : w.pieceOf.data();
  auto keyOf = [&](size_t k) { return size_t(piece ? piece[k] : 0u) * slots + slotOf(tris[k]); };
  // One pass tells whether the keys ascend already and, for the counting sort, counts them.
  const bool counting = buckets <= 4 * tris.size() + 4096;
  if (counting) w.bucket.assign(buckets + 1, 0u);
  bool sorted = true;
  size_t previous = 0;
  for (size_t k = 0; k < tris.size(); ++k) {
    const size_t key = keyOf(k);
    sorted = sorted && previous <= key;
    previous = key;
    ++w.pieceSize[piece ? piece[k] : 0u];
    if (counting) ++w.bucket[key + 1];
  }
  w.identity = sorted;
  if (sorted) return;
  SideTriangle* const ordered = w.ordered.place(tris.size());
  if (counting) {  // the triangles themselves distributed: the writer then reads them in a row
    for (size_t b = 0; b < buckets; ++b) w.bucket[b + 1] += w.bucket[b];
    for (size_t k = 0; k < tris.size(); ++k) ordered[w.bucket[keyOf(k)]++] = tris[k];
    return;
  }
  w.order.resize(tris.size());
  std::iota(w.order.begin(), w.order.end(), 0u);
  std::sort(w.order.begin(), w.order.end(), [&](uint32_t a, uint32_t b) {
    const size_t keyA = keyOf(a), keyB = keyOf(b);
    return keyA != keyB ? keyA < keyB : a < b;
  });
  for (size_t k = 0; k < tris.size(); ++k) ordered[k] = tris[w.order[k]];
}

// The pieceSize[p] triangles of piece p from output position k on: indices through a vertex remap
// (w.localOf), provenance, submesh runs (a run ends where the slot changes). Returns the end.
size_t Splitter::writeTriangles(int side, SideWork& w, size_t k, uint32_t p, const SplitOptions& options,
                                SplitPiece& out) {
  const SideList& tris = sideTris_[side];
  MeshData& m = out.mesh;
  const size_t end = k + w.pieceSize[p];
  m.indices.resize(3 * (end - k));
  out.sourceTriangles.resize(end - k);
  uint32_t* const indices = m.indices.data();
  uint32_t* index = indices;
  uint32_t* provenance = out.sourceTriangles.data();
  const SideTriangle* const list = w.identity ? tris.data() : w.ordered.data();
  uint32_t* const remap = w.localOf.data();
  uint32_t* const refs = w.vertexRefs.place(3 * (end - k));
  uint32_t vertices = 0;
  const int second = mirrored_ ? 2 : 1, third = mirrored_ ? 1 : 2;
  uint32_t slot = kNone, runFirst = 0, reached = 0;
  auto closeRun = [&] {
    uint32_t material = options.capMaterialId;
    if (slot < slotCount_) material = mesh_->submeshes.empty() ? 0u : mesh_->submeshes[slot].materialId;
    const uint32_t count = static_cast<uint32_t>(index - indices) - runFirst;
    m.submeshes.push_back({runFirst, count, material});
    if (slot == capSlot_) out.capTriangles += count / 3;
  };
  for (; k < end; ++k) {
    const SideTriangle& tri = list[k];
    if (const uint32_t triSlot = slotOf(tri); triSlot != slot) {
      if (slot != kNone) closeRun();
      slot = triSlot;
      runFirst = static_cast<uint32_t>(index - indices);
    }
    reached |= tri.source;
    *provenance++ = (tri.source & kCapBit) ? kFromCap | (tri.source & kSourceMask) : tri.source & kSourceMask;
    const uint32_t corner[3] = {tri.v[0], tri.v[second], tri.v[third]};
    // Without a branch (whether a corner is new to the piece does not follow a pattern): the
    // reference is always written past the piece's vertices and only counted when it is new.
    for (uint32_t ref : corner) {
      const uint32_t entry = remap[ref];
      const bool fresh = entry == kNone;
      const uint32_t local = fresh ? vertices : entry;
      remap[ref] = local;
      refs[vertices] = ref;
      vertices += fresh ? 1u : 0u;
      *index++ = local;
    }
  }
  w.vertexCount = vertices;
  if (slot != kNone) closeRun();
  out.reached = (reached & kReachedBit) != 0;
  return end;
}

// Starts piece `out` afresh (its buffers kept). Its indices and provenance keep their size:
// writeTriangles sizes and overwrites them (a clear would make the resize zero them first, a pass
// over memory as large as the piece).
void Splitter::beginPiece(SideWork& w, int side, SplitPiece& out) {
  MeshData& m = out.mesh;
  m.positions.clear();
  m.normals.clear();
  m.tangents.clear();
  m.uv0.clear();
  m.uv1.clear();
  m.colors.clear();
  m.joints.clear();
  m.weights.clear();
  m.submeshes.clear();
  out.side = side == 0 ? 1 : -1;
  out.capTriangles = 0;
  out.capLoops = 0;
  out.reached = false;
  out.mass = MassProperties{};
  w.vertexCount = 0;
}

// Mass properties of the piece just written, on its cut-space positions; a closed piece's winding.
void Splitter::pieceMass(SideWork& w, SplitPiece& out) const {
  const MeshData& m = out.mesh;
  const std::span<const glm::dvec3> pieceCut(w.pieceCut.data(), w.vertexCount);
  if (piecesClosed_) {
    out.mass = detail::integrateWrittenSurface(pieceCut, m.indices, mirrored_, w.pieceLo, w.pieceHi);
  } else {
    std::span<const uint32_t> indices = m.indices;
    if (mirrored_) {
      w.flipped.assign(m.indices.begin(), m.indices.end());
      for (size_t t = 0; t + 2 < w.flipped.size(); t += 3) std::swap(w.flipped[t + 1], w.flipped[t + 2]);
      indices = w.flipped;
    }
    out.mass = computeMassProperties(pieceCut, indices);
  }
  // A closed piece is wound like its source unless its volume says otherwise (a shell of a
  // mesh whose other shells outweigh it in the other direction).
  if (out.weld.closed) {
    out.weld.inverted = container_->inverted() ? out.mass.volume > 0.0 : out.mass.volume < 0.0;
  }
}

// The pieces of one side, numbered from `firstPiece` in result.pieces (sized already).
void Splitter::writeSide(int side, SideWork& w, uint32_t pieces, uint32_t firstPiece, bool weldKnown,
                         const SplitOptions& options, SplitResult& result) {
  const uint32_t refCount = capBase_ + 2 * static_cast<uint32_t>(loopIds_.size());
  if (w.localOf.size() < refCount) w.localOf.resize(refCount, kNone);
  orderSide(side, w, pieces);
  size_t k = 0;
  for (uint32_t p = 0; p < pieces; ++p) {
    SplitPiece& out = result.pieces[firstPiece + p];
    beginPiece(w, side, out);
    k = writeTriangles(side, w, k, p, options, out);
    gatherVertices(w, out.mesh);
    if (weldKnown) {
      pieceWeld(w, out.weld, piecesClosed_);
      out.weld.connected = w.partsOf[p] == 1;
    } else {
      out.weld.positionIds.clear();
      out.weld.representatives.clear();
      out.weld.closed = out.weld.inverted = out.weld.connected = false;
    }
    for (size_t l = 0; l < loops_.size(); ++l) {
      if (loops_[l].capped && loopPiece_[2 * l + side] == p) ++out.capLoops;
    }
    collectUsedJoints(out.mesh, out.joints);
    if (options.computeMass) pieceMass(w, out);
    if (w.joinAfterWrite) {  // what islandStats would give: the bounds of its corners, its reach
      w.contactLo[p] = w.pieceLo;
      w.contactHi[p] = w.pieceHi;
      w.contactReached[p] = out.reached ? 1 : 0;
    }
  }
}

// The pieces of one side; with w.joinAfterWrite, then parts that touch joined and, if any were,
// the side written again as fewer pieces (from firstPiece on still). Returns the piece count.
uint32_t Splitter::writeAndJoin(int side, uint32_t pieces, uint32_t firstPiece, bool weldKnown,
                                const SplitOptions& options, SplitResult& result) {
  SideWork& w = work_[side];
  if (w.joinAfterWrite) {
    w.contactLo.resize(pieces);
    w.contactHi.resize(pieces);
    w.contactReached.resize(pieces);
  }
  writeSide(side, w, pieces, firstPiece, weldKnown, options, result);
  if (!w.joinAfterWrite) return pieces;
  w.joinAfterWrite = false;
  const uint32_t joined = joinTouching(side, w, pieces, options);
  if (joined == pieces) return pieces;
  assignLoops(side, w, joined);
  writeSide(side, w, joined, firstPiece, weldKnown, options, result);
  return joined;
}

// Both sides: islands, then the pieces. With threads > 1 on a big mesh the two sides run at once,
// each on scratch of its own (work_[side]); nothing they write is shared but distinct entries of
// loopPiece_ and of result.pieces, so the output is the same bytes either way.
void Splitter::writePieces(const SplitOptions& options, SplitResult& result) {
  const uint32_t loopVertices = static_cast<uint32_t>(loopIds_.size());
  const uint32_t refCount = capBase_ + 2 * loopVertices;
  // Welded ids by vertex reference past the source: a table (source vertices use the container's).
  extraWelded_.resize(refCount - sourceCount_);
  for (uint32_t ref = sourceCount_; ref < refCount; ++ref) extraWelded_[ref - sourceCount_] = weldedOfAny(ref);
  // A degenerate section loop (no area) is left uncapped: the pieces along it may then be open on
  // their ids, which the split does not work out. Their weld is left unknown (empty), so a next cut
  // welds them from nothing.
  bool weldKnown = true;
  for (const LoopInfo& loop : loops_) weldKnown = weldKnown && (!options.cap || loop.capped);
  loopPiece_.assign(2 * loops_.size(), 0);
  bool wanted[2];
  for (int side = 0; side < 2; ++side) {
    wanted[side] = options.keepSide == 0 || options.keepSide == (side == 0 ? 1 : -1);
  }
  const bool parallel = threads_ > 1 && wanted[0] && wanted[1] &&
                        sideTris_[0].size() + sideTris_[1].size() >= kParallelTriangles;
  oneIslandEach_ = sectionSettlesIslands();
  result.islandsFromSection = oneIslandEach_;
  const bool noCavities = sectionRulesOutCavities(options);
  uint32_t pieces[2] = {0, 0};
  if (parallel || !wanted[0] || !wanted[1]) {
    bothSides(parallel, [&](int side) {
      if (wanted[side]) pieces[side] = labelSide(side, work_[side], options, noCavities, false);
    });
  } else {
    // The smaller side first. Islands of the two sides joined by the loops they share (each loop one
    // island of each side, each island at least one loop: loopsBoundIslands) make a connected graph
    // of as many edges as loops, since the mesh is one part: islands(small) + islands(big) <= loops
    // + 1. So when every loop has an island of its own on the smaller side, the bigger side is one
    // island, found without a search (the union-find would find the same).
    const int small = sideTris_[0].size() <= sideTris_[1].size() ? 0 : 1;
    pieces[small] = labelSide(small, work_[small], options, noCavities, false);
    const bool bigIsOne = loopsBoundIslands() && work_[small].searched && work_[small].islands == loops_.size();
    pieces[1 - small] = labelSide(1 - small, work_[1 - small], options, noCavities, bigIsOne);
    result.islandFromLoops = bigIsOne && !sideTris_[1 - small].empty();  // labelSide took it as shown
  }
  // Each side in its own range; a side that joined touching parts after writing them ends short of
  // its range, and the pieces above are then moved down over the gap.
  const uint32_t firstBelow = pieces[0];
  preparePieces(result, size_t(pieces[0]) + pieces[1]);
  bothSides(parallel, [&](int side) {
    if (pieces[side] == 0) return;
    pieces[side] = writeAndJoin(side, pieces[side], side == 0 ? 0u : firstBelow, weldKnown, options, result);
  });
  if (pieces[0] < firstBelow) {
    for (uint32_t p = 0; p < pieces[1]; ++p) std::swap(result.pieces[pieces[0] + p], result.pieces[firstBelow + p]);
  }
  preparePieces(result, size_t(pieces[0]) + pieces[1]);
}

}  // namespace

std::unique_ptr<IMeshSplitter> makeConcaveSplitter() { return std::make_unique<Splitter>(false); }

SplitResult splitMesh(const MeshData& mesh, const glm::mat4& model, const Plane& plane, const SplitOptions& options) {
  SplitResult result;
  MeshContainer container;
  if (MeshStatus set = container.setMesh(mesh); !set.ok()) {
    result.status = SplitStatus::InvalidInput;
    result.message = std::move(set.message);
    return result;
  }
  container.setTransform(model);
  Splitter splitter(false);
  splitter.split(container, plane, options, result);
  return result;
}
std::unique_ptr<IMeshSplitter> makeConvexSplitter() { return std::make_unique<Splitter>(true); }

}  // namespace cleave::geometry
