#include "io/mesh/obj.h"

#include <fmt/format.h>

#include <cstdint>
#include <limits>

#include "geometry/core/errors.h"
#include "io/file.h"
#include "io/mesh/text_scanner.h"

namespace fabmesh {
namespace {

/// The vertex part of a face corner ("7", "7/2", "7//3", "7/2/3").
std::string_view vertex_part(std::string_view corner) {
  const std::size_t slash = corner.find('/');
  return slash == std::string_view::npos ? corner : corner.substr(0, slash);
}

}  // namespace

TriangleSoup parse_obj(std::string_view bytes, const std::string& name) {
  TextScanner scan(bytes, name);
  TriangleSoup soup;
  std::vector<std::uint32_t> polygon;
  std::int64_t max_forward = 0;  // largest 1-based index beyond the vertices read so far
  int max_forward_line = 0;
  std::string_view line;
  while (scan.next_content_line(line, '#')) {
    std::string_view rest = line;
    const std::string_view key = next_token(rest);
    if (key == "v") {
      Vec3 p;
      for (int a = 0; a < 3; ++a) p[a] = scan.to_double(next_token(rest), "vertex coordinate");
      if (soup.vertices.size() >= std::numeric_limits<std::uint32_t>::max()) scan.fail("too many vertices");
      soup.vertices.push_back(p);
    } else if (key == "f") {
      polygon.clear();
      const auto nv = static_cast<std::int64_t>(soup.vertices.size());
      for (std::string_view corner = next_token(rest); !corner.empty(); corner = next_token(rest)) {
        std::int64_t i = scan.to_int(vertex_part(corner), "face vertex index");
        if (i == 0) scan.fail("face vertex index 0 (OBJ indices start at 1)");
        if (i < 0) {
          if (-i > nv) scan.fail(fmt::format("relative index {} but only {} vertices precede it", i, nv));
          i = nv + i;
        } else {
          if (i > std::numeric_limits<std::uint32_t>::max())
            scan.fail(fmt::format("face vertex index {} too large", i));
          if (i > nv && i > max_forward) {
            max_forward = i;
            max_forward_line = scan.line();
          }
          i -= 1;
        }
        polygon.push_back(static_cast<std::uint32_t>(i));
      }
      if (polygon.size() < 3) scan.fail(fmt::format("face has {} corners, needs at least 3", polygon.size()));
      for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
        soup.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
      }
    }
    // vt, vn, o, g, s, usemtl, mtllib, l, p ...: not geometry of the surface.
  }
  if (max_forward > static_cast<std::int64_t>(soup.vertices.size())) {
    throw FileError(name, max_forward_line, 0,
                    fmt::format("{}:{}: face refers to vertex {} but the file has {} vertices", name,
                                max_forward_line, max_forward, soup.vertices.size()));
  }
  return soup;
}

std::string encode_obj(const TriangleSoup& soup) {
  require_indices_in_range(soup);
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "# written by fabmesh\n");
  for (const Vec3& p : soup.vertices)
    fmt::format_to(std::back_inserter(out), "v {} {} {}\n", p.x(), p.y(), p.z());
  for (const auto& t : soup.triangles) {
    fmt::format_to(std::back_inserter(out), "f {} {} {}\n", t[0] + 1ull, t[1] + 1ull, t[2] + 1ull);
  }
  return fmt::to_string(out);
}

void write_obj(const TriangleSoup& soup, const std::string& path) {
  write_file_atomically(path, encode_obj(soup));
}

void write_obj(const Mesh& mesh, const std::string& path) { write_obj(to_soup(mesh), path); }

}  // namespace fabmesh
