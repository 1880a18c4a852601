#!/usr/bin/env bash
# The manual page and the bash completion against the program itself: every
# command of `fabmesh --help` and every option of `fabmesh COMMAND --help` must
# be in the manual page (in that command's section) and be offered by the
# completion after the command; neither may list an option the program no
# longer has. The page must format without warnings and carry the program's
# version. Usage: cli_docs_test.sh FABMESH MANPAGE COMPLETION
set -uo pipefail
fabmesh=$1 manpage=$2 completion=$3
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# The options of one --help text: the first column of the lines under
# "Options:", split at commas ("-o,--output TEXT" gives -o and --output).
help_options() {
  awk '/^Options:/ {on = 1; next} /^[A-Za-z]/ {on = 0} on && /^  -/ {print $1}' | tr ',' '\n' | grep -E '^-' | sort -u
}
help_commands() {
  awk '/^Subcommands:/ {on = 1; next} /^[A-Za-z]/ {on = 0} on && /^  [a-z]/ {print $1}'
}

top_help=$("$fabmesh" --help) || { fail "fabmesh --help exited non-zero"; exit 1; }
global_options=$(help_options <<<"$top_help")
commands=$(help_commands <<<"$top_help")
[[ -n "$global_options" ]] || fail "no options parsed from fabmesh --help"
[[ $(wc -w <<<"$commands") -ge 7 ]] || fail "fewer than 7 commands parsed from fabmesh --help: $commands"

# The manual page's source with roff's \- as plain '-', and its sections.
man_text=$(sed 's/\\-/-/g' "$manpage")
section() {  # the lines from the heading matching $1 to the next heading
  awk -v head="$1" 'index($0, head) == 1 {on = 1; next} /^\.S[HS] / {on = 0} on' <<<"$man_text"
}
has_option() {  # whether the text on stdin names option $1 as a whole word
  grep -qE -- "(^|[^A-Za-z0-9-])$1([^A-Za-z0-9-]|\$)"
}
long_options_in() { grep -oE -- '(^|[^A-Za-z0-9-])--[a-z][a-z-]*' | sed 's/^[^-]*//' | sort -u; }

# bash completion: what it offers for the words given.
complete_words() {
  bash -c 'shopt -s extglob; source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _fabmesh; printf "%s\n" "${COMPREPLY[@]}"' \
    _ "$completion" "$@"
}

# Global options and the command list.
global_section=$(section ".SH OPTIONS")
for option in $global_options; do
  has_option "$option" <<<"$global_section" || fail "man page OPTIONS lacks $option"
done
offered=$(complete_words fabmesh -)
for option in $global_options; do
  grep -qx -- "$option" <<<"$offered" || fail "completion of 'fabmesh -' lacks $option"
done
offered_commands=$(complete_words fabmesh "")
for command in $commands; do
  grep -qx -- "$command" <<<"$offered_commands" || fail "completion of 'fabmesh ' lacks the command $command"
  grep -q "^\.SS \"fabmesh $command " <<<"$man_text" || fail "man page has no section for the command $command"
done
for command in $offered_commands; do
  grep -qx -- "$command" <<<"$commands" || fail "completion offers the command $command, which fabmesh --help does not list"
done

# Each command's options.
for command in $commands; do
  command_help=$("$fabmesh" "$command" --help) || { fail "fabmesh $command --help exited non-zero"; continue; }
  options=$(help_options <<<"$command_help")
  [[ -n "$options" ]] || fail "no options parsed from fabmesh $command --help"
  man_section=$(section ".SS \"fabmesh $command ")
  offered=$(complete_words fabmesh "$command" -)
  for option in $options; do
    case "$option" in -h | --help) ;; *)
      has_option "$option" <<<"$man_section" || fail "man page section of $command lacks $option" ;;
    esac
    grep -qx -- "$option" <<<"$offered" || fail "completion of 'fabmesh $command -' lacks $option"
  done
  for option in $(long_options_in <<<"$man_section") $offered; do
    grep -qx -- "$option" <<<"$options" || grep -qx -- "$option" <<<"$global_options" ||
      fail "$command: $option is documented or completed but fabmesh $command --help does not list it"
  done
done

# The page formats cleanly and states the program's version.
version=$("$fabmesh" --version | awk '{print $NF}')
grep -q "^\.TH FABMESH 1 .*\"fabmesh $version\"" "$manpage" || fail "man page .TH does not say fabmesh $version"
if ! command -v groff >/dev/null; then
  fail "groff is missing (Debian: groff-base): cannot check the man page formats"
else
  warnings=$(LC_ALL=C.UTF-8 groff -man -Tutf8 -ww -z "$manpage" 2>&1)
  [[ -z "$warnings" ]] || fail "groff warns on the man page: $warnings"
fi

if ((failures > 0)); then
  echo "$failures failure(s)"
  exit 1
fi
echo "man page and completion list every command and option of $("$fabmesh" --version)"
