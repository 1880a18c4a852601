#include "io/mesh/stl.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "geometry/core/errors.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "io/file.h"
#include "io/mesh/text_scanner.h"

namespace fabmesh {
namespace {

constexpr std::size_t kHeader = 84;
constexpr std::size_t kRecord = 50;

std::uint32_t read_u32(const char* p) {
  unsigned char b[4];
  std::memcpy(b, p, 4);
  return std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 | std::uint32_t{b[2]} << 16 |
         std::uint32_t{b[3]} << 24;
}

float read_f32(const char* p) {
  const std::uint32_t bits = read_u32(p);
  float value;
  std::memcpy(&value, &bits, 4);
  return value;
}

void put_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}

// A float's IEEE bits, little-endian, at `dst`.
void store_f32_le(char* dst, float f) {
  std::uint32_t bits;
  std::memcpy(&bits, &f, 4);
  if constexpr (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__) bits = __builtin_bswap32(bits);
  std::memcpy(dst, &bits, 4);
}

void check_encodable(const TriangleSoup& soup) {
  require_indices_in_range(soup);
  if (soup.triangles.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw InputError(fmt::format("binary STL cannot hold {} triangles", soup.triangles.size()));
  }
}

// The 80-byte header text and the triangle count, at `out`.
void encode_header(const TriangleSoup& soup, char* out) {
  std::string header = "binary STL written by fabmesh";
  header.resize(80, ' ');
  std::memcpy(out, header.data(), 80);
  std::string count;
  put_u32(count, static_cast<std::uint32_t>(soup.triangles.size()));
  std::memcpy(out + 80, count.data(), 4);
}

// The records of triangles [first, first + count) at `out`. Each 50-byte record
// depends only on its triangle, so ranges are encoded in parallel with identical bytes.
void encode_records(const TriangleSoup& soup, std::size_t first, std::size_t count, char* out) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(first, first + count, 16384),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const auto& t = soup.triangles[i];
                        const Vec3& a = soup.vertices[t[0]];
                        const Vec3& b = soup.vertices[t[1]];
                        const Vec3& c = soup.vertices[t[2]];
                        const Vec3 n = (b - a).cross(c - a);
                        const double len = n.norm();
                        const Vec3 unit = len > 0.0 ? Vec3(n / len) : Vec3::Zero();
                        float values[12];
                        for (int k = 0; k < 3; ++k) {
                          values[k] = static_cast<float>(unit[k]);
                          values[3 + k] = static_cast<float>(a[k]);
                          values[6 + k] = static_cast<float>(b[k]);
                          values[9 + k] = static_cast<float>(c[k]);
                        }
                        char* record = out + kRecord * (i - first);
                        for (std::ptrdiff_t k = 0; k < 12; ++k) store_f32_le(record + 4 * k, values[k]);
                        record[48] = 0;  // the two attribute bytes (the buffer may be reused)
                        record[49] = 0;
                      }
                    });
}

TriangleSoup parse_binary(std::string_view bytes, const std::string& name) {
  if (bytes.size() < kHeader) {
    throw FileError(
        name, 0, 0,
        fmt::format("{}: binary STL truncated: {} bytes, the header alone is 84", name, bytes.size()));
  }
  const std::uint64_t n = read_u32(bytes.data() + 80);
  const std::uint64_t expected = kHeader + kRecord * n;
  if (expected != bytes.size()) {
    throw FileError(
        name, 0, 0,
        fmt::format("{}: binary STL header says {} triangles ({} bytes) but the file has {} bytes", name, n,
                    expected, bytes.size()));
  }
  if (3 * n > std::numeric_limits<std::uint32_t>::max()) {
    throw FileError(name, 0, 0, fmt::format("{}: {} triangles are more than fabmesh can index", name, n));
  }
  // Records in parallel blocks; the first triangle with a non-finite
  // coordinate (the lowest index, whichever block finds it) is the error.
  TriangleSoup soup;
  soup.vertices.resize(3 * n);
  soup.triangles.resize(n);
  std::atomic<std::uint64_t> bad{n};
  tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, n, 16384),
                    [&](const tbb::blocked_range<std::uint64_t>& r) {
                      for (std::uint64_t t = r.begin(); t != r.end(); ++t) {
                        const char* record = bytes.data() + kHeader + kRecord * t + 12;  // skip the normal
                        for (std::uint64_t c = 0; c < 3; ++c) {
                          Vec3& p = soup.vertices[3 * t + c];
                          for (std::ptrdiff_t a = 0; a < 3; ++a)
                            p[a] = read_f32(record + 12 * static_cast<std::ptrdiff_t>(c) + 4 * a);
                          if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) {
                            std::uint64_t seen = bad.load();
                            while (t < seen && !bad.compare_exchange_weak(seen, t)) {
                            }
                          }
                        }
                        const auto v = static_cast<std::uint32_t>(3 * t);
                        soup.triangles[t] = {v, v + 1, v + 2};
                      }
                    });
  if (bad.load() < n)
    throw FileError(name, 0, 0, fmt::format("{}: triangle {} has a non-finite coordinate", name, bad.load()));
  return soup;
}

TriangleSoup parse_ascii(std::string_view bytes, const std::string& name) {
  TextScanner scan(bytes, name);
  TriangleSoup soup;
  std::vector<Vec3> loop;
  bool in_facet = false;
  std::string_view line;
  while (scan.next_content_line(line, '\0')) {
    std::string_view rest = line;
    const std::string_view key = next_token(rest);
    if (key == "vertex") {
      if (!in_facet) scan.fail("'vertex' outside a facet");
      Vec3 p;
      for (int a = 0; a < 3; ++a) p[a] = scan.to_double(next_token(rest), "vertex coordinate");
      loop.push_back(p);
    } else if (key == "facet") {
      if (in_facet) scan.fail("'facet' inside another facet (missing 'endfacet')");
      in_facet = true;
      loop.clear();
    } else if (key == "endfacet") {
      if (!in_facet) scan.fail("'endfacet' without 'facet'");
      if (loop.size() < 3) scan.fail(fmt::format("facet has {} vertices, needs at least 3", loop.size()));
      if (soup.vertices.size() + loop.size() > std::numeric_limits<std::uint32_t>::max()) {
        scan.fail("more vertices than fabmesh can index");
      }
      const auto first = static_cast<std::uint32_t>(soup.vertices.size());
      soup.vertices.insert(soup.vertices.end(), loop.begin(), loop.end());
      for (std::uint32_t k = 1; k + 1 < loop.size(); ++k)
        soup.triangles.push_back({first, first + k, first + k + 1});
      in_facet = false;
    } else if (key == "outer" || key == "endloop") {
      if (!in_facet) scan.fail(fmt::format("'{}' outside a facet", key));
    } else if (key == "solid" || key == "endsolid") {
      if (in_facet) scan.fail(fmt::format("'{}' inside a facet", key));
    } else {
      scan.fail(fmt::format("unexpected '{}' in an ASCII STL", std::string(key.substr(0, 40))));
    }
  }
  if (in_facet) scan.fail("file ends inside a facet (truncated)");
  return soup;
}

}  // namespace

bool is_binary_stl(std::string_view bytes) {
  return bytes.size() >= kHeader &&
         kHeader + kRecord * std::uint64_t{read_u32(bytes.data() + 80)} == bytes.size();
}

bool looks_like_ascii_stl(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\r' || bytes[i] == '\n'))
    ++i;
  if (bytes.substr(i, 5) != "solid") return false;
  for (std::size_t k = 0; k < bytes.size() && k < 512; ++k) {
    const auto c = static_cast<unsigned char>(bytes[k]);
    if (c < 9 || (c > 13 && c < 32) || c == 127) return false;
  }
  return true;
}

namespace {

// True when the first bytes are text (printable, white space, or beyond ASCII):
// no binary STL header and float records look like that for long.
bool looks_like_text(std::string_view bytes) {
  if (bytes.empty()) return false;
  for (std::size_t k = 0; k < bytes.size() && k < 512; ++k) {
    const auto c = static_cast<unsigned char>(bytes[k]);
    if (c < 9 || (c > 13 && c < 32) || c == 127) return false;
  }
  return true;
}

// The first line of a text, cut to 40 bytes, for a message.
std::string first_line(std::string_view bytes) {
  std::string line(bytes.substr(0, std::min<std::size_t>(bytes.find_first_of("\r\n"), 40)));
  return line.size() < bytes.size() && bytes[line.size()] != '\r' && bytes[line.size()] != '\n' ? line + "..."
                                                                                                : line;
}

}  // namespace

TriangleSoup parse_stl(std::string_view bytes, const std::string& name) {
  if (is_binary_stl(bytes)) return parse_binary(bytes, name);
  if (looks_like_ascii_stl(bytes)) return parse_ascii(bytes, name);
  if (looks_like_text(bytes)) {
    throw FileError(
        name, 0, 0,
        fmt::format("{}: a text file that is no STL: an ASCII STL starts with 'solid', a binary STL "
                    "is an 84-byte header and 50 bytes a triangle; this one starts with '{}'",
                    name, first_line(bytes)));
  }
  return parse_binary(bytes, name);  // fails with the size mismatch
}

std::string encode_stl(const TriangleSoup& soup) {
  check_encodable(soup);
  // Sized once and filled record by record.
  std::string out(kHeader + kRecord * soup.triangles.size(), '\0');
  encode_header(soup, out.data());
  encode_records(soup, 0, soup.triangles.size(), out.data() + kHeader);
  return out;
}

void encode_stl_pieces(const TriangleSoup& soup, const std::function<void(std::string_view)>& sink,
                       std::size_t piece_bytes) {
  check_encodable(soup);
  const std::size_t per_piece = std::max<std::size_t>(1, piece_bytes / kRecord);
  const std::size_t n = soup.triangles.size();
  // Two buffers: the next piece is encoded while the sink takes the current one.
  std::string buffers[2];
  for (std::string& b : buffers) b.assign(kHeader + kRecord * std::min(per_piece, n), '\0');
  encode_header(soup, buffers[0].data());
  std::size_t first = 0, count = std::min(per_piece, n);  // the current piece's triangles
  encode_records(soup, first, count, buffers[0].data() + kHeader);
  std::string_view current(buffers[0].data(), kHeader + kRecord * count);  // the first starts with the header
  for (int side = 1;; side ^= 1) {
    const std::size_t next_first = first + count, next_count = std::min(per_piece, n - next_first);
    tbb::task_group encoding;
    if (next_count > 0) {
      char* const out = buffers[side].data();
      encoding.run(
          [&soup, next_first, next_count, out] { encode_records(soup, next_first, next_count, out); });
    }
    try {
      sink(current);
    } catch (...) {
      encoding.wait();
      throw;
    }
    encoding.wait();
    if (next_count == 0) break;
    current = std::string_view(buffers[side].data(), kRecord * next_count);
    first = next_first;
    count = next_count;
  }
}

void write_stl(const TriangleSoup& soup, const std::string& path) {
  PendingFile file(path);
  encode_stl_pieces(soup, [&](std::string_view piece) { file.write(piece); });
  commit_file(std::move(file));
}

void write_stl(const Mesh& mesh, const std::string& path) { write_stl(to_soup(mesh), path); }

}  // namespace fabmesh
