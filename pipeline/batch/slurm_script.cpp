#include "pipeline/batch/slurm_script.h"

#include <fmt/format.h>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

// 'text' for the shell ('\'' for each quote).
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  return out + "'";
}

}  // namespace

std::string slurm_script(const SlurmScriptOptions& o) {
  if (o.out_dir.find_first_of(" \t\n%\"'\\") != std::string::npos) {
    throw InputError(
        fmt::format("--slurm: the output folder '{}' holds a space, a quote, '\\' or '%', which an #SBATCH "
                    "line cannot carry: "
                    "choose another -o",
                    o.out_dir));
  }
  const std::size_t n = o.shards;
  std::string s;
  s += "#!/bin/bash\n";
  s += fmt::format("# fabmesh batch: {} variants of {} in {} shards\n", o.variants, o.manifest, n);
  s += fmt::format("# (array task I runs shard I/{}: the variants i with i mod {} = I).\n", n, n);
  s += fmt::format("# Submit:  sbatch {}/slurm.sbatch\n", o.out_dir);
  s += fmt::format("# Then:    fabmesh batch --merge {}\n", o.out_dir);
  s += fmt::format("#SBATCH --job-name={}\n", o.job_name);
  s += fmt::format("#SBATCH --array=0-{}\n", n - 1);
  s += "#SBATCH --ntasks=1\n";
  s += fmt::format("#SBATCH --cpus-per-task={}\n", o.cpus_per_task);
  s += fmt::format("#SBATCH --output={}/.batch/slurm/shard-%a-of-{}.log\n", o.out_dir, n);
  s += "#SBATCH --open-mode=append\n";
  s += "set -euo pipefail\n";
  s += fmt::format("exec {} batch {} -o {} --shard \"${{SLURM_ARRAY_TASK_ID}}/{}\" --jobs {} --quiet\n",
                   quoted(o.program), quoted(o.manifest), quoted(o.out_dir), n, o.cpus_per_task);
  return s;
}

}  // namespace fabmesh
