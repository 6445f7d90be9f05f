#!/usr/bin/env bash
# scripts/cluster/parallel-render through real GNU parallel and ssh: an sshd started
# here on a free port, with a key made here, stands for two hosts (127.0.0.1 and
# localhost). The render equals the single render bit for bit; a range that fails
# once is retried; a partial lost afterwards is named by merge, and running the
# command again renders only it.
#   parallel_test.sh VKRT SOURCE_DIR
source "$(dirname "$0")/cluster_lib.sh"

step "starting sshd"
for program in parallel ssh ssh-keygen /usr/sbin/sshd; do
  command -v "$program" >/dev/null || fail "no $program: scripts/setup --tests installs parallel and openssh"
done
mkdir -m 700 "$scratch/ssh"
ssh-keygen -q -t ed25519 -N "" -f "$scratch/ssh/host_key"
ssh-keygen -q -t ed25519 -N "" -f "$scratch/ssh/client_key"
cp "$scratch/ssh/client_key.pub" "$scratch/ssh/authorized_keys"
port=$(free_port)
cat >"$scratch/ssh/sshd_config" <<CONF
ListenAddress 127.0.0.1
Port $port
HostKey $scratch/ssh/host_key
PidFile $scratch/ssh/sshd.pid
AuthorizedKeysFile $scratch/ssh/authorized_keys
PermitRootLogin prohibit-password
PasswordAuthentication no
KbdInteractiveAuthentication no
UsePAM no
StrictModes no
CONF
mkdir -p /run/sshd   # sshd's privilege separation directory
/usr/sbin/sshd -f "$scratch/ssh/sshd_config" -E "$scratch/ssh/sshd.log"
cleanups+=('stop_daemon "$scratch/ssh/sshd.pid"')
ssh_command="ssh -p $port -i $scratch/ssh/client_key -o BatchMode=yes -o StrictHostKeyChecking=no -o UserKnownHostsFile=/dev/null -o LogLevel=ERROR"
ssh_ready() { $ssh_command "$(id -un)@127.0.0.1" true; }
wait_for 120 ssh_ready || fail "cannot ssh to 127.0.0.1:$port: $(cat "$scratch/ssh/sshd.log")"
printf '1/%s %s@127.0.0.1\n1/%s %s@localhost\n' "$ssh_command" "$(id -un)" "$ssh_command" "$(id -un)" >"$scratch/hosts"

# vkrt, but the first try of samples 2:4 fails, as a machine might; every try is logged.
cat >"$scratch/flaky-vkrt" <<WRAPPER
#!/usr/bin/env bash
echo "\$*" >>"$scratch/tries.log"
if [[ " \$* " == *" --samples 2:4 "* ]] && mkdir "$scratch/failed-once" 2>/dev/null; then
  echo "flaky-vkrt: failing on purpose" >&2
  exit 1
fi
exec "$vkrt" "\$@"
WRAPPER
chmod +x "$scratch/flaky-vkrt"

parallel_render() {
  "$scripts/parallel-render" "$scene" --spp "$spp" --tasks 4 --dir "$scratch/parts" --hosts "$scratch/hosts" \
    --retries 2 --vkrt "$scratch/flaky-vkrt" -o "$scratch/parallel.exr" -- "${render_options[@]}"
}

step "four ranges over ssh, one retried: the single render, bit for bit"
parallel_render
expect_whole "$scratch/parallel.exr"
[ -d "$scratch/failed-once" ] || fail "the failure was never injected"
[ "$(grep -c -- "--samples 2:4" "$scratch/tries.log")" -eq 2 ] || fail "2:4 was not tried twice: $(cat "$scratch/tries.log")"
grep -q "@127.0.0.1\|@localhost" "$scratch/parts/logs/parallel.log" || fail "the joblog names no ssh host"

step "a lost partial is named, and the same command renders only it"
rm "$scratch/parts/samples-4-6.exr" "$scratch/parallel.exr"
if "$vkrt" merge --samples "0:$spp" "$scratch/parts"/samples-*.exr -o "$scratch/x.exr" 2>"$scratch/merge.err"; then
  fail "merge accepted partials with a gap"
fi
grep -q "samples 4:6 are missing" "$scratch/merge.err" || fail "merge did not name the gap: $(cat "$scratch/merge.err")"
: >"$scratch/tries.log"
out=$(parallel_render)
echo "$out"
# The missing samples, cut for the four tasks as far as two samples go.
grep -q "rendering 2 ranges: samples 4:5,5:6$" <<<"$out" || fail "the rerun did not render only 4:6"
[ "$(grep -c -e "--samples 4:5 " -e "--samples 5:6 " "$scratch/tries.log")" -eq 2 ] &&
  [ "$(grep -c "^render " "$scratch/tries.log")" -eq 2 ] || fail "the rerun rendered other samples: $(cat "$scratch/tries.log")"
expect_whole "$scratch/parallel.exr"
echo "PASS"
