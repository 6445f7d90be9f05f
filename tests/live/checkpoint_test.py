"""--checkpoint: a render killed outright leaves its latest checkpoint, a whole image
of the output's size; with --samples, a partial file of the samples done, which
vkrt merge reads and whose remaining samples it lists as missing.

    checkpoint_test.py VKRT SOURCE_DIR"""
import os
import signal
import subprocess
import sys
import tempfile
import time

from live_lib import check, fail, png_size

vkrt, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
scene = os.path.join(source, "scenes", "gallery", "k_room.json")
SIZE = ["--width", "160", "--height", "120"]


def killed_after_checkpoints(args, output, work, count=2):
    """Runs vkrt until `output` has been replaced `count` times, then kills it
    (SIGKILL: no chance to finish the file)."""
    proc = subprocess.Popen([vkrt, *args], cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    path = os.path.join(work, output)
    seen, deadline = set(), time.time() + 120
    while len(seen) < count and time.time() < deadline:
        if proc.poll() is not None:
            fail(f"vkrt ended (code {proc.returncode}) before {count} checkpoints: {proc.stderr.read()}")
        try:
            seen.add(os.stat(path).st_ino)  # each checkpoint is a new file renamed over the last
        except FileNotFoundError:
            pass
        time.sleep(0.02)
    check(len(seen) >= count, f"{output}: {len(seen)} checkpoints in 120 s")
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    return path


with tempfile.TemporaryDirectory() as work:
    image = killed_after_checkpoints(["render", scene, *SIZE, "--time", "600", "--checkpoint", "0.5", "-q", "-o",
                                      "out.png"], "out.png", work)
    check(png_size(image) == (160, 120), f"the checkpoint is {png_size(image)}, not a 160x120 PNG")
    read = subprocess.run([vkrt, "compare", image, image], capture_output=True, text=True)
    check(read.returncode == 0, f"vkrt cannot read the checkpoint: {read.stderr}")

    partial = killed_after_checkpoints(["render", scene, *SIZE, "--samples", "0:60000", "--checkpoint", "0.5", "-q",
                                        "-o", "part.exr"], "part.exr", work)
    missing = subprocess.run([vkrt, "merge", "--missing", "--samples", "0:60000", partial], capture_output=True,
                             text=True)
    check(missing.returncode == 0, f"merge --missing cannot read the checkpoint: {missing.stderr}")
    lines = missing.stdout.split()
    check(len(lines) == 1 and lines[0].endswith(":60000") and 0 < int(lines[0].split(":")[0]) < 60000,
          f"merge --missing lists {lines}: expected the samples after the checkpoint's")
    merged = subprocess.run([vkrt, "merge", partial, "-q", "-o", os.path.join(work, "merged.png")],
                            capture_output=True, text=True)
    check(merged.returncode == 0, f"the checkpoint does not merge: {merged.stderr}")
    print(f"ok: killed renders left a whole PNG and a partial of samples 0:{lines[0].split(':')[0]}")
