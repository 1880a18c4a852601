#!/usr/bin/env bash
# Extra CI, beyond the README's test command:
#  (a) fuzz every mesh reader, the design reader (design YAML, points CSV,
#      DXF templates)
#      and the batch readers (manifests, ledgers) with libFuzzer (clang,
#      ASan+UBSan) for a fixed time on the seeds in tests/data/fuzz-seeds/;
#      any finding fails;
#  (b) run the whole suite under the same sanitizers.
# Both use one clang tree, build-sanitize: the fuzz targets are built first,
# the program and the suite after them on the same library.
# Usage: scripts/ci-extra.sh [fuzz|sanitize|all]   (default all); CI runs the
# halves of each apart (fuzz-build, fuzz-run, sanitize-build, sanitize-test).
# Environment: FUZZ_SECONDS (per reader, default 20), JOBS (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."

what="${1:-all}"
FUZZ_SECONDS="${FUZZ_SECONDS:-20}"
JOBS="${JOBS:-2}"
readers=(stl obj ply off draco 3mf gltf design csv dxf manifest ledger)
dir=build-sanitize

# One clang tree for both halves: the library built once with ASan and UBSan,
# libFuzzer's coverage on the readers only (fuzz/CMakeLists.txt), and linked
# into the fuzz targets, the program and its test suite. Line tables are all
# ASan's and UBSan's stacks need, and build markedly faster than full debug
# information. clang's ASan and UBSan are the reference ones, and on this code
# it compiles them 2.3 times faster than g++ does (alpha_wrap.cpp, -O2 and
# line tables: 50 s against 115 s of CPU time; g++'s UBSan at -O2 is the cost).
# The shared library and the Python module are the same pipeline code behind
# a thin layer (an interpreter not built with ASan cannot load an ASan module
# anyway), and are left out.
configure() {
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
    -DCMAKE_CXX_COMPILER=clang++ -DFABMESH_SANITIZE=ON -DFABMESH_BUILD_FUZZERS=ON \
    -DFABMESH_BUILD_TESTS=ON -DFABMESH_PYTHON=OFF
}

fuzz_build() {
  configure
  cmake --build "$dir" -j"$JOBS" --target "${readers[@]/#/fuzz_}"
}

fuzz_run() {
  for r in "${readers[@]}"; do
    # New inputs go to a scratch corpus; the committed seeds are only read.
    local corpus
    corpus="$(mktemp -d)"
    echo "ci-extra: fuzzing the $r reader for ${FUZZ_SECONDS}s"
    # Fuzzing runs single-threaded; libFuzzer exits non-zero on a crash, a
    # sanitizer report, a timeout (-timeout per input: 30 s, above the 8-9 s a
    # manifest of a million variants may take under the sanitizers) or an
    # out-of-memory.
    local log="$dir/fuzz/fuzz-$r.log" status=0
    "$dir/fuzz/fuzz_$r" -max_total_time="$FUZZ_SECONDS" -timeout=30 -rss_limit_mb=2048 \
      -artifact_prefix="$dir/fuzz/finding-$r-" -print_final_stats=1 \
      "$corpus" "tests/data/fuzz-seeds/$r" >"$log" 2>&1 || status=$?
    tail -n 8 "$log"
    rm -rf "$corpus"
    if [[ "$status" -ne 0 ]]; then
      # The report and its stack, not only libFuzzer's closing statistics.
      grep -m1 -A60 -E "ERROR|runtime error|Deadly|out-of-memory|timeout" "$log" >&2 || tail -n 80 "$log" >&2
      echo "ci-extra: the $r fuzzer found a problem (exit $status); see $dir/fuzz/finding-$r-*" >&2
      exit 1
    fi
  done
}

sanitize_build() {
  # The program and its test suite, on the fuzz targets' library. The "router
  # program" tests are left to the main suite: their time goes to the CNCjs
  # interpreter and to the test's own exact-distance measurements, while the
  # planning they measure runs under the sanitizers in the toolpath tests. The
  # studio's server (its session, routes and HTTP module, in-process) runs
  # under the sanitizers through its own test program; its page test, which
  # drives Chromium and node, is left to the main suite. So is the test that
  # gives PrusaSlicer every repaired corpus mesh: it repairs the same files
  # the same way as the corpus test (which asks only for the report as JSON
  # too, repairs each output again and checks it with CGAL), so under the
  # sanitizers it ran that code a second time (166 s of test time). So are
  # the other whole-program sweeps whose code the sanitized suite runs in
  # its own tests: FreeCAD's import of every example's STEP files (318 s
  # under the sanitizers, alone at the end), the byte-for-byte comparison of
  # two runs of every format of every example (643 s), and PrusaSlicer's
  # slicing of every case file (136 s; the cases are built under the
  # sanitizers by the casting tests). The lazy-libraries check reads the
  # shared library, which this build leaves out.
  configure
  cmake --build "$dir" -j"$JOBS" --target fabmesh fabmesh_tests fabmesh_studio_tests fabmesh_cnc_bench
}

sanitize_test() {
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir "$dir" --output-on-failure -j"$JOBS" \
    -E '^fabmesh_api_tests_NOT_BUILT|^studio_page$|^docs\.library_example_|^python$|^install_prefix$|^lazy_libraries$|^router program: |^repair: PrusaSlicer reads every repaired 3MF|^freecad_step$|^run: two runs write byte-identical files|^casting cases: PrusaSlicer '
}

case "$what" in
  fuzz) fuzz_build; fuzz_run ;;
  sanitize) sanitize_build; sanitize_test ;;
  all) fuzz_build; fuzz_run; sanitize_build; sanitize_test ;;
  # The halves, for CI to overlap a build with single-threaded work.
  fuzz-build) fuzz_build ;;
  fuzz-run) fuzz_run ;;
  sanitize-build) sanitize_build ;;
  sanitize-test) sanitize_test ;;
  *) echo "usage: $0 [fuzz|sanitize|all|fuzz-build|fuzz-run|sanitize-build|sanitize-test]" >&2; exit 2 ;;
esac
