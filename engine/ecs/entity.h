// SPDX-License-Identifier: MIT
// Entity: a generational id naming one object of a World.
//
// An entity is a 32-bit slot index plus the 32-bit generation the slot had when the entity was
// created. Destroying an entity bumps the slot's generation, so an id kept after destroy is stale:
// World::alive() reports false for it even after the slot has been reused by a newer entity.
// Generation 0 is never handed out, so a default-constructed Entity (kNullEntity) never refers to
// anything. Entities are plain values: copy them, compare them, order them (by index, then
// generation) and use them as keys of ordered containers. They only mean something to the World
// that made them.
#pragma once

#include <compare>
#include <cstdint>
#include <string>

namespace cleave::ecs {

struct Entity {
  uint32_t index = 0;
  uint32_t generation = 0;  // 0 = null; live entities have generation >= 1

  constexpr bool isNull() const { return generation == 0; }
  friend constexpr auto operator<=>(const Entity&, const Entity&) = default;
};

inline constexpr Entity kNullEntity{};

// "e<index>v<generation>", e.g. "e12v3"; "null" for kNullEntity. For logs and error messages.
inline std::string toString(Entity entity) {
  if (entity.isNull()) return "null";
  std::string text = "e";
  text += std::to_string(entity.index);
  text += 'v';
  text += std::to_string(entity.generation);
  return text;
}

}  // namespace cleave::ecs
