// SPDX-License-Identifier: MIT
// Internal to engine/assets: the tail every mesh reader runs on what it parsed.
#pragma once

#include <string>

#include "cleave/assets/mesh_io.h"

namespace cleave::assets::detail {

// Scales the normals of result.mesh to unit length. When one has zero length or is not finite, all
// normals are dropped (the mesh is read without them) and a warning naming the file is added.
void normalizeNormals(MeshReadResult& result, const std::string& name);

// Checks what every reader promises (at least one triangle, indices within the vertex count,
// finite attributes, per-vertex arrays of the right size, submeshes covering the indices in order),
// fills materialNames when empty and returns the result; on a violation returns a failure naming
// the file and the first offending triangle or vertex.
MeshReadResult finish(MeshReadResult result, const std::string& name);

}  // namespace cleave::assets::detail
