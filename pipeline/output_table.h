#pragma once
// The table of output formats: adding one is an encoder in io/ plus one row
// in output_table.cpp (its encoder in pipeline/encoders/). The design
// reader's `outputs:` list, the defaults of each kind, what the builders
// must make, the error each format's numbers add and the job's encoding all
// come from here.

#include <bitset>
#include <cstddef>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "io/design/design.h"
#include "pipeline/encoders/encoding.h"

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

/// A section of a design an output is made from, beyond its kind.
enum class DesignBlock {
  None,
  Mould,  ///< a vessel's `mould:` (the mould's parts, their casting cases)
  Cnc,    ///< a countertop's `cnc:` (the router path)
  Slab,   ///< a countertop's `slab:` (a kitchen: its pieces on slabs)
};

/// What a row's output is made of, for the builders: they make a drawing
/// or keep the exact shape only when an output asks for it.
enum class OutputSource {
  Meshes,   ///< the meshes (the product, or the mould's parts)
  Drawing,  ///< the design's drawing at true size (a curve, a vessel's profile template, a countertop's
            ///< outline)
  Program,  ///< the router path over the outline (needs the drawing too)
  Curves,   ///< the design's curves as built (a plot)
  Exact,    ///< the exact shape (STEP)
};

/// One output format.
struct OutputFormat {
  std::string_view name;         ///< the file extension and the name in `outputs:`, e.g. "stl"
  std::string_view description;  ///< for help texts and the reference
  OutputSource source;
  DesignBlock block;    ///< the section of the design it needs (None: only the kind)
  KindSet kinds;        ///< the kinds it applies to
  KindSet default_for;  ///< the kinds that get it when a design names no outputs
  std::string_view
      file_suffix;  ///< after the name: ".stl", ".draco.glb"; one file per part: ".mould-PART.stl"
  /// A bound on how far writing moves a vertex whose coordinates are at
  /// most `largest` in absolute value (model units; `export_scale` export
  /// units per model unit), in model units: float32 rounding (stl, ply, glb,
  /// mould_stl), 3MF's micro-unit decimals (3mf, mould_3mf), the scaling of
  /// exact decimals (obj, off). For Draco (drc, glb_draco), which measures its
  /// own within what is left, the share to keep: twice float32's rounding (its
  /// decoded positions are float32, and the fewest bits that fit round about
  /// as much again). Null for outputs that move no vertex.
  double (*writing_error)(double largest, double export_scale);
  /// One file, or several (each with its own suffix).
  /// \throw OutputError when the output cannot be made within the tolerance left
  EncodedFiles (*encode)(const EncodeContext& context);
};

/// Every output format, in the order defaults are listed.
const std::vector<OutputFormat>& output_formats();

/// The format a file name asks for by its ending, in any case (".draco.glb"
/// before ".glb", "X.STL" an STL), or nullptr.
const OutputFormat* format_of_file(const std::string& name);

/// The format called `name`, or nullptr.
const OutputFormat* find_output_format(std::string_view name);

/// True when `design` has the section `block` names (any design has None).
bool has_block(const Design& design, DesignBlock block);

/// True when `format` applies to `design`: its kind and the section it needs.
bool applies_to(const OutputFormat& format, const Design& design);

/// The formats `design` asks for: its `outputs` (each checked: the format
/// exists, applies to the kind, and the design has the section it needs)
/// or, when it names none, its kind's defaults that apply.
/// \throw FileError at the offending `outputs` entry
std::vector<const OutputFormat*> resolve_outputs(const Design& design);

}  // namespace fabmesh
