// SPDX-License-Identifier: MIT
// Internal to the components library: reading a scene's JSON with positions (scene_loader.h). The
// parsed value keeps no line numbers, so every value is read through a Node that knows its JSON
// pointer, and the first error is reported with the line where the offending value starts, found
// by walking the (already valid) text along the pointer.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "cleave/components/scene_loader.h"

namespace cleave::components::scene_json {

using nlohmann::json;

// The line (from 1) where the value at `path` starts in `text`, or that of the deepest ancestor
// found if the path ends early. Comments are skipped as the parser does.
int jsonLineOf(const std::string& text, const std::vector<std::string>& path);
// The last object key that starts before byte `end` (for syntax errors, which have no pointer).
std::string lastKeyBefore(const std::string& text, size_t end);
// "/a/0/b" with '~' and '/' escaped; "/" for the root.
std::string pointerOf(const std::vector<std::string>& path);
const char* typeName(const json& j);  // "an object", "a number", ...
std::string joinNames(std::span<const char* const> names);
std::string joinNames(std::initializer_list<const char*> names);

// A value and its JSON pointer.
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

class Reader {
 public:
  Reader(const std::string& file, const std::string& text) : file_(file), text_(text) {}

  bool failed() const { return !field_.empty() || failed_; }

  bool fail(const Node& n, const std::string& reason) {
    if (failed()) return false;
    failed_ = true;
    field_ = pointerOf(n.path);
    reason_ = reason;
    line_ = jsonLineOf(text_, n.path);
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


}  // namespace cleave::components::scene_json
