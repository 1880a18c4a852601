#include "io/mesh/read_mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <unordered_map>
#include <utility>

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

/// The triangles `faces` of `soup` with only the vertices they use, in
/// the order of their first use.
TriangleSoup sub_soup(const TriangleSoup& soup, const std::vector<std::uint32_t>& faces) {
  TriangleSoup out;
  std::unordered_map<std::uint32_t, std::uint32_t> index;
  out.triangles.reserve(faces.size());
  for (const std::uint32_t f : faces) {
    std::array<std::uint32_t, 3> t{};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = soup.triangles[f][k];
      const auto [it, added] = index.emplace(v, static_cast<std::uint32_t>(out.vertices.size()));
      if (added) out.vertices.push_back(soup.vertices[v]);
      t[k] = it->second;
    }
    out.triangles.push_back(t);
  }
  return out;
}

/// MeshFile::objects of an OBJ file with several objects.
std::vector<MeshObject> obj_objects(const ObjContent& content) {
  if (content.object_names.size() < 2) return {};
  std::vector<std::vector<std::uint32_t>> faces(content.object_names.size());
  for (std::uint32_t f = 0; f < content.face_object.size(); ++f) faces[content.face_object[f]].push_back(f);
  std::vector<MeshObject> objects;
  for (std::size_t i = 0; i < faces.size(); ++i)
    objects.push_back({content.object_names[i], sub_soup(content.soup, faces[i])});
  return objects;
}

/// MeshFile::objects of a glTF scene with several mesh instances.
std::vector<MeshObject> gltf_objects(const GltfContent& content) {
  const std::vector<GltfInstance>& instances = content.instances;
  if (instances.size() < 2) return {};
  std::vector<MeshObject> objects;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const bool last = i + 1 == instances.size();
    const std::size_t v0 = instances[i].first_vertex;
    const std::size_t v1 = last ? content.soup.vertices.size() : instances[i + 1].first_vertex;
    const std::size_t t1 = last ? content.soup.triangles.size() : instances[i + 1].first_triangle;
    MeshObject object{instances[i].name, {}};
    object.soup.vertices.assign(content.soup.vertices.begin() + static_cast<std::ptrdiff_t>(v0),
                                content.soup.vertices.begin() + static_cast<std::ptrdiff_t>(v1));
    const auto base = static_cast<std::uint32_t>(v0);
    for (std::size_t t = instances[i].first_triangle; t < t1; ++t) {
      const auto& c = content.soup.triangles[t];
      object.soup.triangles.push_back({c[0] - base, c[1] - base, c[2] - base});
    }
    objects.push_back(std::move(object));
  }
  return objects;
}

/// MeshFile::objects of a 3MF build with several items that have triangles
/// (moved out of `content`; items without any are left out).
std::vector<MeshObject> threemf_objects(ThreeMfContent& content) {
  const auto bodies = std::count_if(content.objects.begin(), content.objects.end(),
                                    [](const ThreeMfObject& o) { return !o.soup.triangles.empty(); });
  if (bodies < 2) return {};
  std::vector<MeshObject> objects;
  for (ThreeMfObject& object : content.objects) {
    if (object.soup.triangles.empty()) continue;
    std::string name =
        object.name.empty() ? fmt::format("object {}", object.resource_id) : std::move(object.name);
    objects.push_back({std::move(name), std::move(object.soup)});
  }
  return objects;
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
    case MeshFormat::Obj: {
      ObjContent content = parse_obj_objects(bytes, path);
      out.objects = obj_objects(content);
      out.soup = std::move(content.soup);
      break;
    }
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
      out.objects = threemf_objects(content);
      break;
    }
    case MeshFormat::Glb:
    case MeshFormat::Gltf: {
      GltfContent content = parse_gltf(bytes, path);
      out.objects = gltf_objects(content);
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

MeshFile read_mesh_stream(std::istream& in, const std::string& name) {
  std::string bytes;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    bytes.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (bytes.size() > kMaxMeshFileBytes) {
      throw FileError(name, 0, 0,
                      fmt::format("{}: more than {} bytes: larger than a mesh file fabmesh reads", name,
                                  kMaxMeshFileBytes));
    }
  }
  if (in.bad()) throw FileError(name, 0, 0, fmt::format("{}: cannot be read", name));
  return parse_mesh_file(bytes, name);
}

TriangleSoup read_mesh(const std::string& path) { return read_mesh_file(path).soup; }

}  // namespace fabmesh
