#pragma once
// Test helper: decodes PNG bytes to RGB with libspng (the library io encodes with).

#include <spng.h>

#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fabmesh::test {

struct DecodedPng {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< rows top to bottom, 3 bytes per pixel
  std::array<std::uint8_t, 3> at(int x, int y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

/// Decodes `bytes` (any PNG colour type) to 8-bit RGB. \throw std::runtime_error when spng refuses it.
inline DecodedPng decode_png(std::string_view bytes) {
  struct Free {
    void operator()(spng_ctx* c) const { spng_ctx_free(c); }
  };
  const std::unique_ptr<spng_ctx, Free> ctx(spng_ctx_new(0));
  auto check = [](int status, const char* what) {
    if (status != 0) throw std::runtime_error(std::string("spng ") + what + ": " + spng_strerror(status));
  };
  check(spng_set_png_buffer(ctx.get(), bytes.data(), bytes.size()), "buffer");
  spng_ihdr ihdr{};
  check(spng_get_ihdr(ctx.get(), &ihdr), "header");
  std::size_t size = 0;
  check(spng_decoded_image_size(ctx.get(), SPNG_FMT_RGB8, &size), "size");
  DecodedPng out;
  out.width = static_cast<int>(ihdr.width);
  out.height = static_cast<int>(ihdr.height);
  out.rgb.resize(size);
  check(spng_decode_image(ctx.get(), out.rgb.data(), size, SPNG_FMT_RGB8, 0), "decode");
  return out;
}

}  // namespace fabmesh::test
