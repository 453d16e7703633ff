// SPDX-License-Identifier: MIT
// Procedural meshes. Curved shapes are parametric grids; every angle is computed from an integer
// step taken modulo the period, so a seam vertex is a bit-exact copy of its twin and poles are
// exact points. Triangles with two equal positions (at poles and disc centres) are skipped, and
// each triangle is wound so that its geometric normal agrees with the analytic vertex normals,
// which gives counter-clockwise-from-outside winding without per-shape bookkeeping.
#include "cleave/geometry/primitives.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace cleave::geometry::primitives {
namespace {

constexpr double kPi = std::numbers::pi;

struct GridVertex {
  glm::vec3 position{0.f};
  glm::vec3 normal{0.f, 1.f, 0.f};
  glm::vec3 tangent{1.f, 0.f, 0.f};    // direction of increasing u
  glm::vec3 bitangent{0.f, 0.f, 1.f};  // direction of increasing v (only its side matters)
  glm::vec2 uv{0.f};
};

// Removes negative zeros so equal positions are also equal bit for bit.
glm::vec3 clean(const glm::vec3& v) { return v + glm::vec3(0.f); }

uint32_t pushVertex(MeshData& m, const GridVertex& v) {
  glm::vec3 n = glm::normalize(v.normal);
  glm::vec3 t = v.tangent - n * glm::dot(n, v.tangent);  // Gram-Schmidt against the normal
  const float tl = glm::length(t);
  if (tl > 0.f) {
    t /= tl;
  } else {  // no usable direction given: any unit vector perpendicular to the normal
    t = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? glm::vec3(1.f, 0.f, 0.f) : glm::vec3(0.f, 1.f, 0.f)));
  }
  float w = glm::dot(glm::cross(n, t), v.bitangent) >= 0.f ? 1.f : -1.f;
  m.positions.push_back(clean(v.position));
  m.normals.push_back(n);
  m.tangents.emplace_back(t, w);
  m.uv0.push_back(v.uv);
  return static_cast<uint32_t>(m.positions.size() - 1);
}

// Adds (a, b, c) wound to agree with the vertex normals; skips triangles with repeated positions.
void pushTriangle(MeshData& m, uint32_t a, uint32_t b, uint32_t c) {
  const glm::vec3 &pa = m.positions[a], &pb = m.positions[b], &pc = m.positions[c];
  if (pa == pb || pb == pc || pc == pa) return;
  glm::dvec3 da(pa), db(pb), dc(pc);
  glm::dvec3 geometric = glm::cross(db - da, dc - da);
  glm::dvec3 shading = glm::dvec3(m.normals[a]) + glm::dvec3(m.normals[b]) + glm::dvec3(m.normals[c]);
  if (glm::dot(geometric, shading) < 0.0) std::swap(b, c);
  m.indices.insert(m.indices.end(), {a, b, c});
}

// (rows + 1) x (cols + 1) vertices from vertexAt(i, j); two triangles per cell.
template <class F>
void appendGrid(MeshData& m, uint32_t rows, uint32_t cols, F&& vertexAt) {
  const uint32_t base = static_cast<uint32_t>(m.positions.size());
  for (uint32_t i = 0; i <= rows; ++i) {
    for (uint32_t j = 0; j <= cols; ++j) pushVertex(m, vertexAt(i, j));
  }
  for (uint32_t i = 0; i < rows; ++i) {
    for (uint32_t j = 0; j < cols; ++j) {
      uint32_t v00 = base + i * (cols + 1) + j, v01 = v00 + 1;
      uint32_t v10 = v00 + cols + 1, v11 = v10 + 1;
      pushTriangle(m, v00, v10, v11);
      pushTriangle(m, v00, v11, v01);
    }
  }
}

// cos and sin of 2 pi k / n with k taken modulo n: seam vertices repeat exactly.
glm::dvec2 circle(uint32_t k, uint32_t n) {
  k %= n;
  double a = 2.0 * kPi * double(k) / double(n);
  return {std::cos(a), std::sin(a)};
}

// cos and sin of pi k / n for k in [0, n]; exact at both poles.
glm::dvec2 halfCircle(uint32_t k, uint32_t n) {
  if (k == 0) return {1.0, 0.0};
  if (k >= n) return {-1.0, 0.0};
  double a = kPi * double(k) / double(n);
  return {std::cos(a), std::sin(a)};
}

// Ellipsoid grid: theta from +y (row 0) to -y, phi around y with x = cos, z = -sin (so u runs
// counter-clockwise seen from +y and textures are not mirrored).
void appendEllipsoid(MeshData& m, const glm::vec3& centre, const glm::dvec3& radii,
                     uint32_t segments, uint32_t rings, bool inward) {
  appendGrid(m, rings, segments, [&](uint32_t i, uint32_t j) {
    glm::dvec2 th = halfCircle(i, rings);  // (cos theta, sin theta)
    glm::dvec2 ph = circle(j, segments);   // (cos phi, sin phi)
    glm::dvec3 u(th.y * ph.x, th.x, -th.y * ph.y);
    GridVertex v;
    v.position = centre + glm::vec3(radii * u);
    glm::dvec3 n = glm::normalize(u / radii);
    v.normal = glm::vec3(inward ? -n : n);
    v.tangent = glm::vec3(glm::normalize(radii * glm::dvec3(-ph.y, 0.0, -ph.x)));
    v.bitangent = glm::vec3(radii * glm::dvec3(-th.x * ph.x, th.y, th.x * ph.y));
    v.uv = glm::vec2(float(j) / float(segments), 1.f - float(i) / float(rings));
    return v;
  });
}

// A prism: outline (counter-clockwise in the (U, V) plane, U x V = W) extruded along W from h0 to
// h1. `points` holds the outline first, then extra interior cap points; capTriangles index points.
void appendPrism(MeshData& m, const std::vector<glm::dvec2>& points, size_t outlineCount,
                 const std::vector<std::array<uint32_t, 3>>& capTriangles, const glm::dvec3& axisU,
                 const glm::dvec3& axisV, double h0, double h1) {
  const glm::dvec3 axisW = glm::cross(axisU, axisV);
  auto at = [&](const glm::dvec2& p, double h) { return glm::vec3(p.x * axisU + p.y * axisV + h * axisW); };
  // Side walls: four vertices per outline edge (sharp edges keep their own normals).
  double perimeter = 0.0;
  for (size_t k = 0; k < outlineCount; ++k) {
    const glm::dvec2 a = points[k], b = points[(k + 1) % outlineCount];
    const glm::dvec2 d = b - a;
    const double len = glm::length(d);
    const glm::vec3 normal(glm::normalize(d.y * axisU - d.x * axisV));
    const glm::vec3 tangent(glm::normalize(d.x * axisU + d.y * axisV));
    GridVertex corners[4];
    const glm::dvec2 ends[2] = {a, b};
    const double heights[2] = {h0, h1};
    for (int e = 0; e < 2; ++e) {
      for (int h = 0; h < 2; ++h) {
        GridVertex& v = corners[2 * e + h];
        v.position = at(ends[e], heights[h]);
        v.normal = normal;
        v.tangent = tangent;
        v.bitangent = glm::vec3(axisW);
        v.uv = glm::vec2(float(perimeter + (e ? len : 0.0)), float(heights[h] - h0));
      }
    }
    perimeter += len;
    uint32_t i0 = pushVertex(m, corners[0]), i1 = pushVertex(m, corners[1]);
    uint32_t i2 = pushVertex(m, corners[2]), i3 = pushVertex(m, corners[3]);
    pushTriangle(m, i0, i2, i3);
    pushTriangle(m, i0, i3, i1);
  }
  // Caps.
  for (int side = 0; side < 2; ++side) {
    const double h = side ? h1 : h0;
    const glm::vec3 normal(side ? axisW : -axisW);
    const uint32_t base = static_cast<uint32_t>(m.positions.size());
    for (const glm::dvec2& p : points) {
      GridVertex v;
      v.position = at(p, h);
      v.normal = normal;
      v.tangent = glm::vec3(side ? axisU : -axisU);
      v.bitangent = glm::vec3(axisV);
      v.uv = glm::vec2(float(side ? p.x : -p.x), float(p.y));
      pushVertex(m, v);
    }
    for (const auto& t : capTriangles) pushTriangle(m, base + t[0], base + t[1], base + t[2]);
  }
}

bool isEmptyLength(float v) { return !(std::abs(v) > 0.f) || !std::isfinite(v); }

}  // namespace

MeshData box(const glm::vec3& halfExtents) {
  MeshData m;
  const glm::vec3 h = glm::abs(halfExtents);
  if (isEmptyLength(h.x) || isEmptyLength(h.y) || isEmptyLength(h.z)) return m;
  struct FaceAxes {
    glm::vec3 n, t, b;
  };
  static const FaceAxes kFaces[6] = {
      {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
      {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
      {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
  };
  for (const FaceAxes& f : kFaces) {
    appendGrid(m, 1, 1, [&](uint32_t i, uint32_t j) {
      GridVertex v;
      v.position = h * (f.n + (2.f * float(j) - 1.f) * f.t + (2.f * float(i) - 1.f) * f.b);
      v.normal = f.n;
      v.tangent = f.t;
      v.bitangent = f.b;
      v.uv = glm::vec2(float(j), float(i));
      return v;
    });
  }
  return m;
}

MeshData ellipsoid(const glm::vec3& radii, uint32_t segments, uint32_t rings) {
  MeshData m;
  const glm::vec3 r = glm::abs(radii);
  if (isEmptyLength(r.x) || isEmptyLength(r.y) || isEmptyLength(r.z)) return m;
  appendEllipsoid(m, glm::vec3(0.f), glm::dvec3(r), std::max(segments, 3u), std::max(rings, 2u), false);
  return m;
}

MeshData uvSphere(float radius, uint32_t segments, uint32_t rings) {
  return ellipsoid(glm::vec3(radius), segments, rings);
}

MeshData cylinder(float radius, float height, uint32_t segments) {
  MeshData m;
  const double r = std::abs(radius), hh = 0.5 * std::abs(height);
  if (isEmptyLength(radius) || isEmptyLength(height)) return m;
  segments = std::max(segments, 3u);
  appendGrid(m, 1, segments, [&](uint32_t i, uint32_t j) {
    glm::dvec2 ph = circle(j, segments);
    GridVertex v;
    v.position = glm::vec3(glm::dvec3(r * ph.x, i ? hh : -hh, -r * ph.y));
    v.normal = glm::vec3(glm::dvec3(ph.x, 0.0, -ph.y));
    v.tangent = glm::vec3(glm::dvec3(-ph.y, 0.0, -ph.x));
    v.bitangent = glm::vec3(0.f, 1.f, 0.f);
    v.uv = glm::vec2(float(j) / float(segments), float(i));
    return v;
  });
  for (int top = 0; top < 2; ++top) {
    appendGrid(m, 1, segments, [&](uint32_t i, uint32_t j) {
      glm::dvec2 ph = circle(j, segments);
      const double rho = i ? r : 0.0;
      GridVertex v;
      v.position = glm::vec3(glm::dvec3(rho * ph.x, top ? hh : -hh, -rho * ph.y));
      v.normal = glm::vec3(0.f, top ? 1.f : -1.f, 0.f);
      v.tangent = glm::vec3(top ? 1.f : -1.f, 0.f, 0.f);
      v.bitangent = glm::vec3(0.f, 0.f, -1.f);
      const float s = i ? 0.5f : 0.f;
      v.uv = glm::vec2(0.5f + (top ? s : -s) * float(ph.x), 0.5f + s * float(ph.y));
      return v;
    });
  }
  return m;
}

MeshData torus(float major, float minor, uint32_t segments, uint32_t sides) {
  MeshData m;
  const double big = std::abs(major), small = std::abs(minor);
  if (isEmptyLength(major) || isEmptyLength(minor) || !(small < big)) return m;
  segments = std::max(segments, 3u);
  sides = std::max(sides, 3u);
  appendGrid(m, sides, segments, [&](uint32_t i, uint32_t j) {
    glm::dvec2 ps = circle(i, sides);     // tube angle
    glm::dvec2 ph = circle(j, segments);  // angle around y
    const double ring = big + small * ps.x;
    GridVertex v;
    v.position = glm::vec3(glm::dvec3(ring * ph.x, small * ps.y, -ring * ph.y));
    v.normal = glm::vec3(glm::dvec3(ps.x * ph.x, ps.y, -ps.x * ph.y));
    v.tangent = glm::vec3(glm::dvec3(-ph.y, 0.0, -ph.x));
    v.bitangent = glm::vec3(glm::dvec3(-ps.y * ph.x, ps.x, ps.y * ph.y));
    v.uv = glm::vec2(float(j) / float(segments), float(i) / float(sides));
    return v;
  });
  return m;
}

MeshData capsule(float radius, float cylinderHeight, uint32_t segments, uint32_t rings) {
  MeshData m;
  const double r = std::abs(radius), hh = 0.5 * std::abs(cylinderHeight);
  if (isEmptyLength(radius) || !std::isfinite(cylinderHeight)) return m;
  segments = std::max(segments, 3u);
  const uint32_t half = std::max((rings + 1) / 2, 1u);  // rings per hemisphere
  const uint32_t full = 2 * half;
  const double total = 2.0 * r + 2.0 * hh;
  // Rows 0..half: upper hemisphere; rows half+1..full+1: lower hemisphere; the band between is the
  // cylinder (it vanishes into a sphere when cylinderHeight is 0, and then the band is skipped).
  const uint32_t rows = hh > 0.0 ? full + 1 : full;
  appendGrid(m, rows, segments, [&](uint32_t i, uint32_t j) {
    const bool upper = i <= half;
    const uint32_t k = (upper || hh == 0.0) ? i : i - 1;
    glm::dvec2 th = halfCircle(k, full);
    glm::dvec2 ph = circle(j, segments);
    glm::dvec3 u(th.y * ph.x, th.x, -th.y * ph.y);
    const double yOffset = (k < half || (k == half && upper)) ? hh : -hh;
    GridVertex v;
    v.position = glm::vec3(r * u + glm::dvec3(0.0, yOffset, 0.0));
    v.normal = glm::vec3(u);
    v.tangent = glm::vec3(glm::dvec3(-ph.y, 0.0, -ph.x));
    v.bitangent = glm::vec3(glm::dvec3(-th.x * ph.x, th.y, th.x * ph.y));
    v.uv = glm::vec2(float(j) / float(segments), float((v.position.y + r + hh) / total));
    return v;
  });
  return m;
}

MeshData hollowSphere(float outerRadius, float innerRadius, uint32_t segments, uint32_t rings) {
  MeshData m;
  const double outer = std::abs(outerRadius), inner = std::abs(innerRadius);
  if (isEmptyLength(outerRadius) || isEmptyLength(innerRadius) || !(inner < outer)) return m;
  segments = std::max(segments, 3u);
  rings = std::max(rings, 2u);
  appendEllipsoid(m, glm::vec3(0.f), glm::dvec3(outer), segments, rings, false);
  appendEllipsoid(m, glm::vec3(0.f), glm::dvec3(inner), segments, rings, true);
  return m;
}

MeshData nestedShells(uint32_t n, float outerRadius, uint32_t segments, uint32_t rings) {
  MeshData m;
  if (n == 0 || isEmptyLength(outerRadius)) return m;
  segments = std::max(segments, 3u);
  rings = std::max(rings, 2u);
  const double outer = std::abs(outerRadius);
  for (uint32_t k = 0; k < n; ++k) {
    const double r = outer * double(n - k) / double(n);
    appendEllipsoid(m, glm::vec3(0.f), glm::dvec3(r), segments, rings, (k % 2) == 1);
  }
  return m;
}

MeshData combPrism(uint32_t teeth, float pitch, float toothLength, float spineHeight, float depth) {
  MeshData m;
  teeth = std::max(teeth, 1u);
  const double p = std::abs(pitch), len = std::abs(toothLength), s = std::abs(spineHeight);
  const double d = std::abs(depth);
  if (isEmptyLength(pitch) || isEmptyLength(toothLength) || isEmptyLength(spineHeight) ||
      isEmptyLength(depth)) {
    return m;
  }
  const double width = teeth * p, x0 = -0.5 * width;
  // Outline, counter-clockwise seen from +z: bottom left, bottom right, then the top from right to
  // left with each tooth as a detour up and back down.
  std::vector<glm::dvec2> pts = {{x0, 0.0}, {x0 + width, 0.0}, {x0 + width, s}};
  for (uint32_t k = teeth; k-- > 0;) {
    const double left = x0 + (k + 0.25) * p, right = x0 + (k + 0.75) * p;
    pts.push_back({right, s});
    pts.push_back({right, s + len});
    pts.push_back({left, s + len});
    pts.push_back({left, s});
  }
  pts.push_back({x0, s});
  // Cap: fan from the bottom-left corner over the spine (every spine-top vertex is a fan vertex, so
  // no T-junction), plus two triangles per tooth.
  std::vector<std::array<uint32_t, 3>> tris;
  tris.push_back({0, 1, 2});
  std::vector<uint32_t> top = {2};
  for (uint32_t k = 0; k < teeth; ++k) {
    const uint32_t base = 3 + 4 * k;
    top.push_back(base);
    top.push_back(base + 3);
    tris.push_back({base, base + 1, base + 2});
    tris.push_back({base, base + 2, base + 3});
  }
  top.push_back(static_cast<uint32_t>(pts.size() - 1));
  for (size_t k = 0; k + 1 < top.size(); ++k) tris.push_back({0, top[k], top[k + 1]});
  appendPrism(m, pts, pts.size(), tris, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, -0.5 * d, 0.5 * d);
  return m;
}

MeshData starPrism(uint32_t points, float outerRadius, float innerRadius, float height) {
  MeshData m;
  points = std::max(points, 3u);
  const double outer = std::abs(outerRadius), inner = std::abs(innerRadius);
  const double hh = 0.5 * std::abs(height);
  if (isEmptyLength(outerRadius) || isEmptyLength(innerRadius) || isEmptyLength(height)) return m;
  std::vector<glm::dvec2> pts;
  const uint32_t n = 2 * points;
  for (uint32_t k = 0; k < n; ++k) {
    glm::dvec2 c = circle(k, n);
    pts.push_back((k % 2 == 0 ? outer : inner) * c);
  }
  pts.push_back({0.0, 0.0});  // cap centre: the star is star-shaped about it
  std::vector<std::array<uint32_t, 3>> tris;
  for (uint32_t k = 0; k < n; ++k) tris.push_back({n, k, (k + 1) % n});
  // (x, -z) is counter-clockwise seen from +y, and x cross -z = +y.
  appendPrism(m, pts, n, tris, {1.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, -hh, hh);
  return m;
}

MeshData tetrahedron(float circumRadius) {
  MeshData m;
  if (isEmptyLength(circumRadius)) return m;
  const float s = std::abs(circumRadius) / std::sqrt(3.f);
  const glm::vec3 c[4] = {{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}};
  const uint32_t faces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  for (const auto& f : faces) {
    const glm::vec3 a = c[f[0]], b = c[f[1]], d = c[f[2]];
    glm::vec3 n = glm::normalize(glm::cross(b - a, d - a));
    if (glm::dot(n, a + b + d) < 0.f) n = -n;
    const glm::vec3 t = glm::normalize(b - a);
    const glm::vec3 corners[3] = {a, b, d};
    const glm::vec2 uvs[3] = {{0.f, 0.f}, {1.f, 0.f}, {0.5f, 1.f}};
    uint32_t idx[3];
    for (int k = 0; k < 3; ++k) {
      GridVertex v;
      v.position = corners[k];
      v.normal = n;
      v.tangent = t;
      v.bitangent = glm::cross(n, t);
      v.uv = uvs[k];
      idx[k] = pushVertex(m, v);
    }
    pushTriangle(m, idx[0], idx[1], idx[2]);
  }
  return m;
}

MeshData twoDisjointSpheres(float radius, float gap, uint32_t segments, uint32_t rings) {
  MeshData m;
  if (isEmptyLength(radius) || !std::isfinite(gap)) return m;
  const float r = std::abs(radius);
  const float offset = r + 0.5f * std::abs(gap);
  segments = std::max(segments, 3u);
  rings = std::max(rings, 2u);
  appendEllipsoid(m, glm::vec3(-offset, 0.f, 0.f), glm::dvec3(r), segments, rings, false);
  appendEllipsoid(m, glm::vec3(offset, 0.f, 0.f), glm::dvec3(r), segments, rings, false);
  return m;
}

namespace {

template <class T>
void mergeAttribute(std::vector<T>& out, const std::vector<T>& a, size_t countA,
                    const std::vector<T>& b, size_t countB, const T& neutral) {
  if (a.empty() && b.empty()) return;
  out.reserve(countA + countB);
  if (a.empty()) {
    out.insert(out.end(), countA, neutral);
  } else {
    out.insert(out.end(), a.begin(), a.end());
  }
  if (b.empty()) {
    out.insert(out.end(), countB, neutral);
  } else {
    out.insert(out.end(), b.begin(), b.end());
  }
}

}  // namespace

MeshData merge(const MeshData& a, const MeshData& b) {
  MeshData m;
  const size_t na = a.positions.size(), nb = b.positions.size();
  m.positions.reserve(na + nb);
  m.positions.insert(m.positions.end(), a.positions.begin(), a.positions.end());
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  mergeAttribute(m.normals, a.normals, na, b.normals, nb, glm::vec3(0.f, 1.f, 0.f));
  mergeAttribute(m.tangents, a.tangents, na, b.tangents, nb, glm::vec4(1.f, 0.f, 0.f, 1.f));
  mergeAttribute(m.uv0, a.uv0, na, b.uv0, nb, glm::vec2(0.f));
  mergeAttribute(m.uv1, a.uv1, na, b.uv1, nb, glm::vec2(0.f));
  mergeAttribute(m.colors, a.colors, na, b.colors, nb, glm::vec4(1.f));
  mergeAttribute(m.joints, a.joints, na, b.joints, nb, glm::u16vec4(0));
  mergeAttribute(m.weights, a.weights, na, b.weights, nb, glm::vec4(1.f, 0.f, 0.f, 0.f));
  m.indices = a.indices;
  m.indices.reserve(a.indices.size() + b.indices.size());
  for (uint32_t i : b.indices) m.indices.push_back(i + static_cast<uint32_t>(na));
  if (!a.submeshes.empty() || !b.submeshes.empty()) {
    auto runs = [](const MeshData& mesh) {
      if (!mesh.submeshes.empty()) return mesh.submeshes;
      std::vector<SubMesh> one;
      if (!mesh.indices.empty()) one.push_back({0, static_cast<uint32_t>(mesh.indices.size()), 0});
      return one;
    };
    m.submeshes = runs(a);
    for (SubMesh run : runs(b)) {
      run.firstIndex += static_cast<uint32_t>(a.indices.size());
      m.submeshes.push_back(run);
    }
  }
  return m;
}

void transform(MeshData& mesh, const glm::mat4& m) {
  const glm::mat3 linear(m);
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(linear));
  const float det = glm::determinant(linear);
  for (glm::vec3& p : mesh.positions) p = clean(glm::vec3(m * glm::vec4(p, 1.f)));
  for (glm::vec3& n : mesh.normals) {
    glm::vec3 t = normalMatrix * n;
    float len = glm::length(t);
    if (len > 0.f) n = t / len;
  }
  for (glm::vec4& t : mesh.tangents) {
    glm::vec3 x = linear * glm::vec3(t);
    float len = glm::length(x);
    if (len > 0.f) t = glm::vec4(x / len, det < 0.f ? -t.w : t.w);
  }
  if (det < 0.f) {
    for (size_t k = 0; k + 2 < mesh.indices.size(); k += 3) std::swap(mesh.indices[k + 1], mesh.indices[k + 2]);
  }
}

}  // namespace cleave::geometry::primitives
