#include "io/pictures/png.h"

#include <fmt/format.h>
#include <spng.h>

#include <cstdlib>
#include <memory>

#include "geometry/core/error_checks.h"

namespace fabmesh {
namespace {

struct CtxDeleter {
  void operator()(spng_ctx* ctx) const { spng_ctx_free(ctx); }
};

void check(int status, const char* what) {
  if (status != 0) throw InputError(fmt::format("png: {} failed: {}", what, spng_strerror(status)));
}

}  // namespace

std::string encode_png(const Image& image, const PngOptions& options) {
  require_in_range("png width", image.width, 1, 65535);
  require_in_range("png height", image.height, 1, 65535);
  require_in_range("png compression_level", options.compression_level, 0, 9);
  const std::size_t bytes =
      static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3;
  if (image.rgb.size() != bytes) {
    throw InputError(fmt::format("png: a {} x {} RGB image needs {} bytes, got {}", image.width, image.height,
                                 bytes, image.rgb.size()));
  }
  const std::unique_ptr<spng_ctx, CtxDeleter> ctx(spng_ctx_new(SPNG_CTX_ENCODER));
  if (!ctx) throw InputError("png: cannot create an encoder");
  check(spng_set_option(ctx.get(), SPNG_ENCODE_TO_BUFFER, 1), "buffer output");
  check(spng_set_option(ctx.get(), SPNG_IMG_COMPRESSION_LEVEL, options.compression_level),
        "compression level");
  spng_ihdr ihdr{};
  ihdr.width = static_cast<std::uint32_t>(image.width);
  ihdr.height = static_cast<std::uint32_t>(image.height);
  ihdr.bit_depth = 8;
  ihdr.color_type = SPNG_COLOR_TYPE_TRUECOLOR;
  check(spng_set_ihdr(ctx.get(), &ihdr), "header");
  check(spng_encode_image(ctx.get(), image.rgb.data(), bytes, SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE),
        "encoding");
  std::size_t size = 0;
  int error = 0;
  void* buffer = spng_get_png_buffer(ctx.get(), &size, &error);
  check(error, "output");
  if (buffer == nullptr) throw InputError("png: the encoder returned no data");
  std::string out(static_cast<const char*>(buffer), size);
  std::free(buffer);
  return out;
}

}  // namespace fabmesh
