# bash completion for fabmesh: its commands, each command's options, and the
# values they take (files of the kind a command reads, formats, units).
# tests/packaging/cli_docs_test.sh checks that it offers every option of
# `fabmesh COMMAND --help`.

_fabmesh_commands="run plot preview check repair optimize sample params batch studio"
_fabmesh_global_options="-h --help --version -q --quiet -v --verbose"

_fabmesh_options() {
  case "$1" in
    run) echo "-o --output --export-format --export-units --json --report --watch -D --define -P --parameter-set" ;;
    plot) echo "-o --output --width --height -D --define -P --parameter-set" ;;
    preview) echo "-o --output --views --width --height -D --define -P --parameter-set" ;;
    check) echo "--json --weld-tolerance --max-seconds --max-locations --mark" ;;
    repair) echo "-o --output --max-deviation --wrap --weld-distance --no-fill --max-seconds --dry-run --json" ;;
    optimize) echo "-D --define -P --parameter-set --json" ;;
    sample) echo "-D --define -P --parameter-set --csv --tolerance" ;;
    params) echo "-D --define -P --parameter-set --json" ;;
    studio) echo "--port --host --no-open -o --output" ;;
    batch) echo "-o --output --jobs --shard --force --json --slurm --array-size --report --merge" ;;
  esac
}

# COMPREPLY from a word list ($1) or from files matching a pattern ($1, as
# compgen -X takes it; empty: any file) and folders, one name a line so that
# names with spaces stay whole.
_fabmesh_words() {
  local IFS=$' \t\n'
  COMPREPLY=($(compgen -W "$1" -- "$2"))
}
_fabmesh_files() {
  local IFS=$'\n'
  compopt -o filenames 2>/dev/null
  if [[ -n $1 ]]; then
    COMPREPLY=($(compgen -f -X "$1" -- "$2") $(compgen -d -- "$2"))
  else
    COMPREPLY=($(compgen -f -- "$2"))
  fi
}

_fabmesh() {
  local cur prev command="" i
  COMPREPLY=()
  cur="${COMP_WORDS[COMP_CWORD]}"
  prev=""
  ((COMP_CWORD > 0)) && prev="${COMP_WORDS[COMP_CWORD - 1]}"
  for ((i = 1; i < COMP_CWORD; i++)); do
    case " $_fabmesh_commands " in
      *" ${COMP_WORDS[i]} "*) command="${COMP_WORDS[i]}"; break ;;
    esac
  done

  # The value of the option before the cursor.
  case "$prev" in
    --export-format)
      _fabmesh_words "stl drc 3mf glb glb_draco obj ply off dxf svg mould_stl mould_3mf mould_step master_stl master_3mf master_step case_stl case_3mf case_step nc toolpath_svg step plot png" "$cur"
      return ;;
    --export-units)
      _fabmesh_words "mm cm m in" "$cur"
      return ;;
    --views)
      _fabmesh_words "1 2" "$cur"
      return ;;
    --report)
      _fabmesh_files '!*.@(html|HTML)' "$cur"
      return ;;
    --mark)
      _fabmesh_files '!*.@(glb|ply|GLB|PLY)' "$cur"
      return ;;
    --merge)
      local IFS=$'\n'
      compopt -o filenames 2>/dev/null
      COMPREPLY=($(compgen -d -- "$cur"))
      return ;;
    -o | --output)
      _fabmesh_files "" "$cur"
      return ;;
    -D | --define | -P | --parameter-set | --width | --height | --jobs | --shard | --array-size | --weld-tolerance | --max-seconds | --max-locations | --tolerance)
      return ;;
  esac

  if [[ -z "$command" ]]; then
    if [[ "$cur" == -* ]]; then
      _fabmesh_words "$_fabmesh_global_options" "$cur"
    else
      _fabmesh_words "$_fabmesh_commands" "$cur"
    fi
    return
  fi

  if [[ "$cur" == -* ]]; then
    _fabmesh_words "$(_fabmesh_options "$command") -h --help -q --quiet -v --verbose" "$cur"
    return
  fi

  # Positional arguments: the files the command reads.
  case "$command" in
    check | repair) _fabmesh_files '!*.@(stl|STL|obj|OBJ|ply|PLY|off|OFF|drc|DRC|3mf|3MF|glb|GLB|gltf|GLTF)' "$cur" ;;
    preview) _fabmesh_files '!*.@(yaml|yml|YAML|stl|STL|obj|OBJ|ply|PLY|off|OFF|drc|DRC|3mf|3MF|glb|GLB|gltf|GLTF)' "$cur" ;;
    *) _fabmesh_files '!*.@(yaml|yml|YAML)' "$cur" ;;
  esac
}
complete -F _fabmesh fabmesh
