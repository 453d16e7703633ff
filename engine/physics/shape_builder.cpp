// SPDX-License-Identifier: MIT
// Builds Bullet collision shapes from ShapeDefs.
//
// Convex hulls: btConvexHullComputer (Bullet's exact 3D hull, Preparata-Hong style divide and
// conquer on integer-snapped coordinates) gives the hull and its faces. Its "shrink" option moves
// every face inwards along its normal; we shrink by exactly the collision margin, so that Bullet's
// rounded support mapping (shrunken hull + sphere of radius margin) puts every face back where the
// input had it. See shape_def.h for why this matters for small split pieces.
#include "cleave/physics/detail/shape_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <LinearMath/btConvexHullComputer.h>

#include "cleave/geometry/convex_hull.h"
#include "cleave/physics/detail/bullet_convert.h"

namespace cleave::physics::detail {
namespace {

// A hull thinner than this (metres) is treated as flat.
constexpr double kMinHullWidth = 1e-5;
constexpr uint32_t kMaxMaxHullVertices = 4096;

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const glm::quat& q) {
  return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w);
}

BuildOutcome fail(PhysicsStatus status, std::string reason) {
  BuildOutcome outcome;
  outcome.status = status;
  outcome.reason = std::move(reason);
  return outcome;
}

struct Hull {
  std::vector<btVector3> vertices;  // shrunken by `margin`
  float margin = 0.0f;
  PhysicsStatus status = PhysicsStatus::Ok;
  std::string reason;
};

// Smallest distance between a face plane of the hull and the vertex farthest behind it: an upper
// bound of the hull's width that is exact for boxes and prisms. 0 for flat hulls.
double minFaceWidth(const btConvexHullComputer& hc) {
  double best = std::numeric_limits<double>::infinity();
  const int vertexCount = hc.vertices.size();
  for (int f = 0; f < hc.faces.size(); ++f) {
    // Newell normal of the face polygon (robust for n-gons).
    const btConvexHullComputer::Edge* start = &hc.edges[hc.faces[f]];
    const btConvexHullComputer::Edge* edge = start;
    glm::dvec3 normal(0.0);
    glm::dvec3 anchor(0.0);
    int corners = 0;
    do {
      const btVector3& a = hc.vertices[edge->getSourceVertex()];
      const btVector3& b = hc.vertices[edge->getTargetVertex()];
      normal.x += (double(a.y()) - b.y()) * (double(a.z()) + b.z());
      normal.y += (double(a.z()) - b.z()) * (double(a.x()) + b.x());
      normal.z += (double(a.x()) - b.x()) * (double(a.y()) + b.y());
      anchor += glm::dvec3(a.x(), a.y(), a.z());
      ++corners;
      edge = edge->getNextEdgeOfFace();
    } while (edge != start && corners <= vertexCount);
    const double length = glm::length(normal);
    if (corners < 3 || length <= 0.0) continue;
    normal /= length;
    anchor /= double(corners);
    double depth = 0.0;
    for (int v = 0; v < vertexCount; ++v) {
      const glm::dvec3 p(hc.vertices[v].x(), hc.vertices[v].y(), hc.vertices[v].z());
      depth = std::max(depth, std::abs(glm::dot(normal, p - anchor)));
    }
    best = std::min(best, depth);
  }
  return std::isfinite(best) ? best : 0.0;
}

// Keeps the vertices that are extreme along `count` directions spread evenly over the sphere
// (geometry::extremePoints). The result is a subset of the input, so its hull lies inside the input hull.
std::vector<btVector3> reduceBySupport(const std::vector<btVector3>& vertices, uint32_t count) {
  std::vector<glm::dvec3> points;
  points.reserve(vertices.size());
  for (const btVector3& v : vertices) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<btVector3> kept;
  for (uint32_t v : geometry::extremePoints(points, count)) kept.push_back(vertices[v]);
  return kept;
}

Hull buildHull(std::span<const glm::vec3> points, uint32_t maxVertices, const std::string& what) {
  Hull hull;
  if (points.size() < 4) {
    hull.status = PhysicsStatus::InvalidArgument;
    hull.reason = what + ": a convex hull needs at least 4 points, got " +
                  std::to_string(points.size());
    return hull;
  }
  for (size_t i = 0; i < points.size(); ++i) {
    if (!finite(points[i])) {
      hull.status = PhysicsStatus::InvalidArgument;
      hull.reason = what + ": point " + std::to_string(i) + " is not finite";
      return hull;
    }
  }
  // A dense point cloud (a finely tessellated piece) ends up reduced to maxVertices extreme
  // vertices anyway: pick those first, so the exact hull and the width test run on few points.
  std::vector<btVector3> input;
  input.reserve(points.size());
  for (const glm::vec3& p : points) input.emplace_back(p.x, p.y, p.z);
  if (input.size() > size_t(maxVertices) * 2) {
    std::vector<btVector3> reduced = reduceBySupport(input, maxVertices * 2);
    if (reduced.size() >= 4) input = std::move(reduced);
  }
  btConvexHullComputer exact;
  exact.compute(input[0].m_floats, int(sizeof(btVector3)), int(input.size()), 0.0f, 0.0f);
  const double width = exact.vertices.size() >= 4 ? minFaceWidth(exact) : 0.0;
  if (width < kMinHullWidth) {
    hull.status = PhysicsStatus::DegenerateShape;
    hull.reason = what + ": the points are coplanar or colinear (hull width " +
                  std::to_string(width) + " m)";
    return hull;
  }

  const float margin =
      float(std::min<double>(kMaxConvexMargin, kRelativeConvexMargin * width));
  // Shrinking costs far more than hulling and grows with the vertex count: reduce a dense hull
  // (a finely tessellated piece) to its most extreme vertices first.
  std::vector<btVector3> source(&exact.vertices[0], &exact.vertices[0] + exact.vertices.size());
  if (source.size() > maxVertices) {
    std::vector<btVector3> reduced = reduceBySupport(source, maxVertices);
    if (reduced.size() >= 4) source = std::move(reduced);
  }
  btConvexHullComputer shrunk;
  const btScalar applied =
      shrunk.compute(source[0].m_floats, int(sizeof(btVector3)), int(source.size()), margin, 0.0f);
  if (applied >= 0.0f && shrunk.vertices.size() >= 4) {
    hull.vertices.assign(&shrunk.vertices[0], &shrunk.vertices[0] + shrunk.vertices.size());
    hull.margin = applied;
  } else {
    // Shrinking emptied the hull (not expected for margin <= width / 10; kept as a safe path): use
    // the exact hull with no margin, which does not inflate it either.
    hull.vertices = std::move(source);
    hull.margin = 0.0f;
  }
  // Reduce after shrinking: moving faces inwards splits vertices where more than three faces meet,
  // so the shrunken hull can have more vertices than the input.
  if (hull.vertices.size() > maxVertices) {
    std::vector<btVector3> reduced = reduceBySupport(hull.vertices, maxVertices);
    if (reduced.size() >= 4) hull.vertices = std::move(reduced);
  }
  return hull;
}

// A hull given as the vertices of an already shrunken convex polytope: checked and, when dense,
// reduced to its extreme vertices (a subset, so it stays inside), with the margin as given.
Hull preparedHull(std::span<const glm::vec3> points, float margin, uint32_t maxVertices,
                  const std::string& what) {
  Hull hull;
  if (points.size() < 4 || !std::isfinite(margin) || margin > kMaxConvexMargin) {
    hull.status = PhysicsStatus::InvalidArgument;
    hull.reason = what + ": a prepared hull needs at least 4 points and a margin in [0, " +
                  std::to_string(kMaxConvexMargin) + "] m";
    return hull;
  }
  hull.vertices.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    if (!finite(points[i])) {
      hull.status = PhysicsStatus::InvalidArgument;
      hull.reason = what + ": point " + std::to_string(i) + " is not finite";
      return hull;
    }
    hull.vertices.emplace_back(points[i].x, points[i].y, points[i].z);
  }
  if (hull.vertices.size() > maxVertices) {
    std::vector<btVector3> reduced = reduceBySupport(hull.vertices, maxVertices);
    if (reduced.size() >= 4) hull.vertices = std::move(reduced);
  }
  hull.margin = margin;
  return hull;
}

std::unique_ptr<btConvexHullShape> makeHullShape(const Hull& hull) {
  auto shape = std::make_unique<btConvexHullShape>(
      hull.vertices[0].m_floats, int(hull.vertices.size()), int(sizeof(btVector3)));
  shape->setMargin(hull.margin);
  shape->recalcLocalAabb();
  return shape;
}

// Owns the arrays a Bullet triangle mesh interface points into.
class OwnedTriangleArray : public btTriangleIndexVertexArray {
 public:
  OwnedTriangleArray(std::vector<float> vertices, std::vector<int> indices)
      : vertices_(std::move(vertices)), indices_(std::move(indices)) {
    btIndexedMesh part;
    part.m_numTriangles = int(indices_.size() / 3);
    part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(indices_.data());
    part.m_triangleIndexStride = int(3 * sizeof(int));
    part.m_numVertices = int(vertices_.size() / 3);
    part.m_vertexBase = reinterpret_cast<const unsigned char*>(vertices_.data());
    part.m_vertexStride = int(3 * sizeof(float));
    part.m_indexType = PHY_INTEGER;
    part.m_vertexType = PHY_FLOAT;
    addIndexedMesh(part, PHY_INTEGER);
  }

 private:
  std::vector<float> vertices_;
  std::vector<int> indices_;
};

// Validates a triangle list and copies it, dropping degenerate (zero-area) triangles.
BuildOutcome buildMesh(const ShapeDef& def, std::unique_ptr<btStridingMeshInterface>& out) {
  const char* what = def.type == ShapeType::StaticMesh ? "static mesh" : "concave mesh";
  if (def.positions.empty() || def.indices.empty()) {
    return fail(PhysicsStatus::InvalidArgument, std::string(what) + ": no triangles");
  }
  if (def.indices.size() % 3 != 0) {
    return fail(PhysicsStatus::InvalidArgument,
                std::string(what) + ": index count " + std::to_string(def.indices.size()) +
                    " is not a multiple of 3");
  }
  if (def.positions.size() > size_t(std::numeric_limits<int>::max()) ||
      def.indices.size() > size_t(std::numeric_limits<int>::max())) {
    return fail(PhysicsStatus::InvalidArgument, std::string(what) + ": too large");
  }
  std::vector<float> vertices;
  vertices.reserve(def.positions.size() * 3);
  for (size_t i = 0; i < def.positions.size(); ++i) {
    const glm::vec3 p = def.positions[i];
    if (!finite(p)) {
      return fail(PhysicsStatus::InvalidArgument,
                  std::string(what) + ": position " + std::to_string(i) + " is not finite");
    }
    vertices.insert(vertices.end(), {p.x, p.y, p.z});
  }
  std::vector<int> indices;
  indices.reserve(def.indices.size());
  for (size_t t = 0; t < def.indices.size(); t += 3) {
    const uint32_t a = def.indices[t], b = def.indices[t + 1], c = def.indices[t + 2];
    for (uint32_t i : {a, b, c}) {
      if (i >= def.positions.size()) {
        return fail(PhysicsStatus::InvalidArgument,
                    std::string(what) + ": index " + std::to_string(i) + " of triangle " +
                        std::to_string(t / 3) + " is out of range (" +
                        std::to_string(def.positions.size()) + " positions)");
      }
    }
    const glm::dvec3 pa(def.positions[a]), pb(def.positions[b]), pc(def.positions[c]);
    if (glm::length(glm::cross(pb - pa, pc - pa)) <= 1e-12) continue;
    indices.insert(indices.end(), {int(a), int(b), int(c)});
  }
  if (indices.empty()) {
    return fail(PhysicsStatus::DegenerateShape,
                std::string(what) + ": every triangle has zero area");
  }
  out = std::make_unique<OwnedTriangleArray>(std::move(vertices), std::move(indices));
  return {};
}

}  // namespace

BuildOutcome buildShape(const ShapeDef& def) {
  BuildOutcome outcome;
  BuiltShape& built = outcome.built;
  built.type = def.type;
  if (def.maxHullVertices < 4 || def.maxHullVertices > kMaxMaxHullVertices) {
    return fail(PhysicsStatus::InvalidArgument,
                "maxHullVertices must be in [4, " + std::to_string(kMaxMaxHullVertices) +
                    "], got " + std::to_string(def.maxHullVertices));
  }
  switch (def.type) {
    case ShapeType::Box: {
      const glm::vec3 h = def.halfExtents;
      if (!finite(h) || h.x <= 0.0f || h.y <= 0.0f || h.z <= 0.0f) {
        return fail(PhysicsStatus::InvalidArgument,
                    "box: half extents must be finite and > 0");
      }
      // btBoxShape keeps its margin inside the box; a margin above the smallest half extent would
      // make the inner box negative, so small boxes get a proportional margin.
      auto box = std::make_unique<btBoxShape>(toBt(h));
      const float margin = std::min(0.04f, 0.2f * std::min({h.x, h.y, h.z}));
      box->setMargin(margin);
      built.margin = margin;
      built.shape = std::move(box);
      break;
    }
    case ShapeType::Sphere:
      if (!std::isfinite(def.radius) || def.radius <= 0.0f) {
        return fail(PhysicsStatus::InvalidArgument, "sphere: radius must be finite and > 0");
      }
      built.shape = std::make_unique<btSphereShape>(def.radius);
      built.margin = built.shape->getMargin();
      break;
    case ShapeType::Capsule:
      if (!std::isfinite(def.radius) || def.radius <= 0.0f || !std::isfinite(def.halfHeight) ||
          def.halfHeight < 0.0f) {
        return fail(PhysicsStatus::InvalidArgument,
                    "capsule: radius must be finite and > 0, halfHeight finite and >= 0");
      }
      built.shape = std::make_unique<btCapsuleShape>(def.radius, 2.0f * def.halfHeight);
      built.margin = built.shape->getMargin();
      break;
    case ShapeType::ConvexHull: {
      Hull hull = def.preparedMargin >= 0.0f
                      ? preparedHull(def.points, def.preparedMargin, def.maxHullVertices, "convex hull")
                      : buildHull(def.points, def.maxHullVertices, "convex hull");
      if (hull.status != PhysicsStatus::Ok) return fail(hull.status, std::move(hull.reason));
      built.margin = hull.margin;
      built.hullVertices = uint32_t(hull.vertices.size());
      built.shape = makeHullShape(hull);
      break;
    }
    case ShapeType::Compound: {
      if (def.parts.empty()) {
        return fail(PhysicsStatus::InvalidArgument, "compound: no parts");
      }
      auto compound = std::make_unique<btCompoundShape>(true, int(def.parts.size()));
      float smallestMargin = std::numeric_limits<float>::infinity();
      for (size_t i = 0; i < def.parts.size(); ++i) {
        const ConvexPart& part = def.parts[i];
        const std::string what = "compound part " + std::to_string(i);
        const float norm = glm::length(part.rotation);
        if (!finite(part.position) || !finite(part.rotation) || !(norm > 1e-6f)) {
          return fail(PhysicsStatus::InvalidArgument,
                      what + ": the position must be finite and the rotation a finite, non-zero "
                             "quaternion");
        }
        Hull hull = part.margin >= 0.0f ? preparedHull(part.points, part.margin, def.maxHullVertices, what)
                                        : buildHull(part.points, def.maxHullVertices, what);
        if (hull.status != PhysicsStatus::Ok) return fail(hull.status, std::move(hull.reason));
        auto child = makeHullShape(hull);
        smallestMargin = std::min(smallestMargin, hull.margin);
        built.hullVertices += uint32_t(hull.vertices.size());
        compound->addChildShape(toBt(part.position, part.rotation / norm), child.get());
        built.children.push_back(std::move(child));
      }
      built.margin = smallestMargin;
      built.shape = std::move(compound);
      break;
    }
    case ShapeType::ConcaveMesh: {
      std::unique_ptr<btStridingMeshInterface> mesh;
      BuildOutcome meshOutcome = buildMesh(def, mesh);
      if (meshOutcome.status != PhysicsStatus::Ok) return meshOutcome;
      auto gimpact = std::make_unique<btGImpactMeshShape>(mesh.get());
      gimpact->setMargin(kConcaveMeshMargin);
      gimpact->updateBound();
      built.margin = kConcaveMeshMargin;
      built.shape = std::move(gimpact);
      built.mesh = std::move(mesh);
      break;
    }
    case ShapeType::StaticMesh: {
      std::unique_ptr<btStridingMeshInterface> mesh;
      BuildOutcome meshOutcome = buildMesh(def, mesh);
      if (meshOutcome.status != PhysicsStatus::Ok) return meshOutcome;
      built.shape = std::make_unique<btBvhTriangleMeshShape>(mesh.get(), true, true);
      built.margin = built.shape->getMargin();
      built.mesh = std::move(mesh);
      break;
    }
    default:
      return fail(PhysicsStatus::InvalidArgument, "unknown shape type");
  }
  return outcome;
}

}  // namespace cleave::physics::detail
