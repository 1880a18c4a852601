#include "pipeline/planned_outputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

namespace fabmesh {
namespace {

std::string path_in_folder(const Design& design, const JobOptions& options, const std::string& suffix) {
  return (std::filesystem::path(options.out_dir) / (design.common.name + suffix)).string();
}

// The files of mould_stl: one per part, named as build_vessel names the parts.
std::vector<std::string> mould_part_suffixes(const Design& design) {
  std::vector<std::string> suffixes;
  const auto* vessel = std::get_if<VesselDesign>(&design.body);
  if (vessel == nullptr || !vessel->mould) return suffixes;
  for (int k = 1; k <= vessel->mould->parts; ++k) suffixes.push_back(fmt::format(".mould-side-{}.stl", k));
  if (vessel->mould->base_part) suffixes.emplace_back(".mould-base.stl");
  return suffixes;
}

// "a or b", "a, b or c".
std::string either(const std::vector<std::string>& names) {
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) text += i + 1 == names.size() ? " or " : ", ";
    text += names[i];
  }
  return text;
}

}  // namespace

std::vector<PlannedFile> planned_files(const Design& design, const JobOptions& options) {
  std::vector<PlannedFile> files;
  for (const OutputFormat* format : job_formats(design, options)) {
    const std::string name(format->name);
    if (options.output_file) {
      files.push_back({*options.output_file, name});
    } else if (format->content == OutputContent::MouldParts && format->file_suffix == ".mould-PART.stl") {
      for (const std::string& suffix : mould_part_suffixes(design))
        files.push_back({path_in_folder(design, options, suffix), name});
    } else {
      files.push_back({path_in_folder(design, options, std::string(format->file_suffix)), name});
    }
  }
  return files;
}

std::vector<std::string> unused_block_warnings(const Design& design, const JobOptions& options,
                                               const std::vector<const OutputFormat*>& formats) {
  std::vector<std::string> warnings;
  if (options.export_format || design.common.outputs.empty()) return warnings;
  struct Block {
    OutputContent content;
    const char* key;
    const char* what;
  };
  for (const Block& block : {Block{OutputContent::MouldParts, "mould", "the mould is not built"},
                             Block{OutputContent::Toolpath, "cnc", "the router path is not planned"}}) {
    if (!has_content(design, block.content)) continue;
    const bool used = std::any_of(formats.begin(), formats.end(),
                                  [&](const OutputFormat* f) { return f->content == block.content; });
    if (used) continue;
    std::vector<std::string> users;
    for (const OutputFormat& f : output_formats()) {
      if (f.content == block.content && f.kinds.test(design.body.index())) users.emplace_back(f.name);
    }
    warnings.push_back(
        fmt::format("{}: `outputs` asks for no output made from it, so {}: add {} to `outputs` "
                    "(or remove `{}`)",
                    key_label(design.common, block.key), block.what, either(users), block.key));
  }
  return warnings;
}

}  // namespace fabmesh
