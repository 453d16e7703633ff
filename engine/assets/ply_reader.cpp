// SPDX-License-Identifier: MIT
// Stanford PLY reader: ascii, binary_little_endian and binary_big_endian. Reads the `vertex` element
// (x y z; nx ny nz; u v, s t, texture_u texture_v or texture_s texture_t; red green blue [alpha])
// and the `face` element's vertex_indices (or vertex_index) list with any count and index types,
// triangulating polygons. Every other element and property is parsed and skipped. Each
// element's declared count is checked against the bytes that remain before anything is allocated.
#include <array>
#include <cmath>
#include <cstring>

#include "cleave/assets/mesh_reader.h"

namespace cleave::assets::detail {

namespace {

enum class Encoding { Ascii, LittleEndian, BigEndian };

struct ScalarType {
  uint8_t size = 0;  // bytes
  bool isFloat = false;
  bool isSigned = false;
  double normalizer = 1.0;  // colour scale for integer types: the type's maximum
};

bool parseType(std::string_view token, ScalarType& type) {
  struct Entry {
    const char* a;
    const char* b;
    ScalarType t;
  };
  static const Entry kTypes[] = {
      {"char", "int8", {1, false, true, 127.0}},
      {"uchar", "uint8", {1, false, false, 255.0}},
      {"short", "int16", {2, false, true, 32767.0}},
      {"ushort", "uint16", {2, false, false, 65535.0}},
      {"int", "int32", {4, false, true, 2147483647.0}},
      {"uint", "uint32", {4, false, false, 4294967295.0}},
      {"float", "float32", {4, true, true, 1.0}},
      {"double", "float64", {8, true, true, 1.0}},
  };
  for (const Entry& e : kTypes) {
    if (token == e.a || token == e.b) {
      type = e.t;
      return true;
    }
  }
  return false;
}

struct Property {
  std::string name;
  bool isList = false;
  ScalarType countType;  // lists only
  ScalarType type;       // the value, or each item of a list
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
  size_t headerLine = 0;
};

// Reads scalar values from the body in one of the three encodings; tracks line numbers in ascii.
class BodyReader {
 public:
  BodyReader(std::span<const uint8_t> body, Encoding encoding, size_t firstLine)
      : body_(body), encoding_(encoding), line_(firstLine) {}

  size_t remaining() const { return body_.size() - pos_; }
  size_t line() const { return line_; }
  bool ascii() const { return encoding_ == Encoding::Ascii; }

  // False at the end of the data or on a token that is not a number.
  bool read(const ScalarType& type, double& value, std::string& reason) {
    if (encoding_ == Encoding::Ascii) return readAscii(value, reason);
    if (remaining() < type.size) {
      reason = "file ends inside the data";
      return false;
    }
    uint8_t raw[8];
    std::memcpy(raw, body_.data() + pos_, type.size);
    pos_ += type.size;
    if (encoding_ == Encoding::BigEndian) {
      for (int i = 0; i < type.size / 2; ++i) std::swap(raw[i], raw[type.size - 1 - i]);
    }
    // raw is now little-endian; assemble without assuming the host order.
    uint64_t bits = 0;
    for (int i = type.size - 1; i >= 0; --i) bits = (bits << 8) | raw[i];
    if (type.isFloat) {
      if (type.size == 4) {
        const uint32_t b32 = static_cast<uint32_t>(bits);
        float f;
        std::memcpy(&f, &b32, sizeof(f));
        value = f;
      } else {
        double d;
        std::memcpy(&d, &bits, sizeof(d));
        value = d;
      }
    } else if (type.isSigned) {
      const int shift = 64 - 8 * type.size;
      value = static_cast<double>(static_cast<int64_t>(bits << shift) >> shift);
    } else {
      value = static_cast<double>(bits);
    }
    return true;
  }

 private:
  bool readAscii(double& value, std::string& reason) {
    while (pos_ < body_.size()) {
      const uint8_t c = body_[pos_];
      if (c == '\n') ++line_;
      if (c != ' ' && c != '\t' && c != '\r' && c != '\n' && c != '\f' && c != '\v') break;
      ++pos_;
    }
    const size_t start = pos_;
    while (pos_ < body_.size()) {
      const uint8_t c = body_[pos_];
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') break;
      ++pos_;
    }
    const std::string_view token(reinterpret_cast<const char*>(body_.data()) + start, pos_ - start);
    if (token.empty()) {
      reason = "file ends inside the data";
      return false;
    }
    if (!parseDouble(token, value)) {
      reason = "bad number " + quoted(token);
      return false;
    }
    return true;
  }

  std::span<const uint8_t> body_;
  Encoding encoding_;
  size_t pos_ = 0;
  size_t line_;
};

// Property roles of the vertex element.
enum Role : int { kX, kY, kZ, kNx, kNy, kNz, kU, kV, kRed, kGreen, kBlue, kAlpha, kRoleCount };

int roleOf(std::string_view name) {
  if (name == "x") return kX;
  if (name == "y") return kY;
  if (name == "z") return kZ;
  if (name == "nx") return kNx;
  if (name == "ny") return kNy;
  if (name == "nz") return kNz;
  if (name == "u" || name == "s" || name == "texture_u" || name == "texture_s") return kU;
  if (name == "v" || name == "t" || name == "texture_v" || name == "texture_t") return kV;
  if (name == "red" || name == "r" || name == "diffuse_red") return kRed;
  if (name == "green" || name == "g" || name == "diffuse_green") return kGreen;
  if (name == "blue" || name == "b" || name == "diffuse_blue") return kBlue;
  if (name == "alpha" || name == "a" || name == "diffuse_alpha") return kAlpha;
  return -1;
}

// The least number of body bytes one instance of the element can take.
uint64_t minimumBytes(const Element& element, Encoding encoding) {
  uint64_t bytes = 0;
  for (const Property& p : element.properties) {
    if (encoding == Encoding::Ascii) bytes += 2;  // one digit and one separator
    else bytes += p.isList ? p.countType.size : p.type.size;
  }
  return bytes;
}

}  // namespace

MeshReadResult readPly(std::span<const uint8_t> bytes, const std::string& name) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  LineScanner scanner(text, '\0');
  if (!scanner.nextLine() || scanner.nextToken() != "ply") {
    return failureAt(name, 1, "not a PLY file (the first line must be 'ply')");
  }
  Encoding encoding = Encoding::Ascii;
  bool haveFormat = false;
  bool ended = false;
  std::vector<Element> elements;
  while (!ended && scanner.nextLine()) {
    const size_t line = scanner.lineNumber();
    const std::string_view keyword = scanner.nextToken();
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      const std::string_view kind = scanner.nextToken();
      if (kind == "ascii") encoding = Encoding::Ascii;
      else if (kind == "binary_little_endian") encoding = Encoding::LittleEndian;
      else if (kind == "binary_big_endian") encoding = Encoding::BigEndian;
      else return failureAt(name, line, "unknown PLY format " + quoted(kind));
      haveFormat = true;
    } else if (keyword == "element") {
      Element element;
      element.name = std::string(scanner.nextToken());
      const std::string_view countToken = scanner.nextToken();
      int64_t count = 0;
      if (element.name.empty() || !parseInt64(countToken, count) || count < 0) {
        return failureAt(name, line, "bad element declaration");
      }
      element.count = static_cast<uint64_t>(count);
      element.headerLine = line;
      elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (elements.empty()) return failureAt(name, line, "property before any element");
      Property property;
      std::string_view typeToken = scanner.nextToken();
      if (typeToken == "list") {
        property.isList = true;
        const std::string_view countToken = scanner.nextToken();
        if (!parseType(countToken, property.countType) || property.countType.isFloat) {
          return failureAt(name, line, "bad list count type " + quoted(countToken));
        }
        typeToken = scanner.nextToken();
      }
      if (!parseType(typeToken, property.type)) {
        return failureAt(name, line, "unknown property type " + quoted(typeToken));
      }
      property.name = std::string(scanner.nextToken());
      if (property.name.empty()) return failureAt(name, line, "property without a name");
      elements.back().properties.push_back(std::move(property));
    } else if (keyword == "end_header") {
      ended = true;
    } else {
      return failureAt(name, line, "unexpected " + quoted(keyword) + " in the PLY header");
    }
  }
  if (!ended) return failure(name, "PLY header has no end_header");
  if (!haveFormat) return failure(name, "PLY header has no format line");

  const size_t bodyStart = std::min(scanner.offset(), bytes.size());
  BodyReader body(bytes.subspan(bodyStart), encoding, scanner.lineNumber() + 1);

  MeshReadResult result;
  geometry::MeshData& mesh = result.mesh;
  bool haveVertices = false;
  bool haveFaces = false;
  std::array<bool, kRoleCount> present{};
  std::array<double, kRoleCount> colorScale{};
  std::vector<uint32_t> polygon;
  std::vector<glm::vec3> polygonPositions;
  PolygonTriangulator faces;
  std::string reason;
  auto bodyError = [&](const Element& element, uint64_t index) {
    const std::string where = "in " + element.name + " " + std::to_string(index) + ": " + reason;
    return body.ascii() ? failureAt(name, body.line(), where) : failure(name, where);
  };

  for (const Element& element : elements) {
    const uint64_t minBytes = minimumBytes(element, encoding);
    if (minBytes > 0 && element.count > (body.remaining() + 1) / minBytes) {
      return failureAt(name, element.headerLine,
                       "element " + quoted(element.name) + " declares " +
                           std::to_string(element.count) + " entries, more than the file can hold");
    }
    const bool isVertex = element.name == "vertex" && !haveVertices;
    const bool isFace = element.name == "face" && !haveFaces;
    std::vector<int> roles(element.properties.size(), -1);
    int faceList = -1;
    if (isVertex) {
      if (element.count > UINT32_MAX / 2) return failure(name, "too many vertices");
      haveVertices = true;
      for (size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        const int role = property.isList ? -1 : roleOf(property.name);
        if (role >= 0 && !present[static_cast<size_t>(role)]) {
          roles[p] = role;
          present[static_cast<size_t>(role)] = true;
          colorScale[static_cast<size_t>(role)] =
              property.type.isFloat ? 1.0 : 1.0 / property.type.normalizer;
        }
      }
      if (!present[kX] || !present[kY] || !present[kZ]) {
        return failureAt(name, element.headerLine, "vertex element lacks x, y or z");
      }
      mesh.positions.reserve(static_cast<size_t>(element.count));
    }
    if (isFace) {
      haveFaces = true;
      for (size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        if (property.isList && (property.name == "vertex_indices" || property.name == "vertex_index")) {
          faceList = static_cast<int>(p);
          break;
        }
      }
      if (faceList < 0) {
        return failureAt(name, element.headerLine, "face element has no vertex_indices list");
      }
    }
    if (element.properties.empty()) continue;  // nothing to read, whatever the count says
    const bool hasNormals = present[kNx] && present[kNy] && present[kNz];
    const bool hasUv = present[kU] && present[kV];
    const bool hasColor = present[kRed] && present[kGreen] && present[kBlue];

    for (uint64_t e = 0; e < element.count; ++e) {
      std::array<double, kRoleCount> values{};
      values[kAlpha] = 1.0;
      for (size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        if (!property.isList) {
          double value = 0.0;
          if (!body.read(property.type, value, reason)) return bodyError(element, e);
          if (roles[p] >= 0) values[static_cast<size_t>(roles[p])] = value;
          continue;
        }
        double countValue = 0.0;
        if (!body.read(property.countType, countValue, reason)) return bodyError(element, e);
        const uint64_t itemBytes = encoding == Encoding::Ascii ? 2 : property.type.size;
        if (!(countValue >= 0.0) || countValue != std::floor(countValue) ||
            countValue > static_cast<double>((body.remaining() + 1) / itemBytes)) {
          reason = "list length " + std::to_string(countValue) + " is invalid or exceeds the file";
          return bodyError(element, e);
        }
        const uint64_t count = static_cast<uint64_t>(countValue);
        const bool indices = isFace && static_cast<int>(p) == faceList;
        if (indices) polygon.clear();
        for (uint64_t k = 0; k < count; ++k) {
          double value = 0.0;
          if (!body.read(property.type, value, reason)) return bodyError(element, e);
          if (indices) {
            if (!(value >= 0.0) || value != std::floor(value) || value >= 4294967295.0) {
              reason = "bad vertex index " + std::to_string(value);
              return bodyError(element, e);
            }
            polygon.push_back(static_cast<uint32_t>(value));
          }
        }
        if (indices) {
          if (polygon.size() < 3) {
            reason = "a face needs at least 3 corners";
            return bodyError(element, e);
          }
          // A file may list its faces before its vertices: such a face has no positions yet and
          // is fanned.
          polygonPositions.clear();
          for (uint32_t id : polygon) {
            if (id < mesh.positions.size()) polygonPositions.push_back(mesh.positions[id]);
          }
          faces.append(polygon, polygonPositions, mesh.indices);
        }
      }
      if (isVertex) {
        mesh.positions.emplace_back(values[kX], values[kY], values[kZ]);
        if (hasNormals) mesh.normals.emplace_back(values[kNx], values[kNy], values[kNz]);
        if (hasUv) mesh.uv0.emplace_back(values[kU], values[kV]);
        if (hasColor) {
          mesh.colors.emplace_back(values[kRed] * colorScale[kRed], values[kGreen] * colorScale[kGreen],
                                   values[kBlue] * colorScale[kBlue],
                                   present[kAlpha] ? values[kAlpha] * colorScale[kAlpha] : 1.0);
        }
      }
    }
    if (isVertex) present = {};  // roles only apply to the vertex element
  }
  if (!haveVertices) return failure(name, "PLY file has no vertex element");
  if (!haveFaces) return failure(name, "PLY file has no face element");
  if (!mesh.normals.empty()) {
    bool degenerate = false;
    for (glm::vec3& n : mesh.normals) {
      const float length = glm::length(n);
      if (length > 0.f && std::isfinite(length)) n /= length;
      else degenerate = true;
    }
    if (degenerate) {
      mesh.normals.clear();
      result.warnings.push_back(name + ": a normal has zero length or is not finite; normals dropped");
    }
  }
  return finish(std::move(result), name);
}

}  // namespace cleave::assets::detail
