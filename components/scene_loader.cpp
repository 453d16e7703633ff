// SPDX-License-Identifier: MIT
#include "cleave/components/scene_loader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <span>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "cleave/components/scene_components.h"
#include "cleave/assets/mesh_io.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/primitives.h"

namespace cleave::components {

using nlohmann::json;

namespace {


// ---------------------------------------------------------------------------------------------
// Lines of the source text. nlohmann::json keeps no positions, so a semantic error keeps the JSON
// pointer of the offending value and this scanner walks the (already valid) text along the pointer
// to the line where that value starts. Comments are skipped as the parser does.

class LineScanner {
 public:
  explicit LineScanner(const std::string& text) : s_(text) {}

  // Line of the value at `path`; the line of the deepest ancestor found if the path ends early.
  int lineOf(const std::vector<std::string>& path) {
    i_ = 0;
    line_ = 1;
    whitespace();
    for (const std::string& token : path) {
      const size_t saveI = i_;
      const int saveLine = line_;
      if (!descend(token)) {
        i_ = saveI;
        line_ = saveLine;
        break;
      }
    }
    return line_;
  }

 private:
  bool at(char c) const { return i_ < s_.size() && s_[i_] == c; }

  void whitespace() {
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == '\n') {
        ++line_;
        ++i_;
      } else if (c == ' ' || c == '\t' || c == '\r') {
        ++i_;
      } else if (c == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '/') {
        while (i_ < s_.size() && s_[i_] != '\n') ++i_;
      } else if (c == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '*') {
        i_ += 2;
        while (i_ + 1 < s_.size() && !(s_[i_] == '*' && s_[i_ + 1] == '/')) {
          if (s_[i_] == '\n') ++line_;
          ++i_;
        }
        i_ += 2;
      } else {
        break;
      }
    }
  }

  // At a '"': the string's characters with simple escapes resolved (enough to compare keys).
  std::string string() {
    std::string out;
    ++i_;
    while (i_ < s_.size() && s_[i_] != '"') {
      if (s_[i_] == '\\' && i_ + 1 < s_.size()) {
        ++i_;
        switch (s_[i_]) {
          case 'n': out += '\n'; break;
          case 't': out += '\t'; break;
          case 'r': out += '\r'; break;
          case 'b': out += '\b'; break;
          case 'f': out += '\f'; break;
          default: out += s_[i_]; break;
        }
      } else {
        out += s_[i_];
      }
      ++i_;
    }
    ++i_;
    return out;
  }

  void skipValue() {
    whitespace();
    if (at('"')) {
      string();
      return;
    }
    if (at('{') || at('[')) {
      int depth = 0;
      while (i_ < s_.size()) {
        whitespace();
        if (i_ >= s_.size()) return;
        const char c = s_[i_];
        if (c == '"') {
          string();
          continue;
        }
        ++i_;
        if (c == '{' || c == '[') ++depth;
        if (c == '}' || c == ']') {
          if (--depth == 0) return;
        }
      }
      return;
    }
    while (i_ < s_.size() && std::string_view(",]} \t\r\n/").find(s_[i_]) == std::string_view::npos) ++i_;
  }

  bool descend(const std::string& token) {
    whitespace();
    if (at('{')) {
      ++i_;
      while (true) {
        whitespace();
        if (!at('"')) return false;
        const std::string key = string();
        whitespace();
        if (!at(':')) return false;
        ++i_;
        whitespace();
        if (key == token) return true;
        skipValue();
        whitespace();
        if (!at(',')) return false;
        ++i_;
      }
    }
    if (at('[')) {
      size_t index = 0;
      for (char c : token) {
        if (c < '0' || c > '9') return false;
        index = index * 10 + size_t(c - '0');
      }
      ++i_;
      for (size_t k = 0;; ++k) {
        whitespace();
        if (at(']')) return false;
        if (k == index) return true;
        skipValue();
        whitespace();
        if (!at(',')) return false;
        ++i_;
      }
    }
    return false;
  }

  const std::string& s_;
  size_t i_ = 0;
  int line_ = 1;
};

// The last object key that starts before `end` (for syntax errors, which have no pointer).
std::string lastKeyBefore(const std::string& s, size_t end) {
  std::string last;
  size_t i = 0;
  end = std::min(end, s.size());
  while (i < end) {
    if (s[i] == '"') {
      std::string str;
      ++i;
      while (i < end && s[i] != '"') {
        if (s[i] == '\\' && i + 1 < end) ++i;
        str += s[i++];
      }
      ++i;
      size_t j = i;
      while (j < end && (s[j] == ' ' || s[j] == '\t' || s[j] == '\r' || s[j] == '\n')) ++j;
      if (j < end && s[j] == ':') last = str;
      continue;
    }
    ++i;
  }
  return last;
}

// ---------------------------------------------------------------------------------------------
// Reading with positions: every value is read through a Node that knows its JSON pointer, and the
// first error wins.

struct Node {
  const json* value = nullptr;
  std::vector<std::string> path;

  // A key the object does not have gives a null node with the path it would have (for messages
  // about a field left at its default).
  Node child(const std::string& key) const {
    static const nlohmann::json kAbsent;
    const auto it = value->find(key);
    Node n{it == value->end() ? &kAbsent : &*it, path};
    n.path.push_back(key);
    return n;
  }
  Node at(size_t index) const {
    Node n{&(*value)[index], path};
    n.path.push_back(std::to_string(index));
    return n;
  }
  bool has(const std::string& key) const { return value->is_object() && value->contains(key); }
  const json& operator*() const { return *value; }
  const json* operator->() const { return value; }
};

std::string pointerOf(const std::vector<std::string>& path) {
  if (path.empty()) return "/";
  std::string out;
  for (const std::string& token : path) {
    out += '/';
    for (char c : token) {
      if (c == '~') out += "~0";
      else if (c == '/') out += "~1";
      else out += c;
    }
  }
  return out;
}

const char* typeName(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::object: return "an object";
    case json::value_t::array: return "an array";
    case json::value_t::string: return "a string";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return "an integer";
    case json::value_t::number_float: return "a number";
    default: return "an unknown value";
  }
}

std::string joinNames(std::span<const char* const> names) {
  std::string out;
  for (const char* n : names) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

std::string joinNames(std::initializer_list<const char*> names) {
  return joinNames(std::span<const char* const>(names.begin(), names.size()));
}

class Reader {
 public:
  Reader(const std::string& file, const std::string& text) : file_(file), text_(text) {}

  bool failed() const { return !field_.empty() || failed_; }

  bool fail(const Node& n, const std::string& reason) {
    if (failed()) return false;
    failed_ = true;
    field_ = pointerOf(n.path);
    reason_ = reason;
    line_ = LineScanner(text_).lineOf(n.path);
    return false;
  }

  void fillError(SceneLoadResult& r) const {
    r.errorFile = file_;
    r.errorLine = line_;
    r.errorField = field_;
    r.setFailure(base::StatusCode::ParseError, file_ + ":" + std::to_string(line_) + ": " + field_ + ": " + reason_);
  }

  bool expectObject(const Node& n, std::initializer_list<const char*> allowed) {
    return expectObject(n, std::span<const char* const>(allowed.begin(), allowed.size()));
  }
  bool expectObject(const Node& n, std::span<const char* const> allowed) {
    if (!n->is_object()) return fail(n, std::string("expected an object, found ") + typeName(*n));
    for (const auto& item : n->items()) {
      bool known = false;
      for (const char* a : allowed) known = known || item.key() == a;
      if (!known)
        return fail(n.child(item.key()),
                    "unknown field '" + item.key() + "' (expected one of: " + joinNames(allowed) + ")");
    }
    return true;
  }

  bool number(const Node& n, double& out) {
    if (!n->is_number()) return fail(n, std::string("expected a number, found ") + typeName(*n));
    out = n->get<double>();
    if (!std::isfinite(out)) return fail(n, "expected a finite number");
    return true;
  }
  // Reads parent[key] when present (keeps `out` otherwise); checks out > 0 when `positive`.
  bool number(const Node& parent, const char* key, double& out, bool positive = false) {
    if (!parent.has(key)) return true;
    const Node n = parent.child(key);
    if (!number(n, out)) return false;
    if (positive && !(out > 0.0)) return fail(n, "expected a number > 0, found " + n->dump());
    return true;
  }
  bool number(const Node& parent, const char* key, float& out, bool positive = false) {
    double d = out;
    if (!number(parent, key, d, positive)) return false;
    out = float(d);
    return true;
  }
  bool nonNegative(const Node& parent, const char* key, double& out) {
    if (!number(parent, key, out)) return false;
    if (parent.has(key) && out < 0.0) return fail(parent.child(key), "expected a number >= 0");
    return true;
  }
  bool integer(const Node& parent, const char* key, uint64_t& out, uint64_t minimum = 0,
               uint64_t maximum = UINT32_MAX) {
    if (!parent.has(key)) return true;
    const Node n = parent.child(key);
    if (!n->is_number_integer() && !n->is_number_unsigned())
      return fail(n, std::string("expected a whole number, found ") + typeName(*n));
    if (n->is_number_integer() && n->get<int64_t>() < 0)
      return fail(n, "expected a whole number >= " + std::to_string(minimum));
    const uint64_t v = n->get<uint64_t>();
    if (v < minimum || v > maximum)
      return fail(n, "expected a whole number in [" + std::to_string(minimum) + ", " +
                         std::to_string(maximum) + "], found " + std::to_string(v));
    out = v;
    return true;
  }
  template <class T>
  bool integer32(const Node& parent, const char* key, T& out, uint64_t minimum = 0,
                 uint64_t maximum = UINT32_MAX) {
    uint64_t v = uint64_t(out);
    if (!integer(parent, key, v, minimum, maximum)) return false;
    out = T(v);
    return true;
  }
  bool boolean(const Node& parent, const char* key, bool& out) {
    if (!parent.has(key)) return true;
    const Node n = parent.child(key);
    if (!n->is_boolean()) return fail(n, std::string("expected true or false, found ") + typeName(*n));
    out = n->get<bool>();
    return true;
  }
  bool string(const Node& parent, const char* key, std::string& out) {
    if (!parent.has(key)) return true;
    const Node n = parent.child(key);
    if (!n->is_string()) return fail(n, std::string("expected a string, found ") + typeName(*n));
    out = n->get<std::string>();
    return true;
  }
  bool vector(const Node& n, double* out, size_t count) {
    if (!n->is_array() || n->size() != count)
      return fail(n, "expected an array of " + std::to_string(count) + " numbers, found " +
                         (n->is_array() ? "an array of " + std::to_string(n->size()) : typeName(*n)));
    for (size_t k = 0; k < count; ++k)
      if (!number(n.at(k), out[k])) return false;
    return true;
  }
  bool vec3(const Node& parent, const char* key, glm::vec3& out, bool positive = false) {
    if (!parent.has(key)) return true;
    const Node n = parent.child(key);
    double v[3];
    if (!vector(n, v, 3)) return false;
    if (positive && !(v[0] > 0 && v[1] > 0 && v[2] > 0)) return fail(n, "expected three numbers > 0");
    out = glm::vec3(float(v[0]), float(v[1]), float(v[2]));
    return true;
  }
  bool vec4(const Node& parent, const char* key, glm::vec4& out) {
    if (!parent.has(key)) return true;
    double v[4];
    if (!vector(parent.child(key), v, 4)) return false;
    out = glm::vec4(float(v[0]), float(v[1]), float(v[2]), float(v[3]));
    return true;
  }
  // A string that must be one of `names`; returns its index in `index`.
  bool choice(const Node& parent, const char* key, std::initializer_list<const char*> names, int& index) {
    if (!parent.has(key)) return true;
    const Node n = parent.child(key);
    if (!n->is_string()) return fail(n, std::string("expected a string, found ") + typeName(*n));
    const std::string v = n->get<std::string>();
    int k = 0;
    for (const char* name : names) {
      if (v == name) {
        index = k;
        return true;
      }
      ++k;
    }
    return fail(n, "unknown value '" + v + "' (expected one of: " + joinNames(names) + ")");
  }

 private:
  std::string file_;
  const std::string& text_;
  bool failed_ = false;
  std::string field_;
  std::string reason_;
  int line_ = 0;
};

// ---------------------------------------------------------------------------------------------
// The scene as read, before anything is created.

enum class BodyKind { None, Static, Dynamic };

struct EntityDesc {
  std::vector<std::string> path;  // JSON pointer tokens, for errors found while creating it
  std::string name;
  std::string material;
  bool hasMesh = false;
  geometry::MeshData mesh;
  bool isBox = false;          // a box primitive (a static box gets a box collider)
  glm::vec3 boxHalfExtents{0.5f};
  ecs::Transform transform;
  BodyKind body = BodyKind::None;
  double density = 1000.0;
  std::optional<double> mass;
  glm::vec3 linearVelocity{0.f};
  glm::vec3 angularVelocity{0.f};
  ColliderMode collider = ColliderMode::Auto;
  bool splitable = false;
  Splitable split;
  bool splitDensityGiven = false;
  std::string capMaterial;
  bool capMaterialIdGiven = false;
  std::vector<EntityDesc> children;
};

struct FloorDesc {
  bool present = false;
  float height = 0.f;
  glm::vec3 halfExtents{30.f, 0.5f, 30.f};
  std::string material = "floor";
};

struct SceneDesc {
  glm::vec3 gravity{0.f, -9.81f, 0.f};
  FloorDesc floor;
  bool budgetGiven = false;
  SplitBudgetSettings budget;
  bool pieceBudgetGiven = false;
  PieceBudgetSettings pieceBudget;
  glm::vec3 cameraPosition{0.f, 2.f, 6.f};
  glm::vec3 cameraTarget{0.f};
  uint64_t ticks = 0;
  std::vector<EntityDesc> entities;
  std::vector<ScheduledSplitter> splitters;
};

bool readTransform(Reader& rd, const Node& parent, ecs::Transform& t, bool allowScale) {
  if (!parent.has("transform")) return true;
  const Node n = parent.child("transform");
  if (allowScale) {
    if (!rd.expectObject(n, {"position", "rotation", "scale"})) return false;
  } else if (!rd.expectObject(n, {"position", "rotation"})) {
    return false;
  }
  if (!rd.vec3(n, "position", t.position)) return false;
  if (n.has("rotation")) {
    const Node r = n.child("rotation");
    if (!rd.expectObject(r, {"quaternion", "euler_degrees"})) return false;
    if (r.has("quaternion") == r.has("euler_degrees"))
      return rd.fail(r, "give exactly one of 'quaternion' [w, x, y, z] or 'euler_degrees' [x, y, z]");
    if (r.has("quaternion")) {
      double q[4];
      if (!rd.vector(r.child("quaternion"), q, 4)) return false;
      const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      if (!(len > 1e-9)) return rd.fail(r.child("quaternion"), "the quaternion has zero length");
      t.rotation = glm::normalize(glm::quat(float(q[0]), float(q[1]), float(q[2]), float(q[3])));
    } else {
      double e[3];
      if (!rd.vector(r.child("euler_degrees"), e, 3)) return false;
      // Rotations about the world X, then Y, then Z axes.
      const glm::dquat qx = glm::angleAxis(glm::radians(e[0]), glm::dvec3(1, 0, 0));
      const glm::dquat qy = glm::angleAxis(glm::radians(e[1]), glm::dvec3(0, 1, 0));
      const glm::dquat qz = glm::angleAxis(glm::radians(e[2]), glm::dvec3(0, 0, 1));
      t.rotation = glm::quat(glm::normalize(qz * qy * qx));
    }
  }
  if (allowScale && n.has("scale")) {
    const Node s = n.child("scale");
    if (s->is_number()) {
      double v = 1.0;
      if (!rd.number(s, v)) return false;
      if (!(v > 0.0)) return rd.fail(s, "expected a scale > 0");
      t.scale = glm::vec3(float(v));
    } else if (!rd.vec3(n, "scale", t.scale, /*positive=*/true)) {
      return false;
    }
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Mesh primitives: one table row per primitive names its fields (in the order they are read and
// checked), their defaults and limits, and the builder that makes the mesh of the values read.

struct PrimitiveField {
  enum Kind {
    Positive,
    Count,
    Extents
  };                          // a number > 0, a whole number in [min, max], 3 numbers > 0
  const char* key = nullptr;  // null ends a row's fields
  Kind kind = Positive;
  double value = 0.0;  // default of Positive and Count
  uint32_t minimum = 0, maximum = 0;
  glm::vec3 extents{0.f};  // default of Extents
};

constexpr size_t kMaxPrimitiveFields = 5;

// The values of a row's fields, by field slot (number[k] for Positive, count[k] for Count).
struct PrimitiveValues {
  double number[kMaxPrimitiveFields] = {};
  uint32_t count[kMaxPrimitiveFields] = {};
  glm::vec3 extents{0.f};
  float f(size_t k) const { return float(number[k]); }
};

struct PrimitiveRow {
  const char* name;
  PrimitiveField fields[kMaxPrimitiveFields];
  geometry::MeshData (*build)(const PrimitiveValues&);
  // A pair of fields where the first must be below the second (slots), or -1.
  int smaller = -1, larger = -1;
};

PrimitiveField positiveField(const char* key, double value) {
  return {key, PrimitiveField::Positive, value, 0, 0, {}};
}
PrimitiveField countField(const char* key, uint32_t value, uint32_t minimum, uint32_t maximum) {
  return {key, PrimitiveField::Count, double(value), minimum, maximum, {}};
}
PrimitiveField extentsField(const char* key, glm::vec3 value) {
  return {key, PrimitiveField::Extents, 0.0, 0, 0, value};
}

namespace P = geometry::primitives;
using V = PrimitiveValues;

const PrimitiveRow kPrimitives[] = {
    {"box",
     {extentsField("half_extents", glm::vec3(0.5f))},
     [](const V& v) { return P::box(v.extents); }},
    {"sphere",
     {positiveField("radius", 0.5), countField("segments", 32, 3, 1024),
      countField("rings", 16, 2, 1024)},
     [](const V& v) { return P::uvSphere(v.f(0), v.count[1], v.count[2]); }},
    {"ellipsoid",
     {extentsField("radii", glm::vec3(0.5f, 0.35f, 0.35f)), countField("segments", 32, 3, 1024),
      countField("rings", 16, 2, 1024)},
     [](const V& v) { return P::ellipsoid(v.extents, v.count[1], v.count[2]); }},
    {"cylinder",
     {positiveField("radius", 0.4), positiveField("height", 1.0),
      countField("segments", 32, 3, 1024)},
     [](const V& v) { return P::cylinder(v.f(0), v.f(1), v.count[2]); }},
    {"torus",
     {positiveField("major_radius", 0.5), positiveField("minor_radius", 0.2),
      countField("segments", 48, 3, 1024), countField("sides", 24, 3, 1024)},
     [](const V& v) { return P::torus(v.f(0), v.f(1), v.count[2], v.count[3]); },
     1,
     0},
    {"capsule",
     {positiveField("radius", 0.3), positiveField("height", 0.6),
      countField("segments", 24, 3, 1024), countField("rings", 12, 2, 1024)},
     [](const V& v) { return P::capsule(v.f(0), v.f(1), v.count[2], v.count[3]); }},
    {"comb",
     {countField("teeth", 2, 1, 256), positiveField("pitch", 0.2),
      positiveField("tooth_length", 0.6), positiveField("spine_height", 0.2),
      positiveField("depth", 0.3)},
     [](const V& v) { return P::combPrism(v.count[0], v.f(1), v.f(2), v.f(3), v.f(4)); }},
    {"star",
     {countField("points", 5, 3, 256), positiveField("outer_radius", 1.0),
      positiveField("inner_radius", 0.4), positiveField("height", 0.5)},
     [](const V& v) { return P::starPrism(v.count[0], v.f(1), v.f(2), v.f(3)); },
     2,
     1},
    {"tetrahedron",
     {positiveField("radius", 0.5)},
     [](const V& v) { return P::tetrahedron(v.f(0)); }},
    {"hollow_sphere",
     {positiveField("outer_radius", 0.5), positiveField("inner_radius", 0.4),
      countField("segments", 32, 3, 1024), countField("rings", 16, 2, 1024)},
     [](const V& v) { return P::hollowSphere(v.f(0), v.f(1), v.count[2], v.count[3]); },
     1,
     0},
};

// Reads one field into slot k (its default when absent).
bool readPrimitiveField(Reader& rd, const Node& n, const PrimitiveField& field, size_t k,
                        PrimitiveValues& v) {
  switch (field.kind) {
    case PrimitiveField::Positive:
      v.number[k] = field.value;
      return rd.number(n, field.key, v.number[k], true);
    case PrimitiveField::Count:
      v.count[k] = uint32_t(field.value);
      return rd.integer32(n, field.key, v.count[k], field.minimum, field.maximum);
    case PrimitiveField::Extents:
      v.extents = field.extents;
      return rd.vec3(n, field.key, v.extents, true);
  }
  return false;
}

// Reads the fields of `row` from n (defaults for those absent) and checks its limits.
bool readPrimitiveFields(Reader& rd, const Node& n, const PrimitiveRow& row, PrimitiveValues& v) {
  const char* allowed[kMaxPrimitiveFields + 1] = {"primitive"};
  size_t fieldCount = 0;
  while (fieldCount < kMaxPrimitiveFields && row.fields[fieldCount].key != nullptr) {
    allowed[fieldCount + 1] = row.fields[fieldCount].key;
    ++fieldCount;
  }
  if (!rd.expectObject(n, std::span<const char* const>(allowed, fieldCount + 1))) return false;
  for (size_t k = 0; k < fieldCount; ++k) {
    const PrimitiveField& field = row.fields[k];
    if (!readPrimitiveField(rd, n, field, k, v)) return false;
  }
  if (row.smaller >= 0 && !(v.number[row.smaller] < v.number[row.larger])) {
    const std::string smaller = row.fields[row.smaller].key, larger = row.fields[row.larger].key;
    return rd.fail(n.child(smaller), smaller + " must be below " + larger);
  }
  return true;
}

std::string primitiveNames() {
  std::string names;
  for (const PrimitiveRow& row : kPrimitives)
    names += (names.empty() ? "" : ", ") + std::string(row.name);
  return names;
}

bool readPrimitive(Reader& rd, const Node& n, EntityDesc& d) {
  std::string kind;
  if (!rd.string(n, "primitive", kind)) return false;
  for (const PrimitiveRow& row : kPrimitives) {
    if (kind != row.name) continue;
    PrimitiveValues values;
    if (!readPrimitiveFields(rd, n, row, values)) return false;
    d.mesh = row.build(values);
    if (kind == "box") {  // a static box gets a box collider
      d.isBox = true;
      d.boxHalfExtents = values.extents;
    }
    return true;
  }
  return rd.fail(n.child("primitive"),
                 "unknown primitive '" + kind + "' (expected one of: " + primitiveNames() + ")");
}

bool readMeshFile(Reader& rd, const Node& n, const std::string& baseDirectory, EntityDesc& d) {
  if (!rd.expectObject(n, {"file"})) return false;
  std::string file;
  if (!rd.string(n, "file", file)) return false;
  std::filesystem::path p(file);
  if (p.is_relative()) p = std::filesystem::path(baseDirectory) / p;
  assets::MeshReadResult r = assets::loadMesh(p.lexically_normal().string());
  if (!r.ok()) return rd.fail(n.child("file"), "cannot load the model: " + r.message);
  d.mesh = std::move(r.mesh);
  return true;
}

bool readMesh(Reader& rd, const Node& n, const std::string& baseDirectory, EntityDesc& d) {
  if (!n->is_object()) return rd.fail(n, std::string("expected an object, found ") + typeName(*n));
  if (n.has("primitive") == n.has("file"))
    return rd.fail(n, "give exactly one of 'primitive' (a name) or 'file' (a model path)");
  d.hasMesh = true;
  return n.has("file") ? readMeshFile(rd, n, baseDirectory, d) : readPrimitive(rd, n, d);
}

bool readSplitable(Reader& rd, const Node& n, EntityDesc& d) {
  if (n->is_boolean()) {
    d.splitable = n->get<bool>();
    return true;
  }
  if (!rd.expectObject(n, {"convex", "cap", "cap_material", "cap_material_id", "cap_uv", "cap_uv_per_metre",
                           "cap_atlas_rect", "cap_uv_per_border", "mass_mode", "density", "split_impulse",
                           "min_piece_volume", "small_pieces", "separate_islands", "max_depth", "handler",
                           "open_sections", "islands", "retirement"}))
    return false;
  d.splitable = true;
  Splitable& s = d.split;
  int uv = int(s.capUvMode == geometry::CapUvMode::NormalizedBounds);
  int massMode = int(s.massMode);
  int small = int(s.smallPieces);
  int open = int(s.openSections);
  int islands = int(s.islands);
  int retirement = int(s.retirement);
  d.splitDensityGiven = n.has("density");
  d.capMaterialIdGiven = n.has("cap_material_id");
  if (!rd.boolean(n, "convex", s.convexHint) || !rd.boolean(n, "cap", s.cap) ||
      !rd.string(n, "cap_material", d.capMaterial) ||
      !rd.integer32(n, "cap_material_id", s.capMaterialId, 0, 255) ||
      !rd.choice(n, "cap_uv", {"world_planar", "normalized_bounds"}, uv) ||
      !rd.number(n, "cap_uv_per_metre", s.capUvPerMetre, true) ||
      !rd.vec4(n, "cap_atlas_rect", s.capAtlasRect) || !rd.boolean(n, "cap_uv_per_border", s.capUvPerBorder) ||
      !rd.choice(n, "mass_mode", {"density", "keep_parent_mass"}, massMode) ||
      !rd.number(n, "density", s.density, true) || !rd.nonNegative(n, "split_impulse", s.splitImpulse) ||
      !rd.nonNegative(n, "min_piece_volume", s.minPieceVolume) ||
      !rd.choice(n, "small_pieces", {"remove", "debris"}, small) ||
      !rd.boolean(n, "separate_islands", s.separateIslands) ||
      !rd.integer32(n, "max_depth", s.maxDepth, 1, 64) || !rd.string(n, "handler", s.handler) ||
      !rd.choice(n, "open_sections", {"refuse", "cap_closed", "bridge"}, open) ||
      !rd.choice(n, "islands", {"touching", "connected"}, islands) ||
      !rd.choice(n, "retirement", {"default", "freeze", "fade", "remove"}, retirement))
    return false;
  s.retirement = PieceRetirement(retirement);
  s.openSections = geometry::OpenSectionMode(open);
  s.islands = geometry::IslandMode(islands);
  s.capUvMode = uv == 1 ? geometry::CapUvMode::NormalizedBounds : geometry::CapUvMode::WorldPlanar;
  s.massMode = MassMode(massMode);
  s.smallPieces = SmallPieceMode(small);
  return true;
}

bool readEntity(Reader& rd, const Node& n, const std::string& baseDirectory, bool insideBody, EntityDesc& d) {
  if (!rd.expectObject(n, {"name", "mesh", "material", "transform", "body", "splitable", "children"}))
    return false;
  d.path = n.path;
  if (!rd.string(n, "name", d.name) || !rd.string(n, "material", d.material)) return false;
  if (n.has("mesh") && !readMesh(rd, n.child("mesh"), baseDirectory, d)) return false;
  if (!readTransform(rd, n, d.transform, true)) return false;
  if (n.has("body")) {
    const Node b = n.child("body");
    if (insideBody)
      return rd.fail(b, "a child of an object with a body is part of that body and has no body of its own");
    if (!d.hasMesh) return rd.fail(b, "a body needs a 'mesh' on the same object");
    if (!rd.expectObject(b, {"type", "density", "mass", "linear_velocity", "angular_velocity", "collider"}))
      return false;
    int type = 1;
    int collider = 0;
    if (!rd.choice(b, "type", {"static", "dynamic"}, type)) return false;
    d.body = type == 1 ? BodyKind::Dynamic : BodyKind::Static;
    if (b.has("density") && b.has("mass")) return rd.fail(b.child("mass"), "give 'density' or 'mass', not both");
    if (!rd.number(b, "density", d.density, true)) return false;
    if (b.has("mass")) {
      double m = 0.0;
      if (!rd.number(b, "mass", m, true)) return false;
      d.mass = m;
    }
    if (!rd.vec3(b, "linear_velocity", d.linearVelocity) || !rd.vec3(b, "angular_velocity", d.angularVelocity) ||
        !rd.choice(b, "collider", {"auto", "convex_hull", "compound", "concave_mesh"}, collider))
      return false;
    d.collider = ColliderMode(collider);
    if (d.body == BodyKind::Static) {
      for (const char* key : {"mass", "linear_velocity", "angular_velocity"})
        if (b.has(key)) return rd.fail(b.child(key), std::string("a static body has no '") + key + "'");
    }
  }
  if (n.has("splitable")) {
    const Node s = n.child("splitable");
    if (d.body == BodyKind::None)
      return rd.fail(s, insideBody ? "a child of a body is split with its parent: put 'splitable' on the parent"
                                   : "a splitable object needs a 'body'");
    if (!s->is_boolean() && !s->is_object())
      return rd.fail(s, std::string("expected true, false or an object, found ") + typeName(*s));
    if (!readSplitable(rd, s, d)) return false;
  }
  if (n.has("children")) {
    const Node c = n.child("children");
    if (!c->is_array()) return rd.fail(c, std::string("expected an array, found ") + typeName(*c));
    for (size_t k = 0; k < c->size(); ++k) {
      EntityDesc child;
      if (!readEntity(rd, c.at(k), baseDirectory, insideBody || d.body != BodyKind::None, child)) return false;
      d.children.push_back(std::move(child));
    }
  }
  return true;
}

// "kind" and, for "shatter", its fields (geometry::fracture through a split job).
bool readShatter(Reader& rd, const Node& n, ScheduledSplitter& s) {
  int kind = 0;
  if (!rd.choice(n, "kind", {"plane", "shatter"}, kind)) return false;
  s.kind = kind == 1 ? SplitterKind::Shatter : SplitterKind::Plane;
  if (s.kind == SplitterKind::Plane) {
    for (const char* key : {"cells", "seed", "impact_point", "impact_radius", "outward_impulse"})
      if (n.has(key)) return rd.fail(n.child(key), std::string("only a shatter splitter has '") + key + "'");
    return true;
  }
  uint64_t cells = s.shatter.cells;
  glm::vec3 impact(0.f);
  if (!rd.integer(n, "cells", cells, 1, 256) || !rd.integer(n, "seed", s.shatter.seed) ||
      !rd.vec3(n, "impact_point", impact) || !rd.nonNegative(n, "impact_radius", s.shatter.impactRadius) ||
      !rd.nonNegative(n, "outward_impulse", s.shatter.outwardImpulse))
    return false;
  s.shatter.cells = uint32_t(cells);
  s.shatter.impactGiven = n.has("impact_point");
  s.shatter.impactPoint = glm::dvec3(impact);
  return true;
}

bool readSplitter(Reader& rd, const Node& n, ScheduledSplitter& s) {
  if (!rd.expectObject(n, {"name", "lifetime", "half_extents", "transform", "velocity", "fire_tick",
                           "start_tick", "end_tick", "player_caused", "kind", "cells", "seed", "impact_point",
                           "impact_radius", "outward_impulse"}))
    return false;
  if (!readShatter(rd, n, s)) return false;
  int lifetime = 1;
  if (!rd.string(n, "name", s.name) || !rd.choice(n, "lifetime", {"persistent", "one_tick"}, lifetime) ||
      !rd.vec3(n, "half_extents", s.halfExtents, true) || !rd.vec3(n, "velocity", s.velocity) ||
      !rd.boolean(n, "player_caused", s.playerCaused))
    return false;
  s.schedule = lifetime == 0 ? SplitterSchedule::Persistent : SplitterSchedule::OneTick;
  ecs::Transform t;
  if (!readTransform(rd, n, t, false)) return false;
  s.position = t.position;
  s.rotation = t.rotation;
  const uint64_t kMaxTick = uint64_t(1) << 40;
  if (s.schedule == SplitterSchedule::OneTick) {
    for (const char* key : {"start_tick", "end_tick"})
      if (n.has(key)) return rd.fail(n.child(key), std::string("a one-tick splitter has no '") + key + "' (use fire_tick)");
    if (!n.has("fire_tick")) return rd.fail(n, "a one-tick splitter needs 'fire_tick'");
    if (!rd.integer(n, "fire_tick", s.fireTick, 0, kMaxTick)) return false;
  } else {
    if (n.has("fire_tick")) return rd.fail(n.child("fire_tick"), "a persistent splitter has no 'fire_tick' (use start_tick)");
    if (!rd.integer(n, "start_tick", s.startTick, 0, kMaxTick)) return false;
    if (n.has("end_tick")) {
      uint64_t end = 0;
      if (!rd.integer(n, "end_tick", end, s.startTick + 1, kMaxTick)) return false;
      s.endTick = end;
    }
  }
  return true;
}

// The piece budget (piece_budget.h): limits, policy, fade time, hit speed, the smallest body.
bool readPieceBudget(Reader& rd, const Node& b, SceneDesc& scene) {
  if (!rd.expectObject(b, {"enabled", "max_live_pieces", "max_awake_pieces", "max_frozen_pieces", "max_debris",
                           "max_retirements_per_tick", "policy", "fade_seconds", "hit_speed", "restless_seconds",
                           "min_body_volume", "min_body_thickness"}))
    return false;
  scene.pieceBudgetGiven = true;
  PieceBudgetSettings& s = scene.pieceBudget;
  int policy = int(s.policy) - 1;
  double fade = s.fadeSeconds, hit = s.hitSpeed, restless = s.restlessSeconds;
  if (!rd.boolean(b, "enabled", s.enabled) || !rd.integer32(b, "max_live_pieces", s.maxLivePieces, 0) ||
      !rd.integer32(b, "max_awake_pieces", s.maxAwakePieces, 0) ||
      !rd.integer32(b, "max_frozen_pieces", s.maxFrozenPieces, 0) || !rd.integer32(b, "max_debris", s.maxDebris, 0) ||
      !rd.integer32(b, "max_retirements_per_tick", s.maxRetirementsPerTick, 1) ||
      !rd.choice(b, "policy", {"freeze", "fade", "remove"}, policy) || !rd.nonNegative(b, "fade_seconds", fade) ||
      !rd.nonNegative(b, "hit_speed", hit) || !rd.nonNegative(b, "restless_seconds", restless) ||
      !rd.nonNegative(b, "min_body_volume", s.minBodyVolume) ||
      !rd.nonNegative(b, "min_body_thickness", s.minBodyThickness))
    return false;
  s.policy = PieceRetirement(policy + 1);
  s.fadeSeconds = float(fade);
  s.hitSpeed = float(hit);
  s.restlessSeconds = float(restless);
  return true;
}

bool readScene(Reader& rd, const json& root, const std::string& baseDirectory, SceneDesc& scene) {
  const Node n{&root, {}};
  if (!rd.expectObject(n, {"version", "description", "gravity", "floor", "budget", "piece_budget", "camera",
                           "ticks", "entities", "splitters"}))
    return false;
  if (n.has("version")) {
    uint64_t version = 1;
    if (!rd.integer(n, "version", version)) return false;
    if (version != 1) return rd.fail(n.child("version"), "this build reads scene format version 1");
  }
  std::string description;
  if (!rd.string(n, "description", description)) return false;
  if (!rd.vec3(n, "gravity", scene.gravity) || !rd.integer(n, "ticks", scene.ticks, 0, uint64_t(1) << 40))
    return false;
  if (n.has("floor")) {
    const Node f = n.child("floor");
    if (f->is_boolean()) {
      scene.floor.present = f->get<bool>();
    } else {
      if (!rd.expectObject(f, {"height", "half_extents", "material"})) return false;
      scene.floor.present = true;
      if (!rd.number(f, "height", scene.floor.height) ||
          !rd.vec3(f, "half_extents", scene.floor.halfExtents, true) ||
          !rd.string(f, "material", scene.floor.material))
        return false;
    }
  }
  if (n.has("budget")) {
    const Node b = n.child("budget");
    if (!rd.expectObject(b, {"milliseconds_per_tick", "max_splits_per_tick", "max_activations_per_tick",
                             "max_queue_length", "deterministic", "threads", "commit_delay_ticks",
                             "worker_milliseconds_per_tick", "estimated_main_ms",
                             "estimated_worker_ms_per_triangle"}))
      return false;
    scene.budgetGiven = true;
    SplitBudgetSettings& s = scene.budget;
    if (!rd.number(b, "milliseconds_per_tick", s.millisecondsPerTick, true) ||
        !rd.integer32(b, "max_splits_per_tick", s.maxSplitsPerTick, 1) ||
        !rd.integer32(b, "max_activations_per_tick", s.maxActivationsPerTick, 1) ||
        !rd.integer32(b, "max_queue_length", s.maxQueueLength, 1) ||
        !rd.boolean(b, "deterministic", s.deterministic) ||
        !rd.integer32(b, "threads", s.threads, 0) ||
        !rd.integer32(b, "commit_delay_ticks", s.commitDelayTicks, 0) ||
        !rd.nonNegative(b, "worker_milliseconds_per_tick", s.workerMillisecondsPerTick) ||
        !rd.nonNegative(b, "estimated_main_ms", s.estimatedMainMilliseconds) ||
        !rd.nonNegative(b, "estimated_worker_ms_per_triangle", s.estimatedWorkerMillisecondsPerTriangle))
      return false;
  }
  if (n.has("piece_budget") && !readPieceBudget(rd, n.child("piece_budget"), scene)) return false;
  if (n.has("camera")) {
    const Node c = n.child("camera");
    if (!rd.expectObject(c, {"position", "target"}) || !rd.vec3(c, "position", scene.cameraPosition) ||
        !rd.vec3(c, "target", scene.cameraTarget))
      return false;
  }
  if (n.has("entities")) {
    const Node e = n.child("entities");
    if (!e->is_array()) return rd.fail(e, std::string("expected an array, found ") + typeName(*e));
    for (size_t k = 0; k < e->size(); ++k) {
      EntityDesc d;
      if (!readEntity(rd, e.at(k), baseDirectory, false, d)) return false;
      scene.entities.push_back(std::move(d));
    }
  }
  if (n.has("splitters")) {
    const Node s = n.child("splitters");
    if (!s->is_array()) return rd.fail(s, std::string("expected an array, found ") + typeName(*s));
    for (size_t k = 0; k < s->size(); ++k) {
      ScheduledSplitter sp;
      if (!readSplitter(rd, s.at(k), sp)) return false;
      if (sp.name.empty()) sp.name = "splitter " + std::to_string(k);
      scene.splitters.push_back(std::move(sp));
    }
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Creation.

struct Builder {
  SceneContext& ctx;
  SceneLoadResult& result;
  std::vector<ecs::Entity> created;
  std::string error;
  std::vector<std::string> errorPath;

  SplitWorld splitWorld() { return SplitWorld{ctx.world, ctx.physics, ctx.renderer}; }

  render::Material material(const std::string& name, bool cap) const {
    return ctx.materials ? ctx.materials(name, cap) : render::Material{};
  }

  // The object's mesh with its children merged in (each child's transform relative to it), every
  // part on its own material slot; `names` gets the material name of each slot.
  static void gather(const EntityDesc& d, const glm::mat4& toRoot, geometry::MeshData& out,
                     std::vector<std::string>& names) {
    if (d.hasMesh && !d.mesh.indices.empty()) {
      geometry::MeshData part = d.mesh;
      const uint32_t slot = uint32_t(names.size());
      names.push_back(d.material);
      if (part.submeshes.empty()) {
        part.submeshes.push_back(geometry::SubMesh{0, uint32_t(part.indices.size()), slot});
      } else {
        for (auto& sm : part.submeshes) sm.materialId = slot;
      }
      if (toRoot != glm::mat4(1.f)) geometry::primitives::transform(part, toRoot);
      out = out.indices.empty() ? std::move(part) : geometry::primitives::merge(out, part);
    }
    for (const EntityDesc& c : d.children) gather(c, toRoot * ecs::localMatrix(c.transform), out, names);
  }

  ecs::Entity newEntity(const std::string& name, const ecs::Transform& t) {
    const ecs::Entity e = ctx.world.create();
    created.push_back(e);
    ctx.world.add<ecs::Name>(e, ecs::Name{name});
    ctx.world.add<ecs::Transform>(e, t);
    ctx.world.add<ecs::WorldTransform>(e, ecs::WorldTransform{ecs::localMatrix(t)});
    return e;
  }

  void addRenderer(ecs::Entity e, geometry::MeshData mesh, const std::vector<std::string>& names) {
    auto source = std::make_shared<geometry::MeshData>(std::move(mesh));
    MeshRenderer mr;
    mr.source = source;
    if (ctx.renderer) mr.gpu = ctx.renderer->uploadMesh(*source).valueOr({});
    for (const std::string& n : names) mr.materials.push_back(material(n, false));
    if (mr.materials.empty()) mr.materials.push_back(material("", false));
    ctx.world.add<MeshRenderer>(e, std::move(mr));
  }

  bool createFloor(const FloorDesc& f) {
    ecs::Transform t;
    t.position = glm::vec3(0.f, f.height - f.halfExtents.y, 0.f);
    const ecs::Entity e = newEntity("floor", t);
    addRenderer(e, geometry::primitives::box(f.halfExtents), {f.material});
    auto shape = ctx.physics.createShape(physics::ShapeDef::box(f.halfExtents));
    if (!shape.ok()) return failWith("floor: " + shape.message(), {"floor"});
    physics::BodyDef def;
    def.shape = shape.value();
    def.position = t.position;
    def.userData = toUserData(e);
    auto body = ctx.physics.createBody(def);
    if (!body.ok()) {
      ctx.physics.destroyShape(shape.value());
      return failWith("floor: " + body.message(), {"floor"});
    }
    ctx.world.add<RigidBody>(e, RigidBody{body.value(), shape.value()});
    result.floor = e;
    return true;
  }

  bool failWith(const std::string& message, const std::vector<std::string>& path = {}) {
    error = message;
    errorPath = path;
    return false;
  }

  // `group` is the entity of the enclosing object without a body (null at the root) and
  // `groupWorld` its world transform.
  bool create(const EntityDesc& d, ecs::Entity group, const ecs::Transform& groupWorld) {
    const std::string name = d.name.empty() ? "object" : d.name;
    if (d.body == BodyKind::None) {
      const ecs::Entity e = newEntity(name, d.transform);
      if (d.hasMesh) addRenderer(e, d.mesh, {d.material});
      if (!group.isNull()) ecs::setParent(ctx.world, e, group);
      result.entities.push_back(SceneEntity{e, d.name, d.material, false, false, group});
      ecs::Transform world;
      world.position = groupWorld.position + groupWorld.rotation * (groupWorld.scale * d.transform.position);
      world.rotation = groupWorld.rotation * d.transform.rotation;
      world.scale = groupWorld.scale * d.transform.scale;
      for (const EntityDesc& c : d.children)
        if (!create(c, e, world)) return false;
      return true;
    }

    // A body is a root: its pose is the world pose (composed through enclosing groups).
    ecs::Transform t;
    t.position = groupWorld.position + groupWorld.rotation * (groupWorld.scale * d.transform.position);
    t.rotation = groupWorld.rotation * d.transform.rotation;
    t.scale = groupWorld.scale * d.transform.scale;
    geometry::MeshData mesh;
    std::vector<std::string> names;
    gather(d, glm::mat4(1.f), mesh, names);
    if (mesh.indices.empty()) return failWith(name + ": the mesh has no triangles", d.path);
    const bool plainBox = d.isBox && d.children.empty();
    const ecs::Entity e = newEntity(name, t);
    geometry::MeshData keep = mesh;
    addRenderer(e, std::move(mesh), names);

    double density = d.density;
    if (d.splitable) {
      Splitable s = d.split;
      if (!d.capMaterialIdGiven) s.capMaterialId = uint32_t(names.size());
      s.capMaterial = material(d.capMaterial.empty() ? d.material : d.capMaterial, true);
      auto& mr = ctx.world.get<MeshRenderer>(e);
      if (mr.materials.size() <= s.capMaterialId) mr.materials.resize(s.capMaterialId + 1, mr.materials.back());
      mr.materials[s.capMaterialId] = s.capMaterial;
      s.collider = d.collider;
      ctx.world.add<Splitable>(e, s);
    }

    SplitWorld sw = splitWorld();
    if (d.body == BodyKind::Dynamic) {
      if (d.mass) {
        const auto props = geometry::computeMassProperties(keep, glm::dmat4(ecs::localMatrix(t)));
        if (!(props.volume > 0.0)) return failWith(name + ": the mesh encloses no volume", d.path);
        density = *d.mass / props.volume;
      }
      if (auto* s = ctx.world.tryGet<Splitable>(e); s && !d.splitDensityGiven) s->density = density;
      if (const base::Status made = makeDynamicBody(sw, e, density, d.collider, ctx.splits); !made.ok())
        return failWith(name + ": " + made.message, d.path);
      const auto& rb = ctx.world.get<RigidBody>(e);
      if (d.linearVelocity != glm::vec3(0.f) || d.angularVelocity != glm::vec3(0.f))
        ctx.physics.setVelocity(rb.body, d.linearVelocity, d.angularVelocity);
    } else {
      physics::Result<physics::ShapeId> shape =
          plainBox ? ctx.physics.createShape(physics::ShapeDef::box(d.boxHalfExtents * t.scale)) : [&] {
            std::vector<glm::vec3> points;
            points.reserve(keep.positions.size());
            for (const glm::vec3& p : keep.positions) points.push_back(p * t.scale);
            return ctx.physics.createShape(physics::ShapeDef::staticMesh(points, keep.indices));
          }();
      if (!shape.ok()) return failWith(name + ": no collider: " + shape.message(), d.path);
      physics::BodyDef def;
      def.shape = shape.value();
      def.position = t.position;
      def.rotation = t.rotation;
      def.userData = toUserData(e);
      auto body = ctx.physics.createBody(def);
      if (!body.ok()) {
        ctx.physics.destroyShape(shape.value());
        return failWith(name + ": " + body.message(), d.path);
      }
      ctx.world.add<RigidBody>(e, RigidBody{body.value(), shape.value()});
      if (d.splitable && !d.splitDensityGiven) ctx.world.get<Splitable>(e).density = density;
    }
    result.entities.push_back(SceneEntity{e, d.name, d.material, d.body == BodyKind::Dynamic, d.splitable, {}});
    return true;
  }

  void rollback() {
    for (ecs::Entity e : created) ctx.world.destroy(e);  // its hooks free what it holds
    created.clear();
  }
};

SceneLoadResult syntaxError(const std::string& file, const std::string& text, const json::parse_error& e) {
  SceneLoadResult r;
  const size_t byte = e.byte > 0 ? size_t(e.byte - 1) : 0;
  const size_t end = std::min(byte, text.size());
  int line = 1;
  size_t lineStart = 0;
  for (size_t k = 0; k < end; ++k) {
    if (text[k] == '\n') {
      ++line;
      lineStart = k + 1;
    }
  }
  const size_t column = end - lineStart + 1;
  std::string detail = e.what();
  // "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error ..." -> the part
  // after the position.
  if (const size_t p = detail.find("syntax error"); p != std::string::npos) detail = detail.substr(p);
  const std::string key = lastKeyBefore(text, end);
  r.errorFile = file;
  r.errorLine = line;
  r.errorField = key.empty() ? "" : key;
  r.setFailure(base::StatusCode::ParseError, file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " +
            (key.empty() ? std::string("at the start") : "after field '" + key + "'") + ": " + detail);
  return r;
}

}  // namespace

ecs::Entity SceneLoadResult::find(const std::string& name) const {
  for (const SceneEntity& e : entities)
    if (e.name == name) return e.entity;
  return {};
}

ecs::Entity createSplitterEntity(SplitWorld& w, const ScheduledSplitter& s) {
  Splitter splitter;
  splitter.lifetime =
      s.schedule == SplitterSchedule::Persistent ? SplitterLifetime::Persistent : SplitterLifetime::OneTick;
  splitter.playerCaused = s.playerCaused;
  splitter.halfExtents = s.halfExtents;
  splitter.kind = s.kind;
  splitter.shatter = s.shatter;
  return createSplitter(w, s.name, physics::ShapeDef::box(s.halfExtents), s.position, s.rotation, splitter);
}

SceneLoadResult loadSceneFromString(const std::string& text, const std::string& name,
                                    const std::string& baseDirectory, SceneContext& ctx) {
  json root;
  try {
    root = json::parse(text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const json::parse_error& e) {
    return syntaxError(name, text, e);
  } catch (const std::exception& e) {
    SceneLoadResult r;
    r.errorFile = name;
    r.setFailure(base::StatusCode::ParseError, name + ": " + e.what());
    return r;
  }

  SceneDesc scene;
  Reader rd(name, text);
  SceneLoadResult result;
  bool read = false;
  try {
    read = readScene(rd, root, baseDirectory, scene);
  } catch (const std::exception& e) {  // defensive: the reader checks types before every access
    result.errorFile = name;
    result.setFailure(base::StatusCode::ParseError, name + ": " + e.what());
    return result;
  }
  if (!read || rd.failed()) {
    rd.fillError(result);
    return result;
  }

  result.gravity = scene.gravity;
  result.budget = ctx.splits ? ctx.splits->budget().settings() : SplitBudgetSettings{};
  if (scene.budgetGiven) result.budget = scene.budget;
  result.pieceBudget = ctx.splits ? ctx.splits->pieces().settings() : PieceBudgetSettings{};
  if (scene.pieceBudgetGiven) result.pieceBudget = scene.pieceBudget;
  result.cameraPosition = scene.cameraPosition;
  result.cameraTarget = scene.cameraTarget;
  result.ticks = scene.ticks;

  // Gravity first: bodies take the world's gravity when they are created.
  const glm::vec3 previousGravity = ctx.physics.gravity();
  ctx.physics.setGravity(scene.gravity);
  Builder b{ctx, result, {}, {}, {}};
  bool ok = !scene.floor.present || b.createFloor(scene.floor);
  for (size_t k = 0; ok && k < scene.entities.size(); ++k) ok = b.create(scene.entities[k], {}, ecs::Transform{});
  SplitWorld sw{ctx.world, ctx.physics, ctx.renderer};
  for (ScheduledSplitter& s : scene.splitters) {
    if (!ok) break;
    if (s.schedule == SplitterSchedule::Persistent && s.startTick == 0) {
      s.entity = createSplitterEntity(sw, s);
      s.created = true;
      b.created.push_back(s.entity);
    }
  }
  if (!ok) {
    b.rollback();
    ctx.physics.setGravity(previousGravity);
    result = SceneLoadResult();
    rd.fail(Node{&root, b.errorPath}, b.error);
    rd.fillError(result);
    return result;
  }
  if (ctx.splits && scene.budgetGiven) ctx.splits->budget().setSettings(scene.budget);
  if (ctx.splits && scene.pieceBudgetGiven) ctx.splits->pieces().setSettings(scene.pieceBudget);
  ecs::updateWorldTransforms(ctx.world);
  result.splitters = std::move(scene.splitters);
  result.code = base::StatusCode::Ok;
  return result;
}

SceneLoadResult loadScene(const std::string& path, SceneContext& ctx) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  if (!in || std::filesystem::is_directory(path, ec)) {
    SceneLoadResult r;
    r.errorFile = path;
    r.setFailure(base::StatusCode::IoError, path + ": cannot open the scene file (missing or unreadable)");
    return r;
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string base = std::filesystem::path(path).parent_path().string();
  return loadSceneFromString(buffer.str(), path, base.empty() ? "." : base, ctx);
}

void SceneRunner::update(SplitWorld& w, uint64_t tick, double dt) {
  for (ScheduledSplitter& s : splitters_) {
    if (s.schedule == SplitterSchedule::OneTick) {
      if (!s.created && tick == s.fireTick) {
        s.entity = createSplitterEntity(w, s);
        s.created = true;
        s.createdTick = tick;
      }
      continue;
    }
    const bool due = tick >= s.startTick && (!s.endTick || tick < *s.endTick);
    if (!s.created && due) {
      s.entity = createSplitterEntity(w, s);
      s.created = true;
      s.createdTick = tick;
    }
    if (!w.world.alive(s.entity)) continue;
    if (s.endTick && tick >= *s.endTick) {
      w.world.destroy(s.entity);
      s.entity = {};
      continue;
    }
    if (s.velocity != glm::vec3(0.f)) {
      const double elapsed = double(tick - s.createdTick) * dt;
      const glm::vec3 position = glm::vec3(glm::dvec3(s.position) + glm::dvec3(s.velocity) * elapsed);
      auto& t = w.world.get<ecs::Transform>(s.entity);
      t.position = position;
      w.world.get<ecs::WorldTransform>(s.entity).matrix = ecs::localMatrix(t);
      if (const auto* sp = w.world.tryGet<Splitter>(s.entity))
        w.physics.setTriggerTransform(sp->trigger, physics::BodyTransform{position, s.rotation});
    }
  }
}

void runSceneTick(SplitWorld& w, SplitSystem& splits, SceneRunner& runner, uint64_t tick, double dt,
                  const glm::dvec3& cameraPosition) {
  runner.update(w, tick, dt);                  // Gameplay
  splits.gatherTriggerRequests(w, tick);       // Triggers
  splits.runSplits(w, tick, cameraPosition);   // Split (activations first), Commit
  w.physics.step(dt);                          // PhysicsStep
  syncTransformsFromBodies(w);                 // PhysicsSync
  updateDebris(w, float(dt));
  splits.settlePieces(w, tick, dt);
}

}  // namespace cleave::components
