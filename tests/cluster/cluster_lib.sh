# Sourced by the cluster tests: a scratch directory cleaned up on exit, free ports,
# waiting, and the render every distributed one must equal. Not a test.
set -euo pipefail
vkrt=$(realpath "$1")
source_dir=$(realpath "$2")
scripts="$source_dir/scripts/cluster"
scene="$source_dir/scenes/spheres_triangles.json"   # jittered: every sample differs
render_options=(--width 32 --height 24 --backend cpu)
spp=8

scratch=$(mktemp -d "${TMPDIR:-/tmp}/vkrt-cluster.XXXXXX")
chmod 755 "$scratch"
cleanups=()
# Stops the daemon whose pid FILE holds and waits (up to 10 s) until it has gone: a
# daemon still saving its state on the way out would race the scratch removal.
stop_daemon() {
  local pid i
  pid=$(cat "$1" 2>/dev/null) || return 0
  kill "$pid" 2>/dev/null || return 0
  for ((i = 0; i < 100; i++)); do
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.1
  done
  kill -9 "$pid" 2>/dev/null || true
}
# Last started, first stopped: slurmd before slurmctld before munged.
cleanup() {
  local i
  for ((i = ${#cleanups[@]} - 1; i >= 0; i--)); do eval "${cleanups[i]}" || true; done
  rm -rf "$scratch"
}
trap cleanup EXIT

fail() { echo "FAIL: $*" >&2; exit 1; }
step() { echo "--- $*"; }

[ "$(id -u)" -eq 0 ] || fail "this test starts system daemons (sshd, slurmd) and must run as root"

# A TCP port nothing listens on.
free_port() {
  local port
  while :; do
    port=$(shuf -i 20000-60000 -n 1)
    ss -Htln "sport = :$port" | grep -q . || { echo "$port"; return; }
  done
}

# Runs "$@" until it succeeds, for at most $1 seconds.
wait_for() {
  local seconds=$1
  shift
  for _ in $(seq "$seconds"); do
    "$@" >/dev/null 2>&1 && return 0
    sleep 1
  done
  return 1
}

# The image one machine renders: what every distributed render must equal.
"$vkrt" render "$scene" --spp "$spp" -q "${render_options[@]}" -o "$scratch/whole.exr"

# Fails unless IMAGE equals the single render bit for bit.
expect_whole() {
  "$vkrt" compare "$scratch/whole.exr" "$1" --max-abs 0 >/dev/null ||
    fail "$1 differs from the single render: $("$vkrt" compare "$scratch/whole.exr" "$1")"
}
