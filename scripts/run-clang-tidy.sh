#!/usr/bin/env bash
# Runs clang-tidy (.clang-tidy: every warning an error) on fabmesh's own
# sources with the compile commands of a configured build folder.
# Usage: scripts/run-clang-tidy.sh [BUILD_DIR] [--since GIT_REF] [--skip-recorded] [--record]
#   BUILD_DIR        a folder configured by CMake (default: build)
#   --since          only the .cpp files changed since GIT_REF (and those whose
#                    headers changed), for a quick local check
#   --skip-recorded  leave out the files whose content key
#                    (scripts/clang-tidy-keys.py: the file preprocessed by
#                    clang with its flags, comments kept, every header it
#                    includes, .clang-tidy and the clang-tidy version) is in
#                    .ci/clang-tidy-passed: their verdict is known, every input
#                    to it being the same. CI runs this way; any change to a
#                    file, a header, a flag or the tool checks the file again.
#   --record         after a run with no warnings, write the checked files'
#                    keys into .ci/clang-tidy-passed (commit it)
set -euo pipefail
cd "$(dirname "$0")/.."
build=build
since=""
skip_recorded=0
record=0
passed=.ci/clang-tidy-passed
while [[ $# -gt 0 ]]; do
  case "$1" in
    --since) since="$2"; shift 2 ;;
    --skip-recorded) skip_recorded=1; shift ;;
    --record) record=1; shift ;;
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
keys=""
if ((skip_recorded || record)) && [[ ${#files[@]} -gt 0 ]]; then
  keys="$build/clang-tidy-keys.txt"
  scripts/clang-tidy-keys.py "$build" "${files[@]}" >"$keys"
fi
if ((skip_recorded)) && [[ -n $keys ]]; then
  all=${#files[@]}
  touch "$build/clang-tidy-none.txt"
  [[ -f $passed ]] || passed_or_none="$build/clang-tidy-none.txt"
  mapfile -t files < <(awk 'FILENAME == ARGV[1] { known[$1 "  " $2] = 1; next }
                            !(($1 "  " $2) in known) { print $2 }' "${passed_or_none:-$passed}" "$keys")
  echo "run-clang-tidy: $((all - ${#files[@]})) of $all files as recorded passing in $passed (same content key)"
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
if ((record)); then
  # The keys of the files just checked replace their old lines; the others stay.
  printf '%s\n' "${files[@]}" >"$build/clang-tidy-checked.txt"
  touch "$passed"
  awk 'FILENAME == ARGV[1] { checked[$0] = 1; next }
       FILENAME == ARGV[2] { if (!($2 in checked)) print; next }
       ($2 in checked) { print }' "$build/clang-tidy-checked.txt" "$passed" "$keys" | sort -k2 >"$passed.new"
  mv "$passed.new" "$passed"
  echo "run-clang-tidy: $(wc -l <"$passed") files recorded as passing in $passed"
fi
