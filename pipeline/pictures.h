#pragma once
// Pictures of a design and of its mesh, for the `plot` and `preview`
// commands, the `plot` and `png` outputs and the HTML report of a run.

#include <string>

#include "io/design/design.h"
#include "io/pictures/curve_plot.h"
#include "io/pictures/html_report.h"
#include "io/pictures/preview.h"
#include "pipeline/job.h"

namespace fabmesh {

/// What the plot of a design shows: every curve it declares (a curve, a
/// vessel's profile, a countertop's outline and holes) with its control
/// polygons, measured joints and, when faired, the curve before fairing; for a
/// surface, the borders of its patches and their control net seen from above
/// (projected on the xy plane; a projected H-Bézier border is the H-Bézier
/// curve of the projected control points). Titled with the design's name, in
/// its units. \throw as build_curve / build_patch_network
CurvePlot design_plot(const Design& design);

/// The same plot drawn from a shape already built (BuiltMesh::shape, or
/// build_shape): constructs nothing.
CurvePlot shape_plot(const DesignCommon& common, const BuiltShape& shape);

/// The SVG of design_plot(design) (plot_curves_svg).
std::string design_plot_svg(const Design& design, const CurvePlotOptions& options = {});

/// The design's mesh as `run` builds it (validated; nothing written), for a
/// preview. \throw as build_design; InputError for a curve design (no mesh)
TriangleSoup design_mesh(const Design& design);

/// A shaded preview of `soup` as a PNG file's bytes (render_preview, encode_png).
std::string preview_png(const TriangleSoup& soup, const PreviewOptions& options = {});

/// The HTML report's row for a job that ran: name, kind, verdict, measures
/// in model units, timings and files (paths relative to `base`, the folder
/// of the page).
ReportRow report_row(const JobReport& report, const std::string& base);

/// The row for a design that did not run: its file, the exit code's status
/// (1 invalid, 2 bad input, 3 error) and the message.
ReportRow failed_row(const std::string& design_file, int exit_code, const std::string& message);

}  // namespace fabmesh
