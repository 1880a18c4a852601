#include "io/mesh/off.h"

#include <fmt/format.h>

#include <cstdint>
#include <limits>

#include "geometry/core/errors.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "io/file.h"
#include "io/mesh/text_scanner.h"

namespace fabmesh {

TriangleSoup parse_off(std::string_view bytes, const std::string& name) {
  TextScanner scan(bytes, name);
  std::string_view line;
  if (!scan.next_content_line(line, '#')) scan.fail("empty file, expected 'OFF'");
  std::string_view rest = line;
  if (next_token(rest) != "OFF") scan.fail("not an OFF file (must start with 'OFF')");
  std::string_view counts = rest;
  if (next_token(counts).empty()) {  // counts on the next line
    if (!scan.next_content_line(rest, '#')) scan.fail("missing vertex and face counts");
  }
  const std::int64_t nv = scan.to_int(next_token(rest), "vertex count");
  const std::int64_t nf = scan.to_int(next_token(rest), "face count");
  // Each vertex line needs at least 6 bytes ("0 0 0\n"), each face line 8.
  const auto room = static_cast<std::int64_t>(scan.remaining());
  if (nv < 0 || nv > room / 6 + 1 || nv > std::numeric_limits<std::uint32_t>::max()) {
    scan.fail(fmt::format("vertex count {} is impossible for a file of {} bytes", nv, bytes.size()));
  }
  if (nf < 0 || nf > room / 8 + 1) {
    scan.fail(fmt::format("face count {} is impossible for a file of {} bytes", nf, bytes.size()));
  }
  TriangleSoup soup;
  soup.vertices.reserve(static_cast<std::size_t>(nv));
  soup.triangles.reserve(static_cast<std::size_t>(nf));
  for (std::int64_t i = 0; i < nv; ++i) {
    if (!scan.next_content_line(line, '#'))
      scan.fail(fmt::format("file ends after {} of {} vertices", i, nv));
    Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = scan.to_double(next_token(line), "vertex coordinate");
    soup.vertices.push_back(p);
  }
  std::vector<std::uint32_t> polygon;
  for (std::int64_t f = 0; f < nf; ++f) {
    if (!scan.next_content_line(line, '#')) scan.fail(fmt::format("file ends after {} of {} faces", f, nf));
    const std::int64_t n = scan.to_int(next_token(line), "face corner count");
    if (n < 3 || n > static_cast<std::int64_t>(line.size()))
      scan.fail(fmt::format("face with {} corners", n));
    polygon.clear();
    for (std::int64_t k = 0; k < n; ++k) {
      const std::string_view token = next_token(line);
      if (token.empty()) scan.fail(fmt::format("face lists {} of its {} corners", k, n));
      const std::int64_t i = scan.to_int(token, "face vertex index");
      if (i < 0 || i >= nv) scan.fail(fmt::format("face vertex index {} outside [0, {})", i, nv));
      polygon.push_back(static_cast<std::uint32_t>(i));
    }
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
      soup.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
  }
  return soup;
}

std::string encode_off(const TriangleSoup& soup) {
  require_indices_in_range(soup);
  fmt::memory_buffer out;
  auto it = std::back_inserter(out);
  fmt::format_to(it, "OFF\n{} {} 0\n", soup.vertices.size(), soup.triangles.size());
  for (const Vec3& p : soup.vertices) fmt::format_to(it, "{} {} {}\n", p.x(), p.y(), p.z());
  for (const auto& t : soup.triangles) fmt::format_to(it, "3 {} {} {}\n", t[0], t[1], t[2]);
  return fmt::to_string(out);
}

void write_off(const TriangleSoup& soup, const std::string& path) {
  write_file_atomically(path, encode_off(soup));
}

void write_off(const Mesh& mesh, const std::string& path) { write_off(to_soup(mesh), path); }

}  // namespace fabmesh
