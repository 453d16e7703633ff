// SPDX-License-Identifier: MIT
#include "game/arena/arena_art.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/primitives.h"
#include "game/arena/arena_surroundings.h"

namespace cleave::arena {

namespace {

constexpr double kPi = 3.14159265358979323846;

uint32_t hash2(uint32_t x, uint32_t y, uint32_t seed) {
  uint32_t h = x * 0x27d4eb2du ^ y * 0x165667b1u ^ seed * 0x9e3779b9u;
  h ^= h >> 15;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  return h;
}

float unit(uint32_t h) { return float(h & 0xffffu) / 65535.f; }

glm::vec3 toLinear(glm::vec3 display) { return glm::pow(glm::clamp(display, 0.f, 1.f), glm::vec3(2.2f)); }

void put(assets::Image& img, int x, int y, glm::vec3 linear) {
  const glm::vec3 c = glm::clamp(linear, 0.f, 1.f) * 255.f + 0.5f;
  uint8_t* p = &img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
  p[0] = uint8_t(c.r);
  p[1] = uint8_t(c.g);
  p[2] = uint8_t(c.b);
  p[3] = 255;
}

glm::vec3 get(const assets::Image& img, int x, int y) {
  const uint8_t* p = &img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
  return glm::vec3(p[0], p[1], p[2]) / 255.f;
}

assets::Image blank(int size) {
  assets::Image img;
  img.width = img.height = std::max(size, 8);
  img.rgba.assign(size_t(img.width) * size_t(img.height) * 4, 255);
  return img;
}

// 5 x 7 glyphs, one string per row, '#' set.
const char* glyph(char c) {
  switch (c) {
    case 'A': return ".###.#...##...#######...##...##...#";
    case 'Q': return ".###.#...##...##...##.#.##..#..##.#";
    case 'R': return "####.#...##...#####.#.#..#..#.#...#";
    case 'S': return ".#####....#.....###.....#....#####.";
    case 'T': return "#####..#....#....#....#....#....#..";
    case 'U': return "#...##...##...##...##...##...#.###.";
    case 'I': return ".###...#....#....#....#....#...###.";
    default: return nullptr;
  }
}

}  // namespace

assets::Image makeFlagstoneTexture(int size, uint32_t seed) {
  assets::Image img = blank(size);
  const int n = img.width;
  constexpr int kStones = 4;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const glm::vec2 uv(float(x) / float(n), float(y) / float(n));
      // Running bond: odd rows are shifted half a stone.
      const float row = uv.y * kStones;
      const int r = int(std::floor(row));
      const float col = uv.x * kStones + ((r & 1) ? 0.5f : 0.f);
      const int c = int(std::floor(col));
      const float fx = col - float(c), fy = row - float(r);
      // Grout: distance to the stone's edge, roughened by noise so the edges are not ruler-straight.
      const float rough = 0.035f * assets::tileableNoise(uv * 32.f, 32, 2, seed + 7);
      const float edge = std::min(std::min(fx, 1.f - fx), std::min(fy, 1.f - fy)) - rough;
      const uint32_t stoneId = hash2(uint32_t((c % kStones + kStones) % kStones), uint32_t(r), seed);
      const float tint = unit(stoneId);
      const float mottle = assets::tileableNoise(uv * 16.f, 16, 4, seed + 3);
      const float grain = assets::tileableNoise(uv * 64.f, 64, 2, seed + 11);
      glm::vec3 stone = glm::mix(glm::vec3(0.78f, 0.66f, 0.50f), glm::vec3(0.66f, 0.55f, 0.42f), tint);
      stone *= 0.78f + 0.3f * mottle + 0.08f * grain;
      const glm::vec3 grout(0.50f, 0.42f, 0.33f);
      const float g = glm::smoothstep(0.004f, 0.02f, edge);
      // Worn, slightly darker rims next to the grout.
      const float rim = 1.f - 0.08f * (1.f - glm::smoothstep(0.02f, 0.08f, edge));
      put(img, x, y, toLinear(glm::mix(grout, stone * rim, g)));
    }
  }
  return img;
}

assets::Image makeTerracottaTexture(int size, uint32_t seed) {
  assets::Image img = blank(size);
  const int n = img.width;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const glm::vec2 uv(float(x) / float(n), float(y) / float(n));
      const float noise = assets::tileableNoise(uv * 8.f, 8, 4, seed);
      glm::vec3 clay = glm::vec3(0.72f, 0.38f, 0.20f) * (0.85f + 0.25f * noise);
      // v: rows top to bottom are v = 0..1 as uploaded; the lathe's v runs up the urn. A black band
      // with an orange meander around the belly (v about 0.45 - 0.6).
      const float v = uv.y;
      if (v > 0.44f && v < 0.62f) {
        clay = glm::vec3(0.08f, 0.06f, 0.05f);
        const float m = std::fmod(uv.x * 24.f, 1.f);
        const float h = (v - 0.44f) / 0.18f;
        const bool meander = (h > 0.2f && h < 0.32f) || (h > 0.68f && h < 0.8f) ||
                             (m > 0.1f && m < 0.22f && h > 0.2f && h < 0.8f) ||
                             (m > 0.5f && m < 0.62f && h > 0.2f && h < 0.68f && h > 0.32f);
        if (meander) clay = glm::vec3(0.80f, 0.45f, 0.22f);
      }
      if ((v > 0.40f && v < 0.42f) || (v > 0.64f && v < 0.66f)) clay = glm::vec3(0.1f, 0.07f, 0.05f);
      put(img, x, y, toLinear(clay));
    }
  }
  return img;
}

assets::Image makeLetteredMetalTexture(int size, const std::string& word, uint32_t seed) {
  assets::Image img = assets::makeTexture(assets::TextureKind::BrushedMetal, size, seed);
  const int n = img.width;
  // Raised border and rivets.
  const int border = n / 16;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const int d = std::min(std::min(x, n - 1 - x), std::min(y, n - 1 - y));
      glm::vec3 c = get(img, x, y);
      if (d < border) c *= (d < 2 ? 0.45f : 0.8f);
      if (d == border || d == border + 1) c *= 0.5f;
      const int rx = x < n / 2 ? x - border / 2 : n - 1 - border / 2 - x;
      const int ry = y < n / 2 ? y - border / 2 : n - 1 - border / 2 - y;
      if (rx * rx + ry * ry < (border / 3) * (border / 3)) c = glm::vec3(0.9f);
      put(img, x, y, c);
    }
  }
  // Engraved letters: dark grooves with a light lower edge. The texture's first row is the top of
  // the cube face as the box primitive maps it (v = 0 at the bottom of the face, rows from v = 0),
  // so glyph rows are written bottom-up.
  const int letters = int(std::min<size_t>(word.size(), 5));
  if (letters == 0) return img;
  const int scale = std::max(1, (n - 2 * border - 8) / (letters * 6));
  const int width = letters * 6 * scale - scale;
  const int x0 = (n - width) / 2;
  const int y0 = (n - 7 * scale) / 2;
  for (int k = 0; k < letters; ++k) {
    const char* g = glyph(word[size_t(k)]);
    if (!g) continue;
    for (int gy = 0; gy < 7; ++gy) {
      for (int gx = 0; gx < 5; ++gx) {
        if (g[gy * 5 + gx] != '#') continue;
        for (int py = 0; py < scale; ++py) {
          for (int px = 0; px < scale; ++px) {
            const int x = x0 + (k * 6 + gx) * scale + px;
            const int y = n - 1 - (y0 + gy * scale + py);  // flipped: glyph row 0 is the top
            if (x < 0 || x >= n || y < 0 || y >= n) continue;
            const bool lip = py == scale - 1;
            put(img, x, y, lip ? glm::vec3(0.85f, 0.8f, 0.7f) : glm::vec3(0.05f, 0.05f, 0.06f));
          }
        }
      }
    }
  }
  return img;
}

geometry::MeshData lathe(const std::vector<glm::vec2>& profile, uint32_t segments) {
  geometry::MeshData m;
  const size_t rings = profile.size();
  if (rings < 2) return m;
  segments = std::max(segments, 3u);
  const float height = profile.back().y - profile.front().y;
  // One function for every ring position so the seam column and the cap rims repeat the side's
  // vertices bit for bit (the split core welds on equal positions).
  auto ringPoint = [&](size_t k, uint32_t j) {
    const double a = 2.0 * kPi * double(j % segments) / double(segments);
    const double r = profile[k].x;
    return glm::vec3(glm::dvec3(r * std::cos(a), profile[k].y, -r * std::sin(a)));
  };
  // Side.
  for (size_t k = 0; k < rings; ++k) {
    const glm::vec2 prev = profile[k == 0 ? 0 : k - 1], next = profile[std::min(k + 1, rings - 1)];
    const glm::vec2 d = glm::normalize(next - prev);
    const glm::vec2 nrm(d.y, -d.x);  // outward in the (r, y) half-plane
    for (uint32_t j = 0; j <= segments; ++j) {
      const double a = 2.0 * kPi * double(j % segments) / double(segments);
      const float c = float(std::cos(a)), s = float(std::sin(a));
      m.positions.push_back(ringPoint(k, j));
      m.normals.push_back(glm::normalize(glm::vec3(nrm.x * c, nrm.y, -nrm.x * s)));
      m.tangents.push_back(glm::vec4(-s, 0.f, -c, 1.f));
      m.uv0.push_back(glm::vec2(float(j) / float(segments), (profile[k].y - profile.front().y) / height));
    }
  }
  const uint32_t stride = segments + 1;
  for (uint32_t k = 0; k + 1 < rings; ++k) {
    for (uint32_t j = 0; j < segments; ++j) {
      const uint32_t a = k * stride + j, b = a + 1, c = b + stride, d = a + stride;
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    }
  }
  // Caps: a centre vertex and a rim ring each.
  for (int top = 0; top < 2; ++top) {
    const size_t k = top ? rings - 1 : 0;
    const glm::vec3 normal(0.f, top ? 1.f : -1.f, 0.f);
    const uint32_t centre = uint32_t(m.positions.size());
    m.positions.push_back(glm::vec3(0.f, profile[k].y, 0.f));
    m.normals.push_back(normal);
    m.tangents.push_back(glm::vec4(1.f, 0.f, 0.f, top ? 1.f : -1.f));
    m.uv0.push_back(glm::vec2(0.5f));
    for (uint32_t j = 0; j < segments; ++j) {
      const glm::vec3 p = ringPoint(k, j);
      m.positions.push_back(p);
      m.normals.push_back(normal);
      m.tangents.push_back(glm::vec4(1.f, 0.f, 0.f, top ? 1.f : -1.f));
      m.uv0.push_back(glm::vec2(0.5f) + glm::vec2(p.x, p.z) * 0.5f);
    }
    for (uint32_t j = 0; j < segments; ++j) {
      const uint32_t a = centre + 1 + j, b = centre + 1 + (j + 1) % segments;
      if (top)
        m.indices.insert(m.indices.end(), {centre, a, b});
      else
        m.indices.insert(m.indices.end(), {centre, b, a});
    }
  }
  return m;
}

geometry::MeshData urnMesh() {
  const std::vector<glm::vec2> profile = {
      {0.15f, 0.00f}, {0.20f, 0.03f}, {0.21f, 0.08f}, {0.18f, 0.13f}, {0.26f, 0.28f},
      {0.34f, 0.46f}, {0.37f, 0.62f}, {0.35f, 0.78f}, {0.28f, 0.93f}, {0.17f, 1.04f},
      {0.12f, 1.11f}, {0.115f, 1.21f}, {0.16f, 1.27f}, {0.18f, 1.33f}};
  return lathe(profile, 28);
}

void planarUv(geometry::MeshData& mesh, float uvPerMetre) {
  mesh.uv0.resize(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    mesh.uv0[i] = glm::vec2(mesh.positions[i].x, mesh.positions[i].z) * uvPerMetre;
}

void setMaterial(geometry::MeshData& mesh, uint32_t materialId) {
  mesh.submeshes = {geometry::SubMesh{0, uint32_t(mesh.indices.size()), materialId}};
}

geometry::MeshData gladiatorMesh() {
  namespace prim = geometry::primitives;
  geometry::MeshData mesh;
  bool first = true;
  auto add = [&](geometry::MeshData part, uint32_t material, glm::vec3 offset) {
    setMaterial(part, material);
    prim::transform(part, glm::translate(glm::mat4(1.f), offset));
    mesh = first ? std::move(part) : prim::merge(mesh, part);
    first = false;
  };
  // Legs (0.02 - 0.80), torso (0.84 - 1.44), head (1.46 - 1.78), arms (0.83 - 1.43): a few
  // centimetres of air between parts keeps each island convex and the whole mesh closed.
  add(prim::capsule(0.09f, 0.60f, 12, 6), 3, {-0.12f, 0.41f, 0.f});
  add(prim::capsule(0.09f, 0.60f, 12, 6), 3, {0.12f, 0.41f, 0.f});
  add(prim::box(glm::vec3(0.25f, 0.30f, 0.15f)), 0, {0.f, 1.14f, 0.f});
  add(prim::uvSphere(0.16f, 14, 8), 2, {0.f, 1.62f, 0.f});
  add(prim::capsule(0.075f, 0.45f, 10, 6), 2, {-0.355f, 1.13f, 0.f});
  add(prim::capsule(0.075f, 0.45f, 10, 6), 2, {0.355f, 1.13f, 0.f});
  return mesh;
}

namespace {

// The arena's textures, uploaded once (ArenaMaterials::textures owns them).
struct ArenaTextures {
  render::TextureHandle flag, stone, marble, wood, metal, clay, start, quit, turf;
};

// The floor, the wall and its gates, the pillars, and outside the wall the stands, turf and crowd.
void setLevelMaterials(ArenaMaterials& m, const ArenaTextures& t) {
  m.floor.albedo = t.flag;
  m.floor.specular = 0.12f;
  m.floor.shininess = 16.f;
  m.floor.castsShadow = false;  // it only receives: the shadow pass skips the whole arena floor
  m.wall.albedo = t.stone;
  m.wall.baseColor = glm::vec4(1.05f, 0.92f, 0.78f, 1.f);
  m.wall.specular = 0.08f;
  m.wallTrim = m.wall;
  m.wallTrim.baseColor = glm::vec4(0.85f, 0.74f, 0.62f, 1.f);
  m.pillar.albedo = t.marble;
  m.pillar.baseColor = glm::vec4(1.0f, 0.96f, 0.9f, 1.f);
  m.pillar.specular = 0.5f;
  m.pillar.shininess = 50.f;
  m.stands = m.wall;
  m.stands.baseColor = glm::vec4(0.98f, 0.88f, 0.74f, 1.f);
  m.stands.castsShadow = false;  // drawn for the view only: no shadows over the sand
  m.standsRiser = m.stands;
  m.standsRiser.baseColor = glm::vec4(0.66f, 0.56f, 0.46f, 1.f);
  m.turf.albedo = t.turf;
  m.turf.specular = 0.04f;
  m.turf.castsShadow = false;
  // The crowd: tunics of white, madder red, woad blue and ochre (crowdMesh's ids 0..3), then skin.
  for (glm::vec4 c : {glm::vec4(0.85f, 0.82f, 0.74f, 1.f), glm::vec4(0.62f, 0.14f, 0.10f, 1.f),
                      glm::vec4(0.16f, 0.24f, 0.50f, 1.f), glm::vec4(0.72f, 0.52f, 0.18f, 1.f),
                      glm::vec4(0.62f, 0.42f, 0.30f, 1.f)}) {
    render::Material mat;
    mat.baseColor = c;
    mat.specular = 0.05f;
    mat.castsShadow = false;
    m.crowd.push_back(mat);
  }
  m.gate.albedo = t.wood;
  m.gate.baseColor = glm::vec4(0.35f, 0.22f, 0.14f, 1.f);
  m.gate.specular = 0.05f;

}

// The crates and urns, the menu cubes and the weapons.
void setPropMaterials(ArenaMaterials& m, const ArenaTextures& t) {
  m.crate.albedo = t.wood;
  m.crate.specular = 0.12f;
  m.crate.shininess = 20.f;
  m.crateCap = m.crate;
  m.crateCap.baseColor = glm::vec4(1.15f, 1.05f, 0.9f, 1.f);
  m.urn.albedo = t.clay;
  m.urn.specular = 0.3f;
  m.urn.shininess = 30.f;
  m.urnCap.baseColor = glm::vec4(0.55f, 0.28f, 0.16f, 1.f);
  m.urnCap.specular = 0.05f;

  m.startCube.albedo = t.start;
  m.startCube.specular = 1.2f;
  m.startCube.shininess = 90.f;
  m.startCube.reflectivity = 0.45f;
  m.quitCube = m.startCube;
  m.quitCube.albedo = t.quit;
  m.metalCap.albedo = t.metal;
  m.metalCap.baseColor = glm::vec4(0.75f, 0.75f, 0.8f, 1.f);
  m.metalCap.specular = 0.8f;
  m.metalCap.reflectivity = 0.15f;

  m.disc.shading = render::Shading::Unlit;
  m.disc.baseColor = glm::vec4(0.35f, 0.95f, 1.0f, 1.f);
  m.blade = m.disc;
  m.bladeCore.shading = render::Shading::Unlit;
  m.bladeCore.baseColor = glm::vec4(0.85f, 1.0f, 1.0f, 1.f);

}

// The gladiators' parts, the player and the skinned warriors.
void setFigureMaterials(ArenaMaterials& m, const ArenaTextures& t, const std::vector<glm::vec4>& characterColors) {
  m.armour.albedo = t.metal;
  m.armour.baseColor = glm::vec4(0.78f, 0.42f, 0.16f, 1.f);  // bronze
  m.armour.specular = 1.2f;
  m.armour.shininess = 60.f;
  m.armour.reflectivity = 0.12f;
  m.skin.baseColor = glm::vec4(0.55f, 0.36f, 0.26f, 1.f);
  m.skin.specular = 0.2f;
  m.cloth.baseColor = glm::vec4(0.42f, 0.08f, 0.07f, 1.f);
  m.cloth.specular = 0.05f;
  m.flesh.shading = render::Shading::Unlit;
  m.flesh.baseColor = glm::vec4(1.0f, 0.42f, 0.08f, 1.f);  // the energy blade's burn

  // The player: the character's colours, restyled as a gladiator (bronze-red tunic).
  for (size_t i = 0; i < characterColors.size(); ++i) {
    render::Material mat;
    mat.baseColor = characterColors[i];
    mat.specular = 0.25f;
    m.player.push_back(mat);
  }
  if (m.player.size() > 2) {
    m.player[2].baseColor = glm::vec4(0.62f, 0.12f, 0.08f, 1.f);
    m.player[2].specular = 0.3f;
  }
  if (m.player.size() > 3) m.player[3].baseColor = glm::vec4(0.30f, 0.22f, 0.15f, 1.f);
  // The skinned enemies: the same character in a dark red tunic with bronze skin, black trousers
  // and bronze boots, so they never read as the player; their caps (id 1) are the blade's burn.
  m.skinnedEnemy = m.player;
  if (m.skinnedEnemy.size() < 5) m.skinnedEnemy.resize(5);
  m.skinnedEnemy[0].baseColor = glm::vec4(0.58f, 0.36f, 0.18f, 1.f);
  m.skinnedEnemy[0].specular = 0.45f;
  m.skinnedEnemy[0].shininess = 30.f;
  m.skinnedEnemy[1] = m.flesh;
  m.skinnedEnemy[2].baseColor = glm::vec4(0.20f, 0.02f, 0.04f, 1.f);
  m.skinnedEnemy[2].specular = 0.2f;
  m.skinnedEnemy[3].baseColor = glm::vec4(0.07f, 0.06f, 0.07f, 1.f);
  m.skinnedEnemy[4].baseColor = glm::vec4(0.62f, 0.42f, 0.16f, 1.f);
  m.skinnedEnemy[4].specular = 0.6f;
  m.skinnedEnemy[4].shininess = 40.f;
}

}  // namespace

ArenaMaterials createArenaMaterials(render::Renderer& r, const std::vector<glm::vec4>& characterColors) {
  ArenaMaterials m;
  auto upload = [&](const assets::Image& img) {
    const render::TextureHandle h = r.createTexture(img.width, img.height, img.rgba).valueOr({});
    m.textures.push_back(h);
    return h;
  };
  ArenaTextures t;
  t.flag = upload(makeFlagstoneTexture(512, 21));
  t.stone = upload(assets::makeTexture(assets::TextureKind::Stone, 256, 4));
  t.marble = upload(assets::makeTexture(assets::TextureKind::Marble, 256, 6));
  t.wood = upload(assets::makeTexture(assets::TextureKind::Wood, 256, 8));
  t.metal = upload(assets::makeTexture(assets::TextureKind::BrushedMetal, 256, 10));
  t.clay = upload(makeTerracottaTexture(256, 12));
  t.start = upload(makeLetteredMetalTexture(256, "START", 14));
  t.quit = upload(makeLetteredMetalTexture(256, "QUIT", 16));
  t.turf = upload(makeTurfTexture(256, 18));
  setLevelMaterials(m, t);
  setPropMaterials(m, t);
  setFigureMaterials(m, t, characterColors);
  return m;
}

}  // namespace cleave::arena
