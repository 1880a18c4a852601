# bash completion for fabmesh: its commands, each command's options, and the
# values they take (files of the kind a command reads, formats, units).
# tests/packaging/cli_docs_test.sh checks that it offers every option of
# `fabmesh COMMAND --help`.

_fabmesh_commands="run plot preview check optimize sample batch"
_fabmesh_global_options="-h --help --version -q --quiet -v --verbose"

_fabmesh_options() {
  case "$1" in
    run) echo "-o --output --export-format --export-units --json --report -D --define" ;;
    plot) echo "-o --output --width --height -D --define" ;;
    preview) echo "-o --output --views --width --height -D --define" ;;
    check) echo "--json --weld-tolerance --max-seconds" ;;
    optimize) echo "-D --define --json" ;;
    sample) echo "-D --define --csv --tolerance" ;;
    batch) echo "-o --output --jobs --shard --force --json --slurm --array-size --report --merge" ;;
  esac
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
      COMPREPLY=($(compgen -W "stl drc 3mf glb glb_draco obj ply off dxf svg mould_stl mould_3mf nc toolpath_svg plot png" -- "$cur"))
      return ;;
    --export-units)
      COMPREPLY=($(compgen -W "mm cm m in" -- "$cur"))
      return ;;
    --views)
      COMPREPLY=($(compgen -W "1 2" -- "$cur"))
      return ;;
    --report)
      compopt -o filenames 2>/dev/null
      COMPREPLY=($(compgen -f -X '!*.html' -- "$cur") $(compgen -d -- "$cur"))
      return ;;
    --merge)
      compopt -o filenames 2>/dev/null
      COMPREPLY=($(compgen -d -- "$cur"))
      return ;;
    -o | --output)
      compopt -o filenames 2>/dev/null
      COMPREPLY=($(compgen -f -- "$cur"))
      return ;;
    -D | --define | --width | --height | --jobs | --shard | --array-size | --weld-tolerance | --max-seconds | --tolerance)
      return ;;
  esac

  if [[ -z "$command" ]]; then
    if [[ "$cur" == -* ]]; then
      COMPREPLY=($(compgen -W "$_fabmesh_global_options" -- "$cur"))
    else
      COMPREPLY=($(compgen -W "$_fabmesh_commands" -- "$cur"))
    fi
    return
  fi

  if [[ "$cur" == -* ]]; then
    COMPREPLY=($(compgen -W "$(_fabmesh_options "$command") -h --help -q --quiet -v --verbose" -- "$cur"))
    return
  fi

  # Positional arguments: the files the command reads.
  compopt -o filenames 2>/dev/null
  case "$command" in
    check)
      COMPREPLY=($(compgen -f -X '!*.@(stl|STL|obj|OBJ|ply|PLY|off|OFF|drc|DRC|3mf|3MF|glb|GLB|gltf|GLTF)' -- "$cur") $(compgen -d -- "$cur")) ;;
    preview)
      COMPREPLY=($(compgen -f -X '!*.@(yaml|yml|stl|STL|obj|OBJ|ply|PLY|off|OFF|drc|DRC|3mf|3MF|glb|GLB|gltf|GLTF)' -- "$cur") $(compgen -d -- "$cur")) ;;
    *)
      COMPREPLY=($(compgen -f -X '!*.@(yaml|yml)' -- "$cur") $(compgen -d -- "$cur")) ;;
  esac
}
complete -F _fabmesh fabmesh
