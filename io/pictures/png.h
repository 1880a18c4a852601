#pragma once
// RGB images and their PNG encoding (Debian libspng).

#include <cstdint>
#include <string>
#include <vector>

namespace fabmesh {

/// An 8-bit RGB image: `rgb` holds width * height * 3 bytes, rows top to
/// bottom, pixels left to right, channels R, G, B.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;
};

struct PngOptions {
  /// zlib level 0 (store) .. 9 (smallest); the default balances size and speed.
  int compression_level = 6;
};

/// The PNG file bytes of `image` (truecolour, 8 bits per channel, no
/// ancillary chunks: the same image always gives the same bytes).
/// \throw RangeError for a size outside [1, 65535] or a bad compression
/// level, InputError when `rgb` does not hold width * height * 3 bytes or the
/// encoder fails.
std::string encode_png(const Image& image, const PngOptions& options = {});

}  // namespace fabmesh
