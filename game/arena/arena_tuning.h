// SPDX-License-Identifier: MIT
// How a match of the arena plays, as data: the player's health and cooldowns, each enemy kind's pace
// and blows, the waves and the pauses between them. Nothing else in the arena holds a difficulty
// number; change one here and every system reads it (ArenaGame keeps a copy, `ArenaGame::tuning`).
//
// Units: seconds, metres, metres per second, health points (the HUD bar is `player.health` wide).
// Times are turned into 60 Hz ticks by `ticksOf` (rounded to the nearest tick), so replays stay exact.
//
// The defaults are tuned for a first match: a grace period after START before anyone comes through a
// gate, arrivals one after another, at most `match.maxAttackers` enemies striking at once (the others
// wait their turn a little further out), a pause with health back to full between waves. A player
// who stands in the middle and presses the spin attack whenever it is ready lives through two waves;
// one who does nothing at all is beaten after about half a minute (tests/arena checks both).
#pragma once

#include <cmath>
#include <cstdint>

namespace cleave::arena {

struct PlayerTuning {
  int health = 100;                    // points at the start of a match and after each refill
  float speed = 5.f;                   // m/s
  float swordCooldownSeconds = 20.f / 60.f;
  float spinCooldownSeconds = 4.f;
  float hammerCooldownSeconds = 2.5f;
  uint32_t hammerCells = 12;           // cells of what the hammer shatters
  float hammerOutwardImpulse = 3.f;    // m/s, the cells thrown out from where it lands
};

// One enemy kind's pace and blows.
struct EnemyTuning {
  float walkSpeed = 1.8f;      // m/s
  float attackRange = 1.25f;   // m, centre to centre on the floor
  int attackDamage = 4;        // health points per blow
  float attackSeconds = 1.6f;  // between two blows
  float windupSeconds = 0.7f;  // from stepping into range to the first blow (the lunge can be seen)
  float radius = 0.42f;        // m, on the floor (crowding, obstacles)
};

// Who comes, where and when. Wave n (from 1) has gladiators + (n - 1) * gladiatorsPerWave gladiators
// and skinned + (n - 1) * skinnedPerWave skinned warriors. Wave 1 comes through the north gate; later
// waves through the four gates in turn (north, east, south, west), the slower skinned warriors last.
struct WaveTuning {
  int gladiators = 4;
  int gladiatorsPerWave = 4;
  int skinned = 2;
  int skinnedPerWave = 1;
  float firstArrivalSeconds = 0.5f;    // from the wave's banner to the first arrival
  float arrivalSeconds = 2.0f;         // wave 1: between one arrival and the next
  float laterArrivalSeconds = 0.9f;    // later waves: between one arrival and the next (any gate)
};

// The match's pacing.
struct MatchTuning {
  float startingSeconds = 80.f / 60.f;  // the Start cube's pieces fall while the camera moves in
  float graceSeconds = 5.f;             // then "GET READY": nobody comes through a gate yet
  float intermissionSeconds = 6.f;      // from a wave's last kill to the next wave's banner
  float refillDelaySeconds = 0.75f;     // "WAVE CLEARED", then the health bar fills up
  float refillSeconds = 1.5f;           // from empty to full (a partly full bar takes its share)
  int maxAttackers = 3;                 // enemies that close in and strike at once; the rest wait
  float waitDistance = 2.4f;            // m from the player, where the others wait their turn
  float defeatMenuDelaySeconds = 1.5f;  // after DEFEATED before Enter (or a click) goes to the menu
  float quitSeconds = 50.f / 60.f;      // after the Quit cube is cut, before the game ends
};

struct ArenaTuning {
  PlayerTuning player;
  EnemyTuning gladiator;
  // The skinned warriors: slower and heavier-handed than the gladiators.
  EnemyTuning skinned{1.5f, 1.3f, 5, 1.9f, 0.8f, 0.4f};
  WaveTuning waves;
  MatchTuning match;
};

// Whole ticks of the fixed 60 Hz step in `seconds` (rounded; negative counts as 0).
inline uint64_t ticksOf(float seconds) { return seconds > 0.f ? uint64_t(std::lround(seconds * 60.f)) : 0u; }

}  // namespace cleave::arena
