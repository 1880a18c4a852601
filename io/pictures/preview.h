#pragma once
// Shaded previews of triangle meshes rendered on the CPU: no display, no GPU.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/core/soup.h"
#include "io/pictures/png.h"

namespace fabmesh {

using Rgb = std::array<std::uint8_t, 3>;

/// An orthographic view direction: the camera looks at the mesh from
/// azimuth (degrees, counter-clockwise from +x about +z) and elevation
/// (degrees above the xy plane); z is up on screen.
struct PreviewView {
  double azimuth_deg = 35.0;    ///< [-360, 360]
  double elevation_deg = 25.0;  ///< [-89, 89]
};

struct PreviewOptions {
  int width = 800;   ///< image width, pixels, [16, 8192]
  int height = 600;  ///< image height, pixels, [16, 8192]
  /// 1: `first` fills the image; 2: `first` and `second` side by side (left,
  /// right), each in half the width, at the same scale.
  int views = 1;
  PreviewView first{35.0, 25.0};     ///< three-quarter view from above
  PreviewView second{215.0, -30.0};  ///< the opposite side from below (bases, feet)
  int supersample = 1;               ///< 1, or 2 for 2 x 2 samples per pixel (anti-aliasing)
  double margin = 0.05;              ///< free border of each view, fraction of its width/height, [0, 0.45]
  Rgb background{235, 235, 235};     ///< light grey
  Rgb front_color{205, 150, 110};    ///< faces seen from outside (clay)
  Rgb back_color{90, 130, 200};      ///< faces seen from inside: open or inside-out meshes show blue
  double ambient = 0.2;              ///< light reaching faces turned away from the lamp, [0, 1]
  /// One line of text drawn at the bottom left of the image (e.g. the overall
  /// size, "120 x 80 x 95 mm"), in a built-in pixel font of digits, ". - x",
  /// space and the letters of the unit names (c i m n); at most 64 characters.
  std::string caption;
  /// Straight guide lines in model space (e.g. a vessel's axis), drawn dashed
  /// over the shading in each view: dark where nothing hides them, faint where
  /// the mesh is in front. Their ends are fitted into the frame with the mesh.
  std::vector<std::array<Vec3, 2>> guides;
};

/// Renders `soup` with a z-buffer: flat face normals, Lambert shading from a
/// key lamp above-left of the viewer (3/4) and a lamp at the eye (1/4) plus
/// `ambient`, faces two-sided (back faces in `back_color`). The mesh is fitted to the frame: in each view the
/// bounding box of the projected vertices is centred in the view's frame and
/// the scale (pixels per model unit, shared by both views) is the largest
/// that keeps it inside the frame less `margin` on every side. Pixel (i, j)
/// samples the point (i + 0.5, j + 0.5) (per subsample when supersampled).
/// An empty soup gives the background. Deterministic: the same input gives
/// the same pixels whatever the thread count.
/// \throw RangeError for a bad option, InputError for a non-finite vertex or
/// guide, an index out of range, or a caption character the font lacks.
Image render_preview(const TriangleSoup& soup, const PreviewOptions& options = {});

}  // namespace fabmesh
