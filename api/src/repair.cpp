#include "fabmesh/repair.h"

#include <cmath>
#include <exception>

#include "api/src/detail.h"
#include "api/src/soup.h"
#include "api/src/validation_report.h"
#include "geometry/repair/repair.h"
#include "pipeline/repair_mesh.h"
#include "pipeline/repair_mesh_report.h"
#include "pipeline/report.h"

namespace fabmesh::api {
namespace {

fabmesh::RepairOptions engine_options(const RepairOptions& options) {
  if (!(options.max_deviation >= 0.0) || !std::isfinite(options.max_deviation))
    detail::bad_argument("max_deviation", "must be >= 0 (0: no limit)");
  if (!(options.max_seconds >= 0.0)) detail::bad_argument("max_seconds", "must be >= 0 (0: no limit)");
  if (std::isnan(options.weld_distance) || std::isinf(options.weld_distance))
    detail::bad_argument("weld_distance", "must be a number (< 0: chosen from the data)");
  fabmesh::RepairOptions o;
  o.max_deviation = options.max_deviation;
  o.wrap = options.wrap;
  o.weld_distance = options.weld_distance < 0.0 ? -1.0 : options.weld_distance;
  o.fill_holes = options.fill_holes;
  o.validation.max_self_intersection_seconds = options.max_seconds;
  return o;
}

Point point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

std::optional<std::size_t> index(std::uint32_t i) {
  return i == fabmesh::kNoIndex ? std::nullopt : std::optional<std::size_t>(i);
}

RepairStep public_step(const fabmesh::RepairAction& a) {
  RepairStep step{fabmesh::to_key(a.step), a.count, a.detail, {}};
  for (const fabmesh::RepairPlace& p : a.places)
    step.places.push_back({index(p.face), index(p.vertex), point(p.point), p.detail});
  return step;
}

RepairReport public_report(const fabmesh::RepairResult& r, const std::string& units) {
  RepairReport report;
  report.valid = r.ok();
  report.changed = r.changed;
  report.mesh = detail::public_mesh(r.soup);
  if (!units.empty()) report.mesh.units = unit_named(units);
  for (const fabmesh::RepairAction& a : r.actions) report.steps.push_back(public_step(a));
  for (const fabmesh::DroppedComponent& d : r.dropped)
    report.dropped.push_back({d.faces, index(d.first_face), d.area, point(d.lo), point(d.hi), d.why});
  report.weld_distance = r.weld.distance;
  report.distance = r.measure.distance;
  report.components_before = r.components_before;
  report.components_after = r.after.components;
  report.volume_before = r.before.volume;
  report.volume_after = r.after.volume;
  report.area_before = r.before.area;
  report.area_after = r.after.area;
  report.unresolved = r.unresolved;
  report.after = detail::public_report(r.after, fabmesh::validation_json(r.after));
  report.set_json(fabmesh::repair_result_json(r).dump());
  return report;
}

}  // namespace

RepairReport repair(const MeshView& mesh, const RepairOptions& options) {
  return detail::translated([&] {
    const fabmesh::RepairOptions o = engine_options(options);
    return public_report(fabmesh::repair_soup(detail::internal_soup(mesh), o), "");
  });
}

RepairReport repair(const Mesh& mesh, const RepairOptions& options) {
  RepairReport report = repair(detail::view_of(mesh), options);
  report.mesh.units = mesh.units;
  return report;
}

std::string repair_file(const std::filesystem::path& input, const std::filesystem::path& output,
                        const RepairOptions& options) {
  return detail::translated([&] {
    fabmesh::RepairFileOptions o;
    o.repair = engine_options(options);
    o.output = output.string();
    const fabmesh::FileRepair r = fabmesh::repair_file(input.string(), o);
    if (!r.readable || r.exit_code() == kExitBadInput || r.exit_code() == kExitEnvironment) {
      // The command line's failure as the library's exception of its kind.
      if (r.exit_code() == kExitEnvironment) throw fabmesh::MachineError(r.output, 0, r.failure.message);
      throw fabmesh::InputError(r.failure.message);
    }
    return fabmesh::repair_json(r).dump();
  });
}

}  // namespace fabmesh::api
