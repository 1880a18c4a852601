#!/usr/bin/env bash
# Runs clang-tidy (.clang-tidy: every warning an error) on fabmesh's own
# sources with the compile commands of a configured build folder.
# Usage: scripts/run-clang-tidy.sh [BUILD_DIR] [--since GIT_REF]
#   BUILD_DIR  a folder configured by CMake (default: build)
#   --since    only the .cpp files changed since GIT_REF (and those whose
#              headers changed), for a quick local check; CI checks all.
set -euo pipefail
cd "$(dirname "$0")/.."
build=build
since=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --since) since="$2"; shift 2 ;;
    *) build="$1"; shift ;;
  esac
done
[[ -f "$build/compile_commands.json" ]] || {
  echo "run-clang-tidy: $build/compile_commands.json not found; configure first (cmake -S . -B $build)" >&2; exit 2; }

mapfile -t files < <(git ls-files 'geometry/*.cpp' 'io/*.cpp' 'pipeline/*.cpp' 'api/*.cpp')
if [[ -n "$since" ]]; then
  mapfile -t changed < <(git diff --name-only "$since" -- geometry io pipeline api)
  selected=()
  for f in "${files[@]}"; do
    for c in "${changed[@]}"; do
      if [[ "$f" == "$c" || "$f" == "${c%.h}.cpp" ]]; then selected+=("$f"); break; fi
    done
  done
  files=("${selected[@]}")
fi
if [[ ${#files[@]} -eq 0 ]]; then echo "run-clang-tidy: no files to check"; exit 0; fi
echo "run-clang-tidy: checking ${#files[@]} files"
# run-clang-tidy exits non-zero when any file has an error (every warning is one here).
run-clang-tidy -p "$build" -j "${JOBS:-2}" -quiet "${files[@]/#/$PWD/}" > "$build/clang-tidy.log" 2>&1 || {
  sed 's/\x1b\[[0-9;]*m//g' "$build/clang-tidy.log" | grep -E "(warning|error):" | sort -u >&2
  echo "run-clang-tidy: clang-tidy found problems (full log: $build/clang-tidy.log)" >&2
  exit 1
}
echo "run-clang-tidy: no warnings"
