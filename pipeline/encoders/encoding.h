#pragma once
// What an output's encoder gets and gives (pipeline/output_table.h holds the
// rows that name them): a job's Result in, the bytes of its file (or files)
// out, with the error writing added. No I/O.

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/soup.h"
#include "io/design/design.h"
#include "pipeline/result.h"

namespace fabmesh {

/// What an encoder gets: the result, its product's mesh in the export unit,
/// and the error it may still add.
struct EncodeContext {
  const DesignCommon& common;
  const Result& result;
  const TriangleSoup& exported;   ///< the product's mesh scaled to common.export_units (empty: none)
  double export_scale = 1.0;      ///< export units per model unit
  double output_tolerance = 0.0;  ///< tolerance left after the build, model units
  std::string path;               ///< where the file will go (for messages)
  /// The part a mesh output writes (`exported` is its mesh in the export
  /// unit): a kitchen's piece; null: the product.
  const Part* part = nullptr;
};

/// An encoded output: its bytes, the unit they are in, and the largest
/// distance by which writing moved any vertex (a proven bound or a measured
/// value over every vertex), in model units.
struct Encoded {
  std::string bytes;
  std::string units;
  double added_error = 0.0;
  /// Replaces the format's file_suffix when an output is several files
  /// (one per mould part: ".mould-side-1.stl").
  std::string suffix;
  /// When set, `bytes` is empty and this hands them to its sink in pieces
  /// instead (a large STL is written straight to its file, never held whole).
  /// It refers to the Result's meshes: call it while they live.
  std::function<void(const std::function<void(std::string_view)>&)> stream = nullptr;
  /// Mesh outputs: true when the mesh as written (moved by added_error) is
  /// itself proven valid: written exactly, moved less than the built mesh's
  /// embedding margin, or decoded and validated (Draco); false when only the
  /// move is bounded. Unset for drawings and programs.
  std::optional<bool> valid_as_written = std::nullopt;
  /// The parts the file holds (empty: the design as a whole).
  std::vector<std::string> parts = {};
};

using EncodedFiles = std::vector<Encoded>;

// Bounds on how far a number format moves a vertex whose coordinates are at
// most `largest` in absolute value (export units; `export_scale` export units
// per model unit), in model units.

/// float32 rounding (STL, PLY, glTF) and the scaling by a double.
double float32_bound(double largest_exported, double export_scale);
/// Exact shortest decimals (OBJ, OFF): only the scaling rounds.
double decimal_bound(double largest_exported, double export_scale);
/// 3MF's micro-unit decimals of float32 values, and the scaling.
double threemf_bound(double largest_exported, double export_scale);

/// A router program and what it cuts: a countertop's one, or one per slab
/// of a kitchen.
struct RouterProgram {
  const Toolpath* path = nullptr;  ///< in the result it was made from
  std::vector<CutLoop> part;       ///< the loops it cuts, drawn under the path
  std::string suffix;              ///< ".slab-1" (empty: the design's own file)
  std::vector<std::string> parts;  ///< the pieces on the slab
};

/// The countertop's router programs (encoders/drawing_encoders.cpp): its
/// own, or a kitchen's one per slab. Only for a countertop with `cnc`
/// (a toolpath, or a kitchen's slab toolpaths).
std::vector<RouterProgram> router_programs(const CountertopProducts& countertop);

// The encoders of the output table's rows (pipeline/output_table.cpp).
// Each \throw OutputError when its output cannot be made within the tolerance left.

// Meshes (encoders/mesh_encoders.cpp): the product.
EncodedFiles encode_stl_output(const EncodeContext& c);
EncodedFiles encode_obj_output(const EncodeContext& c);
EncodedFiles encode_ply_output(const EncodeContext& c);
EncodedFiles encode_off_output(const EncodeContext& c);
EncodedFiles encode_3mf_output(const EncodeContext& c);
EncodedFiles encode_drc_output(const EncodeContext& c);
EncodedFiles encode_glb_output(const EncodeContext& c);
EncodedFiles encode_glb_draco_output(const EncodeContext& c);
// The mould's parts (encoders/mesh_encoders.cpp).
EncodedFiles encode_mould_stl_output(const EncodeContext& c);
EncodedFiles encode_mould_3mf_output(const EncodeContext& c);
// A vessel's casting master (encoders/mesh_encoders.cpp, encoders/step_encoders.cpp).
EncodedFiles encode_master_stl_output(const EncodeContext& c);
EncodedFiles encode_master_3mf_output(const EncodeContext& c);
// The mould parts' casting cases (encoders/mesh_encoders.cpp). When no part
// has one: an OutputError for `format` with every part's reason.
void require_cases(const EncodeContext& c, const char* format);
EncodedFiles encode_case_stl_output(const EncodeContext& c);
EncodedFiles encode_case_3mf_output(const EncodeContext& c);
EncodedFiles encode_case_step_output(const EncodeContext& c);  // encoders/step_encoders.cpp
// Drawings, programs and pictures (encoders/drawing_encoders.cpp).
EncodedFiles encode_dxf_output(const EncodeContext& c);
EncodedFiles encode_svg_output(const EncodeContext& c);
EncodedFiles encode_nc_output(const EncodeContext& c);
EncodedFiles encode_toolpath_svg_output(const EncodeContext& c);
EncodedFiles encode_layout_svg_output(const EncodeContext& c);
EncodedFiles encode_layout_dxf_output(const EncodeContext& c);
EncodedFiles encode_shop_dxf_output(const EncodeContext& c);
EncodedFiles encode_shop_svg_output(const EncodeContext& c);
EncodedFiles encode_cutlist_output(const EncodeContext& c);
EncodedFiles encode_plot_output(const EncodeContext& c);
EncodedFiles encode_png_output(const EncodeContext& c);
// Exact geometry (encoders/step_encoders.cpp).
EncodedFiles encode_step_output(const EncodeContext& c);
EncodedFiles encode_mould_step_output(const EncodeContext& c);
EncodedFiles encode_master_step_output(const EncodeContext& c);

}  // namespace fabmesh
