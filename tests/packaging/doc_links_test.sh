#!/usr/bin/env bash
# The installed README and documentation link to what is installed: every
# relative link of a Markdown file under DOCDIR (README.md, docs/*.md) names a
# file or folder that exists where it is installed, and so does every path
# under configs/examples/ the README names (the example designs it tells a
# user to run). Usage: doc_links_test.sh DOCDIR   (e.g. PREFIX/share/doc/fabmesh)
set -uo pipefail
docdir=$1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
[[ -f $docdir/README.md ]] || { echo "FAIL: no README.md in $docdir"; exit 1; }
checked=0
while IFS= read -r -d '' page; do
  folder=$(dirname "$page")
  # Inline links [text](target) outside code spans; anchors and web addresses are not files.
  # shellcheck disable=SC2016  # the backquotes are sed's, not the shell's
  while IFS= read -r target; do
    target=${target%%#*}
    [[ -z $target || $target == *://* || $target == mailto:* ]] && continue
    checked=$((checked + 1))
    [[ -e $folder/$target ]] || fail "${page#"$docdir"/} links $target, which is not installed"
  done < <(sed 's/`[^`]*`//g' "$page" | grep -oE '\]\([^) ]+\)' | sed -E 's/^\]\(//; s/\)$//')
done < <(find "$docdir" -name '*.md' -print0)
while IFS= read -r path; do
  checked=$((checked + 1))
  [[ -e $docdir/$path ]] || fail "README.md names $path, which is not installed"
done < <(grep -oE 'configs/examples/[A-Za-z0-9_.*-]*' "$docdir/README.md" | grep -v '\*' | sort -u)
((checked > 20)) || fail "only $checked links found in $docdir: not the installed documentation?"
if ((failures > 0)); then
  echo "$failures failure(s)"
  exit 1
fi
echo "the $checked links and paths of the installed documentation in $docdir resolve"
