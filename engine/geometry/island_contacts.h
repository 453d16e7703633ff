// SPDX-License-Identifier: MIT
// Island contacts: which surface components of a piece touch, overlap or hold one another, so that
// multi-part art (a robot built of plates, bolts and limbs that only touch or pass into one
// another) stays one piece per side when it is cut, unless a side really falls apart.
//
// Input: triangles as three cut-space corners each (metres), each with the component it belongs to
// (the connected parts of one side, numbered 0 .. count - 1). Two components are joined when
//  - a triangle of one crosses a triangle of the other, or a corner of one lies within `tolerance`
//    of a triangle of the other (touching, flush or interpenetrating parts), or
//  - a point of one lies inside the other (generalised winding number above 1/2: a part hidden in
//    another), tested only where the first's bounding box lies inside the second's.
// Only pairs whose bounding boxes (grown by the tolerance) overlap are examined, and of them only
// the triangles inside the overlap, hashed on a grid: near-linear for art made of many small parts.
// Joins are transitive. Deterministic: the result depends on the input only, not on any ordering
// of the search. Winding: counter-clockwise seen from outside. Ownership: the caller's spans are
// read only during the call; scratch memory is kept in ContactScratch between calls.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace cleave::geometry {

struct ContactScratch {
  std::vector<glm::dvec3> lo, hi;          // per component: bounds
  std::vector<uint32_t> byX;               // components by lower x bound
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  std::vector<uint32_t> first, next;       // per component: its triangles as a linked list
  std::vector<uint32_t> trianglesA, trianglesB;
  std::vector<uint32_t> big;               // triangles of B over too many grid cells
  std::vector<uint64_t> cells;             // (cell << 32 | triangle) of B, sorted
  std::vector<uint32_t> parent;
};

// Fills `root` with, per component, the smallest component number it is joined with (directly or
// through others). `corners` holds 3 points per triangle, `component` one number per triangle.
// Returns the number of joins made (0: every component stays apart).
uint32_t joinTouchingComponents(std::span<const glm::dvec3> corners, std::span<const uint32_t> component,
                                uint32_t count, double tolerance, std::vector<uint32_t>& root,
                                ContactScratch& scratch);

// The pairs (a < b, sorted) of non-empty boxes [lo, hi] that overlap once grown by `tolerance`, by a
// sweep along x; an empty box has lo > hi. Cheap: callers check it before gathering any triangle.
void overlappingBoxes(std::span<const glm::dvec3> lo, std::span<const glm::dvec3> hi, double tolerance,
                      std::vector<std::pair<uint32_t, uint32_t>>& pairs, std::vector<uint32_t>& byX);

// Exact small predicates, exposed for their tests.
// Whether the segment [p, q] crosses or touches triangle (a, b, c) (orientation signs in double).
bool segmentCrossesTriangle(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& a, const glm::dvec3& b,
                            const glm::dvec3& c);
// Squared distance from p to triangle (a, b, c).
double pointTriangleDistance2(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

}  // namespace cleave::geometry
