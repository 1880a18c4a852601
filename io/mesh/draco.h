#pragma once
// Draco (.drc): compressed triangle meshes, positions quantized.

#include <functional>
#include <string>
#include <string_view>

#include "geometry/core/soup.h"
#include "geometry/core/types.h"
#include "geometry/mesh/halfedge_mesh.h"

namespace fabmesh {

/// Options of the Draco writer.
struct DracoOptions {
  /// The largest distance (model units) any vertex may move through
  /// float32 conversion and quantization; it chooses the quantization bits.
  double tolerance = 0.01;
  int encoding_speed = 5;  ///< 0 (best compression) .. 10 (fastest)
  int decoding_speed = 5;  ///< 0 .. 10
};

/// Position quantization for one mesh: the bits and the error they allow.
struct DracoQuantization {
  int bits = 0;            ///< in [1, 30]
  double max_error = 0.0;  ///< proven bound on any vertex's decoded displacement, model units
};

/// Upper bound on how far a vertex of a mesh with bounding box
/// [lo, hi] (model units) moves when encoded with `bits` of position
/// quantization: per axis, half a quantization step (max extent / (2^bits - 1))
/// plus float32 rounding; times sqrt(3) for the Euclidean distance.
double draco_max_error(const Vec3& lo, const Vec3& hi, int bits);

/// The fewest quantization bits (in [1, 30]) whose draco_max_error is <=
/// `tolerance`. \throw RangeError when tolerance is not > 0 or when even 30
/// bits (or float32) cannot meet it for this bounding box.
DracoQuantization draco_quantization(const Vec3& lo, const Vec3& hi, double tolerance);

/// Most triangles a Draco file may declare by default: as many as the largest
/// binary STL fabmesh reads holds.
inline constexpr std::size_t kMaxDracoTriangles = 86'000'000;

/// Most triangles a Draco file may declare per byte of its data. Edgebreaker
/// with 1-bit positions packs a smooth 7e5-triangle vessel at 160 per byte;
/// a declared count beyond this is a corrupt header, refused before libdraco
/// allocates for it (it would reserve 3 GB for a 100-byte file).
inline constexpr std::size_t kMaxDracoTrianglesPerByte = 1024;

/// Decodes a Draco triangle mesh (positions only). \param name the path, for
/// messages. \param max_triangles the most triangles the file may declare.
/// \throw FileError when the data is not a valid Draco mesh (a point cloud,
/// corrupt data, no positions, a non-finite position), or declares more
/// triangles than max_triangles or than kMaxDracoTrianglesPerByte allows.
TriangleSoup parse_draco(std::string_view bytes, const std::string& name,
                         std::size_t max_triangles = kMaxDracoTriangles);

/// Draco bytes of `soup`, quantized by draco_quantization(bbox, options.tolerance).
/// \throw RangeError (tolerance), InputError (index out of range or the
/// encoder refuses the mesh).
std::string encode_draco(const TriangleSoup& soup, const DracoOptions& options = {});

/// Draco bytes of `soup` (positions as float32) with `bits` of position
/// quantization, in [1, 30]. \throw RangeError (bits), InputError (the encoder refuses the mesh)
std::string encode_draco_bits(const TriangleSoup& soup, int bits, const DracoOptions& options = {});

/// A quantization of one mesh, measured by encoding and decoding it.
struct DracoFit {
  int bits = 0;
  double max_displacement = 0.0;  ///< measured: the farthest any vertex moved, model units
  TriangleSoup decoded;           ///< the decoded mesh with the input's vertex order and faces
  std::string bytes;              ///< the Draco file (no extra attributes) that decodes to `decoded`
};

/// What fit_draco knows of which decoded meshes are acceptable.
struct DracoAccept {
  /// Takes or refuses a decoded mesh (its triangles are the input's).
  std::function<bool(const TriangleSoup& decoded)> accept;
  /// Vertex moves below this keep the mesh acceptable (its proven embedding
  /// margin in the input's frame; 0: none proven): the search jumps to the
  /// fewest bits whose bound (draco_max_error) stays below it.
  double margin = 0.0;
  /// Whether a mesh with two vertices at one position is never acceptable
  /// (a valid mesh: two faces then touch, or one collapses). Bit counts at
  /// which Draco's quantizer puts two vertices at one position are then
  /// passed over without encoding.
  bool distinct_positions = false;
};

/// A quantization whose MEASURED displacement of every vertex is <=
/// `tolerance` and whose decoded mesh `accept` takes (quantization can
/// collapse or fold faces): the fewest bits whose half step fits, or the
/// next; failing both, the fewest found by bisection up to the fewest bits
/// whose bound stays below accept.margin, or else the most bits worth trying
/// (where the step falls below float32 rounding) and affordable (Draco's
/// encoder needs memory per quantization level: at most 2^24 levels, or 64
/// per vertex). About seven tries at most; none when float32 rounding alone
/// moves a vertex farther than the tolerance, or when the fewest bits that
/// could fit are not affordable. Each try encodes the mesh once, as it is
/// written, decodes it, and matches every decoded point to its input vertex
/// by the position Draco's quantizer gives that vertex; the match is
/// accepted only as a bijection under which the decoded faces are the
/// input's faces with their orientation, so `decoded` is exactly what the
/// file decodes to, in the input's order. When the match fails (two
/// vertices quantize to the same position, or Draco split a vertex), that
/// try falls back to an encoding with an extra id attribute and checks the
/// id-free file against it. `format` names the output in messages ("drc",
/// "glb_draco").
/// \throw OutputError when no quantization fits, saying by how much and what to change
DracoFit fit_draco(const TriangleSoup& soup, double tolerance, const DracoAccept& accept,
                   const std::string& format, const DracoOptions& options = {});

/// fit_draco knowing nothing of `accept` but its answers.
inline DracoFit fit_draco(const TriangleSoup& soup, double tolerance,
                          std::function<bool(const TriangleSoup& decoded)> accept, const std::string& format,
                          const DracoOptions& options = {}) {
  return fit_draco(soup, tolerance, DracoAccept{std::move(accept)}, format, options);
}

/// Throws std::logic_error unless `bytes` decode to `fit.decoded`'s faces and
/// positions (as multisets): the file written is the mesh that was validated.
/// fit_draco's `bytes` pass by construction; this is the independent check.
void require_draco_matches(std::string_view bytes, const DracoFit& fit);

/// Writes `soup` (or `mesh`) as Draco to `path`, atomically.
/// \throw as encode_draco, and FileError when the file cannot be written.
void write_draco(const TriangleSoup& soup, const std::string& path, const DracoOptions& options = {});
void write_draco(const Mesh& mesh, const std::string& path, const DracoOptions& options = {});

}  // namespace fabmesh
