#include "pipeline/batch/slurm_script.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "geometry/core/errors.h"
#include "pipeline/batch/shell_quote.h"

namespace fabmesh {

std::string slurm_script(const SlurmScriptOptions& o) {
  const bool control = std::any_of(o.out_dir.begin(), o.out_dir.end(), [](char c) {
    return static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) == 0x7F;
  });
  if (control || o.out_dir.find_first_of(" %\"'\\") != std::string::npos) {
    throw InputError(
        fmt::format("--slurm: the output folder {} holds a space, a control character, a quote, '\\' or '%', "
                    "which an #SBATCH line cannot carry: choose another -o",
                    shell_quote(o.out_dir)));
  }
  const bool plain_name = std::all_of(o.job_name.begin(), o.job_name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
  if (o.job_name.empty() || !plain_name) {
    throw InputError(fmt::format("--slurm: the job name {} is not made of letters, digits, '_', '-' and '.'",
                                 shell_quote(o.job_name)));
  }
  const std::size_t n = o.shards;
  std::string s;
  s += "#!/bin/bash\n";
  // Every value is quoted for the shell, in comments too: a newline in a path must not end the comment.
  s += fmt::format("# fabmesh batch: {} variants of {} in {} shards\n", o.variants, shell_quote(o.manifest),
                   n);
  s += fmt::format("# (array task I runs shard I/{}: the variants i with i mod {} = I).\n", n, n);
  s += fmt::format("# Submit:  sbatch {}\n", shell_quote(o.out_dir + "/slurm.sbatch"));
  s += fmt::format("# Then:    fabmesh batch --merge {}\n", shell_quote(o.out_dir));
  s += fmt::format("#SBATCH --job-name={}\n", o.job_name);
  s += fmt::format("#SBATCH --array=0-{}\n", n - 1);
  s += "#SBATCH --ntasks=1\n";
  s += fmt::format("#SBATCH --cpus-per-task={}\n", o.cpus_per_task);
  s += fmt::format("#SBATCH --output={}/.batch/slurm/shard-%a-of-{}.log\n", o.out_dir, n);
  s += "#SBATCH --open-mode=append\n";
  s += "set -euo pipefail\n";
  s += fmt::format("exec {} batch {} -o {} --shard \"${{SLURM_ARRAY_TASK_ID}}/{}\" --jobs {} --quiet\n",
                   shell_quote(o.program), shell_quote(o.manifest), shell_quote(o.out_dir), n,
                   o.cpus_per_task);
  return s;
}

}  // namespace fabmesh
