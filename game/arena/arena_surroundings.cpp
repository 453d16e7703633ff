// SPDX-License-Identifier: MIT
#include "game/arena/arena_surroundings.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/primitives.h"

namespace cleave::arena {

namespace {

constexpr double kTwoPi = 6.283185307179586;

// Appends `src` (positions, normals, uv0, tangents) to `dst` as triangles of `material`, extending
// the last submesh run when it has the same material. Callers append grouped by material.
void appendAs(geometry::MeshData& dst, const geometry::MeshData& src, uint32_t material) {
  const uint32_t base = uint32_t(dst.positions.size());
  const uint32_t first = uint32_t(dst.indices.size());
  dst.positions.insert(dst.positions.end(), src.positions.begin(), src.positions.end());
  dst.normals.insert(dst.normals.end(), src.normals.begin(), src.normals.end());
  dst.uv0.insert(dst.uv0.end(), src.uv0.begin(), src.uv0.end());
  dst.tangents.insert(dst.tangents.end(), src.tangents.begin(), src.tangents.end());
  for (uint32_t i : src.indices) dst.indices.push_back(base + i);
  const uint32_t count = uint32_t(dst.indices.size()) - first;
  if (!dst.submeshes.empty() && dst.submeshes.back().materialId == material)
    dst.submeshes.back().indexCount += count;
  else
    dst.submeshes.push_back(geometry::SubMesh{first, count, material});
}

// One edge of a swept section as a band of quads around the y axis.
geometry::MeshData band(glm::vec2 from, glm::vec2 to, uint32_t segments, float uvPerMetre) {
  geometry::MeshData m;
  const glm::vec2 d = glm::normalize(to - from);
  const glm::vec2 outward(d.y, -d.x);  // right of the edge: outside of a counter-clockwise section
  const float length = glm::length(to - from);
  for (int end = 0; end < 2; ++end) {
    const glm::vec2 p = end ? to : from;
    for (uint32_t j = 0; j <= segments; ++j) {
      // The seam column repeats the first one's positions bit for bit (angle of j % segments).
      const double a = kTwoPi * double(j % segments) / double(segments);
      const float c = float(std::cos(a)), s = float(std::sin(a));
      m.positions.push_back(glm::vec3(p.x * c, p.y, -p.x * s));
      m.normals.push_back(glm::normalize(glm::vec3(outward.x * c, outward.y, -outward.x * s)));
      m.tangents.push_back(glm::vec4(-s, 0.f, -c, 1.f));
      const float along = float(kTwoPi * double(j) / double(segments)) * std::max(p.x, 0.5f);
      m.uv0.push_back(glm::vec2(along, end ? length : 0.f) * uvPerMetre);
    }
  }
  const uint32_t stride = segments + 1;
  for (uint32_t j = 0; j < segments; ++j) {
    const uint32_t a = j, b = j + 1, c = b + stride, e = a + stride;
    m.indices.insert(m.indices.end(), {a, b, c, a, c, e});
  }
  return m;
}

// The stands' section, counter-clockwise in (radius, height): the foot, the outer wall, then down the
// steps from the top tier to the front row and down behind the arena wall. `risers` gets the index of
// every edge that is a riser (facing the sand).
std::vector<glm::vec2> standsSection(const StandsLayout& s, std::vector<size_t>& risers) {
  const float outer = s.outerRadius(), wall = outer + s.outerWallThickness;
  const float top = s.topHeight() + s.outerWallHeight;
  std::vector<glm::vec2> p = {{s.innerRadius, 0.f}, {wall, 0.f}, {wall, top}, {outer, top}};
  p.push_back({outer, s.topHeight()});  // down the outer wall's inner face to the top tread
  for (int t = s.tiers - 1; t >= 0; --t) {
    const float height = s.firstTierHeight + s.tierRise * float(t);
    p.push_back({s.innerRadius + s.tierDepth * float(t), height});  // along the tread, towards the sand
    if (t == 0) break;
    risers.push_back(p.size() - 1);  // the edge from here down to the next tread
    p.push_back({s.innerRadius + s.tierDepth * float(t), height - s.tierRise});
  }
  risers.push_back(p.size() - 1);  // the front, down behind the arena wall
  return p;
}

}  // namespace

geometry::MeshData sweepAround(const std::vector<glm::vec2>& section, uint32_t segments, float uvPerMetre) {
  geometry::MeshData m;
  segments = std::max(segments, 3u);
  for (size_t k = 0; k < section.size(); ++k) {
    const glm::vec2 a = section[k], b = section[(k + 1) % section.size()];
    if (glm::length(b - a) > 1e-6f) appendAs(m, band(a, b, segments, uvPerMetre), 0);
  }
  return m;
}

geometry::MeshData standsMesh(const StandsLayout& layout) {
  std::vector<size_t> risers;
  const std::vector<glm::vec2> section = standsSection(layout, risers);
  geometry::MeshData treads, faces;
  for (size_t k = 0; k < section.size(); ++k) {
    const glm::vec2 a = section[k], b = section[(k + 1) % section.size()];
    if (glm::length(b - a) <= 1e-6f) continue;
    const bool riser = std::find(risers.begin(), risers.end(), k) != risers.end();
    appendAs(riser ? faces : treads, band(a, b, layout.segments, 0.5f), 0);
  }
  geometry::MeshData m;
  appendAs(m, treads, 0);
  appendAs(m, faces, 2);
  return m;
}

geometry::MeshData crowdMesh(const StandsLayout& layout, uint32_t seed) {
  namespace prim = geometry::primitives;
  // Every figure's boxes by material, then appended material by material (contiguous runs).
  std::array<std::vector<glm::mat4>, kCrowdColours + 1> bodies;
  const geometry::MeshData body = prim::box(glm::vec3(0.17f, 0.23f, 0.12f));
  const geometry::MeshData head = prim::box(glm::vec3(0.1f, 0.11f, 0.1f));
  for (int t = 0; t < layout.tiers; ++t) {
    const float radius = layout.innerRadius + layout.tierDepth * (float(t) + 0.55f);
    const float floor = layout.firstTierHeight + layout.tierRise * float(t);
    const int seats = int(kTwoPi * radius / 0.7);
    for (int k = 0; k < seats; ++k) {
      uint32_t h = uint32_t(t) * 0x9e3779b1u ^ uint32_t(k) * 0x85ebca77u ^ seed * 0xc2b2ae3du;
      h ^= h >> 15;
      h *= 0x2c1b3c6du;
      h ^= h >> 12;
      if ((h & 0xff) > 170) continue;  // an empty seat
      const double a = kTwoPi * (double(k) + 0.5 * double(t % 2)) / double(seats);
      const glm::vec3 at(radius * float(std::cos(a)), floor, -radius * float(std::sin(a)));
      const float lean = float(int((h >> 8) & 0xf) - 8) * 0.01f;
      const glm::mat4 frame = glm::rotate(glm::translate(glm::mat4(1.f), at), float(a) + lean, glm::vec3(0, 1, 0));
      bodies[(h >> 16) % kCrowdColours].push_back(glm::translate(frame, glm::vec3(0.f, 0.23f, 0.f)));
      bodies[kCrowdColours].push_back(glm::translate(frame, glm::vec3(0.f, 0.58f, 0.f)));
    }
  }
  geometry::MeshData m;
  for (uint32_t material = 0; material <= kCrowdColours; ++material) {
    for (const glm::mat4& model : bodies[material]) {
      geometry::MeshData part = material == kCrowdColours ? head : body;
      prim::transform(part, model);
      appendAs(m, part, material);
    }
  }
  return m;
}

geometry::MeshData groundRing(float innerRadius, float outerRadius, float top, float uvPerMetre) {
  const std::vector<glm::vec2> section = {
      {innerRadius, top - 0.5f}, {outerRadius, top - 0.5f}, {outerRadius, top}, {innerRadius, top}};
  geometry::MeshData m = sweepAround(section, 96, uvPerMetre);
  // Planar uv from above: the turf's pattern keeps its size from the wall out to the fog.
  for (size_t i = 0; i < m.positions.size(); ++i) m.uv0[i] = glm::vec2(m.positions[i].x, m.positions[i].z) * uvPerMetre;
  return m;
}

assets::Image makeTurfTexture(int size, uint32_t seed) {
  assets::Image img;
  img.width = img.height = std::max(size, 8);
  img.rgba.resize(size_t(img.width) * size_t(img.height) * 4);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const glm::vec2 uv(float(x) / float(img.width), float(y) / float(img.height));
      const float patches = assets::tileableNoise(uv * 4.f, 4, 3, seed);
      const float blades = assets::tileableNoise(uv * 64.f, 64, 2, seed + 1);
      const glm::vec3 dry(0.62f, 0.56f, 0.30f), green(0.36f, 0.44f, 0.17f), earth(0.50f, 0.38f, 0.25f);
      glm::vec3 c = glm::mix(dry, green, glm::smoothstep(0.35f, 0.7f, patches));
      c = glm::mix(c, earth, glm::smoothstep(0.72f, 0.8f, 1.f - patches) * 0.8f);
      c *= 0.82f + 0.3f * blades;
      uint8_t* p = &img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
      for (int k = 0; k < 3; ++k) p[k] = uint8_t(std::clamp(std::pow(c[k], 2.2f) * 255.f + 0.5f, 0.f, 255.f));
      p[3] = 255;
    }
  }
  return img;
}

}  // namespace cleave::arena
