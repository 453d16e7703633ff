// SPDX-License-Identifier: MIT
// The compute stage: container set-up, the cut, and a PieceSpec per piece with its collider planned
// (carried parts clipped by the plane, hulls shrunk by their margin) and, for skinned ragdoll pieces,
// its bones and joints planned. Nothing here touches the world, physics or the renderer.
#include "cleave/components/split_compute.h"

#include "cleave/components/piece_kind.h"
#include "cleave/components/split_hierarchy.h"
#include "cleave/components/split_shatter.h"
#include "cleave/components/split_clock.h"

#include <algorithm>
#include <utility>
#include <cmath>
#include <limits>
#include <span>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/components/skinned.h"
#include "cleave/geometry/convex_polytope.h"
#include "cleave/geometry/fracture.h"
#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/primitives.h"
#include "cleave/physics/shape_def.h"

namespace cleave::components {
namespace {

constexpr double kMinPartWidth = 1e-5;  // metres: flatter parts hold nothing
constexpr uint32_t kMaxHullVertices = 48;  // per collider hull, as the bridge would reduce it

// Sets the container up for the job: the shared mesh (with its weld when known) or the merged
// hierarchy, then the cut space (model matrix, or the pose). Returns false with out.message.
bool setUpContainer(const SplitJob& job, const geometry::MeshData* merged, SplitComputeScratch& s, SplitOutcome& out) {
  geometry::MeshStatus set;
  if (merged) {
    set = s.container.setMesh(*merged);
  } else {
    if (job.weld) set = s.container.setMesh(job.mesh, job.weld.get());
    if (!job.weld || !set.ok()) {  // no weld, or a stale one: weld anew and hand it back
      set = s.container.setMesh(job.mesh, nullptr);
      if (set.ok()) {
        auto weld = std::make_shared<geometry::MeshWeld>();
        s.container.copyWeld(*weld);
        out.sourceWeld = std::move(weld);
      }
    }
  }
  if (set.ok() && job.skinned()) {
    set = s.container.setSkinningPose(job.jointMatrices, glm::mat4(job.model));
  } else if (set.ok()) {
    s.container.setTransform(glm::mat4(job.model));
  }
  if (set.ok()) return true;
  out.status = geometry::SplitStatus::InvalidInput;
  out.message = std::move(set.message);
  return false;
}

// The per-piece context shared by every piece of one job.
struct PieceContext {
  const SplitJob& job;
  SplitComputeScratch& scratch;
  const MergedParts* merged = nullptr;    // hierarchies: the merged parts that were cut
  double totalVolume = 0.0;
  bool shareParentMass = false;
  glm::dvec3 normal{0.0};                 // unit plane normal, world
  std::vector<glm::dmat4> globals;        // ragdolls: joint world transforms in the cut pose
  std::vector<geometry::ColliderPartSet> clipped;  // carried parts per piece (rigid jobs)
  bool carried = false;                   // `clipped` is meaningful
  bool shatter = false;                   // cells, not a cut: skinned pieces are baked
};

// True when the mesh, seen in its body frame (principal axes), is thinner than `thickness` along
// one of the axes.
bool thinnerThan(const geometry::MeshData& mesh, const glm::dmat4& toBody, double thickness) {
  if (thickness <= 0.0 || mesh.positions.empty()) return false;
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : mesh.positions) {
    const glm::dvec3 q(toBody * glm::dvec4(p, 1.0));
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  const glm::dvec3 size = hi - lo;
  return std::min({size.x, size.y, size.z}) < thickness;
}

// Plans one piece; returns false when the piece is removed (small, SmallPieceMode::Remove).
bool planPiece(PieceContext& c, size_t index, geometry::SplitPiece& piece, uint32_t k, PieceSpec& spec) {
  const SplitJob& job = c.job;
  const Splitable& sp = job.settings;
  spec.volume = std::max(piece.mass.volume, 0.0);
  spec.mass = c.shareParentMass ? job.parent.mass * spec.volume / c.totalVolume : sp.density * spec.volume;
  spec.frame = bodyFrameFor(piece.mass, std::max(spec.mass, 1e-9), job.model);
  // Too small for the solver: by volume, or (a rigid piece) by its thinnest extent.
  const bool small = spec.volume < std::max(sp.minPieceVolume, job.minBodyVolume) ||
                     (!job.skinned() && thinnerThan(piece.mesh, spec.frame.meshOffset, job.minBodyThickness));
  if (small && sp.smallPieces == SmallPieceMode::Remove) return false;
  spec.side = piece.side;
  spec.capLoops = piece.capLoops;
  spec.closed = piece.mass.closed;
  spec.offsetFromParent = spec.frame.position - job.parent.centre;
  spec.impulse = c.normal * (double(piece.side) * sp.splitImpulse);
  spec.velocity = job.parent.velocity + glm::cross(job.parent.angularVelocity, spec.offsetFromParent) + spec.impulse;
  spec.name = (job.targetName.empty() ? std::string("piece") : job.targetName) + "/" + (piece.side > 0 ? "a" : "b") +
              std::to_string(k);

  // What the piece becomes (piece_kind.h), and what its kind plans for it. Skinned pieces: the posed
  // mesh gives the collider; baked and small ones are drawn from it too, the others keep their skin
  // (bind space).
  geometry::MeshData posed;
  spec.kind = small ? PieceKind::Debris : sp.rigidPieces;
  if (job.skinned()) {
    bakeSkin(piece.mesh, job.jointMatrices, posed);
    const SkinnedPieceMode mode = small || c.shatter ? SkinnedPieceMode::Bake : sp.skinnedPieces;
    spec.kind = small ? PieceKind::Debris
                : mode == SkinnedPieceMode::Bake ? PieceKind::Baked
                : mode == SkinnedPieceMode::Ragdoll ? PieceKind::Ragdoll
                                                    : PieceKind::KeepAnimating;
  }
  pieceKind(spec.kind).plan(PiecePlan{job, piece, posed, c.globals}, spec);
  const PieceKindStrategy& kind = pieceKind(spec.kind);  // the plan may have changed it
  const bool keepSkin = kind.keepsSkin();
  geometry::MeshData whole;
  if (job.hierarchy()) {
    whole = std::move(piece.mesh);
    // Part 0 is the target's own mesh when it has one; a target without a mesh of its own draws the
    // caps only (its parts are its children).
    const bool ownMesh = job.hierarchyParts[0].entity == job.request.target;
    piece.mesh = extractPart(whole, piece.sourceTriangles, *c.merged, ownMesh ? 0u : kNoPart, true);
    planHierarchyChildren(job, *c.merged, whole, piece.sourceTriangles, spec);
  }
  const bool weldKnown = !job.hierarchy() && (keepSkin || !job.skinned()) && !piece.weld.positionIds.empty();
  if (weldKnown && job.depth < sp.maxDepth) spec.weld = std::make_shared<geometry::MeshWeld>(std::move(piece.weld));
  auto drawn = std::make_shared<geometry::MeshData>(job.skinned() && !keepSkin ? std::move(posed) : std::move(piece.mesh));
  spec.mesh = drawn;
  if (job.packForGpu) {
    spec.packed = std::make_shared<render::PackedMesh>(render::packMesh(*drawn));
    spec.packedFrom = drawn.get();
  }
  if (!kind.hasCollider()) return true;

  // The collider: carried parts for rigid pieces of a static mesh, planned from the mesh otherwise.
  const geometry::MeshData& colliderMesh = job.hierarchy() ? whole : kind.colliderFromPose() ? posed : *drawn;
  geometry::SharedColliderParts carried;
  if (c.carried) carried = std::make_shared<const geometry::ColliderPartSet>(std::move(c.clipped[index]));
  ColliderPlan plan = planCollider(colliderMesh, spec.frame.meshOffset, sp.collider, sp.convexHint, std::move(carried),
                                   *c.scratch.concave);
  // A shatter piece much smaller than the carried parts around it (a sliver of a curved part): its
  // own hull fits it better.
  if (c.shatter && plan.colliderVolume > 1.5 * spec.volume) {
    ColliderPlan hull = planCollider(colliderMesh, spec.frame.meshOffset, ColliderMode::ConvexHull, true, nullptr,
                                     *c.scratch.concave);
    if (!hull.hulls.empty() && hull.colliderVolume < plan.colliderVolume) plan = std::move(hull);
  }
  spec.hulls = std::move(plan.hulls);
  spec.concavePositions = std::move(plan.concavePositions);
  spec.concaveIndices = std::move(plan.concaveIndices);
  spec.colliderVolume = plan.colliderVolume;
  // Parts stay with the piece when they are in the space of the mesh it draws.
  if (kind.keepsParts(job.hierarchy())) spec.parts = std::move(plan.parts);
  if (spec.hulls.empty() && spec.concavePositions.empty()) spec.kind = PieceKind::Debris;  // a flat sliver
  return true;
}

// The carried parts of a rigid job, clipped by the plane into the pieces (mesh space). Decomposes
// the source first when its parts are not known yet (handed back for the split system to keep).
geometry::SharedColliderParts carriedParts(PieceContext& c, SplitOutcome& out) {
  const SplitJob& job = c.job;
  const Splitable& sp = job.settings;
  const bool usesParts = sp.collider == ColliderMode::Auto || sp.collider == ColliderMode::Compound ||
                         (sp.convexHint && sp.collider != ColliderMode::ConcaveMesh);
  if (job.hierarchy() || job.skinned() || !usesParts) return nullptr;
  geometry::SharedColliderParts parts = job.parts;
  if (!parts) {
    geometry::ColliderPartSet decomposed;
    if (sp.convexHint) {
      geometry::ConvexPolytope hull =
          geometry::simplifyPolytope(geometry::polytopeOfPoints(job.mesh->positions), geometry::kMaxPartVertices);
      if (!hull.empty()) decomposed.push_back(std::move(hull));
    } else {
      decomposed = geometry::decomposeConvex(*job.mesh, *c.scratch.concave);
    }
    parts = std::make_shared<const geometry::ColliderPartSet>(std::move(decomposed));
    // Kept for the mesh's other instances, unless it is one hull only because this Splitable says so.
    if (!sp.convexHint) out.sourceParts = parts;
  }
  return parts;
}

void clipCarriedParts(PieceContext& c, SplitOutcome& out) {
  const geometry::SharedColliderParts parts = carriedParts(c, out);
  if (!parts) return;
  geometry::clipPartsToPieces(*parts, planeInMeshSpace(c.job.plane, c.job.model), c.scratch.result, {}, c.clipped);
  c.carried = true;
}

}  // namespace

BodyFrame bodyFrameFor(const geometry::MassProperties& props, double mass, const glm::dmat4& model) {
  BodyFrame f;
  f.position = props.centerOfMass;
  const double scale = props.volume > 0.0 ? mass / props.volume : 0.0;
  const geometry::PrincipalInertia principal = geometry::principalInertia(props.inertia * scale);
  f.rotation = glm::normalize(glm::quat_cast(principal.axes));
  // A piece must never get zero inertia (a sliver): floor each moment at a small share of the largest.
  const double largest = std::max({principal.moments.x, principal.moments.y, principal.moments.z, 1e-12});
  f.moments = glm::max(principal.moments, glm::dvec3(largest * 1e-3));
  const glm::dmat4 bodyToWorld = glm::translate(glm::dmat4(1.0), f.position) * glm::mat4_cast(f.rotation);
  f.meshOffset = glm::inverse(bodyToWorld) * model;
  return f;
}

std::vector<glm::vec3> transformedPoints(const geometry::MeshData& mesh, const glm::dmat4& m) {
  std::vector<glm::vec3> points;
  points.reserve(mesh.positions.size());
  for (const glm::vec3& p : mesh.positions) points.push_back(glm::vec3(m * glm::dvec4(p, 1.0)));
  return points;
}

geometry::Plane planeInMeshSpace(const geometry::Plane& world, const glm::dmat4& model) {
  // dot(n, M p + t) = d  <=>  dot(L^T n, p) = d - dot(n, t)
  geometry::Plane out;
  out.normal = glm::transpose(glm::dmat3(model)) * world.normal;
  out.offset = world.offset - glm::dot(world.normal, glm::dvec3(model[3]));
  return out;
}

std::vector<HullSpec> hullsInBodyFrame(const geometry::ColliderPartSet& parts, const glm::dmat4& meshOffset,
                                       double* volume) {
  std::vector<HullSpec> hulls;
  double sum = 0.0;
  for (const geometry::ConvexPolytope& part : parts) {
    const geometry::ConvexPolytope body = geometry::transformPolytope(part, meshOffset);
    const double width = geometry::polytopeWidth(body);
    if (body.empty() || width < kMinPartWidth) continue;
    sum += geometry::polytopeVolume(body);
    const double margin = std::min<double>(physics::kMaxConvexMargin, physics::kRelativeConvexMargin * width);
    geometry::ConvexPolytope shrunk = geometry::shrinkPolytope(body, margin);
    HullSpec hull;
    hull.margin = shrunk.empty() ? 0.f : float(margin);
    const geometry::ConvexPolytope& kept = shrunk.empty() ? body : shrunk;
    // Moving faces inwards splits the vertices where more than three faces meet: keep the extreme
    // ones (a subset, so the hull stays inside) and the bridge has nothing left to reduce.
    const std::vector<uint32_t> extreme = geometry::extremeVertices(kept, kMaxHullVertices);
    hull.points.reserve(extreme.size());
    for (uint32_t v : extreme) hull.points.push_back(glm::vec3(kept.vertices[v]));
    hulls.push_back(std::move(hull));
  }
  if (volume) *volume = sum;
  return hulls;
}

ColliderPlan planCollider(const geometry::MeshData& mesh, const glm::dmat4& meshOffset, ColliderMode mode,
                          bool knownConvex, geometry::SharedColliderParts carried, geometry::IMeshSplitter& splitter) {
  ColliderPlan plan;
  auto hullOfPoints = [&] {
    geometry::ColliderPartSet one;
    geometry::ConvexPolytope hull =
        geometry::simplifyPolytope(geometry::polytopeOfPoints(mesh.positions), geometry::kMaxPartVertices);
    if (!hull.empty()) one.push_back(std::move(hull));
    return std::make_shared<const geometry::ColliderPartSet>(std::move(one));
  };
  if (mode == ColliderMode::ConcaveMesh) {
    plan.concavePositions = transformedPoints(mesh, meshOffset);
    plan.concaveIndices = mesh.indices;
    plan.parts = hullOfPoints();
  } else if (mode == ColliderMode::ConvexHull || (knownConvex && !(carried && !carried->empty()))) {
    plan.parts = hullOfPoints();  // a convex mesh's carried part is its hull already: clipped, it stays exact
  } else if (!carried) {
    plan.parts = std::make_shared<const geometry::ColliderPartSet>(geometry::decomposeConvex(mesh, splitter));
  } else {
    plan.parts = carried->empty() ? hullOfPoints() : std::move(carried);
  }
  plan.hulls = hullsInBodyFrame(*plan.parts, meshOffset, &plan.colliderVolume);
  if (plan.hulls.empty()) {  // every part flat (or one part that decomposition got wrong): the hull of the points
    plan.parts = hullOfPoints();
    plan.hulls = hullsInBodyFrame(*plan.parts, meshOffset, &plan.colliderVolume);
  }
  return plan;
}

void computeSplit(const SplitJob& job, SplitComputeScratch& s, SplitOutcome& out) {
  const double start = nowMilliseconds();
  out = SplitOutcome{};
  MergedParts merged;
  if (job.hierarchy()) merged = mergeHierarchyParts(job.hierarchyParts);
  if (!setUpContainer(job, job.hierarchy() ? &merged.mesh : nullptr, s, out)) {
    out.times.total = out.times.setup = nowMilliseconds() - start;
    return;
  }
  out.times.setup = nowMilliseconds() - start;
  const double geometryStart = nowMilliseconds();
  geometry::IMeshSplitter& splitter = job.settings.convexHint ? *s.convex : *s.concave;
  if (job.skinned() && s.container.closed()) {  // closed on the container's weld: no weld again
    std::vector<glm::dvec3> unused;  // a posed container holds its doubles: doubles() copies nothing
    out.posedVolume = geometry::integrateClosedSurface(s.container.cutPositions().doubles(unused),
                                                       s.container.mesh().indices, s.container.mirrored())
                          .volume;
  }
  std::string shatterMessage;
  std::vector<geometry::ConvexCell> cells;
  std::vector<uint32_t> pieceCell;
  if (job.request.shatter) {
    out.status = shatterInto(job, s, shatterMessage, cells, pieceCell);
  } else {
    out.status = splitter.split(s.container, job.plane, job.options, s.result);
  }
  s.container.release();  // do not keep the (doomed) target's mesh alive
  out.times.geometry = nowMilliseconds() - geometryStart;
  if (out.status != geometry::SplitStatus::Ok) {
    out.message = job.request.shatter ? shatterMessage : s.result.message;
    out.times.total = nowMilliseconds() - start;
    return;
  }
  out.openChains = s.result.openChains;
  PieceContext c{job, s, job.hierarchy() ? &merged : nullptr, 0.0, false, glm::dvec3(0.0), {}, {}, false,
                 job.request.shatter};
  for (const auto& piece : s.result.pieces) c.totalVolume += std::max(piece.mass.volume, 0.0);
  out.piecesVolume = c.totalVolume;
  if (!(c.totalVolume > 0.0)) {
    out.status = geometry::SplitStatus::InvalidInput;
    out.message = "pieces enclose no volume";
    out.times.total = nowMilliseconds() - start;
    return;
  }
  const double colliderStart = nowMilliseconds();
  c.normal = job.request.shatter ? glm::dvec3(0.0) : glm::normalize(job.plane.normal);
  // Skinned targets share the parent's mass by posed volume whatever the mass mode: skinning does not
  // keep volume exactly, so density x posed volume would make the mass drift with the pose.
  c.shareParentMass = job.settings.massMode == MassMode::KeepParentMass || (job.skinned() && job.parent.mass > 0.0);
  if (job.skinned() && job.settings.skinnedPieces == SkinnedPieceMode::Ragdoll)
    posedJointGlobals(job.skin->skeleton, job.jointMatrices, job.model, c.globals);
  if (job.request.shatter) {
    if (const geometry::SharedColliderParts parts = carriedParts(c, out)) {
      clipPartsToCells(*parts, job.model, s.result.pieces, cells, pieceCell, c.clipped);
      c.carried = true;
    }
  } else {
    clipCarriedParts(c, out);
  }
  uint32_t k = 0;
  for (size_t i = 0; i < s.result.pieces.size(); ++i) {
    PieceSpec spec;
    if (!planPiece(c, i, s.result.pieces[i], k, spec)) continue;
    if (job.request.shatter) finishShatterPiece(job, k, spec);
    out.pieces.push_back(std::move(spec));
    ++k;
  }
  out.times.collider = nowMilliseconds() - colliderStart;
  out.times.total = nowMilliseconds() - start;
}

}  // namespace cleave::components
