# Sourced by slurm-render and parallel-render: the options they share and the plan
# of sample ranges. Not a command.
#
# parse_common USAGE "$@" sets scene, spp, tasks, dir, output, vkrt and
# render_options (after --), and leaves the driver's own options in `rest`: those
# named in `driver_flags` alone, those in `driver_values` with their value.

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

die() { echo "$(basename "$0"): $*" >&2; exit 2; }

parse_common() {
  local usage=$1
  shift
  scene="" spp="" tasks="" dir="" output="" vkrt="vkrt"
  render_options=() rest=()
  while [ $# -gt 0 ]; do
    case "$1" in
      --spp) spp=${2:?--spp needs a number}; shift 2 ;;
      --tasks) tasks=${2:?--tasks needs a number}; shift 2 ;;
      --dir) dir=${2:?--dir needs a directory}; shift 2 ;;
      -o|--output) output=${2:?-o needs an image path}; shift 2 ;;
      --vkrt) vkrt=${2:?--vkrt needs the path of vkrt}; shift 2 ;;
      -h|--help) echo "$usage"; exit 0 ;;
      --) shift; render_options=("$@"); break ;;
      -*)
        if [[ " ${driver_flags[*]} " == *" $1 "* ]]; then
          rest+=("$1"); shift
        elif [[ " ${driver_values[*]} " == *" $1 "* ]]; then
          [ $# -ge 2 ] || die "$1 needs a value"
          rest+=("$1" "$2"); shift 2
        else
          die "unknown option '$1'"$'\n'"$usage"
        fi ;;
      *) [ -z "$scene" ] || die "one scene only ('$scene', then '$1')"; scene=$1; shift ;;
    esac
  done
  [ -n "$scene" ] && [ -n "$spp" ] && [ -n "$tasks" ] && [ -n "$dir" ] && [ -n "$output" ] ||
    die "SCENE, --spp, --tasks, --dir and -o are required"$'\n'"$usage"
  [[ "$spp" =~ ^[1-9][0-9]*$ ]] || die "--spp must be a whole number above 0, not '$spp'"
  [[ "$tasks" =~ ^[1-9][0-9]*$ ]] || die "--tasks must be a whole number above 0, not '$tasks'"
  [ -f "$scene" ] || die "no scene file '$scene'"
  # Every machine must find these at the same paths.
  scene=$(realpath "$scene")
  mkdir -p "$dir/logs"
  dir=$(realpath "$dir")
  output=$(realpath -m "$output")
  if [[ "$vkrt" == */* ]]; then vkrt=$(realpath "$vkrt"); fi
  command -v "$vkrt" >/dev/null || die "no vkrt at '$vkrt' (give its path with --vkrt)"
}

# The partial files finished so far.
partials() { compgen -G "$dir/samples-*.exr" || true; }

# Writes $dir/ranges.txt: the samples of 0:spp no finished partial holds, cut for
# `tasks` machines (vkrt merge --missing). Sets `count` to its number of lines.
plan_ranges() {
  local files
  mapfile -t files < <(partials)
  "$vkrt" merge --missing --samples "0:$spp" --tasks "$tasks" "${files[@]}" >"$dir/ranges.txt"
  count=$(wc -l <"$dir/ranges.txt")
}

# The command that merges every partial into the output, as one shell line.
merge_command() {
  printf '%q merge --samples 0:%s %q/samples-*.exr -o %q' "$vkrt" "$spp" "$dir" "$output"
}
