#pragma once
// The sbatch script of a batch: a Slurm job array whose task I runs shard
// I/N of the manifest into one output folder.

#include <cstddef>
#include <string>

namespace fabmesh {

struct SlurmScriptOptions {
  std::string program;   ///< absolute path of the fabmesh executable
  std::string manifest;  ///< absolute path of the manifest
  std::string out_dir;   ///< absolute path of the batch folder
  std::string job_name = "fabmesh-batch";
  std::size_t variants = 0;       ///< in the plan (for the script's comment)
  std::size_t shards = 1;         ///< array tasks, 1 <= shards <= variants
  std::size_t cpus_per_task = 1;  ///< also the shard's --jobs
};

/// The script's text: #SBATCH --array=0-(N-1), --cpus-per-task, --output into
/// out_dir/.batch/slurm/ (which must exist before submission), then `exec
/// fabmesh batch MANIFEST -o DIR --shard ${SLURM_ARRAY_TASK_ID}/N --jobs C -q`.
/// Every value is quoted for the shell (shell_quote), comment lines
/// included: a path holding a newline, quotes, $(...) or backticks stays one
/// word of its line. \throw InputError when out_dir holds a character an
/// #SBATCH line cannot carry (space, control characters, '%', quotes, '\\'),
/// or job_name anything but letters, digits, '_', '-' and '.'.
std::string slurm_script(const SlurmScriptOptions& options);

}  // namespace fabmesh
