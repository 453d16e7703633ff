// SPDX-License-Identifier: MIT
// Cap triangulation: ear clipping of polygons with holes.
//
// Method. The holes are bridged into the outer ring one by one, leftmost first, with David Eberly's
// bridge search ("Triangulation by Ear Clipping", 2002): a ray from the hole's leftmost point to the
// left finds the nearest outer edge; the bridge goes to that edge's visible end point or, when reflex
// vertices hide it, to the reflex vertex of smallest angle with the ray. The single ring that results
// is clipped ear by ear; rings over 80 points index their nodes along a z-order (Morton) curve so an
// ear test only visits the points inside the ear's bounding box. The shape of the algorithm, its
// repair passes and its predicates follow mapbox's earcut, written anew here for index-linked nodes
// and for one difference that matters for a mesh cap: no point is ever dropped. Collinear and
// duplicate points are taken out before clipping and fanned back into the triangle holding their
// edge afterwards; degenerate ears found while clipping are clipped as zero-area triangles rather
// than removed, so every ring edge stays in the output and the cap meets the side triangles edge to
// edge. A final area check (the unsigned triangle areas must add up to the polygon area) turns any
// overlap or gap into a failure instead of a wrong cap.
#include "cleave/geometry/cap_triangulator.h"

#include <algorithm>
#include <cmath>

namespace cleave::geometry {

namespace {

// Relative threshold under which three points count as collinear: |cross| <= k * length^2.
constexpr double kCollinear = 1e-12;

bool pointInTriangleXY(double ax, double ay, double bx, double by, double cx, double cy, double px,
                       double py) {
  return (cx - px) * (ay - py) >= (ax - px) * (cy - py) &&
         (ax - px) * (by - py) >= (bx - px) * (ay - py) &&
         (bx - px) * (cy - py) >= (cx - px) * (by - py);
}

bool collinearForward(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  const glm::dvec2 u = b - a, v = c - b;
  const double cross = u.x * v.y - u.y * v.x;
  const double len = std::abs(u.x) + std::abs(u.y) + std::abs(v.x) + std::abs(v.y);
  return std::abs(cross) <= kCollinear * len * len && glm::dot(u, v) >= 0.0;
}

// Squared distance from p to the segment [a, c].
double segmentDistance2(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& c) {
  const glm::dvec2 d = c - a, w = p - a;
  const double len2 = glm::dot(d, d);
  const double t = len2 > 0.0 ? std::clamp(glm::dot(w, d) / len2, 0.0, 1.0) : 0.0;
  const glm::dvec2 e = w - t * d;
  return glm::dot(e, e);
}

}  // namespace

bool CapTriangulator::ringContains(std::span<const glm::dvec2> points, CapRing ring, const glm::dvec2& q) {
  bool inside = false;
  for (uint32_t i = ring.begin, j = ring.end - 1; i < ring.end; j = i++) {
    const glm::dvec2 a = points[i], b = points[j];
    if ((a.y > q.y) != (b.y > q.y) && q.x < (b.x - a.x) * (q.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
  }
  return inside;
}

double CapTriangulator::twiceSignedArea(std::span<const glm::dvec2> points, CapRing ring) {
  double sum = 0.0;
  if (ring.end <= ring.begin) return 0.0;
  const glm::dvec2 o = points[ring.begin];
  for (uint32_t i = ring.begin; i < ring.end; ++i) {
    const uint32_t j = i + 1 == ring.end ? ring.begin : i + 1;
    const glm::dvec2 a = points[i] - o, b = points[j] - o;
    sum += a.x * b.y - a.y * b.x;
  }
  return sum;
}

// True when every point strictly between a and c along the ring lies within the tolerance of the
// segment [a, c]: hiding them all behind that segment moves the boundary by no more than that.
bool CapTriangulator::hiddenFit(std::span<const glm::dvec2> points, uint32_t a, uint32_t c) const {
  const double tolerance2 = tolerance_ * tolerance_;
  for (uint32_t m = nextPoint_[a]; m != c; m = nextPoint_[m]) {
    if (segmentDistance2(points[m], points[a], points[c]) > tolerance2) return false;
  }
  return true;
}

// Marks the points of a ring that are not corners (kept_ = 0) and links the rest (nextKept_). A
// point is not a corner when it is collinear with its neighbours, or when it and every point hidden
// before it lie within the tolerance of the segment joining the neighbouring corners: rounding
// leaves runs of nearly collinear points that zig-zag by a few ulps, and near-coincident points whose
// order along the run is reversed, so the exact ring can overlap itself at the scale of the rounding.
// Those points are not dropped: finish() fans them back in.
void CapTriangulator::prepareRing(std::span<const glm::dvec2> points, CapRing ring) {
  const uint32_t n = ring.end - ring.begin;
  for (uint32_t i = ring.begin; i < ring.end; ++i) {
    kept_[i] = 1;
    nextPoint_[i] = i + 1 == ring.end ? ring.begin : i + 1;
    ringNext_[i] = static_cast<int32_t>(nextPoint_[i]);
    ringPrev_[i] = static_cast<int32_t>(i == ring.begin ? ring.end - 1 : i - 1);
  }
  const double tolerance2 = tolerance_ * tolerance_;
  uint32_t count = n;
  uint32_t start = ring.begin;
  bool changed = true;
  while (changed && count > 3) {
    changed = false;
    uint32_t p = start;
    const uint32_t steps = count;
    for (uint32_t s = 0; s < steps && count > 3; ++s) {
      const uint32_t a = static_cast<uint32_t>(ringPrev_[p]);
      const uint32_t c = static_cast<uint32_t>(ringNext_[p]);
      const bool hide = collinearForward(points[a], points[p], points[c]) ||
                        (tolerance2 > 0.0 && segmentDistance2(points[p], points[a], points[c]) <= tolerance2 &&
                         hiddenFit(points, a, c));
      if (hide) {
        kept_[p] = 0;
        ringNext_[a] = static_cast<int32_t>(c);
        ringPrev_[c] = static_cast<int32_t>(a);
        if (p == start) start = c;
        --count;
        changed = true;
      }
      p = c;
    }
  }
  uint32_t p = start;
  for (uint32_t s = 0; s < count; ++s) {
    nextKept_[p] = static_cast<uint32_t>(ringNext_[p]);
    p = nextKept_[p];
  }
}

int32_t CapTriangulator::newNode(uint32_t i) {
  Node node;
  node.i = i;
  node.x = points_[i].x;
  node.y = points_[i].y;
  nodes_.push_back(node);
  const int32_t id = static_cast<int32_t>(nodes_.size() - 1);
  nodes_[id].prev = nodes_[id].next = id;
  return id;
}

// Links the kept points of a ring into a circular node list; returns one node of it (or -1).
int32_t CapTriangulator::linkKept(CapRing ring) {
  uint32_t first = ring.begin;
  while (first < ring.end && !kept_[first]) ++first;
  if (first == ring.end) return -1;
  int32_t head = -1, last = -1;
  uint32_t p = first;
  do {
    const int32_t id = newNode(p);
    if (last < 0) {
      head = id;
    } else {
      nodes_[id].prev = last;
      nodes_[id].next = head;
      nodes_[last].next = id;
      nodes_[head].prev = id;
    }
    last = id;
    p = nextKept_[p];
  } while (p != first);
  return head;
}

void CapTriangulator::removeNode(int32_t p) {
  Node& n = nodes_[p];
  nodes_[n.next].prev = n.prev;
  nodes_[n.prev].next = n.next;
  if (n.prevZ >= 0) nodes_[n.prevZ].nextZ = n.nextZ;
  if (n.nextZ >= 0) nodes_[n.nextZ].prevZ = n.prevZ;
}

// Twice the signed area of the turn p -> q -> r: positive for a left (convex) turn.
double CapTriangulator::area(int32_t p, int32_t q, int32_t r) const {
  const Node &a = nodes_[p], &b = nodes_[q], &c = nodes_[r];
  return (b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x);
}

bool CapTriangulator::equals(int32_t a, int32_t b) const {
  return nodes_[a].x == nodes_[b].x && nodes_[a].y == nodes_[b].y;
}

bool CapTriangulator::pointInTriangle(int32_t a, int32_t b, int32_t c, int32_t p) const {
  const Node &na = nodes_[a], &nb = nodes_[b], &nc = nodes_[c], &np = nodes_[p];
  return pointInTriangleXY(na.x, na.y, nb.x, nb.y, nc.x, nc.y, np.x, np.y);
}

// A reflex or flat point inside the candidate ear (other than a copy of its first corner) blocks it.
bool CapTriangulator::blocksEar(int32_t a, int32_t b, int32_t c, int32_t p) const {
  if (p == a || p == b || p == c) return false;
  const Node& np = nodes_[p];
  const Node &na = nodes_[a], &nb = nodes_[b], &nc = nodes_[c];
  const double x0 = std::min({na.x, nb.x, nc.x}), x1 = std::max({na.x, nb.x, nc.x});
  const double y0 = std::min({na.y, nb.y, nc.y}), y1 = std::max({na.y, nb.y, nc.y});
  if (np.x < x0 || np.x > x1 || np.y < y0 || np.y > y1) return false;
  if (np.x == na.x && np.y == na.y) return false;
  return pointInTriangle(a, b, c, p) && area(np.prev, p, np.next) <= 0.0;
}

bool CapTriangulator::isEar(int32_t ear) const {
  const int32_t a = nodes_[ear].prev, c = nodes_[ear].next;
  if (area(a, ear, c) <= 0.0) return false;
  for (int32_t p = nodes_[c].next; p != a; p = nodes_[p].next) {
    if (blocksEar(a, ear, c, p)) return false;
  }
  return true;
}

bool CapTriangulator::isEarHashed(int32_t ear) const {
  const int32_t a = nodes_[ear].prev, c = nodes_[ear].next;
  if (area(a, ear, c) <= 0.0) return false;
  const Node &na = nodes_[a], &nb = nodes_[ear], &nc = nodes_[c];
  const uint32_t minZ = zOrder(std::min({na.x, nb.x, nc.x}), std::min({na.y, nb.y, nc.y}));
  const uint32_t maxZ = zOrder(std::max({na.x, nb.x, nc.x}), std::max({na.y, nb.y, nc.y}));
  int32_t p = nb.prevZ, n = nb.nextZ;
  while (p >= 0 && nodes_[p].z >= minZ && n >= 0 && nodes_[n].z <= maxZ) {
    if (blocksEar(a, ear, c, p)) return false;
    p = nodes_[p].prevZ;
    if (blocksEar(a, ear, c, n)) return false;
    n = nodes_[n].nextZ;
  }
  while (p >= 0 && nodes_[p].z >= minZ) {
    if (blocksEar(a, ear, c, p)) return false;
    p = nodes_[p].prevZ;
  }
  while (n >= 0 && nodes_[n].z <= maxZ) {
    if (blocksEar(a, ear, c, n)) return false;
    n = nodes_[n].nextZ;
  }
  return true;
}

void CapTriangulator::emit(int32_t a, int32_t b, int32_t c) {
  raw_.push_back(nodes_[a].i);
  raw_.push_back(nodes_[b].i);
  raw_.push_back(nodes_[c].i);
}

// An ear whose tip lies within the tolerance of the segment joining its neighbours, in a polygon of
// more than three corners: clipped, it would be a sliver (three points that are collinear up to
// the rounding of the section, as where earlier clips leave several points of one straight edge of
// the section next to each other). Written as float, such a triangle has zero area.
bool CapTriangulator::sliver(int32_t a, int32_t b, int32_t c) const {
  if (!(tolerance_ > 0.0) || nodes_[c].next == a) return false;
  const glm::dvec2 pa(nodes_[a].x, nodes_[a].y), pb(nodes_[b].x, nodes_[b].y), pc(nodes_[c].x, nodes_[c].y);
  return segmentDistance2(pb, pa, pc) <= tolerance_ * tolerance_;
}

// Takes b off the polygon without a triangle: the triangle that later gets edge a -> c is split at b.
void CapTriangulator::hide(int32_t a, int32_t b, int32_t c) {
  hidden_.push_back({(uint64_t(nodes_[a].i) << 32) | nodes_[c].i, nodes_[b].i});
  removeNode(b);
}

void CapTriangulator::earcutLinked(int32_t ear, int pass) {
  if (ear < 0) return;
  if (pass == 0 && hashed_) indexCurve(ear);
  int32_t stop = ear;
  while (nodes_[ear].prev != nodes_[ear].next) {
    const int32_t prev = nodes_[ear].prev, next = nodes_[ear].next;
    if (hashed_ ? isEarHashed(ear) : isEar(ear)) {
      if (sliver(prev, ear, next)) {  // the point before may now be one too: look at it again
        hide(prev, ear, next);
        ear = stop = prev;
        continue;
      }
      emit(prev, ear, next);
      removeNode(ear);
      // Skipping the next point gives fewer sliver triangles.
      ear = nodes_[next].next;
      stop = ear;
      continue;
    }
    ear = next;
    if (ear == stop) {  // a whole turn without an ear: repair and go on
      if (pass == 0) {
        earcutLinked(clipDegenerate(ear), 1);
      } else if (pass == 1) {
        earcutLinked(cureLocalIntersections(clipDegenerate(ear)), 2);
      } else {
        splitEarcut(ear);
      }
      break;
    }
  }
}

// Clips zero-area corners (duplicate or collinear points left by bridging) as zero-area triangles,
// which keeps every ring edge in the output. Returns a node of what is left.
int32_t CapTriangulator::clipDegenerate(int32_t start) {
  if (start < 0) return start;
  int32_t p = start, end = start;
  bool again;
  do {
    again = false;
    const int32_t prev = nodes_[p].prev, next = nodes_[p].next;
    if (prev == next) break;
    if (equals(p, next) || area(prev, p, next) == 0.0) {
      const glm::dvec2 a(nodes_[prev].x, nodes_[prev].y), b(nodes_[p].x, nodes_[p].y), c(nodes_[next].x, nodes_[next].y);
      if (!equals(p, next) && nodes_[next].next != prev && collinearForward(a, b, c)) {
        hide(prev, p, next);  // a straight corner: fanned back in, never a zero-area triangle
      } else {
        emit(prev, p, next);
        removeNode(p);
      }
      p = end = prev;
      if (nodes_[p].next == nodes_[p].prev) break;
      again = true;
    } else {
      p = next;
    }
  } while (again || p != end);
  return end;
}

// Clips a -> p -> p.next -> b where the ring crosses itself locally (a and b see each other).
int32_t CapTriangulator::cureLocalIntersections(int32_t start) {
  if (start < 0) return start;
  int32_t p = start;
  do {
    const int32_t a = nodes_[p].prev, b = nodes_[nodes_[p].next].next;
    if (nodes_[p].next == nodes_[p].prev) break;
    if (!equals(a, b) && intersects(a, p, nodes_[p].next, b) && locallyInside(a, b) &&
        locallyInside(b, a)) {
      emit(a, p, b);
      const int32_t pn = nodes_[p].next;
      removeNode(p);
      removeNode(pn);
      p = start = b;
    }
    p = nodes_[p].next;
  } while (p != start);
  return clipDegenerate(p);
}

// Last resort: split the ring along a valid diagonal and clip both halves.
void CapTriangulator::splitEarcut(int32_t start) {
  int32_t a = start;
  do {
    int32_t b = nodes_[nodes_[a].next].next;
    while (b != nodes_[a].prev) {
      if (nodes_[a].i != nodes_[b].i && isValidDiagonal(a, b)) {
        const int32_t c = splitPolygon(a, b);
        earcutLinked(a, 0);
        earcutLinked(c, 0);
        return;
      }
      b = nodes_[b].next;
    }
    a = nodes_[a].next;
  } while (a != start);
}

int32_t CapTriangulator::eliminateHoles(std::span<const CapRing> rings, int32_t outer) {
  holeQueue_.clear();
  for (size_t k = 1; k < rings.size(); ++k) {
    const int32_t list = linkKept(rings[k]);
    if (list >= 0) holeQueue_.push_back(leftmost(list));
  }
  std::sort(holeQueue_.begin(), holeQueue_.end(), [&](int32_t a, int32_t b) {
    const Node &na = nodes_[a], &nb = nodes_[b];
    if (na.x != nb.x) return na.x < nb.x;
    if (na.y != nb.y) return na.y < nb.y;
    return a < b;
  });
  for (int32_t hole : holeQueue_) {
    const int32_t bridge = findHoleBridge(hole, outer);
    if (bridge < 0) continue;  // leaves a gap: the area check reports it
    splitPolygon(bridge, hole);
  }
  return outer;
}

// Eberly's bridge: the outer node that the hole's leftmost node can see.
int32_t CapTriangulator::findHoleBridge(int32_t hole, int32_t outer) const {
  const double hx = nodes_[hole].x, hy = nodes_[hole].y;
  double qx = -INFINITY;
  int32_t m = -1;
  int32_t p = outer;
  do {
    const Node& np = nodes_[p];
    const Node& nn = nodes_[np.next];
    if (equals(hole, p)) return p;
    if (hy <= np.y && hy >= nn.y && nn.y != np.y) {
      const double x = np.x + (hy - np.y) * (nn.x - np.x) / (nn.y - np.y);
      if (x <= hx && x > qx) {
        qx = x;
        m = np.x < nn.x ? p : np.next;
        if (x == hx) return m;  // the hole touches this edge
      }
    }
    p = np.next;
  } while (p != outer);
  if (m < 0) return -1;

  // Reflex points inside the triangle (hole point, ray hit, m) hide m: take the one closest in angle.
  const int32_t stop = m;
  const double mx = nodes_[m].x, my = nodes_[m].y;
  double tanMin = INFINITY;
  p = m;
  do {
    const Node& np = nodes_[p];
    if (hx >= np.x && np.x >= mx && hx != np.x &&
        pointInTriangleXY(hy < my ? hx : qx, hy, mx, my, hy < my ? qx : hx, hy, np.x, np.y)) {
      const double tan = std::abs(hy - np.y) / (hx - np.x);
      if (locallyInside(p, hole) &&
          (tan < tanMin ||
           (tan == tanMin && (np.x > nodes_[m].x || (np.x == nodes_[m].x && sectorContainsSector(m, p)))))) {
        m = p;
        tanMin = tan;
      }
    }
    p = np.next;
  } while (p != stop);
  return m;
}

bool CapTriangulator::sectorContainsSector(int32_t m, int32_t p) const {
  return area(nodes_[m].prev, m, nodes_[p].prev) > 0.0 && area(nodes_[p].next, m, nodes_[m].next) > 0.0;
}

// Links a and b by a two-way bridge (copies of both); returns the copy of b.
int32_t CapTriangulator::splitPolygon(int32_t a, int32_t b) {
  const int32_t a2 = newNode(nodes_[a].i);
  const int32_t b2 = newNode(nodes_[b].i);
  const int32_t an = nodes_[a].next, bp = nodes_[b].prev;
  nodes_[a].next = b;
  nodes_[b].prev = a;
  nodes_[a2].next = an;
  nodes_[an].prev = a2;
  nodes_[b2].next = a2;
  nodes_[a2].prev = b2;
  nodes_[bp].next = b2;
  nodes_[b2].prev = bp;
  return b2;
}

bool CapTriangulator::onSegment(int32_t p, int32_t q, int32_t r) const {
  const Node &np = nodes_[p], &nq = nodes_[q], &nr = nodes_[r];
  return nq.x <= std::max(np.x, nr.x) && nq.x >= std::min(np.x, nr.x) && nq.y <= std::max(np.y, nr.y) &&
         nq.y >= std::min(np.y, nr.y);
}

bool CapTriangulator::intersects(int32_t p1, int32_t q1, int32_t p2, int32_t q2) const {
  auto sign = [](double v) { return v > 0.0 ? 1 : v < 0.0 ? -1 : 0; };
  const int o1 = sign(area(p1, q1, p2)), o2 = sign(area(p1, q1, q2));
  const int o3 = sign(area(p2, q2, p1)), o4 = sign(area(p2, q2, q1));
  if (o1 != o2 && o3 != o4) return true;
  if (o1 == 0 && onSegment(p1, p2, q1)) return true;
  if (o2 == 0 && onSegment(p1, q2, q1)) return true;
  if (o3 == 0 && onSegment(p2, p1, q2)) return true;
  if (o4 == 0 && onSegment(p2, q1, q2)) return true;
  return false;
}

bool CapTriangulator::intersectsPolygon(int32_t a, int32_t b) const {
  int32_t p = a;
  do {
    const int32_t pn = nodes_[p].next;
    const uint32_t ia = nodes_[a].i, ib = nodes_[b].i;
    if (nodes_[p].i != ia && nodes_[pn].i != ia && nodes_[p].i != ib && nodes_[pn].i != ib &&
        intersects(p, pn, a, b)) {
      return true;
    }
    p = pn;
  } while (p != a);
  return false;
}

bool CapTriangulator::locallyInside(int32_t a, int32_t b) const {
  const int32_t prev = nodes_[a].prev, next = nodes_[a].next;
  return area(prev, a, next) > 0.0 ? area(a, b, next) <= 0.0 && area(a, prev, b) <= 0.0
                                   : area(a, b, prev) > 0.0 || area(a, next, b) > 0.0;
}

bool CapTriangulator::middleInside(int32_t a, int32_t b) const {
  bool inside = false;
  const double px = 0.5 * (nodes_[a].x + nodes_[b].x), py = 0.5 * (nodes_[a].y + nodes_[b].y);
  int32_t p = a;
  do {
    const Node& np = nodes_[p];
    const Node& nn = nodes_[np.next];
    if ((np.y > py) != (nn.y > py) && nn.y != np.y &&
        px < (nn.x - np.x) * (py - np.y) / (nn.y - np.y) + np.x) {
      inside = !inside;
    }
    p = np.next;
  } while (p != a);
  return inside;
}

bool CapTriangulator::isValidDiagonal(int32_t a, int32_t b) const {
  const Node &na = nodes_[a], &nb = nodes_[b];
  if (nodes_[na.next].i == nb.i || nodes_[na.prev].i == nb.i || intersectsPolygon(a, b)) return false;
  if (locallyInside(a, b) && locallyInside(b, a) && middleInside(a, b) &&
      (area(na.prev, a, nb.prev) != 0.0 || area(a, nb.prev, b) != 0.0)) {
    return true;
  }
  return equals(a, b) && area(na.prev, a, na.next) < 0.0 && area(nb.prev, b, nb.next) < 0.0;
}

int32_t CapTriangulator::leftmost(int32_t start) const {
  int32_t p = start, best = start;
  do {
    const Node &np = nodes_[p], &nb = nodes_[best];
    if (np.x < nb.x || (np.x == nb.x && np.y < nb.y)) best = p;
    p = np.next;
  } while (p != start);
  return best;
}

uint32_t CapTriangulator::zOrder(double px, double py) const {
  const double fx = std::clamp((px - minX_) * invSize_, 0.0, 32767.0);
  const double fy = std::clamp((py - minY_) * invSize_, 0.0, 32767.0);
  uint32_t x = static_cast<uint32_t>(fx), y = static_cast<uint32_t>(fy);
  x = (x | (x << 8)) & 0x00FF00FFu;
  x = (x | (x << 4)) & 0x0F0F0F0Fu;
  x = (x | (x << 2)) & 0x33333333u;
  x = (x | (x << 1)) & 0x55555555u;
  y = (y | (y << 8)) & 0x00FF00FFu;
  y = (y | (y << 4)) & 0x0F0F0F0Fu;
  y = (y | (y << 2)) & 0x33333333u;
  y = (y | (y << 1)) & 0x55555555u;
  return x | (y << 1);
}

void CapTriangulator::indexCurve(int32_t start) {
  int32_t p = start;
  do {
    Node& n = nodes_[p];
    n.z = zOrder(n.x, n.y);
    n.prevZ = n.prev;
    n.nextZ = n.next;
    p = n.next;
  } while (p != start);
  nodes_[nodes_[p].prevZ].nextZ = -1;
  nodes_[p].prevZ = -1;
  sortLinked(p);
}

// Simon Tatham's merge sort of a linked list, on the z-order links.
void CapTriangulator::sortLinked(int32_t list) {
  int inSize = 1;
  int numMerges;
  do {
    int32_t p = list;
    list = -1;
    int32_t tail = -1;
    numMerges = 0;
    while (p >= 0) {
      ++numMerges;
      int32_t q = p;
      int pSize = 0;
      for (int i = 0; i < inSize; ++i) {
        ++pSize;
        q = nodes_[q].nextZ;
        if (q < 0) break;
      }
      int qSize = inSize;
      while (pSize > 0 || (qSize > 0 && q >= 0)) {
        int32_t e;
        if (pSize != 0 && (qSize == 0 || q < 0 || nodes_[p].z <= nodes_[q].z)) {
          e = p;
          p = nodes_[p].nextZ;
          --pSize;
        } else {
          e = q;
          q = nodes_[q].nextZ;
          --qSize;
        }
        if (tail >= 0) {
          nodes_[tail].nextZ = e;
        } else {
          list = e;
        }
        nodes_[e].prevZ = tail;
        tail = e;
      }
      p = q;
    }
    nodes_[tail].nextZ = -1;
    inSize *= 2;
  } while (numMerges > 1);
}

bool CapTriangulator::triangulate(std::span<const glm::dvec2> points, std::span<const CapRing> rings,
                                  std::vector<uint32_t>& triangles, double tolerance) {
  const size_t outputStart = triangles.size();
  tolerance_ = tolerance > 0.0 && std::isfinite(tolerance) ? tolerance : 0.0;
  strict_ = false;
  if (rings.empty()) return false;
  if (kept_.size() < points.size()) {
    kept_.resize(points.size());
    nextPoint_.resize(points.size());
    nextKept_.resize(points.size());
    ringPrev_.resize(points.size());
    ringNext_.resize(points.size());
  }
  points_ = points;
  nodes_.clear();
  raw_.clear();
  hidden_.clear();
  for (const CapRing& ring : rings) {
    if (ring.end < ring.begin + 3 || ring.end > points.size()) return false;
    prepareRing(points, ring);
  }
  int32_t outer = linkKept(rings[0]);
  if (outer < 0) return false;
  const size_t outerNodes = nodes_.size();
  if (rings.size() > 1) outer = eliminateHoles(rings, outer);
  hashed_ = nodes_.size() > 80;
  if (hashed_) {
    double maxX = -INFINITY, maxY = -INFINITY;
    minX_ = minY_ = INFINITY;
    for (size_t k = 0; k < outerNodes; ++k) {
      minX_ = std::min(minX_, nodes_[k].x);
      minY_ = std::min(minY_, nodes_[k].y);
      maxX = std::max(maxX, nodes_[k].x);
      maxY = std::max(maxY, nodes_[k].y);
    }
    const double size = std::max(maxX - minX_, maxY - minY_);
    invSize_ = size > 0.0 ? 32767.0 / size : 0.0;
    hashed_ = invSize_ > 0.0;
  }
  earcutLinked(outer, 0);
  return finish(points, rings, triangles, outputStart);
}

bool CapTriangulator::triangulateConvex(std::span<const glm::dvec2> points, CapRing ring,
                                        std::vector<uint32_t>& triangles, double tolerance) {
  const size_t outputStart = triangles.size();
  tolerance_ = tolerance > 0.0 && std::isfinite(tolerance) ? tolerance : 0.0;
  strict_ = false;
  strict_ = true;  // a fast path: any inverted sliver sends the ring to the general path instead
  if (ring.end < ring.begin + 3 || ring.end > points.size()) return false;
  if (kept_.size() < points.size()) {
    kept_.resize(points.size());
    nextPoint_.resize(points.size());
    nextKept_.resize(points.size());
    ringPrev_.resize(points.size());
    ringNext_.resize(points.size());
  }
  raw_.clear();
  hidden_.clear();
  prepareRing(points, ring);
  uint32_t first = ring.begin;
  while (!kept_[first]) ++first;
  // Strictly convex with one turn: every kept corner turns left (by less than pi), and the edge
  // direction, turning counter-clockwise all the way, passes the +x direction once (from below the
  // x axis to on or above it: once per full turn).
  uint32_t count = 0, turns = 0;
  uint32_t p = first;
  do {
    const uint32_t q = nextKept_[p], r = nextKept_[q];
    const glm::dvec2 u = points[q] - points[p], v = points[r] - points[q];
    const double cross = u.x * v.y - u.y * v.x;
    if (!(cross > 0.0)) return false;
    turns += u.y < 0.0 && v.y >= 0.0 ? 1 : 0;
    ++count;
    p = q;
  } while (p != first);
  if (count < 3 || turns != 1) return false;
  uint32_t a = nextKept_[first];
  while (nextKept_[a] != first) {
    raw_.push_back(first);
    raw_.push_back(a);
    raw_.push_back(nextKept_[a]);
    a = nextKept_[a];
  }
  return finish(points, std::span<const CapRing>(&ring, 1), triangles, outputStart);
}

bool CapTriangulator::triangulateFace(std::span<const glm::vec3> corners,
                                      std::vector<uint32_t>& triangles) {
  const uint32_t n = static_cast<uint32_t>(corners.size());
  auto fan = [&] {
    for (uint32_t k = 1; k + 1 < n; ++k) triangles.insert(triangles.end(), {0u, k, k + 1});
  };
  if (n <= 3) {
    fan();
    return n == 3;
  }
  // The Newell normal: twice the vector area, whatever the face's small departures from a plane.
  // Summed about the first corner so the terms stay small next to the coordinates.
  const glm::dvec3 origin(corners[0]);
  glm::dvec3 normal(0.0);
  for (uint32_t k = 1; k + 1 < n; ++k) {
    normal += glm::cross(glm::dvec3(corners[k]) - origin, glm::dvec3(corners[k + 1]) - origin);
  }
  const double length = glm::length(normal);
  if (!(length > 0.0) || !std::isfinite(length)) {
    fan();
    return false;
  }
  normal /= length;
  // Any unit u across the normal with v = normal x u makes u x v = normal, so the face projects
  // counter-clockwise (positive area) and the triangles keep its winding.
  const glm::dvec3 an = glm::abs(normal);
  glm::dvec3 axis(0.0);
  axis[an.x <= an.y && an.x <= an.z ? 0 : (an.y <= an.z ? 1 : 2)] = 1.0;
  const glm::dvec3 u = glm::normalize(glm::cross(axis, normal));
  const glm::dvec3 v = glm::cross(normal, u);
  facePoints_.resize(n);
  for (uint32_t k = 0; k < n; ++k) {
    const glm::dvec3 d = glm::dvec3(corners[k]) - origin;
    facePoints_[k] = {glm::dot(d, u), glm::dot(d, v)};
  }
  // Strictly convex with one turn: the fan is right, and it is what every reader made before, so a
  // convex face (nearly all of them) triangulates exactly as it always did.
  double turning = 0.0;
  bool convex = true;
  for (uint32_t k = 0; k < n && convex; ++k) {
    const glm::dvec2 a = facePoints_[k == 0 ? n - 1 : k - 1], b = facePoints_[k],
                     c = facePoints_[(k + 1) % n];
    const glm::dvec2 e = b - a, f = c - b;
    const double cross = e.x * f.y - e.y * f.x;
    convex = cross > 0.0;
    turning += std::atan2(cross, glm::dot(e, f));
  }
  if (convex && turning < 3.0 * 3.14159265358979323846) {
    fan();
    return true;
  }
  const CapRing ring{0, n};
  if (triangulate(facePoints_, std::span<const CapRing>(&ring, 1), triangles)) return true;
  fan();
  return false;
}

// Fans the collinear points back in, then checks areas: the unsigned triangle areas must add up to
// the polygon area (no overlap, no gap).
bool CapTriangulator::finish(std::span<const glm::dvec2> points, std::span<const CapRing> rings,
                             std::vector<uint32_t>& triangles, size_t outputStart) {
  stack_.clear();
  std::sort(hidden_.begin(), hidden_.end());
  auto hiddenAt = [&](uint32_t p, uint32_t q) {
    const uint64_t key = (uint64_t(p) << 32) | q;
    const auto it = std::lower_bound(hidden_.begin(), hidden_.end(), std::pair<uint64_t, uint32_t>{key, 0u});
    return it != hidden_.end() && it->first == key ? it->second : UINT32_MAX;
  };
  for (size_t k = raw_.size(); k >= 3; k -= 3) {  // reversed: the stack pops them in order
    stack_.push_back(raw_[k - 3]);
    stack_.push_back(raw_[k - 2]);
    stack_.push_back(raw_[k - 1]);
  }
  while (!stack_.empty()) {
    const uint32_t t[3] = {stack_[stack_.size() - 3], stack_[stack_.size() - 2], stack_[stack_.size() - 1]};
    stack_.resize(stack_.size() - 3);
    bool split = false;
    for (int e = 0; e < 3 && !split && !hidden_.empty(); ++e) {
      const uint32_t p = t[e], q = t[(e + 1) % 3], x = t[(e + 2) % 3];
      const uint32_t b = hiddenAt(p, q);
      if (b == UINT32_MAX) continue;
      // Edge p -> q was made by taking b off during clipping: (p, b, x) and (b, q, x) instead.
      const uint32_t halves[6] = {b, q, x, p, b, x};
      stack_.insert(stack_.end(), halves, halves + 6);
      split = true;
    }
    for (int e = 0; e < 3 && !split; ++e) {
      const uint32_t p = t[e], q = t[(e + 1) % 3], x = t[(e + 2) % 3];
      if (!kept_[p] || !kept_[q] || nextKept_[p] != q || nextPoint_[p] == q) continue;
      // Edge p -> q of a ring hides collinear points: fan them from the opposite corner x, pushed in
      // reverse so they come out in ring order.
      uint32_t count = 0;
      for (uint32_t m = p; m != q; m = nextPoint_[m]) ++count;
      const size_t base = stack_.size();
      stack_.resize(base + 3 * size_t(count));
      uint32_t cur = p;
      for (uint32_t k = 0; k < count; ++k) {
        const uint32_t nxt = nextPoint_[cur];
        const size_t at = base + 3 * size_t(count - 1 - k);
        stack_[at] = cur;
        stack_[at + 1] = nxt;
        stack_[at + 2] = x;
        cur = nxt;
      }
      split = true;
    }
    if (!split) triangles.insert(triangles.end(), t, t + 3);
  }

  double polygon = 0.0;
  double extent = 0.0;
  for (const CapRing& ring : rings) {
    polygon += twiceSignedArea(points, ring);
    for (uint32_t i = ring.begin; i < ring.end; ++i) {
      const glm::dvec2 d = points[i] - points[rings[0].begin];
      extent = std::max({extent, std::abs(d.x), std::abs(d.y)});
    }
  }
  // An inverted triangle no wider than twice the tolerance is the fold of a rounding run (two
  // near-coincident points in reversed order fanned from a far corner): a sliver, not an overlap.
  double sumSigned = 0.0, sumAbs = 0.0, slivers = 0.0;
  for (size_t k = outputStart; k < triangles.size(); k += 3) {
    const glm::dvec2 a = points[triangles[k]], b = points[triangles[k + 1]], c = points[triangles[k + 2]];
    const glm::dvec2 u = b - a, v = c - a;
    const double twice = u.x * v.y - u.y * v.x;
    sumSigned += twice;
    sumAbs += std::abs(twice);
    if (twice < 0.0 && tolerance_ > 0.0 && !strict_) {
      const glm::dvec2 w = c - b;
      const double longest = std::sqrt(std::max({glm::dot(u, u), glm::dot(v, v), glm::dot(w, w)}));
      if (-twice <= 2.0 * tolerance_ * longest) slivers -= twice;
    }
  }
  const double slack = 1e-9 * std::abs(polygon) + 1e-12 * extent * extent;
  const bool ok =
      polygon > 0.0 && std::abs(sumSigned - polygon) <= slack && sumAbs - 2.0 * slivers - polygon <= slack;
  if (!ok) triangles.resize(outputStart);
  return ok;
}

}  // namespace cleave::geometry
