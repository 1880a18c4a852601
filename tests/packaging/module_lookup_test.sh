#!/usr/bin/env bash
# fabmesh finds its modules (fabmesh-step.so, fabmesh-http.so) relative to
# its own real file, never the working folder. Run as a user runs it, from an
# unrelated folder: by the bare name `fabmesh` found on PATH, through a
# symbolic link (by path and on PATH), it writes a STEP file, and `fabmesh
# studio` serves its page. A copy of the program with no modules beside it,
# asked for STEP, exits 5 naming the module and where it was looked for, and
# writes nothing (an installation fault, not a skipped output).
# Usage: module_lookup_test.sh FABMESH DESIGN.yaml
# (FABMESH the build's or an installed program; DESIGN a vessel design file.)
set -uo pipefail
program=$(realpath "$1") design=$(realpath "$2")
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
work=$(mktemp -d "${TMPDIR:-/tmp}/fabmesh-modules.XXXXXX")
studio_pid=""
cleanup() {
  if [[ -n $studio_pid ]]; then kill "$studio_pid" 2>/dev/null; fi
  rm -rf "$work"
}
trap cleanup EXIT
mkdir -p "$work/elsewhere" "$work/links" "$work/alone/bin"
ln -s "$program" "$work/links/fabmesh"
program_dir=$(dirname "$program")

# writes_step HOW COMMAND...: runs COMMAND in an unrelated folder asking for a STEP file.
writes_step() {
  local how=$1
  shift
  rm -rf "$work/elsewhere/out"
  if ! (cd "$work/elsewhere" && "$@" run "$design" --export-format step -o out/ -q) >"$work/log" 2>&1; then
    fail "fabmesh $how failed to write a STEP file: $(cat "$work/log")"
  elif ! grep -q "ISO-10303-21" "$work/elsewhere/out/"*.step; then
    fail "fabmesh $how wrote no STEP file"
  fi
}
writes_step "from PATH" env PATH="$program_dir:$PATH" fabmesh
writes_step "through a symbolic link" "$work/links/fabmesh"
writes_step "through a symbolic link on PATH" env PATH="$work/links:$PATH" fabmesh
writes_step "by a relative path" ../links/fabmesh

# The studio from PATH: it prints its address once it serves, and serves the page.
(cd "$work/elsewhere" && exec env PATH="$program_dir:$PATH" fabmesh studio "$design" --no-open -q) \
  >"$work/studio.out" 2>"$work/studio.err" &
studio_pid=$!
url=""
for _ in $(seq 1 300); do
  url=$(head -n 1 "$work/studio.out")
  [[ -n $url ]] && break
  kill -0 "$studio_pid" 2>/dev/null || break
  sleep 0.1
done
if [[ -z $url ]]; then
  fail "fabmesh studio from PATH did not start: $(cat "$work/studio.err")"
elif ! /usr/bin/python3 -c "import sys, urllib.request; sys.exit(urllib.request.urlopen(sys.argv[1], timeout=30).status != 200)" "$url"; then
  fail "fabmesh studio from PATH does not serve its page at $url"
fi
kill -TERM "$studio_pid" 2>/dev/null
wait "$studio_pid" 2>/dev/null
studio_pid=""

# A copy of the program with no modules beside it: STEP asked for, exit 5.
cp "$program" "$work/alone/bin/fabmesh"
{ sed '/^outputs:/d' "$design"; echo "outputs: [stl, step]"; } >"$work/asks_step.yaml"
for asked in "$work/asks_step.yaml" "$design --export-format step"; do
  rm -rf "$work/alone/out"
  # shellcheck disable=SC2086
  (cd "$work/elsewhere" && "$work/alone/bin/fabmesh" run $asked -o "$work/alone/out/") >"$work/alone.out" 2>"$work/alone.err"
  code=$?
  [[ $code == 5 ]] || fail "'fabmesh run $asked' without its STEP module exited $code, not 5: $(cat "$work/alone.err")"
  grep -q "environment error: step: fabmesh's module fabmesh-step.so was not found" "$work/alone.err" ||
    fail "the message does not name the module: $(cat "$work/alone.err")"
  grep -qF "$work/alone/lib/fabmesh/fabmesh-step.so" "$work/alone.err" ||
    fail "the message does not say where the module was looked for: $(cat "$work/alone.err")"
  if [[ -e $work/alone/out ]] && [[ -n $(ls -A "$work/alone/out") ]]; then
    fail "'fabmesh run $asked' without its STEP module wrote $(ls -A "$work/alone/out")"
  fi
done

if ((failures > 0)); then
  echo "$failures failure(s)"
  exit 1
fi
echo "$program finds its modules from PATH, through links and from any folder; a missing module is exit 5"
