// SPDX-License-Identifier: MIT
// cleave.read_mesh and cleave.write_mesh: the mesh readers and writers of engine/assets (the ones
// cleave-split uses) for NumPy arrays. Reads OBJ, OFF, STL, PLY, glTF and GLB; writes OBJ and GLB.
//
// Failure: a file that does not exist, is a folder or cannot be opened or written raises OSError
// (FileNotFoundError, IsADirectoryError, PermissionError by errno where it is known); a file whose
// contents the reader refuses, an unknown extension or bad arrays raise ValueError with the
// reader's one-line reason ("<file>:<line>: <reason>"). Nothing else escapes.
#pragma once

#include <pybind11/pybind11.h>

namespace cleave::python {

namespace py = pybind11;

// Adds read_mesh() and write_mesh() to the module.
void bindMeshIo(py::module_& module);

}  // namespace cleave::python
