// Kernels of the mesh builders and writers: revolve, STL encoding, welding.
#include <benchmark/benchmark.h>

#include <map>

#include "bench/bench_meshes.h"
#include "geometry/mesh/weld.h"
#include "io/mesh/stl.h"

namespace fabmesh::bench {
namespace {

/// The STL-style torus of `triangles` triangles, built once per size.
const TriangleSoup& stl_soup(std::size_t triangles) {
  static std::map<std::size_t, TriangleSoup> cache;
  auto it = cache.find(triangles);
  if (it == cache.end()) it = cache.emplace(triangles, torus_stl_soup(triangles)).first;
  return it->second;
}

void revolve_torus(benchmark::State& state) {
  const auto triangles = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) {
    const TriangleSoup soup = torus_soup(triangles);
    benchmark::DoNotOptimize(soup.triangles.size());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * triangles));
}
BENCHMARK(revolve_torus)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond)->UseRealTime();

void encode_stl_torus(benchmark::State& state) {
  const TriangleSoup soup = torus_soup(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(encode_stl(soup).size());
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * (84 + 50 * soup.triangles.size())));
}
BENCHMARK(encode_stl_torus)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond)->UseRealTime();

/// Weld of an STL-style torus; range(1) is the tolerance in 1e-6 units (0: exact).
void weld_torus(benchmark::State& state) {
  const TriangleSoup& soup = stl_soup(static_cast<std::size_t>(state.range(0)));
  const WeldOptions options{static_cast<double>(state.range(1)) * 1e-6};
  std::size_t merged = 0;
  for (auto _ : state) merged = weld(soup, options).merged_vertices;
  state.counters["merged"] = static_cast<double>(merged);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * soup.vertices.size()));
}
// Exact; a tolerance well under the edge length (1e-6); one larger than the
// whole torus (100: every vertex in one cell, quadratic before the grid of
// united cells).
BENCHMARK(weld_torus)
    ->Args({100'000, 0})
    ->Args({1'000'000, 0})
    ->Args({1'000'000, 1})
    ->Args({1'000'000, 100'000'000})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace fabmesh::bench
