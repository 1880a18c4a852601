// fabmesh plot DESIGN... [-o FILE.svg | DIR] [-D path=value]... [--width W --height H]:
// the design's curves as the papers draw them.

#include <fmt/format.h>

#include <filesystem>
#include <memory>

#include "geometry/core/errors.h"
#include "io/file.h"
#include "pipeline/cli/commands.h"
#include "pipeline/load_design.h"
#include "pipeline/pictures.h"

namespace fabmesh::cli {
namespace {

namespace fs = std::filesystem;

struct PlotArgs {
  std::vector<std::string> designs;
  std::vector<std::string> defines;
  std::string out = ".";
  int width = 1200;
  int height = 600;
};

bool ends_with(const std::string& s, std::string_view suffix) {
  return s.size() > suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

int plot_designs(const PlotArgs& args, Streams io) {
  const std::vector<Override> overrides = parse_overrides(args.defines);
  const bool one_file = ends_with(ascii_lower(args.out), ".svg");
  std::error_code ec;
  if (!one_file && names_a_file(args.out) && !fs::is_directory(args.out, ec)) {
    throw InputError(fmt::format("-o {}: plot writes SVG: name the file *.svg, or give a folder (-o {}/)",
                                 args.out, args.out));
  }
  if (one_file && args.designs.size() != 1) {
    throw InputError(fmt::format("-o {}: one SVG file takes one design ({} given); use -o DIR", args.out,
                                 args.designs.size()));
  }
  CurvePlotOptions options;
  options.width = args.width;
  options.height = args.height;
  // Every plot is made before any is written: a bad design writes nothing.
  // A curve whose joints contradict their declared continuity is drawn all
  // the same, the joint flagged, since that is when the picture is needed.
  std::vector<FileWrite> files;
  std::vector<std::string> contradicted;
  for (const std::string& path : args.designs) {
    const Design design = load_design(path, overrides);
    const std::string target =
        one_file ? args.out : (fs::path(args.out) / (design.common.name + ".plot.svg")).string();
    files.push_back(
        {target, in_design(design, [&] { return design_plot_svg(design, options, &contradicted); })});
  }
  for (const FileWrite& f : files) {
    const fs::path folder = fs::path(f.path).parent_path();
    if (!folder.empty()) fs::create_directories(folder);
  }
  write_files_atomically(files);
  if (io.verbosity > 0) {
    for (const FileWrite& f : files) io.out << fmt::format("wrote {}\n", f.path);
  }
  for (const std::string& message : contradicted) {
    io.err << fmt::format(
        "fabmesh: warning: {} (drawn all the same, the joint marked with an orange diamond; `run` "
        "refuses the design until it is fixed)\n",
        message);
  }
  return 0;
}

}  // namespace

Runner add_plot_command(CLI::App& app) {
  auto args = std::make_shared<PlotArgs>();
  CLI::App* cmd = app.add_subcommand("plot",
                                     "Draw a design's curves as SVG: control polygons dotted, joints with "
                                     "their continuity, curvature combs, "
                                     "curvature against arc length, true to scale with a scale bar");
  cmd->add_option("designs", args->designs, "Design files (YAML)")->required();
  cmd->add_option("-o,--output", args->out,
                  "A folder for NAME.plot.svg (default: the current folder), or one FILE.svg for one design");
  cmd->add_option("--width", args->width, "Picture width, pixels")->check(CLI::Range(200, 10000));
  cmd->add_option("--height", args->height, "Picture height, pixels")->check(CLI::Range(150, 10000));
  add_define_option(cmd, args->defines);
  return [args](Streams io) { return plot_designs(*args, io); };
}

}  // namespace fabmesh::cli
