#include "io/mesh/ply.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>

#include "geometry/core/errors.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "io/file.h"
#include "io/mesh/text_scanner.h"

namespace fabmesh {
namespace {

enum class Type { I8, U8, I16, U16, I32, U32, F32, F64 };
enum class Format { Ascii, BinaryLE, BinaryBE };

struct Property {
  std::string name;
  Type type = Type::F32;  // the item type for a list
  bool is_list = false;
  Type count_type = Type::U8;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::size_t body = 0;  // offset of the first data byte
  int body_line = 0;     // line number of the first data line (ascii)
};

std::size_t size_of(Type t) {
  switch (t) {
    case Type::I8:
    case Type::U8:
      return 1;
    case Type::I16:
    case Type::U16:
      return 2;
    case Type::I32:
    case Type::U32:
    case Type::F32:
      return 4;
    case Type::F64:
      return 8;
  }
  return 1;
}

std::optional<Type> type_named(std::string_view s) {
  if (s == "char" || s == "int8") return Type::I8;
  if (s == "uchar" || s == "uint8") return Type::U8;
  if (s == "short" || s == "int16") return Type::I16;
  if (s == "ushort" || s == "uint16") return Type::U16;
  if (s == "int" || s == "int32") return Type::I32;
  if (s == "uint" || s == "uint32") return Type::U32;
  if (s == "float" || s == "float32") return Type::F32;
  if (s == "double" || s == "float64") return Type::F64;
  return std::nullopt;
}

Header parse_header(std::string_view bytes, const std::string& name) {
  TextScanner scan(bytes, name);
  std::string_view line;
  if (!scan.next_line(line) || line != "ply") scan.fail("not a PLY file (first line must be 'ply')");
  Header header;
  bool have_format = false;
  while (true) {
    if (!scan.next_line(line)) scan.fail("header ends without 'end_header'");
    std::string_view rest = line;
    const std::string_view key = next_token(rest);
    if (key == "end_header") break;
    if (key == "comment" || key == "obj_info" || key.empty()) continue;
    if (key == "format") {
      const std::string_view f = next_token(rest);
      if (f == "ascii")
        header.format = Format::Ascii;
      else if (f == "binary_little_endian")
        header.format = Format::BinaryLE;
      else if (f == "binary_big_endian")
        header.format = Format::BinaryBE;
      else
        scan.fail(fmt::format("unknown PLY format '{}'", std::string(f.substr(0, 40))));
      have_format = true;
    } else if (key == "element") {
      Element e;
      e.name = std::string(next_token(rest));
      const std::int64_t n = scan.to_int(next_token(rest), "element count");
      if (n < 0) scan.fail(fmt::format("negative element count {}", n));
      e.count = static_cast<std::uint64_t>(n);
      header.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (header.elements.empty()) scan.fail("'property' before any 'element'");
      Property p;
      std::string_view t = next_token(rest);
      if (t == "list") {
        p.is_list = true;
        const auto count_type = type_named(next_token(rest));
        if (!count_type || *count_type == Type::F32 || *count_type == Type::F64)
          scan.fail("bad list count type");
        p.count_type = *count_type;
        t = next_token(rest);
      }
      const auto type = type_named(t);
      if (!type) scan.fail(fmt::format("unknown property type '{}'", std::string(t.substr(0, 40))));
      p.type = *type;
      p.name = std::string(next_token(rest));
      header.elements.back().properties.push_back(std::move(p));
    } else {
      scan.fail(fmt::format("unexpected '{}' in the PLY header", std::string(key.substr(0, 40))));
    }
  }
  if (!have_format) scan.fail("PLY header has no 'format' line");
  header.body = scan.position();
  header.body_line = scan.line() + 1;
  return header;
}

/// Reads the values of the body, binary or ascii, with bounds checks.
class Values {
 public:
  Values(std::string_view body, Format format, const std::string& name, int first_line)
      : body_(body), format_(format), scan_(body, name, first_line) {}

  double read(Type t) { return format_ == Format::Ascii ? read_ascii() : read_binary(t); }
  std::size_t remaining() const {
    return format_ == Format::Ascii ? scan_.remaining() + rest_.size() : body_.size() - pos_;
  }
  Format format() const { return format_; }
  [[noreturn]] void fail(const std::string& message) const {
    if (format_ == Format::Ascii) scan_.fail(message);
    throw FileError(scan_.name(), 0, 0,
                    fmt::format("{}: byte {} of the PLY data: {}", scan_.name(), pos_, message));
  }

 private:
  double read_ascii() {
    std::string_view token = next_token(rest_);
    while (token.empty()) {
      if (!scan_.next_line(rest_)) fail("data ends early (truncated file?)");
      token = next_token(rest_);
    }
    return scan_.to_double(token, "PLY value");
  }

  double read_binary(Type t) {
    const std::size_t n = size_of(t);
    if (body_.size() - pos_ < n) fail("data ends early (truncated file?)");
    unsigned char b[8];
    std::memcpy(b, body_.data() + pos_, n);
    pos_ += n;
    std::uint64_t u = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t shift = format_ == Format::BinaryLE ? i : n - 1 - i;
      u |= std::uint64_t{b[i]} << (8 * shift);
    }
    switch (t) {
      case Type::I8:
        return static_cast<std::int8_t>(u);
      case Type::U8:
        return static_cast<double>(u);
      case Type::I16:
        return static_cast<std::int16_t>(u);
      case Type::U16:
        return static_cast<double>(u);
      case Type::I32:
        return static_cast<std::int32_t>(u);
      case Type::U32:
        return static_cast<double>(u);
      case Type::F32: {
        const auto bits = static_cast<std::uint32_t>(u);
        float f;
        std::memcpy(&f, &bits, 4);
        return f;
      }
      case Type::F64: {
        double d;
        std::memcpy(&d, &u, 8);
        return d;
      }
    }
    return 0.0;
  }

  std::string_view body_;
  Format format_;
  std::size_t pos_ = 0;
  TextScanner scan_;
  std::string_view rest_;
};

/// The fewest bytes one element can take: guards counts before any allocation.
std::uint64_t min_bytes(const Element& e, Format format) {
  std::uint64_t n = 0;
  for (const Property& p : e.properties)
    n += format == Format::Ascii ? 2 : size_of(p.is_list ? p.count_type : p.type);
  return n;
}

bool is_index_list(const Property& p) {
  return p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index");
}

void read_element(const Element& e, Values& values, TriangleSoup& soup, std::vector<std::uint32_t>& polygon) {
  const bool vertex = e.name == "vertex";
  const bool face = e.name == "face";
  if (e.properties.empty()) return;  // nothing to read, however large the count
  for (std::uint64_t i = 0; i < e.count; ++i) {
    Vec3 p = Vec3::Zero();
    polygon.clear();
    for (const Property& prop : e.properties) {
      if (!prop.is_list) {
        const double v = values.read(prop.type);
        if (vertex && (prop.name == "x" || prop.name == "y" || prop.name == "z")) {
          if (!std::isfinite(v)) values.fail(fmt::format("vertex {} has a non-finite {}", i, prop.name));
          p[prop.name[0] - 'x'] = v;
        }
        continue;
      }
      const double count = values.read(prop.count_type);
      if (count < 0 || count > static_cast<double>(values.remaining())) {
        values.fail(fmt::format("list of {} items in {} {} cannot fit in the file", count, e.name, i));
      }
      const bool keep = face && is_index_list(prop);
      for (std::uint64_t k = 0; k < static_cast<std::uint64_t>(count); ++k) {
        const double index = values.read(prop.type);
        if (!keep) continue;
        if (!(index >= 0) || index != std::floor(index) ||
            index > std::numeric_limits<std::uint32_t>::max()) {
          values.fail(fmt::format("face {} has vertex index {}", i, index));
        }
        polygon.push_back(static_cast<std::uint32_t>(index));
      }
      if (keep && polygon.size() < 3)
        values.fail(fmt::format("face {} has {} corners, needs at least 3", i, polygon.size()));
    }
    if (vertex) soup.vertices.push_back(p);
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
      soup.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
  }
}

void put_le(std::string& out, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}

}  // namespace

TriangleSoup parse_ply(std::string_view bytes, const std::string& name) {
  const Header header = parse_header(bytes, name);
  Values values(bytes.substr(header.body), header.format, name, header.body_line);
  TriangleSoup soup;
  std::vector<std::uint32_t> polygon;
  bool have_vertices = false;
  for (const Element& e : header.elements) {
    const std::uint64_t need = min_bytes(e, header.format);
    if (need > 0 && e.count > values.remaining() / need + 1) {
      values.fail(
          fmt::format("{} {} elements cannot fit in the {} bytes left", e.count, e.name, values.remaining()));
    }
    if (e.name == "vertex") {
      if (have_vertices) values.fail("more than one 'vertex' element");
      have_vertices = true;
      for (const char* axis : {"x", "y", "z"}) {
        bool found = false;
        for (const Property& p : e.properties) found = found || (p.name == axis && !p.is_list);
        if (!found) values.fail(fmt::format("the vertex element has no '{}' property", axis));
      }
      if (e.count > std::numeric_limits<std::uint32_t>::max()) values.fail("too many vertices");
      soup.vertices.reserve(e.count);
    }
    read_element(e, values, soup, polygon);
  }
  for (const auto& t : soup.triangles) {
    for (const std::uint32_t i : t) {
      if (i >= soup.vertices.size()) {
        throw FileError(name, 0, 0,
                        fmt::format("{}: a face refers to vertex {} but the file has {} vertices", name, i,
                                    soup.vertices.size()));
      }
    }
  }
  return soup;
}

std::string encode_ply(const TriangleSoup& soup, const PlyOptions& options) {
  require_indices_in_range(soup);
  const bool dbl = options.double_precision;
  const char* type = dbl ? "double" : "float";
  const bool colours = !options.face_colours.empty();
  if (colours && options.face_colours.size() != soup.triangles.size()) {
    throw InputError(
        fmt::format("PLY: {} face colours for {} faces", options.face_colours.size(), soup.triangles.size()));
  }
  std::string out = fmt::format(
      "ply\nformat binary_little_endian 1.0\ncomment written by fabmesh\nelement vertex {}\n"
      "property {} x\nproperty {} y\nproperty {} z\nelement face {}\n"
      "property list uchar uint vertex_indices\n{}end_header\n",
      soup.vertices.size(), type, type, type, soup.triangles.size(),
      colours ? "property uchar red\nproperty uchar green\nproperty uchar blue\n" : "");
  out.reserve(out.size() + (dbl ? 24 : 12) * soup.vertices.size() + 13 * soup.triangles.size());
  for (std::size_t i = 0; i < soup.vertices.size(); ++i) {
    const Vec3& p = soup.vertices[i];
    for (int a = 0; a < 3; ++a) {
      const double d = p[a];
      const float f = static_cast<float>(d);
      if (!std::isfinite(dbl ? d : static_cast<double>(f))) {
        throw InputError(fmt::format("PLY: vertex {} has coordinate {}, not a finite {}", i, d, type));
      }
      if (dbl) {
        std::uint64_t bits;
        std::memcpy(&bits, &d, 8);
        put_le(out, bits, 8);
      } else {
        std::uint32_t bits;
        std::memcpy(&bits, &f, 4);
        put_le(out, bits, 4);
      }
    }
  }
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    out.push_back(3);
    for (const std::uint32_t i : soup.triangles[f]) put_le(out, i, 4);
    if (colours) {
      for (const std::uint8_t c : options.face_colours[f]) out.push_back(static_cast<char>(c));
    }
  }
  return out;
}

void write_ply(const TriangleSoup& soup, const std::string& path, const PlyOptions& options) {
  write_file_atomically(path, encode_ply(soup, options));
}

void write_ply(const Mesh& mesh, const std::string& path, const PlyOptions& options) {
  write_ply(to_soup(mesh), path, options);
}

}  // namespace fabmesh
