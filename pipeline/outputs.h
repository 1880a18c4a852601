#pragma once
// The table of output formats: adding one is an encoder in io/ plus one row
// in outputs.cpp. The design reader's `outputs:` list, the defaults of each
// kind and the job's encoding all come from here.

#include <bitset>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "io/design/design.h"
#include "pipeline/built_mesh.h"

namespace fabmesh {

/// A set of design kinds (one bit per DesignBody alternative).
using KindSet = std::bitset<std::variant_size_v<DesignBody>>;

namespace detail {
template <class T, std::size_t I = 0>
constexpr std::size_t kind_index() {
  static_assert(I < std::variant_size_v<DesignBody>, "not a DesignBody alternative");
  if constexpr (std::is_same_v<T, std::variant_alternative_t<I, DesignBody>>) {
    return I;
  } else {
    return kind_index<T, I + 1>();
  }
}
}  // namespace detail

/// The set of the given kinds, e.g. kinds<VesselDesign, SurfaceDesign>().
template <class... Kinds>
KindSet kinds() {
  KindSet set;
  (set.set(detail::kind_index<Kinds>()), ...);
  return set;
}

/// What an encoder gets: the built design, the same mesh in the export unit,
/// and the error it may still add.
struct EncodeContext {
  const DesignCommon& common;
  const BuiltMesh& built;
  const TriangleSoup& exported;   ///< built.soup scaled to common.export_units
  double export_scale = 1.0;      ///< export units per model unit
  double output_tolerance = 0.0;  ///< tolerance left after the build, model units
  std::string path;               ///< where the file will go (for messages)
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
  /// It refers to the EncodeContext's meshes: call it while they live.
  std::function<void(const std::function<void(std::string_view)>&)> stream = nullptr;
  /// Mesh outputs: true when the mesh as written (moved by added_error) is
  /// itself proven valid: written exactly, moved less than the built mesh's
  /// embedding margin, or decoded and validated (Draco); false when only the
  /// move is bounded. Unset for drawings and programs.
  std::optional<bool> valid_as_written = std::nullopt;
};

/// A bound on how far writing `format` moves a vertex whose coordinates are
/// at most `largest` in absolute value (model units; `export_scale` export
/// units per model unit), in model units: float32 rounding (stl, ply, glb,
/// mould_stl), 3MF's micro-unit decimals (3mf, mould_3mf), the scaling of
/// exact decimals (obj, off). For Draco (drc, glb_draco), which measures its
/// own within what is left, the share to keep: twice float32's rounding (its
/// decoded positions are float32, and the fewest bits that fit round about
/// as much again). 0 for outputs that are no mesh.
double writing_error_bound(std::string_view format, double largest, double export_scale);

/// What an output is made from: the builders make the cutting outline only when an output needs it.
enum class OutputContent {
  Triangles,  ///< the design's mesh
  Drawing,  ///< its curves at true size: a countertop's cutting outline, a vessel's profile template, a curve
  MouldParts,  ///< the parts of a vessel's slip-casting mould (key `mould`)
  Toolpath,    ///< a countertop's router path (key `cnc`)
  Design,      ///< the design itself: its curves (a plot), whatever its kind
  Exact,       ///< the exact solid (countertop, vessel, thickened surface), curves, or open surface: step
};

/// True when `design` has what `content` is made from (a mould for MouldParts, ...).
bool has_content(const Design& design, OutputContent content);

/// One output format.
struct OutputFormat {
  std::string_view name;         ///< the file extension and the name in `outputs:`, e.g. "stl"
  std::string_view description;  ///< for help texts and the reference
  OutputContent content;
  KindSet kinds;                 ///< the kinds it applies to
  KindSet default_for;           ///< the kinds that get it when a design names no outputs
  std::string_view file_suffix;  ///< after the name: ".stl", ".draco.glb", ...
  /// One file, or several (each with its own suffix).
  /// \throw OutputError when the output cannot be made within the tolerance left
  std::vector<Encoded> (*encode)(const EncodeContext& context);
};

/// Every output format, in the order defaults are listed.
const std::vector<OutputFormat>& output_formats();

/// The format a file name asks for by its ending, in any case (".draco.glb"
/// before ".glb", "X.STL" an STL), or nullptr.
const OutputFormat* format_of_file(const std::string& name);

/// The format called `name`, or nullptr.
const OutputFormat* find_output_format(std::string_view name);

/// The formats `design` asks for: its `outputs` (each checked: the format
/// exists, applies to the kind, and the design has its content) or, when it
/// names none, its kind's defaults whose content the design has.
/// \throw FileError at the offending `outputs` entry
std::vector<const OutputFormat*> resolve_outputs(const Design& design);

}  // namespace fabmesh
