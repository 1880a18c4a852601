// Times render_preview + encode_png on a 1e6-triangle torus (the preview's
// budget: under 0.5 s in a Release build). Standalone until it is folded into
// bench/CMakeLists.txt; build it against a Release build of fabmesh::io:
//
//   cmake -S . -B build-bench -G Ninja -DCMAKE_BUILD_TYPE=Release -DFABMESH_BUILD_TESTS=OFF
//   cmake --build build-bench -j2 --target fabmesh_io
//   g++ -std=c++17 -O2 -DNDEBUG -D_USE_MATH_DEFINES -I. -I/usr/include/eigen3 \
//       bench/preview_timing.cpp build-bench/io/libfabmesh_io.a build-bench/geometry/libfabmesh_geometry.a \
//       -lspng -ltbb -lfmt -lOpenMeshCore -o build-bench/preview_timing
//   build-bench/preview_timing [OUT.png]
//
// Prints the best of 5 runs for each configuration; OUT.png receives the last image.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "io/pictures/png.h"
#include "io/pictures/preview.h"

namespace {

// A torus of `around` x `across` quads, two triangles each, outward oriented.
fabmesh::TriangleSoup torus(double big, double small, int around, int across) {
  fabmesh::TriangleSoup s;
  for (int i = 0; i < around; ++i) {
    const double u = 2 * M_PI * i / around;
    for (int j = 0; j < across; ++j) {
      const double v = 2 * M_PI * j / across;
      const double r = big + small * std::cos(v);
      s.vertices.emplace_back(r * std::cos(u), r * std::sin(u), small * std::sin(v));
    }
  }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>((i % around) * across + (j % across)); };
  for (int i = 0; i < around; ++i) {
    for (int j = 0; j < across; ++j) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return s;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const fabmesh::TriangleSoup soup = torus(3.0, 1.0, 1000, 500);
  std::printf("torus: %zu triangles, %zu vertices\n", soup.triangles.size(), soup.vertices.size());
  struct Config {
    const char* name;
    int views, supersample;
  };
  std::string png;
  for (const Config c : {Config{"800x600, 1 view", 1, 1}, Config{"800x600, 2 views", 2, 1},
                         Config{"800x600, 1 view, 2x2 supersampled", 1, 2}}) {
    fabmesh::PreviewOptions o;
    o.views = c.views;
    o.supersample = c.supersample;
    double best_render = 1e9, best_total = 1e9;
    for (int run = 0; run < 5; ++run) {
      const auto t0 = std::chrono::steady_clock::now();
      const fabmesh::Image image = fabmesh::render_preview(soup, o);
      const double render = seconds_since(t0);
      png = fabmesh::encode_png(image);
      best_render = std::min(best_render, render);
      best_total = std::min(best_total, seconds_since(t0));
    }
    std::printf("%-36s render %.3f s, render + PNG %.3f s (%zu bytes)\n", c.name, best_render, best_total,
                png.size());
  }
  if (argc > 1) std::ofstream(argv[1], std::ios::binary) << png;
  return 0;
}
