#!/usr/bin/env bash
# The options of scripts/cluster/slurm-render and parallel-render: every mistake is
# one line naming it and exit status 2, before anything is submitted or run.
#   usage_test.sh VKRT SOURCE_DIR
set -euo pipefail
vkrt=$(realpath "$1")
scripts="$(realpath "$2")/scripts/cluster"
scene="$(realpath "$2")/scenes/default.json"
scratch=$(mktemp -d "${TMPDIR:-/tmp}/vkrt-usage.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# expect_refusal TEXT COMMAND...: exit 2 and TEXT in the message.
expect_refusal() {
  local text=$1 status=0
  shift
  "$@" >"$scratch/out" 2>"$scratch/err" || status=$?
  [ "$status" -eq 2 ] || fail "exit $status, not 2, for: $* ($(cat "$scratch/err"))"
  grep -qF -- "$text" "$scratch/err" || fail "no '$text' in the message for: $*: $(cat "$scratch/err")"
}

common=("$scene" --spp 8 --tasks 2 --dir "$scratch/parts" -o "$scratch/out.exr" --vkrt "$vkrt")
for driver in slurm-render parallel-render; do
  expect_refusal "are required" "$scripts/$driver" "$scene" --spp 8
  expect_refusal "--spp must be a whole number" "$scripts/$driver" "$scene" --spp x --tasks 2 --dir "$scratch/p" -o o.exr
  expect_refusal "--tasks must be a whole number" "$scripts/$driver" "$scene" --spp 8 --tasks 0 --dir "$scratch/p" -o o.exr
  expect_refusal "no scene file" "$scripts/$driver" "$scratch/none.json" --spp 8 --tasks 2 --dir "$scratch/p" -o o.exr
  expect_refusal "unknown option '--bogus'" "$scripts/$driver" "${common[@]}" --bogus
  expect_refusal "no vkrt at" "$scripts/$driver" "$scene" --spp 8 --tasks 2 --dir "$scratch/p" -o o.exr --vkrt "$scratch/none"
done
expect_refusal "--hosts FILE is required" "$scripts/parallel-render" "${common[@]}"
expect_refusal "no hosts file" "$scripts/parallel-render" "${common[@]}" --hosts "$scratch/none"
echo localhost >"$scratch/hosts"
expect_refusal "--retries must be" "$scripts/parallel-render" "${common[@]}" --hosts "$scratch/hosts" --retries 0
echo "PASS"
