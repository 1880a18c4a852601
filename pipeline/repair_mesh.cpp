#include "pipeline/repair_mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <utility>

#include "geometry/core/errors.h"
#include "geometry/mesh/bounding_box.h"
#include "geometry/mesh/weld.h"
#include "geometry/repair/solids.h"
#include "io/file.h"
#include "io/mesh/obj.h"
#include "io/mesh/off.h"
#include "io/mesh/ply.h"
#include "io/mesh/read_mesh.h"
#include "io/mesh/stl.h"
#include "io/mesh/threemf.h"

namespace fabmesh {
namespace {

namespace fs = std::filesystem;

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return text;
}

/// The output format named by the path's ending. \throw OutputError for one repair does not write.
std::string output_format(const std::string& path) {
  const std::string ext = lower(fs::path(path).extension().string());
  if (ext == ".3mf") return "3MF";
  if (ext == ".stl") return "STL";
  if (ext == ".obj") return "OBJ";
  if (ext == ".ply") return "PLY";
  if (ext == ".off") return "OFF";
  throw OutputError(ext, fmt::format("{}: repair writes .3mf (the default: one object per solid, its unit "
                                     "kept), .stl, .obj, .ply or .off, not '{}'",
                                     path, ext));
}

/// A solid and its name in the output.
struct NamedSolid {
  std::string name;
  TriangleSoup soup;
};

double max_abs_coordinate(const std::vector<NamedSolid>& solids) {
  double m = 0.0;
  for (const NamedSolid& s : solids) {
    for (const Vec3& p : s.soup.vertices) m = std::max(m, p.cwiseAbs().maxCoeff());
  }
  return m;
}

TriangleSoup joined(const std::vector<NamedSolid>& solids) {
  TriangleSoup all;
  for (const NamedSolid& s : solids) {
    const auto base = static_cast<std::uint32_t>(all.vertices.size());
    all.vertices.insert(all.vertices.end(), s.soup.vertices.begin(), s.soup.vertices.end());
    for (const auto& t : s.soup.triangles) all.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  }
  return all;
}

/// The bytes of `solids` in `format`, and the most writing moves a vertex.
std::pair<std::string, double> encode(const std::vector<NamedSolid>& solids, const std::string& format,
                                      const std::string& units) {
  const double m = max_abs_coordinate(solids);
  const double float32 = std::sqrt(3.0) * std::ldexp(m, -24);
  if (format == "3MF") {
    std::vector<ThreeMfObject> objects;
    objects.reserve(solids.size());
    for (const NamedSolid& s : solids) objects.push_back(ThreeMfObject{s.name, s.soup, 0});
    ThreeMfOptions options;
    options.units = units;
    return {encode_3mf(objects, options), threemf_max_error(m)};
  }
  const TriangleSoup all = joined(solids);
  if (format == "STL") return {encode_stl(all), float32};
  if (format == "PLY") return {encode_ply(all), float32};
  if (format == "OBJ") return {encode_obj(all), 0.0};
  return {encode_off(all), 0.0};
}

/// The objects of a file read back, each welded exactly as `check` welds.
std::vector<NamedSolid> read_back(const std::string& bytes, const std::string& path) {
  MeshFile file = parse_mesh_file(bytes, path);
  std::vector<NamedSolid> objects;
  if (file.objects.empty()) {
    objects.push_back({"", weld(file.soup).soup});
  } else {
    for (MeshObject& o : file.objects) objects.push_back({o.name, weld(o.soup).soup});
  }
  return objects;
}

/// The solids of every object, named: an object's name when it gives one
/// solid, else "solid K" (K counting every solid of the file).
std::vector<NamedSolid> named_solids(const std::vector<RepairedObject>& objects) {
  std::vector<NamedSolid> solids;
  for (const RepairedObject& o : objects) {
    const std::vector<TriangleSoup> parts = solids_of(o.result.soup, o.result.after);
    for (const TriangleSoup& part : parts) {
      const std::string name =
          parts.size() == 1 && !o.name.empty() ? o.name : fmt::format("solid {}", solids.size() + 1);
      solids.push_back({name, part});
    }
  }
  return solids;
}

std::string unresolved_message(const FileRepair& r) {
  std::string text = "could not be made valid:";
  for (const RepairedObject& o : r.objects) {
    for (const std::string& line : o.result.unresolved)
      text += "\n" + (o.name.empty() ? std::string() : "object '" + o.name + "': ") + line;
  }
  return text + "\n(try --wrap: a closed surface around it, lossy by design, its distance measured)";
}

Failure failure_of(int code, const std::string& message) {
  Failure f;
  f.exit_code = code;
  f.label = code == kExitOk ? "" : code == kExitInvalid ? "invalid" : "error";
  f.message = message;
  return f;
}

/// Encodes `solids` until reading back and encoding again gives the same
/// bytes (a writer that rounds, like 3MF's decimals, settles in a few
/// rounds), so that repairing the output writes it again unchanged.
std::string settled_bytes(std::vector<NamedSolid> solids, FileRepair& r) {
  auto [bytes, error] = encode(solids, r.output_format, r.output_units);
  r.writing_error = error;
  for (int round = 0; round < 16; ++round) {
    std::vector<NamedSolid> back = read_back(bytes, r.output);
    for (std::size_t i = 0; i < back.size() && i < solids.size(); ++i) back[i].name = solids[i].name;
    auto [again, more] = encode(back, r.output_format, r.output_units);
    if (again == bytes) break;
    bytes = std::move(again);
    r.writing_error += more;
  }
  return bytes;
}

/// Validates the file as written, object by object; true when every one is valid.
bool valid_as_written(const std::string& bytes, FileRepair& r, const RepairOptions& options,
                      std::string* why) {
  for (const NamedSolid& o : read_back(bytes, r.output)) {
    const ValidationReport report = validate(o.soup, options.validation);
    if (report.valid()) continue;
    *why = "as written (coordinates rounded for the file) the result is not valid";
    for (const std::string& line : describe_defects(report)) *why += "\n" + line;
    return false;
  }
  return true;
}

/// The engine's options for a file: copies of a split vertex kept apart by
/// far more than writing moves a vertex (16 times the 3MF bound; at least
/// 1e-5 of the size, the engine's default).
RepairOptions engine_options(const MeshFile& file, const RepairFileOptions& options) {
  RepairOptions engine = options.repair;
  if (engine.separation > 0.0) return engine;
  double m = 0.0;
  for (const Vec3& p : file.soup.vertices) m = std::max(m, p.cwiseAbs().maxCoeff());
  for (const MeshObject& o : file.objects)
    for (const Vec3& p : o.soup.vertices) m = std::max(m, p.cwiseAbs().maxCoeff());
  const BoundingBox box = bounding_box(file.soup.vertices);
  const double size = file.soup.vertices.empty() ? 0.0 : box.size().norm();
  engine.separation = std::max(1e-5 * size, 16.0 * threemf_max_error(m));
  return engine;
}

void repair_objects(MeshFile& file, const RepairFileOptions& options, FileRepair& r) {
  const RepairOptions engine = engine_options(file, options);
  if (file.objects.empty()) {
    r.objects.push_back({"", repair(file.soup, engine)});
    return;
  }
  for (MeshObject& o : file.objects) r.objects.push_back({o.name, repair(o.soup, engine)});
}

void require_not_input(const std::string& input, const std::string& output) {
  std::error_code ec;
  if (output == input || fs::equivalent(input, output, ec))
    throw FileError(output, 0, 0,
                    fmt::format("{}: repair would write over its input: give -o another file", output));
}

void finish(const std::string& path, const RepairFileOptions& options, FileRepair& r, StageTimer& timer) {
  const std::vector<NamedSolid> solids = named_solids(r.objects);
  r.solids = solids.size();
  const std::string bytes = settled_bytes(solids, r);
  std::string why;
  r.valid_as_written = valid_as_written(bytes, r, options.repair, &why);
  timer.lap("write_check");
  double distance = 0.0;
  for (const RepairedObject& o : r.objects) distance = std::max(distance, o.result.measure.distance);
  r.distance = distance + r.writing_error;
  if (!r.valid_as_written) {
    r.failure = failure_of(kExitInvalid, why);
    return;
  }
  const double limit = options.repair.max_deviation;
  if (limit > 0.0 && r.distance > limit) {
    r.failure = failure_of(kExitInvalid,
                           fmt::format("the file written would be up to {:.4g} from the input "
                                       "(repair {:.4g}, writing {:.3g}), more than --max-deviation {:.4g}",
                                       r.distance, distance, r.writing_error, limit));
    return;
  }
  if (options.write) {
    require_not_input(path, r.output);
    const fs::path folder = fs::path(r.output).parent_path();
    if (!folder.empty()) fs::create_directories(folder);
    write_file_atomically(r.output, bytes);
    r.written = true;
    timer.lap("write");
  }
  const bool changed = std::any_of(r.objects.begin(), r.objects.end(),
                                   [](const RepairedObject& o) { return o.result.changed; });
  r.failure = failure_of(kExitOk, changed ? "repaired" : "already valid");
}

}  // namespace

std::string repair_output_path(const std::string& input, const RepairFileOptions& options) {
  const fs::path in(input);
  if (options.output.empty()) return (in.parent_path() / (in.stem().string() + ".repaired.3mf")).string();
  if (options.output_is_folder || options.output.back() == '/')
    return (fs::path(options.output) / (in.stem().string() + ".3mf")).string();
  return options.output;
}

FileRepair repair_file(const std::string& path, const RepairFileOptions& options) {
  FileRepair r;
  r.file = path;
  try {
    StageTimer timer(r.timings_ms);
    r.output = repair_output_path(path, options);
    r.output_format = output_format(r.output);
    MeshFile file = read_mesh_file(path);
    timer.lap("read");
    r.readable = true;
    r.format = to_string(file.format);
    r.units = file.units;
    r.notes = std::move(file.notes);
    r.output_units = r.units.empty() ? "mm" : r.units;
    if (r.units.empty() && r.output_format == "3MF")
      r.notes.push_back("the input states no unit: written as millimetres, the numbers unchanged");
    repair_objects(file, options, r);
    timer.lap("repair");
    const bool mended = std::all_of(r.objects.begin(), r.objects.end(),
                                    [](const RepairedObject& o) { return o.result.ok(); });
    if (!mended) {
      r.failure = failure_of(kExitInvalid, unresolved_message(r));
      return r;
    }
    finish(path, options, r, timer);
  } catch (...) {
    r.failure = describe_failure(std::current_exception(), path);
  }
  return r;
}

RepairResult repair_soup(const TriangleSoup& soup, const RepairOptions& options) {
  return repair(soup, options);
}

}  // namespace fabmesh
