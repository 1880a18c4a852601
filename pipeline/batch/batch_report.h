#pragma once
// The HTML report of a batch (`fabmesh batch ... --report FILE.html`): the
// summary's rows as one page, each variant with a thumbnail of its mesh.

#include <string>

namespace fabmesh {

/// Writes `report_path` (an HTML page) from `batch_dir`/summary.jsonl: one
/// row per variant (status, message, measures in the design's units, files
/// linked relative to the page) and, for each variant that wrote an STL, a
/// shaded thumbnail `batch_dir/NAME/NAME.thumb.png` (240 x 180, rendered
/// from that STL, made once: a rerun keeps it). Thumbnails are lazy-loaded,
/// so a page of thousands of variants stays small and usable.
/// \throw FileError (no summary, unreadable files), InputError (a malformed summary row)
void write_batch_report(const std::string& batch_dir, const std::string& report_path);

}  // namespace fabmesh
