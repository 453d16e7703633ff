// SPDX-License-Identifier: MIT
#include "cleave/ecs/world.h"


#include "cleave/ecs/command_buffer.h"
#include "cleave/ecs/hierarchy.h"

namespace cleave::ecs {

World::~World() = default;

Entity World::takeSlot(SlotState state) {
  uint32_t index;
  if (!freeSlots_.empty()) {
    index = freeSlots_.front();
    freeSlots_.pop_front();
  } else {
    index = static_cast<uint32_t>(slots_.size());
    slots_.push_back(Slot{});
  }
  slots_[index].state = state;
  return Entity{index, slots_[index].generation};
}

void World::freeSlot(uint32_t index) {
  Slot& slot = slots_[index];
  slot.state = SlotState::Free;
  ++slot.generation;
  // A slot whose generation would wrap to 0 (the null generation) is retired instead of reused,
  // so a stale id can never become alive again.
  if (slot.generation != 0) freeSlots_.push_back(index);
}

Entity World::create() {
  assert(structuralChangesAllowed() && "structural change during iteration; use a CommandBuffer");
  ++aliveCount_;
  return takeSlot(SlotState::Alive);
}

bool World::destroy(Entity entity) {
  assert(structuralChangesAllowed() && "structural change during iteration; use a CommandBuffer");
  if (!alive(entity) || lock_ != 0) return false;
  if (slots_[entity.index].state == SlotState::Dying) return false;
  slots_[entity.index].state = SlotState::Dying;
  // By index: a hook may make new pools (a first add of some type), which moves pools_.
  ++hookDepth_;
  for (size_t i = 0; i < hookOrder_.size(); ++i) pools_[hookOrder_[i]]->release(*this, entity);
  --hookDepth_;
  for (size_t i = 0; i < pools_.size(); ++i) {
    if (pools_[i]) pools_[i]->erase(entity);
  }
  freeSlot(entity.index);
  --aliveCount_;
  return true;
}

size_t World::clear() {
  assert(structuralChangesAllowed() && "clear during iteration");
  size_t destroyed = 0;
  for (int pass = 0; pass < 64 && aliveCount_ > 0 && lock_ == 0; ++pass) {
    for (const Entity entity : entities()) destroyed += destroy(entity) ? 1 : 0;
  }
  return destroyed;
}

bool World::removeHook(HookId id) {
  assert(hookDepth_ == 0 && "destroy hooks are removed outside hooks");
  if (hookDepth_ != 0) return false;
  const auto it = std::find_if(hookTypes_.begin(), hookTypes_.end(), [id](const auto& h) { return h.first == id; });
  if (it == hookTypes_.end()) return false;
  const detail::ComponentTypeId type = it->second;
  hookTypes_.erase(it);
  pools_[type]->removeHook(id);
  // A type without hooks left gives up its place in the order (a later first hook puts it last).
  const bool typeHasHooks = std::any_of(hookTypes_.begin(), hookTypes_.end(), [type](const auto& h) { return h.second == type; });
  if (!typeHasHooks) std::erase(hookOrder_, type);
  return true;
}

bool World::alive(Entity entity) const {
  if (entity.isNull() || entity.index >= slots_.size()) return false;
  const Slot& slot = slots_[entity.index];
  return (slot.state == SlotState::Alive || slot.state == SlotState::Dying) && slot.generation == entity.generation;
}

std::vector<Entity> World::entities() const {
  std::vector<Entity> result;
  result.reserve(aliveCount_);
  for (uint32_t i = 0; i < slots_.size(); ++i) {
    if (slots_[i].state == SlotState::Alive || slots_[i].state == SlotState::Dying)
      result.push_back(Entity{i, slots_[i].generation});
  }
  return result;
}

Entity World::reserve() { return takeSlot(SlotState::Reserved); }

bool World::commitReservation(Entity entity) {
  if (entity.index >= slots_.size()) return false;
  Slot& slot = slots_[entity.index];
  if (slot.state != SlotState::Reserved || slot.generation != entity.generation) return false;
  slot.state = SlotState::Alive;
  ++aliveCount_;
  return true;
}

void World::releaseReservation(Entity entity) {
  if (entity.index >= slots_.size()) return;
  const Slot& slot = slots_[entity.index];
  if (slot.state == SlotState::Reserved && slot.generation == entity.generation)
    freeSlot(entity.index);
}

ApplyResult World::apply(CommandBuffer& buffer) {
  assert(buffer.world_ == this && "CommandBuffer applied to another World");
  assert(structuralChangesAllowed() && "apply during iteration");
  ApplyResult result;
  if (buffer.world_ != this || lock_ != 0) return result;
  // Take the commands out first: an edit may not record into the buffer being applied, but this
  // keeps the buffer consistent even if it does.
  std::vector<CommandBuffer::Command> commands = std::move(buffer.commands_);
  buffer.commands_.clear();
  for (CommandBuffer::Command& command : commands) {
    bool done = false;
    switch (command.kind) {
      case CommandBuffer::Kind::Create:
        done = commitReservation(command.entity);
        break;
      case CommandBuffer::Kind::Destroy:
        done = destroy(command.entity);
        break;
      case CommandBuffer::Kind::DestroyRecursive:
        done = destroyRecursive(*this, command.entity) > 0;
        break;
      case CommandBuffer::Kind::Edit:
        if (alive(command.entity)) {
          command.edit(*this, command.entity);
          done = true;
        }
        break;
    }
    ++(done ? result.applied : result.skipped);
  }
  return result;
}

Entity CommandBuffer::create() {
  const Entity entity = world_->reserve();
  commands_.push_back({Kind::Create, entity, {}});
  return entity;
}

void CommandBuffer::clear() {
  for (const Command& command : commands_) {
    if (command.kind == Kind::Create) world_->releaseReservation(command.entity);
  }
  commands_.clear();
}

}  // namespace cleave::ecs
