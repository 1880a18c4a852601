// Kernels of validation: topology (sort-based on a soup; a halfedge Mesh is
// analysed through to_soup) and the self-intersection test (fast vs the CGAL
// reference).
#include <benchmark/benchmark.h>

#include <map>

#include "bench/bench_meshes.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/validation/detail/self_intersect.h"
#include "geometry/validation/detail/self_intersect_reference.h"
#include "geometry/validation/detail/topology.h"

namespace fabmesh::bench {
namespace {

/// The indexed torus of `triangles` triangles, built once per size.
const TriangleSoup& soup(std::size_t triangles) {
  static std::map<std::size_t, TriangleSoup> cache;
  auto it = cache.find(triangles);
  if (it == cache.end()) it = cache.emplace(triangles, torus_soup(triangles)).first;
  return it->second;
}

void topology_soup(benchmark::State& state) {
  const TriangleSoup& s = soup(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(analyse_topology(s).edges);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * s.triangles.size()));
}
BENCHMARK(topology_soup)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond)->UseRealTime();

void topology_mesh(benchmark::State& state) {
  const Mesh mesh = torus_mesh(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(analyse_topology(to_soup(mesh)).edges);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * mesh.n_faces()));
}
BENCHMARK(topology_mesh)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond)->UseRealTime();

/// range(1): 1 = the fast test, 0 = the reference; range(2): 1 = all cores.
void self_intersection(benchmark::State& state) {
  const TriangleSoup& s = soup(static_cast<std::size_t>(state.range(0)));
  SelfIntersectOptions options;
  options.parallel = state.range(2) != 0;
  std::size_t count = 0;
  for (auto _ : state) {
    count = state.range(1) ? find_self_intersections(s, {}, options).count
                           : find_self_intersections_reference(s, {}, options).count;
  }
  state.counters["pairs"] = static_cast<double>(count);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * s.triangles.size()));
}
BENCHMARK(self_intersection)
    ->ArgNames({"triangles", "fast", "parallel"})
    ->ArgsProduct({{100'000, 1'000'000}, {1, 0}, {1, 0}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace fabmesh::bench
