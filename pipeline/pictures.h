#pragma once
// Pictures of a design and of its mesh, for the `plot` and `preview`
// commands, the `plot` and `png` outputs and the HTML report of a run.

#include <string>
#include <vector>

#include "io/design/design.h"
#include "io/pictures/curve_plot.h"
#include "io/pictures/html_report.h"
#include "io/pictures/preview.h"
#include "pipeline/design_curves.h"
#include "pipeline/report.h"
#include "pipeline/result.h"

namespace fabmesh {

/// What the plot of a design shows: every curve it declares (a curve, a
/// vessel's profile, a countertop's outline and holes) with its control
/// polygons, measured joints and, when faired, the curve before fairing; for a
/// surface, the borders of its patches and their control net seen from above
/// (projected on the xy plane; a projected H-Bézier border is the H-Bézier
/// curve of the projected control points); for a vessel, its axis of
/// revolution and its section (a shell's inner wall, rim and base; none when
/// the profile makes no section), in (r, z). Titled with the design's name, in
/// its units. With `contradicted`, a curve whose joints contradict their
/// declared continuity is drawn as constructed with those joints flagged
/// ("joint lost") and the error appended there (build_shape); without, it is
/// an error. \throw as build_curve / build_patch_network
CurvePlot design_plot(const Design& design, std::vector<std::string>* contradicted = nullptr);

/// The same plot drawn from curves, patches and a vessel's section already
/// built (build_shape, or a job's Result): constructs nothing. `section`
/// null: not a vessel (no axis of revolution). `overhangs` (a vessel that
/// prints upright: its stretches beyond overhang_limit_deg) are flagged red.
CurvePlot shape_plot(const DesignCommon& common, const std::vector<NamedBuiltCurve>& curves,
                     const PatchNetwork* patches, const std::vector<std::vector<Vec2>>* section,
                     const std::vector<std::vector<Vec2>>& overhangs, double overhang_limit_deg);
/// The plot of a shape build_shape made.
CurvePlot shape_plot(const DesignCommon& common, const BuiltShape& shape);
/// The plot of a job's result: its curves and a surface's patches.
CurvePlot shape_plot(const DesignCommon& common, const Result& result);

/// The SVG of design_plot(design, contradicted) (plot_curves_svg).
std::string design_plot_svg(const Design& design, const CurvePlotOptions& options = {},
                            std::vector<std::string>* contradicted = nullptr);

/// A shaded preview of `soup` as a PNG file's bytes (render_preview, encode_png).
std::string preview_png(const TriangleSoup& soup, const PreviewOptions& options = {});

/// The overall size of `soup` (its bounding box) as a preview caption, four
/// significant digits, in `units` when given: "120.0 x 80.00 x 95.00 mm".
std::string size_caption(const TriangleSoup& soup, const std::string& units);

/// The design's mesh and, with a mould, the mould's parts exploded apart around
/// it: each part moved by the mould's radius away from the axis (along
/// the direction of its vertices' mean), or, for a part centred on the axis
/// (the base), by half the mould's height down (up when it sits above the
/// vessel's middle).
/// A kitchen's scene is its pieces instead: the top's pieces moved apart
/// from its middle (the seams opened by a twentieth of the top's size), the
/// backsplash strips in a row beyond its far edge.
TriangleSoup exploded_scene(const Result& result);

/// exploded_scene, and which triangles are whose: the parts in the scene's
/// order, each its Part::name and how many triangles it has there (the
/// product, then each mould part; a kitchen's pieces and strips).
struct ExplodedScene {
  TriangleSoup soup;
  struct Range {
    std::string name;
    std::size_t triangles = 0;
  };
  std::vector<Range> parts;
};
ExplodedScene exploded_scene_parts(const Result& result);

/// A design's preview (the `preview` command and the `png` output): its mesh;
/// with a mould, the mould's parts beside it, exploded apart (exploded_scene),
/// so each can be seen; a vessel's
/// axis (the z axis its profile turns about) as a dashed guide; the mesh's
/// overall size in the design's units as the caption. `options` gives the
/// picture's size and views.
std::string design_preview_png(const DesignCommon& common, const Result& result, PreviewOptions options = {});

/// The HTML report's status of an item: its own, Missing and Environment
/// shown as Error.
ReportStatus report_status(ItemStatus status);

/// `path` as the HTML report links it: relative to `base`, the folder of
/// the page ("" for the working folder).
std::string page_link(const std::string& path, const std::string& base);

/// The HTML report's row of an item (of a run or a batch): name, status,
/// message, its mesh facts in model units (counts, volume and area only when
/// measured), timings in seconds and files (page_link). No pictures.
ReportRow report_row(const ItemFacts& item, const std::string& base);

}  // namespace fabmesh
