// fabmesh sample DESIGN [--csv] [--tolerance T]: the sampled curve points.

#include <fmt/format.h>

#include <memory>

#include "geometry/core/error_checks.h"
#include "geometry/fairing/build_curve.h"
#include "geometry/sampling/sample_curve.h"
#include "pipeline/cli/commands.h"
#include "pipeline/design_curves.h"
#include "pipeline/load_design.h"
#include "pipeline/report.h"

namespace fabmesh::cli {
namespace {

struct SampleArgs {
  std::string design;
  std::vector<std::string> defines;
  bool csv = false;
  double tolerance = 0.0;  // used when tolerance_given, else the design's
  bool tolerance_given = false;
};

int run_sample(const SampleArgs& args, Streams io) {
  // Checked here, not by CLI11: its PositiveNumber lets NaN through and calls
  // 4.9e-324 "not in range 0.000000 to 1797693134862315708...".
  if (args.tolerance_given) require_positive("--tolerance", args.tolerance);
  const Design design = load_design(args.design, parse_overrides(args.defines));
  SampleOptions options;
  options.tolerance = args.tolerance_given ? args.tolerance : design.common.tolerance;
  if (design_curves(design).empty()) {
    io.out << fmt::format(
        "# {}: a {} design has no curves to sample (its patches are tessellated by `fabmesh run`)\n",
        design.common.name, kind_name(design));
    return 0;
  }
  if (args.csv) io.out << "curve,x,y\n";
  // Errors at a curve's key (or the tolerance) are reported where the design gives it.
  in_design(design, [&] {
    for (const NamedCurve& nc : design_curves(design)) {
      const BuiltCurve built = build_curve(nc.spec);
      std::vector<CurveParam> params;
      Polyline2 line;
      try {
        line = sample_curve(built.curve, options, &params);
      } catch (const BudgetError& e) {
        // At the tolerance that asked for it: the option, or the design's key.
        if (args.tolerance_given) {
          throw BudgetError(
              e.requested(), e.budget(),
              fmt::format("--tolerance {:g} {}: {}", args.tolerance, design.common.units, e.what()));
        }
        throw BudgetError(e.requested(), e.budget(),
                          fmt::format("{:g} {}: {}", options.tolerance, design.common.units, e.what()),
                          ErrorLocation{"tolerance"});
      }
      require_simple_closed(line, params, nc.spec.key);  // as `run` does
      if (args.csv) {
        for (const Vec2& p : line.points) io.out << fmt::format("{},{},{}\n", nc.name, p.x(), p.y());
        continue;
      }
      io.out << fmt::format("# {} {}: {} {} segment(s), {} points, max deviation {:.6g} (tolerance {})\n",
                            design.common.name, nc.name, built.curve.closed() ? "closed" : "open",
                            built.curve.size(), line.points.size(), line.max_deviation, options.tolerance);
      for (std::size_t i = 0; i < built.joints.size(); ++i) io.out << "# " << joint_line(built, i) << "\n";
      if (!built.through.empty()) {
        io.out << fmt::format(
            "# {}: through {} points; the control points solved from them (each through point within {:.3g} "
            "of its joint, proven):\n",
            nc.name, built.through.size(), built.through_deviation);
        for (std::size_t i = 0; i < nc.spec.bspline_points.size(); ++i) {
          const Vec2& p = nc.spec.bspline_points[i];
          io.out << fmt::format("#   p{} = [{}, {}]\n", i, p.x(), p.y());
        }
      }
      for (const Vec2& p : line.points) io.out << fmt::format("{} {}\n", p.x(), p.y());
    }
  });
  return 0;
}

}  // namespace

Runner add_sample_command(CLI::App& app) {
  auto args = std::make_shared<SampleArgs>();
  CLI::App* cmd = app.add_subcommand("sample", "Print the sampled points of a design's curves");
  cmd->add_option("design", args->design, "Design file (YAML)")->required();
  add_define_option(cmd, args->defines);
  cmd->add_flag("--csv", args->csv, "Print CSV with columns curve,x,y");
  CLI::Option* tolerance =
      cmd->add_option("--tolerance", args->tolerance, "Sampling tolerance, > 0 (default: the design's)");
  return [args, tolerance](Streams io) {
    args->tolerance_given = tolerance->count() > 0;
    return run_sample(*args, io);
  };
}

}  // namespace fabmesh::cli
