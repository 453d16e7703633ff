// SPDX-License-Identifier: MIT
#include "cleave/assets/procedural_textures.h"

#include <algorithm>
#include <cmath>

namespace cleave::assets {

namespace {

uint32_t hash(uint32_t x, uint32_t y, uint32_t seed) {
  uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return h;
}

float lattice(int x, int y, int period, uint32_t seed) {
  const int px = ((x % period) + period) % period;
  const int py = ((y % period) + period) % period;
  return float(hash(uint32_t(px), uint32_t(py), seed) & 0xffffu) / 65535.f;
}

float smooth(float t) { return t * t * (3.f - 2.f * t); }

float valueNoise(glm::vec2 p, int period, uint32_t seed) {
  const int x0 = int(std::floor(p.x)), y0 = int(std::floor(p.y));
  const float fx = smooth(p.x - float(x0)), fy = smooth(p.y - float(y0));
  const float a = lattice(x0, y0, period, seed), b = lattice(x0 + 1, y0, period, seed);
  const float c = lattice(x0, y0 + 1, period, seed), d = lattice(x0 + 1, y0 + 1, period, seed);
  return glm::mix(glm::mix(a, b, fx), glm::mix(c, d, fx), fy);
}

glm::vec3 srgbToLinear(glm::vec3 c) { return glm::pow(c, glm::vec3(2.2f)); }

void put(Image& img, int x, int y, glm::vec3 linearColor) {
  // Textures are stored as display-referred values; the renderer multiplies them into the linear
  // base colour, so store linear values directly (no gamma), clamped.
  const glm::vec3 c = glm::clamp(linearColor, 0.f, 1.f) * 255.f + 0.5f;
  uint8_t* p = &img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
  p[0] = uint8_t(c.r);
  p[1] = uint8_t(c.g);
  p[2] = uint8_t(c.b);
  p[3] = 255;
}

}  // namespace

float tileableNoise(glm::vec2 p, int period, int octaves, uint32_t seed) {
  float sum = 0.f, amplitude = 0.5f, norm = 0.f;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * valueNoise(p, period, seed + uint32_t(o) * 101u);
    norm += amplitude;
    p *= 2.f;
    period *= 2;
    amplitude *= 0.5f;
  }
  return sum / norm;
}

Image makeTexture(TextureKind kind, int size, uint32_t seed) {
  Image img;
  size = std::clamp(size, 4, 4096);
  img.width = img.height = size;
  img.rgba.assign(size_t(size) * size_t(size) * 4, 255);
  const float inv = 1.f / float(size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const glm::vec2 uv(float(x) * inv, float(y) * inv);
      glm::vec3 color(1.f);
      switch (kind) {
        case TextureKind::Wood: {
          // Rings: distance from a virtual trunk axis, disturbed by noise; grain streaks along v.
          const float n = tileableNoise(uv * glm::vec2(4.f, 1.f), 4, 4, seed);
          const float rings = std::sin((uv.x * 6.f + n * 2.5f) * 6.2831853f * 2.f) * 0.5f + 0.5f;
          const float grain = tileableNoise(glm::vec2(uv.x * 64.f, uv.y * 2.f), 64, 2, seed + 7);
          const glm::vec3 light = srgbToLinear({0.80f, 0.58f, 0.34f});
          const glm::vec3 dark = srgbToLinear({0.52f, 0.32f, 0.16f});
          color = glm::mix(light, dark, 0.55f * std::pow(rings, 3.f) + 0.35f * grain);
          break;
        }
        case TextureKind::Marble: {
          const float n = tileableNoise(uv * 4.f, 4, 5, seed);
          const float vein = std::abs(std::sin((uv.x + uv.y + n * 1.6f) * 6.2831853f * 2.f));
          const float sharp = std::pow(1.f - vein, 8.f);
          const float cloud = tileableNoise(uv * 8.f, 8, 3, seed + 3);
          const glm::vec3 stone = srgbToLinear(glm::vec3(0.92f, 0.91f, 0.88f) - 0.08f * cloud);
          const glm::vec3 veinColor = srgbToLinear({0.30f, 0.32f, 0.36f});
          color = glm::mix(stone, veinColor, sharp * 0.85f);
          break;
        }
        case TextureKind::Melon: {
          if (uv.x < 0.5f) {
            // Rind: dark and light green stripes along v.
            const float n = tileableNoise(uv * glm::vec2(8.f, 8.f), 8, 3, seed);
            const float stripe = std::sin((uv.x * 2.f * 12.f + n * 1.5f) * 6.2831853f) * 0.5f + 0.5f;
            color = glm::mix(srgbToLinear({0.16f, 0.42f, 0.14f}), srgbToLinear({0.45f, 0.68f, 0.30f}),
                             std::pow(stripe, 2.f));
          } else {
            // Flesh: red with lighter fibres and black seeds on a sparse lattice.
            const float n = tileableNoise(uv * 16.f, 16, 3, seed + 5);
            color = glm::mix(srgbToLinear({0.86f, 0.16f, 0.18f}), srgbToLinear({0.97f, 0.45f, 0.42f}),
                             n * 0.6f);
            const glm::vec2 cell = uv * 12.f;
            const glm::vec2 id = glm::floor(cell);
            const float jx = float(hash(uint32_t(id.x), uint32_t(id.y), seed) & 255u) / 255.f;
            const float jy = float(hash(uint32_t(id.y), uint32_t(id.x), seed + 1) & 255u) / 255.f;
            const glm::vec2 d = (cell - id - glm::vec2(0.3f + 0.4f * jx, 0.3f + 0.4f * jy)) *
                                glm::vec2(1.f, 0.6f);
            if (glm::dot(d, d) < 0.012f) color = srgbToLinear({0.05f, 0.04f, 0.03f});
          }
          break;
        }
        case TextureKind::BrushedMetal: {
          const float streak = tileableNoise(glm::vec2(uv.x * 2.f, uv.y * 256.f), 256, 2, seed);
          color = glm::vec3(0.62f + 0.12f * streak);
          break;
        }
        case TextureKind::Checker: {
          const int cx = int(uv.x * 8.f), cy = int(uv.y * 8.f);
          color = ((cx + cy) & 1) ? glm::vec3(0.75f) : glm::vec3(0.25f);
          break;
        }
        case TextureKind::Stone: {
          const float n = tileableNoise(uv * 8.f, 8, 5, seed);
          color = srgbToLinear(glm::vec3(0.45f + 0.3f * n, 0.43f + 0.28f * n, 0.40f + 0.25f * n));
          break;
        }
      }
      put(img, x, y, color);
    }
  }
  return img;
}

}  // namespace cleave::assets
