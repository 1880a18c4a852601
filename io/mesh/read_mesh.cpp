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

const char* to_string(MeshFormat format) {
  switch (format) {
    case MeshFormat::Stl:
      return "STL";
    case MeshFormat::Obj:
      return "OBJ";
    case MeshFormat::Ply:
      return "PLY";
    case MeshFormat::Off:
      return "OFF";
    case MeshFormat::Draco:
      return "Draco";
    case MeshFormat::ThreeMf:
      return "3MF";
    case MeshFormat::Glb:
      return "GLB";
    case MeshFormat::Gltf:
      return "glTF";
  }
  return "unknown";
}

MeshFile parse_mesh_file(std::string_view bytes, const std::string& path) {
  MeshFile out;
  out.format = detect_format(bytes, path);
  switch (out.format) {
    case MeshFormat::Stl:
      out.soup = parse_stl(bytes, path);
      break;
    case MeshFormat::Obj:
      out.soup = parse_obj(bytes, path);
      break;
    case MeshFormat::Ply:
      out.soup = parse_ply(bytes, path);
      break;
    case MeshFormat::Off:
      out.soup = parse_off(bytes, path);
      break;
    case MeshFormat::Draco:
      out.soup = parse_draco(bytes, path);
      break;
    case MeshFormat::ThreeMf: {
      ThreeMfContent content = parse_3mf(bytes, path);
      out.soup = merged_soup(content);
      out.units = content.unit;
      out.notes = content.warnings;
      out.notes.push_back(fmt::format("{} object(s)", content.objects.size()));
      break;
    }
    case MeshFormat::Glb:
    case MeshFormat::Gltf: {
      GltfContent content = parse_gltf(bytes, path);
      out.soup = std::move(content.soup);
      out.units = "m";
      out.notes.push_back(
          fmt::format("{} triangle primitive(s), {} Draco-compressed, {} point/line skipped; "
                      "coordinates as stored (Y up)",
                      content.primitives, content.draco_primitives, content.skipped_primitives));
      break;
    }
  }
  return out;
}

TriangleSoup parse_mesh(std::string_view bytes, const std::string& path) {
  return parse_mesh_file(bytes, path).soup;
}

MeshFile read_mesh_file(const std::string& path) {
  return parse_mesh_file(read_file(path, kMaxMeshFileBytes, "mesh file"), path);
}

TriangleSoup read_mesh(const std::string& path) { return read_mesh_file(path).soup; }

}  // namespace fabmesh
