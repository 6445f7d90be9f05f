"""What the live preview's tests share: starting vkrt with --serve and finding its
address, raw HTTP exchanges, and failing with a message."""
import os
import re
import socket
import subprocess
import sys
import time


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def check(condition, message):
    if not condition:
        fail(message)


def start_vkrt(vkrt, args, cwd):
    """Starts `vkrt ARGS` (which serve a page) and returns the process and the page's
    address, read from the line vkrt prints on standard error."""
    err_path = os.path.join(cwd, "stderr.txt")
    err = open(err_path, "w")
    proc = subprocess.Popen([vkrt] + args, cwd=cwd, stdout=open(os.path.join(cwd, "stdout.txt"), "w"), stderr=err)
    deadline = time.time() + 60
    while time.time() < deadline:
        with open(err_path) as f:
            found = re.search(r"live +(http://\S+)", f.read())
        if found:
            return proc, found.group(1)
        if proc.poll() is not None:
            fail(f"vkrt exited with {proc.returncode} before serving:\n{open(err_path).read()}")
        time.sleep(0.05)
    proc.kill()
    fail("vkrt did not print its address within 60 s")


def host_port(url):
    found = re.match(r"http://([^/:]+):(\d+)/", url)
    return found.group(1), int(found.group(2))


def complete(reply):
    """Whether `reply` holds a whole response: its head and Content-Length bytes."""
    head, sep, body = reply.partition(b"\r\n\r\n")
    if not sep:
        return False
    found = re.search(rb"(?i)\r\ncontent-length: *(\d+)", head)
    return len(body) >= (int(found.group(1)) if found else 0)


def exchange(url, data, timeout=10.0):
    """Sends raw bytes to the server and returns its first response, or whatever
    came back before it closed the connection or the timeout passed, as bytes."""
    with socket.create_connection(host_port(url), timeout=timeout) as s:
        try:
            s.sendall(data)
        except (BrokenPipeError, ConnectionResetError):
            pass  # the server may answer and close before reading all of an oversized request
        reply = b""
        try:
            while not complete(reply):
                chunk = s.recv(65536)
                if not chunk:
                    break
                reply += chunk
        except (socket.timeout, ConnectionResetError):
            pass
    return reply


def status_code(reply):
    found = re.match(rb"HTTP/1\.[01] (\d{3})", reply)
    return int(found.group(1)) if found else None


def png_size(path):
    """Width and height from a PNG's header, or None when it is not a PNG."""
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")
