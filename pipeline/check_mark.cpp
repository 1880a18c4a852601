#include "pipeline/check_mark.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "geometry/core/errors.h"
#include "geometry/core/units.h"
#include "io/file.h"
#include "io/mesh/gltf.h"
#include "io/mesh/ply.h"

namespace fabmesh {
namespace {

/// The colour of each defect kind that lists faces, in Defect order (the
/// first kind listing a face colours it), and of faces without a defect.
std::vector<MarkColour> palette() {
  const auto colour = [](Defect kind, const char* words, const char* name, std::array<std::uint8_t, 3> rgb) {
    return MarkColour{to_key(kind), words, name, rgb, 0};
  };
  return {
      colour(Defect::BoundaryEdge, "faces on a boundary edge", "orange", {255, 140, 0}),
      colour(Defect::NonManifoldEdge, "faces on a non-manifold edge", "magenta", {230, 0, 230}),
      colour(Defect::NonManifoldVertex, "faces around a non-manifold vertex", "purple", {130, 40, 200}),
      colour(Defect::InconsistentOrientation, "faces on an inconsistently oriented edge", "yellow",
             {240, 220, 0}),
      colour(Defect::InvertedComponent, "faces of an inverted component", "blue", {30, 90, 255}),
      colour(Defect::NestedSameOrientation, "faces of a wrongly nested component", "cyan", {0, 200, 220}),
      colour(Defect::DegenerateFace, "degenerate faces", "black", {20, 20, 20}),
      colour(Defect::DuplicateFace, "duplicate faces", "green", {0, 170, 60}),
      colour(Defect::SelfIntersection, "self-intersecting faces", "red", {230, 0, 0}),
      MarkColour{"none", "faces without a defect", "light grey", {200, 200, 200}, 0},
  };
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

/// Metres per unit of the file's `units`; a unit fabmesh does not know (or none) is taken as mm.
double metres_per(const std::string& units) {
  for (const LengthUnit& u : kLengthUnits) {
    if (u.name == units) return u.metres;
  }
  return 1e-3;
}

}  // namespace

MarkedMesh marked_mesh(const FileCheck& check) {
  MarkedMesh marked;
  marked.colours = palette();
  marked.units = check.units;
  const auto none = static_cast<std::uint32_t>(marked.colours.size() - 1);
  for (const ObjectCheck& object : check.objects) {
    const auto first_vertex = static_cast<std::uint32_t>(marked.soup.vertices.size());
    const std::size_t first_face = marked.soup.triangles.size();
    marked.soup.vertices.insert(marked.soup.vertices.end(), object.welded.vertices.begin(),
                                object.welded.vertices.end());
    for (const auto& t : object.welded.triangles)
      marked.soup.triangles.push_back({t[0] + first_vertex, t[1] + first_vertex, t[2] + first_vertex});
    marked.face_colour.resize(marked.soup.triangles.size(), none);
    for (std::uint32_t c = 0; c < none; ++c) {
      for (const DefectReport& d : object.report.defects) {
        if (marked.colours[c].key != to_key(d.kind)) continue;
        for (const DefectLocation& at : d.locations) {
          for (const std::uint32_t f : at.faces) {
            std::uint32_t& colour = marked.face_colour[first_face + f];
            if (colour == none) colour = c;
          }
        }
      }
    }
  }
  for (const std::uint32_t c : marked.face_colour) ++marked.colours[c].faces;
  if (check.format == "GLB" || check.format == "glTF") {  // read as glTF stores it: Y up, metres
    marked.soup = from_gltf_frame(marked.soup, 1.0);
    marked.units = "m";
  }
  return marked;
}

void write_marked(const MarkedMesh& marked, const std::string& path) {
  const std::string ext = lower_extension(path);
  std::string bytes;
  if (ext == ".glb") {
    GlbOptions options;
    options.name = "marked";
    options.scale_to_metres = metres_per(marked.units);
    for (const MarkColour& c : marked.colours) {
      options.materials.push_back({c.key, {c.rgb[0] / 255.0, c.rgb[1] / 255.0, c.rgb[2] / 255.0, 1.0}});
    }
    options.face_materials = marked.face_colour;
    bytes = encode_glb(marked.soup, options);
  } else if (ext == ".ply") {
    PlyOptions options;
    for (const std::uint32_t c : marked.face_colour) options.face_colours.push_back(marked.colours[c].rgb);
    bytes = encode_ply(marked.soup, options);
  } else {
    throw InputError(fmt::format("--mark {}: the marked mesh is written as .glb or .ply", path));
  }
  write_file_atomically(path, bytes);
}

std::vector<std::string> legend_lines(const MarkedMesh& marked) {
  std::vector<std::string> lines;
  for (const MarkColour& c : marked.colours) {
    if (c.faces > 0) lines.push_back(fmt::format("{}: {} {}", c.name, c.faces, c.words));
  }
  return lines;
}

}  // namespace fabmesh
