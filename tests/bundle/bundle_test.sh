#!/usr/bin/env bash
# scripts/bundle's archive: under 64 MiB; unpacked into an empty root file system that
# holds only glibc and a Vulkan driver (lavapipe's ICD and the libraries it needs),
# through bubblewrap, it renders a scene and a textured glTF asset on both backends
# bit for bit as the build's program does; a library taken out of it makes it fail,
# so a library the bundle forgets fails here; and its GPU check runs scaled down
# (scripts/gpu-check --smoke) with every part done and every scene agreeing.
#   bundle_test.sh VKRT SOURCE_DIR
set -euo pipefail
vkrt=$(realpath "$1")
source_dir=$(realpath "$2")
scratch=$(mktemp -d "${TMPDIR:-/tmp}/vkrt-bundle-test.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

VKRT="$vkrt" "$source_dir/scripts/bundle" "$scratch/out" >"$scratch/bundle.log" 2>&1 || { cat "$scratch/bundle.log"; fail "scripts/bundle"; }
archive=$(ls "$scratch"/out/vkrt-*-linux-x86_64.tar.gz)
size=$(stat -c %s "$archive")
echo "archive: $(basename "$archive"), $((size / 1024)) KiB"
[ "$size" -lt $((64 * 1024 * 1024)) ] || fail "the bundle is over 64 MiB"
mkdir "$scratch/unpacked"
tar -C "$scratch/unpacked" -xzf "$archive"
bundle=$(ls -d "$scratch"/unpacked/vkrt-*)
for f in README bin/vkrt bin/gpu-check share/vkrt/scenes/default.json licenses/libvulkan1/copyright; do
  [ -e "$bundle/$f" ] || fail "the bundle has no $f"
done

# The empty root: glibc, the dynamic loader, lavapipe and what it links, nothing else.
icd=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json
driver=$(sed -n 's/.*"library_path": *"\([^"]*\)".*/\1/p' "$icd")
root_args=(--tmpfs / --proc /proc --dev /dev --tmpfs /tmp --symlink usr/lib /lib --symlink usr/lib64 /lib64
           --setenv VK_DRIVER_FILES "$icd")
for f in /usr/lib/x86_64-linux-gnu/libc.so.6 /usr/lib/x86_64-linux-gnu/libm.so.6 /usr/lib64/ld-linux-x86-64.so.2 \
         "$icd" "$driver" $(ldd "$driver" | awk '$3 ~ /^\// { print $3 }'); do
  root_args+=(--ro-bind "$(readlink -f "$f")" "$f")
done
in_root() {  # in_root BUNDLE_DIR COMMAND...: runs COMMAND with the bundle at /opt/vkrt
  local dir=$1; shift
  bwrap "${root_args[@]}" --ro-bind "$dir" /opt/vkrt --bind "$scratch/images" /out "$@"
}
mkdir "$scratch/images"

for scene in default.json gltf/still_life.glb; do
  name=$(echo "$scene" | tr '/.' '__')
  for backend in vulkan cpu; do
    in_root "$bundle" /opt/vkrt/bin/vkrt render "/opt/vkrt/share/vkrt/scenes/$scene" --backend "$backend" \
      --width 48 --height 36 --spp 4 -q -o "/out/$name.$backend.bundle.pfm" ||
      fail "$scene on $backend in the empty root"
    "$vkrt" render "$source_dir/scenes/$scene" --backend "$backend" --width 48 --height 36 --spp 4 -q \
      -o "$scratch/images/$name.$backend.build.pfm"
    cmp -s "$scratch/images/$name.$backend.bundle.pfm" "$scratch/images/$name.$backend.build.pfm" ||
      fail "$scene on $backend: the bundle's image differs from the build's"
    echo "$scene on $backend: bit for bit the build's image"
  done
done

# Without one of its libraries it cannot start: the root really holds nothing else.
cp -r "$bundle" "$scratch/broken"
rm "$scratch/broken/lib/libfmt.so.9"
if in_root "$scratch/broken" /opt/vkrt/bin/vkrt --version >"$scratch/broken.log" 2>&1; then
  fail "the bundle ran without libfmt"
fi
grep -q "libfmt.so.9" "$scratch/broken.log" || { cat "$scratch/broken.log"; fail "the loader's message does not name libfmt"; }
echo "without lib/libfmt.so.9 it refuses to start, naming it"

"$bundle/bin/gpu-check" --smoke "$scratch/check" 2>"$scratch/check.log" || { cat "$scratch/check.log"; fail "gpu-check --smoke"; }
report="$scratch/check/report.md"
for part in devices crosscheck spd sweep convergence largest submission; do
  grep -q "^| $part | ok |" "$report" || { cat "$report"; fail "gpu-check's part $part did not finish"; }
done
line=$(grep '^## Cross-check: ' "$report")
agreed=$(echo "$line" | sed -n 's/^## Cross-check: \([0-9]*\) of \([0-9]*\) scenes agree.*/\1/p')
total=$(echo "$line" | sed -n 's/^## Cross-check: \([0-9]*\) of \([0-9]*\) scenes agree.*/\2/p')
[ -n "$total" ] && [ "$total" -gt 40 ] && [ "$agreed" = "$total" ] || { cat "$report"; fail "gpu-check: $line"; }
grep -qE '^The device (reaches|did not reach) it' "$report" || { cat "$report"; fail "gpu-check: no error-against-time verdict"; }
grep -qE '^Largest rendered: [0-9]+ spheres' "$report" || { cat "$report"; fail "gpu-check: no largest scene"; }
timed=$(grep -cE '^\| (k_room|i_sphereflake|f_temple|j_torus_knot) \| [0-9]+ x [0-9]+ \|.* \| [0-9.]+ \|$' "$report" || true)
[ "$timed" = 4 ] || { cat "$report"; fail "gpu-check: $timed of 4 scenes with a longest submission"; }
echo "gpu-check --smoke: every part done; $line"

# --only runs the parts named, alone; a part that does not exist is refused by name.
"$bundle/bin/gpu-check" --smoke --only devices,submission "$scratch/only" 2>/dev/null || fail "gpu-check --only"
parts=$(sed -n 's/^| \([a-z]*\) | ok |.*/\1/p' "$scratch/only/report.md" | tr '\n' ' ')
[ "$parts" = "devices submission " ] || { cat "$scratch/only/report.md"; fail "gpu-check --only ran: $parts"; }
if "$bundle/bin/gpu-check" --only devices,nosuch "$scratch/bad" 2>"$scratch/bad.log"; then fail "gpu-check took a part 'nosuch'"; fi
grep -q "no part 'nosuch'" "$scratch/bad.log" || { cat "$scratch/bad.log"; fail "gpu-check's refusal does not name the part"; }
echo "gpu-check --only: the parts named alone; an unknown part refused by name"
