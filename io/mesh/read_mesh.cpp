#include "io/mesh/read_mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "geometry/core/errors.h"
#include "io/file.h"
#include "io/mesh/draco.h"
#include "io/mesh/gltf.h"
#include "io/mesh/obj.h"
#include "io/mesh/off.h"
#include "io/mesh/ply.h"
#include "io/mesh/stl.h"
#include "io/mesh/text_scanner.h"
#include "io/mesh/threemf.h"

namespace fabmesh {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool starts_with_line(std::string_view bytes, std::string_view word) {
  return bytes.substr(0, word.size()) == word &&
         (bytes.size() == word.size() || bytes[word.size()] == '\n' || bytes[word.size()] == '\r' ||
          bytes[word.size()] == ' ' || bytes[word.size()] == '\t');
}

/// The first meaningful line of a text file starts with an OBJ record.
bool looks_like_obj(std::string_view bytes) {
  TextScanner scan(bytes.substr(0, 4096), "");
  std::string_view line;
  if (!scan.next_content_line(line, '#')) return false;
  const std::string_view key = next_token(line);
  for (const char* k : {"v", "vt", "vn", "vp", "f", "o", "g", "s", "usemtl", "mtllib", "l", "p"}) {
    if (key == k) return true;
  }
  return false;
}

std::string_view skip_comments_and_space(std::string_view bytes) {
  while (true) {
    std::size_t i = 0;
    while (i < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
    bytes.remove_prefix(i);
    if (bytes.empty() || bytes.front() != '#') return bytes;
    const std::size_t eol = bytes.find('\n');
    bytes.remove_prefix(eol == std::string_view::npos ? bytes.size() : eol + 1);
  }
}

/// A JSON object (first non-space character '{') with an "asset" member.
bool looks_like_gltf_json(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
  return i < bytes.size() && bytes[i] == '{' && bytes.find("\"asset\"") != std::string_view::npos;
}

}  // namespace

MeshFormat detect_format(std::string_view bytes, const std::string& path) {
  if (bytes.substr(0, 5) == "DRACO") return MeshFormat::Draco;
  if (starts_with_line(bytes, "ply")) return MeshFormat::Ply;
  if (starts_with_line(skip_comments_and_space(bytes), "OFF")) return MeshFormat::Off;
  if (bytes.substr(0, 4) == "glTF") return MeshFormat::Glb;
  if (looks_like_3mf(bytes)) return MeshFormat::ThreeMf;
  if (looks_like_gltf_json(bytes)) return MeshFormat::Gltf;
  if (is_binary_stl(bytes) || looks_like_ascii_stl(bytes)) return MeshFormat::Stl;
  if (looks_like_obj(bytes)) return MeshFormat::Obj;
  const std::string ext = lower_extension(path);
  if (ext == ".stl") return MeshFormat::Stl;  // a lying or truncated binary STL: parse_stl says why
  if (ext == ".obj") return MeshFormat::Obj;
  throw FileError(
      path, 0, 0,
      fmt::format("{}: not a mesh file fabmesh can read (STL, OBJ, PLY, OFF, Draco, 3MF, GLB or glTF){}",
                  path, bytes.empty() ? " (the file is empty)" : ""));
}

TriangleSoup parse_mesh(std::string_view bytes, const std::string& path) {
  switch (detect_format(bytes, path)) {
    case MeshFormat::Stl:
      return parse_stl(bytes, path);
    case MeshFormat::Obj:
      return parse_obj(bytes, path);
    case MeshFormat::Ply:
      return parse_ply(bytes, path);
    case MeshFormat::Off:
      return parse_off(bytes, path);
    case MeshFormat::Draco:
      return parse_draco(bytes, path);
    case MeshFormat::ThreeMf:
      return merged_soup(parse_3mf(bytes, path));
    case MeshFormat::Glb:
    case MeshFormat::Gltf:
      return parse_gltf(bytes, path).soup;
  }
  throw FileError(path, 0, 0, fmt::format("{}: unknown mesh format", path));
}

TriangleSoup read_mesh(const std::string& path) {
  const std::string bytes = read_file(path);
  return parse_mesh(bytes, path);
}

}  // namespace fabmesh
