// SPDX-License-Identifier: MIT
// The words of `open`, `uv` and `islands` are those of the cleave-split command line
// (docs/cleave-split.md), so a cut described for one is described for the other.
#include "python/split_binding.h"

#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "cleave/geometry/mesh_splitter.h"
#include "python/numpy_arrays.h"

namespace cleave::python {
namespace {

namespace geometry = cleave::geometry;

PyObject* splitErrorType = nullptr;  // cleave.SplitError; created once with the module, never freed

// The value of a word argument among `choices`, or ValueError listing them.
template <class Enum>
Enum chooseWord(py::handle value, const char* name,
                std::initializer_list<std::pair<const char*, Enum>> choices) {
  std::string words;
  for (const auto& [word, choice] : choices)
    words += (words.empty() ? "" : ", ") + std::string(word);
  if (!py::isinstance<py::str>(value)) {
    throw py::value_error(std::string(name) + " must be one of " + words + ", not " +
                          py::repr(value).cast<std::string>());
  }
  const std::string given = value.cast<std::string>();
  for (const auto& [word, choice] : choices) {
    if (given == word) return choice;
  }
  throw py::value_error(std::string(name) + " must be one of " + words + ", not '" + given + "'");
}

// islands: True (touching), False (each side one piece), "touching" or "connected". NumPy's bool
// counts as a bool.
void setIslands(py::handle value, geometry::SplitOptions& options) {
  const std::string type = py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>();
  if (py::isinstance<py::bool_>(value) || type == "bool_" || type == "bool") {
    options.separateIslands = py::bool_(py::reinterpret_borrow<py::object>(value));
    options.islands = geometry::IslandMode::Touching;
    return;
  }
  if (!py::isinstance<py::str>(value)) {
    throw py::value_error("islands must be True, False, 'touching' or 'connected', not " +
                          py::repr(value).cast<std::string>());
  }
  options.separateIslands = true;
  options.islands =
      chooseWord<geometry::IslandMode>(value, "islands",
                                       {{"touching", geometry::IslandMode::Touching},
                                        {"connected", geometry::IslandMode::Connected}});
}

geometry::SplitOptions splitOptions(bool cap, py::handle open, py::handle islands, py::handle uv) {
  geometry::SplitOptions options;
  options.cap = cap;
  options.openSections = chooseWord<geometry::OpenSectionMode>(
      open, "open",
      {{"refuse", geometry::OpenSectionMode::Refuse},
       {"cap-closed", geometry::OpenSectionMode::CapClosedLoops},
       {"bridge", geometry::OpenSectionMode::Bridge}});
  options.uvMode =
      chooseWord<geometry::CapUvMode>(uv, "uv",
                                      {{"world", geometry::CapUvMode::WorldPlanar},
                                       {"bounds", geometry::CapUvMode::NormalizedBounds}});
  setIslands(islands, options);
  options.computeMass = true;
  return options;
}

Piece makePiece(const geometry::SplitPiece& piece) {
  Piece out;
  out.vertices = fromVec3Rows(piece.mesh.positions, false);
  out.faces = fromTriangleList(piece.mesh.indices);
  out.normals = fromVec3Rows(piece.mesh.normals, true);
  out.uvs = fromVec2Rows(piece.mesh.uv0, true);
  std::vector<int64_t> sources(piece.sourceTriangles.size());
  for (size_t k = 0; k < sources.size(); ++k) {
    const uint32_t source = piece.sourceTriangles[k];
    sources[k] = (source & geometry::kFromCap) != 0 ? -1 : static_cast<int64_t>(source);
  }
  out.sourceTriangles = fromInt64(sources);
  out.side = piece.side;
  out.closed = piece.mass.closed;
  out.reached = piece.reached;
  out.volume = piece.mass.volume;
  out.centerOfMass = fromVector(piece.mass.centerOfMass);
  out.inertia = fromMatrix(piece.mass.inertia);
  out.capTriangles = piece.capTriangles;
  out.capLoops = piece.capLoops;
  return out;
}

[[noreturn]] void raiseSplitError(const geometry::SplitResult& result) {
  const std::string status = geometry::toString(result.status);
  const std::string message =
      "split failed: " + status + (result.message.empty() ? "" : ": " + result.message);
  py::object error = py::reinterpret_borrow<py::object>(splitErrorType)(message);
  error.attr("status") = status;
  PyErr_SetObject(splitErrorType, error.ptr());
  throw py::error_already_set();
}

py::list split(py::handle vertices, py::handle faces, py::handle normal, double offset, bool cap,
               py::handle open, py::handle islands, py::handle uv, py::handle normals,
               py::handle uvs) {
  geometry::MeshData mesh;
  mesh.positions = toVec3Rows(vertices, "vertices");
  mesh.indices = toTriangleList(faces, mesh.positions.size());
  if (!normals.is_none()) mesh.normals = toVec3Rows(normals, "normals", mesh.positions.size());
  if (!uvs.is_none()) mesh.uv0 = toVec2Rows(uvs, "uvs", mesh.positions.size());
  const glm::dvec3 planeNormal = toNormal(normal);
  if (!std::isfinite(offset)) throw py::value_error("offset must be finite");
  const double length = glm::length(planeNormal);
  // {x : dot(n, x) = d} is the plane {x : dot(n/|n|, x) = d/|n|}, as cleave-split normalises it.
  const geometry::Plane plane{planeNormal / length, offset / length};
  const geometry::SplitOptions options = splitOptions(cap, open, islands, uv);
  geometry::SplitResult result;
  {
    py::gil_scoped_release release;  // the core touches no Python object: other threads may run
    result = geometry::splitMesh(mesh, glm::mat4(1.f), plane, options);
  }
  if (result.status != geometry::SplitStatus::Ok) raiseSplitError(result);
  py::list pieces;
  for (const geometry::SplitPiece& piece : result.pieces) pieces.append(py::cast(makePiece(piece)));
  return pieces;
}

std::string pieceRepr(const Piece& piece) {
  return "<cleave.Piece side=" + std::to_string(piece.side) +
         " vertices=" + std::to_string(py::len(piece.vertices)) +
         " faces=" + std::to_string(py::len(piece.faces)) +
         " volume=" + py::repr(py::float_(piece.volume)).cast<std::string>() +
         (piece.closed ? " closed" : " open") + ">";
}

// Pickling (pieces returned from worker processes, Dask or Ray tasks): every attribute in order.
py::tuple pieceState(const Piece& p) {
  return py::make_tuple(p.vertices, p.faces, p.normals, p.uvs, p.sourceTriangles, p.side, p.closed,
                        p.reached, p.volume, p.centerOfMass, p.inertia, p.capTriangles, p.capLoops);
}

Piece pieceFromState(const py::tuple& state) {
  if (state.size() != 13) throw py::value_error("cleave.Piece: a pickled state has 13 fields");
  Piece p;
  p.vertices = state[0];
  p.faces = state[1];
  p.normals = state[2];
  p.uvs = state[3];
  p.sourceTriangles = state[4];
  p.side = state[5].cast<int>();
  p.closed = state[6].cast<bool>();
  p.reached = state[7].cast<bool>();
  p.volume = state[8].cast<double>();
  p.centerOfMass = state[9];
  p.inertia = state[10];
  p.capTriangles = state[11].cast<uint32_t>();
  p.capLoops = state[12].cast<uint32_t>();
  return p;
}

constexpr const char* kSplitDoc =
    R"doc(split(vertices, faces, normal=(0, 1, 0), offset=0.0, cap=True, open="cap-closed",
      islands=True, uv="world", normals=None, uvs=None) -> list[Piece]

Cut a triangle mesh by the plane {x : dot(normal, x) = offset}, cap the holes, separate the pieces
and compute each piece's volume, centre of mass and inertia (density 1, the input's units).

vertices  N x 3 real numbers (stored as float32 by the split core: float64 input is rounded).
faces     M x 3 integers, indices into vertices from 0, counter-clockwise seen from outside.
normal    three numbers, not all zero; normal and offset are scaled together to a unit normal.
          "Above" (side +1) means dot(normal, x) > offset.
cap       False cuts hollow: no cap triangles, the pieces stay open where they were cut.
open      what a capped cut does where the mesh is not watertight (as cleave-split --open):
          "refuse" fails with SplitError, "cap-closed" caps the closed loops and leaves the open
          chains open, "bridge" also closes chains whose ends are close or whose chord crosses
          nothing. Pieces along an open chain are open; their mass is that of their convex hull.
islands   True: a side that falls apart gives one piece per part, parts that touch staying
          together ("touching"); "connected": every separate part is a piece; False: one piece
          per side.
uv        cap texture coordinates: "world" (planar, in metres, stable over re-cuts) or "bounds"
          (normalised to the cap's bounds), as cleave-split --uv.
normals   optional N x 3 per-vertex normals, interpolated onto the pieces.
uvs       optional N x 2 per-vertex texture coordinates, interpolated onto the pieces.

Returns the pieces above the plane first, then those below, in a deterministic order.
Raises ValueError for bad arguments (wrong dtype or shape, NaN, an index out of range, an unknown
word) and cleave.SplitError (a ValueError with .status) when the core refuses the cut, for example
"PlaneMissesMesh" when every vertex lies on one side.)doc";

void bindPiece(py::module_& module) {
  py::class_<Piece>(module, "Piece",
                    "One piece of a split (see cleave.split); every attribute is read-only.")
      .def_readonly("vertices", &Piece::vertices, "N x 3 float32 positions, in the input's space.")
      .def_readonly("faces", &Piece::faces,
                    "M x 3 int64 vertex indices, counter-clockwise seen from outside.")
      .def_readonly("normals", &Piece::normals,
                    "N x 3 float32 normals, or None when the input had none.")
      .def_readonly("uvs", &Piece::uvs,
                    "N x 2 float32 texture coordinates, or None when the input had none.")
      .def_readonly("source_triangles", &Piece::sourceTriangles,
                    "M int64: per face, the input face it comes from (kept or cut), -1 for a cap "
                    "face of this cut.")
      .def_readonly("side", &Piece::side, "+1 above the plane, -1 below.")
      .def_readonly("closed", &Piece::closed,
                    "True when the piece is a closed, consistently wound surface (else its mass is "
                    "its convex hull's).")
      .def_readonly("reached", &Piece::reached, "True when the plane cut or touched this piece.")
      .def_readonly("volume", &Piece::volume, "Volume (units cubed).")
      .def_readonly("center_of_mass", &Piece::centerOfMass, "Centre of mass, 3 float64.")
      .def_readonly("inertia", &Piece::inertia,
                    "3 x 3 float64 inertia tensor about the centre of mass, density 1.")
      .def_readonly("cap_triangles", &Piece::capTriangles,
                    "Faces in the cap material (0 for a hollow cut).")
      .def_readonly("cap_loops", &Piece::capLoops,
                    "Boundary loops capped on this piece (outer borders and holes).")
      .def("__repr__", &pieceRepr, "A one-line summary: side, sizes, volume, closed or open.")
      .def(py::pickle(&pieceState, &pieceFromState));
}

}  // namespace

void bindSplit(py::module_& module) {
  splitErrorType = PyErr_NewExceptionWithDoc(
      "cleave.SplitError",
      "The split core refused a cut; `status` is its status name (PlaneMissesMesh, OpenSection, "
      "TriangulationFailed, InvalidInput). A subclass of ValueError.",
      PyExc_ValueError, nullptr);
  if (splitErrorType == nullptr) throw py::error_already_set();
  module.add_object("SplitError", py::reinterpret_borrow<py::object>(splitErrorType));
  bindPiece(module);
  module.def("split", &split, kSplitDoc, py::arg("vertices"), py::arg("faces"),
             py::arg("normal") = py::make_tuple(0.0, 1.0, 0.0), py::arg("offset") = 0.0,
             py::arg("cap") = true, py::arg("open") = "cap-closed", py::arg("islands") = true,
             py::arg("uv") = "world", py::arg("normals") = py::none(), py::arg("uvs") = py::none());
}

}  // namespace cleave::python
