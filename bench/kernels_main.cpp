// Google Benchmark's main for fabmesh_bench (the kernels are registered in
// the other files of this target).
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
