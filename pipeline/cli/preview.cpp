// fabmesh preview MESH|DESIGN -o FILE.png [--views 1|2] [--width W --height H] [-D path=value]...:
// a shaded picture of a mesh, rendered on the CPU.

#include <fmt/format.h>

#include <filesystem>
#include <memory>

#include "geometry/core/errors.h"
#include "io/file.h"
#include "io/mesh/read_mesh.h"
#include "pipeline/cli/commands.h"
#include "pipeline/job.h"
#include "pipeline/load_design.h"
#include "pipeline/pictures.h"

namespace fabmesh::cli {
namespace {

namespace fs = std::filesystem;

struct PreviewArgs {
  std::string input;
  std::vector<std::string> defines;
  std::string out;
  int views = 1;
  int width = 800;
  int height = 600;
};

bool is_design(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  return ext == ".yaml" || ext == ".yml";
}

int preview(const PreviewArgs& args, Streams io) {
  if (ascii_lower(fs::path(args.out).extension().string()) != ".png")
    throw InputError(fmt::format("-o {}: the preview is a PNG file; name it *.png", args.out));
  if (!args.defines.empty() && !is_design(args.input))
    throw InputError(fmt::format("-D applies to designs; {} is a mesh file", args.input));
  PreviewOptions options;
  options.views = args.views;
  options.width = args.width;
  options.height = args.height;
  options.supersample = 2;
  std::string png;
  std::size_t triangles = 0;
  if (is_design(args.input)) {
    const Design design = load_design(args.input, parse_overrides(args.defines));
    const Result built = in_design(design, [&] { return build_preview(design); });
    triangles = product(built) != nullptr ? product(built)->mesh.triangles.size() : 0;
    png = design_preview_png(design.common, built, options);
  } else {
    // A mesh file's size, in the file's unit (most formats state none).
    const TriangleSoup soup = read_mesh(args.input);
    triangles = soup.triangles.size();
    options.caption = size_caption(soup, "");
    png = preview_png(soup, options);
  }
  const fs::path folder = fs::path(args.out).parent_path();
  if (!folder.empty()) fs::create_directories(folder);
  write_file_atomically(args.out, png);
  if (io.verbosity > 0)
    io.out << fmt::format("wrote {} ({} x {}, {} triangles)\n", args.out, args.width, args.height, triangles);
  return 0;
}

}  // namespace

Runner add_preview_command(CLI::App& app) {
  auto args = std::make_shared<PreviewArgs>();
  CLI::App* cmd = app.add_subcommand(
      "preview",
      "Render a shaded picture (PNG) of a mesh file or of the mesh a design builds, without a display");
  cmd->add_option("input", args->input,
                  "A mesh file (STL, OBJ, PLY, OFF, Draco, 3MF, glTF) or a design (YAML)")
      ->required();
  cmd->add_option("-o,--output", args->out, "The PNG file to write")->required();
  cmd->add_option("--views", args->views,
                  "1: a three-quarter view from above; 2: that and the opposite side from below")
      ->check(CLI::Range(1, 2));
  cmd->add_option("--width", args->width, "Image width, pixels")->check(CLI::Range(16, 8192));
  cmd->add_option("--height", args->height, "Image height, pixels")->check(CLI::Range(16, 8192));
  add_define_option(cmd, args->defines);
  return [args](Streams io) { return preview(*args, io); };
}

}  // namespace fabmesh::cli
