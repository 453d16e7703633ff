// SPDX-License-Identifier: MIT
// The plain data of a split: the plane, the options, the status, the weld of a mesh, and the
// pieces of a result. Units follow the mesh's positions (metres in the engine); cut space is the
// space the container's model matrix or pose maps the mesh into (mesh_container.h). Winding:
// counter-clockwise seen from outside. Ownership: plain values.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/mesh_data.h"

namespace cleave::geometry {

// The plane {x : dot(normal, x) = offset} in cut space. `normal` need not be unit length; the
// splitter normalises it. "Above" means dot(normal, x) > offset.
struct Plane {
  glm::dvec3 normal{0.0, 1.0, 0.0};
  double offset = 0.0;
};

enum class SplitStatus : uint8_t {
  Ok = 0,
  PlaneMissesMesh,      // every vertex on one side (or on the plane), or all that lies on one side is
                        // thinner than float precision: nothing to cut
  InvalidInput,         // NaN/Inf position, index out of range, index count not a multiple of 3, ...
  OpenSection,          // the section has open chains (open or non-manifold input) and caps were asked for
  TriangulationFailed,  // a cap polygon could not be triangulated without overlap
};
const char* toString(SplitStatus status);

enum class CapUvMode : uint8_t {
  WorldPlanar,       // u,v = cut-space coordinates on the cap plane times texelsPerMetre: stable over re-cuts
  NormalizedBounds,  // u,v in [0,1] over the bounds of the cap (per border or per cap), as in the thesis
};

// What a capped split does with a section that is not made of closed loops only (art that is not
// watertight, or non-manifold where it is cut).
enum class OpenSectionMode : uint8_t {
  Refuse,          // the split fails with OpenSection; the caller keeps its object whole
  CapClosedLoops,  // cut everything, cap the closed loops, leave the open chains uncapped (reported
                   // in SplitResult::openChains); pieces along an open chain are open, and their mass
                   // properties come from their convex hull (MassProperties::fromConvexHull). When
                   // the pieces are open anyway, a loop that cannot be capped is left open too
                   // (SplitResult::uncappedLoops) instead of failing the split.
  Bridge,          // as CapClosedLoops, and an open chain is closed and capped too (counted in
                   // SplitResult::bridgedChains) when its two ends lie within the bridge gap, or by
                   // its chord when that chord crosses no other part of the section and the cap it
                   // closes neither holds nor lies in another loop. The pieces stay open along the
                   // chord (mass from the convex hull, as for CapClosedLoops).
};

// How the surface of one side is divided into pieces (with SplitOptions::separateIslands).
enum class IslandMode : uint8_t {
  Touching,   // parts that touch, pass into or hold one another stay one piece (island_contacts.h),
              // and a part the plane did not reach that touches nothing goes with the nearest piece
              // of its side that the plane did reach: multi-part art, as a robot built of plates and
              // bolts, gives one piece per side unless the cut really separates it
  Connected,  // strictly by shared vertices: every separate part of the mesh is its own piece
};

struct SplitOptions {
  bool cap = true;                      // false: hollow mode, no cap triangles, open sections allowed
  OpenSectionMode openSections = OpenSectionMode::CapClosedLoops;
  double bridgeGap = 0.01;              // Bridge: chain ends this close are joined, times the bounds diagonal
  uint32_t capMaterialId = 1;           // material of the cap submesh (reused if the mesh already has it)
  CapUvMode uvMode = CapUvMode::WorldPlanar;
  double uvPerMetre = 1.0;              // WorldPlanar scale: UV units per metre of cut space
  glm::vec4 atlasRect{0.f, 0.f, 1.f, 1.f};  // x, y, width, height: cap UVs are mapped into this rectangle
  bool uvPerBorder = false;             // NormalizedBounds: normalise per outer border, not per whole cap
  bool separateIslands = true;          // false: each side stays one piece even if disconnected
  IslandMode islands = IslandMode::Touching;
  double touchTolerance = 1e-4;         // Touching: parts this close touch, times the bounds diagonal
  double relativeTolerance = 1e-6;      // on-plane tolerance, times the cut-space bounding-box diagonal
  bool computeMass = true;              // mass properties per piece (cut space)
  int keepSide = 0;                     // 0: the pieces of both sides; -1: only those below the plane,
                                        // +1: only those above (a clip; fracture keeps the inside)
  // Threads the split may use, the calling one included (at most 8): with 2 or more, a mesh of
  // 50,000 triangles or more is classified and cut in chunks on threads, and the islands, pieces
  // and mass properties of its two sides are worked out at once. The splitter starts the threads on
  // first use and keeps them: they sleep between splits and, while a split runs, spin between its
  // passes (at most 2 ms at a time), so the cores they use are busy for the whole split. The output
  // is the same bytes for any count; 1 (default) or 0: the calling thread only.
  uint32_t threads = 1;
};

// The weld of a mesh: position ids (vertices at one point share an id), closedness and winding,
// kept with the mesh so that cutting it again does not weld it again. MeshContainer::setMesh works
// it out from the positions (copyWeld gives it); a split gives each piece the weld of its own
// topology (SplitPiece::weld), so re-cutting pieces never re-welds.
struct MeshWeld {
  std::vector<uint32_t> positionIds;      // per vertex
  std::vector<uint32_t> representatives;  // per position id: its first vertex (ascending)
  bool closed = false;                    // see MeshContainer::closed
  bool inverted = false;                  // closed and wound inwards: see MeshContainer::inverted
  bool connected = false;                 // known to be one part: see MeshContainer::connected
};

// The cap plane's basis for a unit normal: u and v unit, (u, v, normal) right-handed, chosen from the
// normal alone (its smallest axis), so world-planar cap UVs (dot(p, u), dot(p, v)) line up across
// cuts and fractures on one plane.
void capPlaneBasis(const glm::dvec3& unitNormal, glm::dvec3& u, glm::dvec3& v);

// SplitPiece::sourceTriangles of a cap triangle of the split: this flag | the section loop it caps
// (the outer border of its cap, numbered among the split's closed and bridged loops).
inline constexpr uint32_t kFromCap = 0x80000000u;

struct SplitPiece {
  MeshData mesh;                // in the source space of the container
  // The position ids of `mesh` as the split made them (vertices at one cut point or one source
  // position share an id; merged near-coincident cut points too) and whether the piece is closed:
  // give it to MeshContainer::setMesh with the mesh to cut the piece again without a weld. Empty
  // (unknown) when a degenerate section loop was left uncapped; the piece is then welded anew.
  MeshWeld weld;
  int side = 0;                 // +1 above the plane, -1 below
  uint32_t capTriangles = 0;     // triangles in the cap-material run (earlier cuts' caps included)
  uint32_t capLoops = 0;        // boundary loops capped on this piece (outer borders and holes)
  MassProperties mass;          // in cut space
  // Skinned meshes: the joints this piece still uses (some vertex weight > 0), ascending. Joint ids
  // in the mesh stay those of the source skeleton, so the piece renders with the same joint
  // matrices; joints not listed are unused by this piece (a ragdoll builds bones for these only).
  // Empty for meshes without skin.
  std::vector<uint16_t> joints;
  // The plane reached this piece: some of its triangles were cut or touch the plane, or it has a cap.
  // False for a part of the mesh that lies wholly on one side and touches nothing the plane reached
  // (IslandMode::Touching joins it to what it touches).
  bool reached = false;
  // Provenance, as manifold's MeshGL: per triangle of `mesh`, the triangle of the container's mesh it
  // comes from (kept whole or cut; an earlier cut's cap is a triangle of the mesh cut here), or
  // kFromCap | loop for a cap triangle of this split. Lets a caller take merged meshes apart again.
  std::vector<uint32_t> sourceTriangles;
};

struct SplitResult {
  SplitStatus status = SplitStatus::Ok;
  std::string message;          // a reason a person can act on, empty when Ok
  std::vector<SplitPiece> pieces;  // above pieces first, then below; each side ordered deterministically
  uint32_t sectionLoops = 0;    // closed loops found in the section
  uint32_t openChains = 0;      // open chains of the section, left uncapped (CapClosedLoops, Bridge)
  uint32_t bridgedChains = 0;   // open chains closed and capped (Bridge); not in openChains
  // Closed loops of open art that could not be capped (wound against the others, or overlapping
  // themselves) and were left open instead of failing the split (CapClosedLoops, open pieces only).
  uint32_t uncappedLoops = 0;
  bool sidesDisagree = false;   // the section differed between the two sides (non-manifold where cut)
  // Each side's islands were settled by the section (a closed mesh known to be one part, every cut
  // point on a loop, one loop or loops one cap joins): no island search was made.
  bool islandsFromSection = false;
  // One side was found to be one island without a search: every loop of the section was an island
  // of its own on the other side, and the mesh is one part, so the loops join all of this side.
  // Only on one thread: with SplitOptions::threads the two sides are searched at once (the pieces
  // are the same bytes either way).
  bool islandFromLoops = false;
};


}  // namespace cleave::geometry
