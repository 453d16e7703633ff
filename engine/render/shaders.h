// SPDX-License-Identifier: MIT
// GLSL 330 core sources of the renderer, kept in one place so every program shares the same sky and
// lighting functions.
#pragma once

namespace cleave::render::shaders {

extern const char* const kMeshVertex;
extern const char* const kMeshFragment;
extern const char* const kShadowVertex;
extern const char* const kShadowFragment;
extern const char* const kSkyVertex;
extern const char* const kSkyFragment;
extern const char* const kLineVertex;
extern const char* const kLineFragment;

}  // namespace cleave::render::shaders
