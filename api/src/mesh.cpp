#include "fabmesh/mesh.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "api/src/detail.h"
#include "api/src/soup.h"
#include "api/src/validation_report.h"
#include "geometry/core/units.h"
#include "io/file.h"
#include "io/mesh/draco.h"
#include "io/mesh/gltf.h"
#include "io/mesh/obj.h"
#include "io/mesh/off.h"
#include "io/mesh/ply.h"
#include "io/mesh/read_mesh.h"
#include "io/mesh/stl.h"
#include "io/mesh/threemf.h"
#include "pipeline/check_mesh.h"

namespace fabmesh::api {
namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// The bytes of `soup` in the format `ext` names; empty for an unknown one.
std::string encoded(const std::string& ext, const fabmesh::TriangleSoup& soup, const std::string& units,
                    const WriteOptions& options, const std::string& name) {
  if (ext == ".stl") return fabmesh::encode_stl(soup);
  if (ext == ".obj") return fabmesh::encode_obj(soup);
  if (ext == ".ply") return fabmesh::encode_ply(soup);
  if (ext == ".off") return fabmesh::encode_off(soup);
  if (ext == ".3mf") {
    fabmesh::ThreeMfOptions o;
    o.units = units;
    o.title = name;
    return fabmesh::encode_3mf({fabmesh::ThreeMfObject{name, soup}}, o);
  }
  if (ext == ".glb") {
    fabmesh::GlbOptions o;
    o.name = name;
    o.scale_to_metres = fabmesh::metres_per_unit(units);
    return fabmesh::encode_glb(soup, o);
  }
  if (ext == ".drc") {
    fabmesh::DracoOptions o;
    o.tolerance = options.draco_tolerance;
    return fabmesh::encode_draco(soup, o);
  }
  return {};
}

fabmesh::CheckOptions check_options(const ValidationOptions& options) {
  if (!(options.weld_tolerance >= 0.0) || !std::isfinite(options.weld_tolerance))
    detail::bad_argument("weld_tolerance", "must be >= 0");
  if (!(options.max_seconds >= 0.0)) detail::bad_argument("max_seconds", "must be >= 0 (0: no limit)");
  return fabmesh::CheckOptions{options.weld_tolerance, options.max_seconds};
}

}  // namespace

const char* to_string(Unit unit) {
  switch (unit) {
    case Unit::mm:
      return "mm";
    case Unit::cm:
      return "cm";
    case Unit::m:
      return "m";
    case Unit::inch:
      return "in";
  }
  return "mm";
}

Unit unit_named(std::string_view name) {
  for (const Unit u : {Unit::mm, Unit::cm, Unit::m, Unit::inch}) {
    if (name == to_string(u)) return u;
  }
  detail::bad_argument("units", "'" + std::string(name) + "' is not one of mm, cm, m, in");
}

const char* to_string(DefectKind kind) { return fabmesh::to_key(detail::internal_kind(kind)); }

ValidationReport validate(const MeshView& mesh, const ValidationOptions& options) {
  return detail::translated([&] {
    const fabmesh::CheckOptions o = check_options(options);
    const fabmesh::FileCheck check = fabmesh::check_soup(detail::internal_soup(mesh), o);
    return detail::public_report(check.objects.front().report, fabmesh::check_json(check));
  });
}

ValidationReport validate(const Mesh& mesh, const ValidationOptions& options) {
  return validate(detail::view_of(mesh), options);
}

ValidationReport check_file(const std::filesystem::path& path, const ValidationOptions& options) {
  return detail::translated([&] {
    const fabmesh::FileCheck check = fabmesh::check_file(path.string(), check_options(options));
    return detail::file_report(check, fabmesh::check_json(check));
  });
}

Mesh read_mesh(const std::filesystem::path& path) {
  return detail::translated([&] {
    fabmesh::MeshFile file = fabmesh::read_mesh_file(path.string());
    Mesh mesh = detail::public_mesh(file.soup);
    if (!file.units.empty()) mesh.units = unit_named(file.units);
    return mesh;
  });
}

void write_mesh(const std::filesystem::path& path, const Mesh& mesh, const WriteOptions& options) {
  detail::translated([&] {
    const std::string units = to_string(options.units.value_or(mesh.units.value_or(Unit::mm)));
    const fabmesh::TriangleSoup soup = detail::internal_soup(detail::view_of(mesh));
    for (std::size_t i = 0; i < soup.vertices.size(); ++i) {
      if (!soup.vertices[i].allFinite())
        detail::bad_argument("vertices",
                             "vertex " + std::to_string(i) + " has a coordinate that is not finite");
    }
    const std::string ext = lower_extension(path);
    std::string bytes = encoded(ext, soup, units, options, path.stem().string());
    if (bytes.empty()) {
      detail::bad_argument(
          "path", "'" + path.string() + "' ends in neither .stl, .obj, .ply, .off, .3mf, .glb nor .drc");
    }
    fabmesh::write_files_atomically({fabmesh::FileWrite{path.string(), std::move(bytes)}});
  });
}

}  // namespace fabmesh::api
