"""Malformed, oversized and hostile requests to the live preview: each gets an error
status or a closed connection, none reaches a file or stops the render, and the
render finishes with the image it gives without a server, bit for bit.

    hostile_test.py VKRT SOURCE_DIR"""
import os
import socket
import subprocess
import sys
import tempfile
import threading
import time

from live_lib import check, exchange, fail, host_port, start_vkrt, status_code

vkrt, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
scene = os.path.join(source, "scenes", "gallery", "k_room.json")
# Long enough on lavapipe for every request below to arrive during the passes.
RENDER = [scene, "--width", "160", "--height", "120", "--spp", "1024", "-q"]


def hold_open(url, partial, seconds, held):
    """A slow client: sends part of a request, then nothing."""
    try:
        with socket.create_connection(host_port(url), timeout=seconds + 5) as s:
            s.sendall(partial)
            held.append(s.recv(1024) if seconds == 0 else b"")
            time.sleep(seconds)
    except OSError:
        held.append(b"")


with tempfile.TemporaryDirectory() as work:
    subprocess.run([vkrt, "render", *RENDER, "-o", "plain.exr"], cwd=work, check=True)

    proc, url = start_vkrt(vkrt, ["render", *RENDER, "--serve", "0", "-o", "served.exr", "--stats", "stats.json"], work)
    host, port = host_port(url)

    big = b"A" * (1 << 20)
    requests = {
        "garbage": (b"\x00\xff\xfe not http at all\r\n\r\n", {400, None}),
        "no version": (b"GET /\r\n\r\n", {400, None}),
        "huge URI": (b"GET /" + big + b" HTTP/1.1\r\nHost: x\r\n\r\n", {400, 414, None}),
        "huge header": (b"GET / HTTP/1.1\r\nHost: x\r\nX-Big: " + big + b"\r\n\r\n", {400, 431, None}),
        "many headers": (b"GET / HTTP/1.1\r\n" + b"".join(b"X-%d: y\r\n" % i for i in range(20000)) + b"\r\n",
                         {400, 431, None}),
        "oversized body": (b"POST /stop HTTP/1.1\r\nHost: x\r\nX-Vkrt-Stop: 1\r\nContent-Length: 100000000\r\n\r\n"
                           + big, {413, 400, None}),
        "path out of the root": (b"GET /../../../../etc/passwd HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n",
                                 {400, 404}),
        "encoded path out": (b"GET /%2e%2e/%2e%2e/etc/passwd HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n",
                             {400, 404}),
        "unknown method": (b"BREW /pot HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n", {400, 405, None}),
        "delete": (b"DELETE /status HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n", {400, 404, 405}),
        "stop without the header": (b"POST /stop HTTP/1.1\r\nHost: x\r\nContent-Length: 0\r\nConnection: close\r\n\r\n",
                                    {403}),
        "cross-site form stop": (b"POST /stop HTTP/1.1\r\nHost: x\r\nOrigin: http://evil.example\r\nContent-Type: "
                                 b"application/x-www-form-urlencoded\r\nContent-Length: 3\r\nConnection: close\r\n\r\na=1",
                                 {403}),
        "bad chunked body": (b"POST /stop HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\nConnection: close\r\n\r\n"
                             b"zz\r\nnope\r\n", {400, 403, 413, None}),
    }
    for name, (data, allowed) in requests.items():
        began = time.time()
        reply = exchange(url, data, timeout=30)  # generous: a loaded machine answers late
        print(f"{name}: {status_code(reply)} in {time.time() - began:.2f} s", file=sys.stderr)
        code = status_code(reply)
        check(code in allowed, f"{name}: answered {code} ({reply[:120]!r}), expected one of {allowed}")
        check(b"root:" not in reply, f"{name}: the reply holds a system file")
        check(proc.poll() is None, f"{name}: vkrt ended (code {proc.returncode}) while the render should go on")
    # Slow clients hold every worker the server has, and more: the render goes on.
    slow = []
    threads = [threading.Thread(target=hold_open, args=(url, b"GET /status HTTP/1.1\r\nHost: x\r\n", 4, slow))
               for _ in range(8)]
    for t in threads:
        t.start()

    # Connections opened and dropped at once, browsers closed in the middle of an
    # image, and a storm of good requests; the render may end meanwhile (the slow
    # clients keep the workers busy for seconds).
    try:
        for _ in range(200):
            socket.create_connection((host, port)).close()
        exchange(url, b"GET /status HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n", timeout=30)
        time.sleep(1.0)  # watched now: the next pass publishes an image
        for _ in range(50):
            with socket.create_connection((host, port)) as s:
                s.sendall(b"GET /image.png HTTP/1.1\r\nHost: x\r\n\r\n")
                s.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, b"\x01\x00\x00\x00\x00\x00\x00\x00")
        for _ in range(100):
            exchange(url, b"GET /status HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n", timeout=30)
    except ConnectionRefusedError:
        # The server closes when the render ends; the process then still writes its
        # files. A refusal is fine when vkrt goes on to finish well (checked below).
        pass

    code = proc.wait(timeout=240)
    for t in threads:
        t.join()
    check(code == 0, f"vkrt exited with {code}:\n{open(os.path.join(work, 'stderr.txt')).read()}")
    compare = subprocess.run([vkrt, "compare", "plain.exr", "served.exr", "--max-abs", "0"], cwd=work,
                             capture_output=True, text=True)
    check(compare.returncode == 0, f"the served render differs from the plain one: {compare.stdout}{compare.stderr}")
    stats = open(os.path.join(work, "stats.json")).read()
    check('"samples_per_pixel": 1024' in stats, "the render did not take all its samples (was it stopped?)")

    # A second vkrt cannot take the port the first holds: refused before rendering.
    with socket.socket() as holder:
        holder.bind(("127.0.0.1", 0))
        holder.listen()
        taken = holder.getsockname()[1]
        busy = subprocess.run([vkrt, "render", *RENDER, "--serve", str(taken), "-o", "busy.png"], cwd=work,
                              capture_output=True, text=True)
        check(busy.returncode == 1 and "cannot listen" in busy.stderr and not os.path.exists(
            os.path.join(work, "busy.png")), f"a port in use: exit {busy.returncode}, {busy.stderr}")
    print(f"ok: {len(requests)} hostile requests and {len(threads)} slow clients answered or dropped; "
          "the render finished with the same image")
