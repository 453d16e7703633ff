// SPDX-License-Identifier: MIT
// The phases of one fixed tick, declared in one place. Systems are free functions registered for a
// phase; phases run in this order every tick (Render only on ticks that produce a frame).
#pragma once

#include <array>
#include <cstdint>

namespace cleave::app {

enum class Phase : uint8_t {
  Input,        // fold this tick's input events into the input state
  Gameplay,     // game rules, controllers, spawning
  Triggers,     // read trigger events of the last physics step, emit split requests
  Split,        // prepare split requests gathered in earlier ticks, within the split budget; their
                // compute stage starts on worker threads
  Commit,       // commit the split jobs due this tick (pieces appear), in request order
  PhysicsStep,  // one fixed physics step
  PhysicsSync,  // copy body transforms back to entities
  Animation,    // sample clips, joint matrices
  Render,       // submit meshes to the renderer (frames only)
  Count
};

inline constexpr std::array<const char*, size_t(Phase::Count)> kPhaseNames = {
    "Input", "Gameplay", "Triggers", "Split", "Commit", "PhysicsStep", "PhysicsSync", "Animation", "Render"};

inline constexpr double kTickSeconds = 1.0 / 60.0;  // the fixed tick: 60 Hz

}  // namespace cleave::app
