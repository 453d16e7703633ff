// SPDX-License-Identifier: MIT
// Stanford PLY reader: ascii, binary_little_endian and binary_big_endian. Reads the `vertex` element
// (x y z; nx ny nz; u v, s t, texture_u texture_v or texture_s texture_t; red green blue [alpha])
// and the `face` element's vertex_indices (or vertex_index) list with any count and index types,
// triangulating polygons. Every other element and property is parsed and skipped. Each
// element's declared count is checked against the bytes that remain before anything is allocated.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>

#include "cleave/assets/line_scanner.h"
#include "cleave/assets/mesh_finish.h"
#include "cleave/assets/mesh_reader.h"
#include "cleave/assets/polygon_triangulator.h"

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

// Reads scalar values from the body in one of the three encodings. Ascii bodies are read with the
// text formats' tokenizer, which keeps the line number for messages.
class BodyReader {
 public:
  BodyReader(std::span<const uint8_t> body, Encoding encoding, size_t headerLines)
      : body_(body),
        encoding_(encoding),
        text_(reinterpret_cast<const char*>(body.data()), body.size()),
        scanner_(text_, '\0', /*nulSeparates=*/false),
        headerLines_(headerLines) {}

  size_t remaining() const {
    return ascii() ? text_.size() - std::min(scanner_.position(), text_.size())
                   : body_.size() - pos_;
  }
  // The line of the last token read (past the end of the data, the line after the last line
  // end): one more than the LF bytes before it, so a lone CR inside the data is no line end here.
  // Counted only for a message.
  size_t line() const {
    const std::string_view before = text_.substr(0, std::min(scanner_.position(), text_.size()));
    return headerLines_ + 1 + static_cast<size_t>(std::count(before.begin(), before.end(), '\n'));
  }
  bool ascii() const { return encoding_ == Encoding::Ascii; }

  // False at the end of the data or on a token that is not a number.
  bool read(const ScalarType& type, double& value, std::string& reason) {
    if (ascii()) return readAscii(value, reason);
    if (body_.size() - pos_ < type.size) {
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
    value = decode(type, bits);
    return true;
  }

 private:
  static double decode(const ScalarType& type, uint64_t bits) {
    if (type.isFloat && type.size == 4) {
      const uint32_t b32 = static_cast<uint32_t>(bits);
      float f;
      std::memcpy(&f, &b32, sizeof(f));
      return f;
    }
    if (type.isFloat) {
      double d;
      std::memcpy(&d, &bits, sizeof(d));
      return d;
    }
    if (type.isSigned) {
      const int shift = 64 - 8 * type.size;
      return static_cast<double>(static_cast<int64_t>(bits << shift) >> shift);
    }
    return static_cast<double>(bits);
  }

  bool readAscii(double& value, std::string& reason) {
    const std::string_view token = scanner_.nextTokenAnyLine();
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
  size_t pos_ = 0;  // binary
  std::string_view text_;
  LineScanner scanner_;  // ascii
  size_t headerLines_;
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
    if (encoding == Encoding::Ascii)
      bytes += 2;  // one digit and one separator
    else
      bytes += p.isList ? p.countType.size : p.type.size;
  }
  return bytes;
}

struct PlyHeader {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
};

// Reads the header, from "ply" to "end_header". Each line handler returns the reason of a failure
// on that line, empty when the line is good.
class HeaderReader {
 public:
  HeaderReader(LineScanner& scanner, const std::string& name) : scanner_(scanner), name_(name) {}

  std::optional<MeshReadResult> read(PlyHeader& header) {
    if (!scanner_.nextLine() || scanner_.nextToken() != "ply") {
      return failureAt(name_, 1, "not a PLY file (the first line must be 'ply')");
    }
    bool ended = false;
    while (!ended && scanner_.nextLine()) {
      const std::string_view keyword = scanner_.nextToken();
      ended = keyword == "end_header";
      const std::string reason = ended ? std::string() : line(keyword, header);
      if (!reason.empty()) return failureAt(name_, scanner_.lineNumber(), reason);
    }
    if (!ended) return failure(name_, "PLY header has no end_header");
    if (!haveFormat_) return failure(name_, "PLY header has no format line");
    return std::nullopt;
  }

 private:
  std::string line(std::string_view keyword, PlyHeader& header) {
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info") return {};
    if (keyword == "format") return format(header.encoding);
    if (keyword == "element") return element(header.elements);
    if (keyword == "property") {
      if (header.elements.empty()) return "property before any element";
      return property(header.elements.back());
    }
    return "unexpected " + quoted(keyword) + " in the PLY header";
  }

  std::string format(Encoding& encoding) {
    const std::string_view kind = scanner_.nextToken();
    if (kind == "ascii")
      encoding = Encoding::Ascii;
    else if (kind == "binary_little_endian")
      encoding = Encoding::LittleEndian;
    else if (kind == "binary_big_endian")
      encoding = Encoding::BigEndian;
    else
      return "unknown PLY format " + quoted(kind);
    haveFormat_ = true;
    return {};
  }

  std::string element(std::vector<Element>& elements) {
    Element element;
    element.name = std::string(scanner_.nextToken());
    const std::string_view countToken = scanner_.nextToken();
    int64_t count = 0;
    if (element.name.empty() || !parseInt64(countToken, count) || count < 0) {
      return "bad element declaration";
    }
    element.count = static_cast<uint64_t>(count);
    element.headerLine = scanner_.lineNumber();
    elements.push_back(std::move(element));
    return {};
  }

  std::string property(Element& element) {
    Property property;
    std::string_view typeToken = scanner_.nextToken();
    if (typeToken == "list") {
      property.isList = true;
      const std::string_view countToken = scanner_.nextToken();
      if (!parseType(countToken, property.countType) || property.countType.isFloat) {
        return "bad list count type " + quoted(countToken);
      }
      typeToken = scanner_.nextToken();
    }
    if (!parseType(typeToken, property.type)) return "unknown property type " + quoted(typeToken);
    property.name = std::string(scanner_.nextToken());
    if (property.name.empty()) return "property without a name";
    element.properties.push_back(std::move(property));
    return {};
  }

  LineScanner& scanner_;
  const std::string& name_;
  bool haveFormat_ = false;
};

// Reads the body element by element: the first `vertex` element gives the vertices, the first
// `face` element the faces, every other element is read and dropped.
class BodyElements {
 public:
  BodyElements(BodyReader& body, Encoding encoding, const std::string& name)
      : body_(body), encoding_(encoding), name_(name) {}

  std::optional<MeshReadResult> read(const std::vector<Element>& elements) {
    for (const Element& element : elements) {
      std::optional<MeshReadResult> failed = begin(element);
      if (!failed && !element.properties.empty()) failed = readEntries(element);
      if (failed) return failed;
      if (isVertex_) present_ = {};  // roles only apply to the vertex element
    }
    if (!haveVertices_) return failure(name_, "PLY file has no vertex element");
    if (!haveFaces_) return failure(name_, "PLY file has no face element");
    return std::nullopt;
  }

  MeshReadResult& result() { return result_; }

 private:
  // Checks the element's count against the bytes left and sets up its roles.
  std::optional<MeshReadResult> begin(const Element& element) {
    const uint64_t minBytes = minimumBytes(element, encoding_);
    if (minBytes > 0 && element.count > (body_.remaining() + 1) / minBytes) {
      return failureAt(name_, element.headerLine,
                       "element " + quoted(element.name) + " declares " +
                           std::to_string(element.count) + " entries, more than the file can hold");
    }
    isVertex_ = element.name == "vertex" && !haveVertices_;
    isFace_ = element.name == "face" && !haveFaces_;
    roles_.assign(element.properties.size(), -1);
    faceList_ = -1;
    if (isVertex_) {
      if (element.count > UINT32_MAX / 2) return failure(name_, "too many vertices");
      haveVertices_ = true;
      assignRoles(element);
      if (!present_[kX] || !present_[kY] || !present_[kZ]) {
        return failureAt(name_, element.headerLine, "vertex element lacks x, y or z");
      }
      result_.mesh.positions.reserve(static_cast<size_t>(element.count));
    }
    if (isFace_) {
      haveFaces_ = true;
      for (size_t p = 0; p < element.properties.size() && faceList_ < 0; ++p) {
        const Property& property = element.properties[p];
        if (property.isList &&
            (property.name == "vertex_indices" || property.name == "vertex_index")) {
          faceList_ = static_cast<int>(p);
        }
      }
      if (faceList_ < 0)
        return failureAt(name_, element.headerLine, "face element has no vertex_indices list");
    }
    return std::nullopt;
  }

  void assignRoles(const Element& element) {
    for (size_t p = 0; p < element.properties.size(); ++p) {
      const Property& property = element.properties[p];
      const int role = property.isList ? -1 : roleOf(property.name);
      if (role >= 0 && !present_[static_cast<size_t>(role)]) {
        roles_[p] = role;
        present_[static_cast<size_t>(role)] = true;
        colorScale_[static_cast<size_t>(role)] =
            property.type.isFloat ? 1.0 : 1.0 / property.type.normalizer;
      }
    }
  }

  std::optional<MeshReadResult> bodyError(const Element& element, uint64_t index) const {
    const std::string where = "in " + element.name + " " + std::to_string(index) + ": " + reason_;
    return body_.ascii() ? failureAt(name_, body_.line(), where) : failure(name_, where);
  }

  std::optional<MeshReadResult> readEntries(const Element& element) {
    for (uint64_t e = 0; e < element.count; ++e) {
      std::array<double, kRoleCount> values{};
      values[kAlpha] = 1.0;
      for (size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        const bool ok = property.isList
                            ? readList(property, isFace_ && static_cast<int>(p) == faceList_)
                            : readScalar(property, roles_[p], values);
        if (!ok) return bodyError(element, e);
      }
      if (isVertex_) addVertex(values);
    }
    return std::nullopt;
  }

  bool readScalar(const Property& property, int role, std::array<double, kRoleCount>& values) {
    double value = 0.0;
    if (!body_.read(property.type, value, reason_)) return false;
    if (role >= 0) values[static_cast<size_t>(role)] = value;
    return true;
  }

  // A list property; the face element's index list becomes a polygon.
  bool readList(const Property& property, bool indices) {
    double countValue = 0.0;
    if (!body_.read(property.countType, countValue, reason_)) return false;
    const uint64_t itemBytes = encoding_ == Encoding::Ascii ? 2 : property.type.size;
    if (!(countValue >= 0.0) || countValue != std::floor(countValue) ||
        countValue > static_cast<double>((body_.remaining() + 1) / itemBytes)) {
      reason_ = "list length " + std::to_string(countValue) + " is invalid or exceeds the file";
      return false;
    }
    const uint64_t count = static_cast<uint64_t>(countValue);
    if (indices) polygon_.clear();
    for (uint64_t k = 0; k < count; ++k) {
      double value = 0.0;
      if (!body_.read(property.type, value, reason_)) return false;
      if (!indices) continue;
      if (!(value >= 0.0) || value != std::floor(value) || value >= 4294967295.0) {
        reason_ = "bad vertex index " + std::to_string(value);
        return false;
      }
      polygon_.push_back(static_cast<uint32_t>(value));
    }
    if (!indices) return true;
    if (polygon_.size() < 3) {
      reason_ = "a face needs at least 3 corners";
      return false;
    }
    faces_.appendIndexed(polygon_, result_.mesh.positions, result_.mesh.indices);
    return true;
  }

  void addVertex(const std::array<double, kRoleCount>& values) {
    geometry::MeshData& mesh = result_.mesh;
    mesh.positions.emplace_back(values[kX], values[kY], values[kZ]);
    if (present_[kNx] && present_[kNy] && present_[kNz]) {
      mesh.normals.emplace_back(values[kNx], values[kNy], values[kNz]);
    }
    if (present_[kU] && present_[kV]) mesh.uv0.emplace_back(values[kU], values[kV]);
    if (present_[kRed] && present_[kGreen] && present_[kBlue]) {
      mesh.colors.emplace_back(values[kRed] * colorScale_[kRed],
                               values[kGreen] * colorScale_[kGreen],
                               values[kBlue] * colorScale_[kBlue],
                               present_[kAlpha] ? values[kAlpha] * colorScale_[kAlpha] : 1.0);
    }
  }

  BodyReader& body_;
  Encoding encoding_;
  const std::string& name_;
  MeshReadResult result_;
  bool haveVertices_ = false;
  bool haveFaces_ = false;
  bool isVertex_ = false;
  bool isFace_ = false;
  std::vector<int> roles_;
  int faceList_ = -1;
  std::array<bool, kRoleCount> present_{};
  std::array<double, kRoleCount> colorScale_{};
  std::vector<uint32_t> polygon_;
  PolygonTriangulator faces_;
  std::string reason_;
};

}  // namespace

MeshReadResult readPly(std::span<const uint8_t> bytes, const std::string& name) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  LineScanner scanner(text, '\0');
  PlyHeader header;
  if (std::optional<MeshReadResult> failed = HeaderReader(scanner, name).read(header))
    return *failed;

  const size_t bodyStart = std::min(scanner.offset(), bytes.size());
  BodyReader body(bytes.subspan(bodyStart), header.encoding, scanner.lineNumber());
  BodyElements elements(body, header.encoding, name);
  if (std::optional<MeshReadResult> failed = elements.read(header.elements)) return *failed;
  MeshReadResult& result = elements.result();
  if (!result.mesh.normals.empty()) normalizeNormals(result, name);
  return finish(std::move(result), name);
}

}  // namespace cleave::assets::detail
