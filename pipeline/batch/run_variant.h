#pragma once
// One variant of a batch: resolve its design, run its job into its folder,
// digest its files, and say whether an earlier row still stands for it.

#include <cstddef>
#include <string>
#include <string_view>

#include "io/design/manifest.h"
#include "pipeline/batch/batch_row.h"
#include "pipeline/batch/plan.h"
#include "pipeline/plane_memo.h"

namespace fabmesh {

/// The folder of variant `name` in the batch folder `out_dir` (out_dir/NAME).
std::string variant_folder(const std::string& out_dir, const std::string& name);

/// Runs variant `index` of `manifest` (planned as `planned`) into
/// variant_folder(out_dir, name): resolves its design, checks its key, runs
/// the job (all files or none), digests the files it wrote, and removes
/// files of earlier runs that are not among them (the folder then holds
/// exactly the variant's outputs; a failed variant has no folder). Never
/// throws for the variant's own failures: they are the row's status, exit
/// code and message (pipeline/failure.h). A countertop takes its work in the
/// plane from `planes` when an earlier variant of the same design (but its
/// name and thickness) left it there, and leaves its own there (null: neither).
BatchRow run_variant(const BatchManifest& manifest, std::size_t index, const PlannedVariant& planned,
                     const std::string& out_dir, PlaneMemo* planes = nullptr);

/// True when the committed `row_json` of a variant can stand for running it
/// again: its status is final (ok, invalid, bad input; not an internal error
/// nor the machine's) and, when ok, every file it lists is a regular file in
/// `out_dir` with its size and SHA-256 digest. When an ok row does not stand
/// because a file is missing or changed, `*why` says which and how.
bool row_stands(std::string_view row_json, const std::string& out_dir, std::string* why = nullptr);

}  // namespace fabmesh
