#!/usr/bin/python3
"""make test-vm: runs QEMU and captures the guest's scan-out from outside.

The guest prints "VMSHOT NAME K" on its console once the Linux board has
flipped frame K of stream NAME onto the display, then blocks reading its
second serial port.  This script, reading the console, asks QEMU (QMP
`screendump`: the display surface of the bochs-display, i.e. the buffer the
KMS driver scans out) for a PPM into SHOTS/NAME-K.ppm, then writes "go" to
that serial port.  Everything the console prints goes to CONSOLE_LOG.

Usage: qemu_capture.py CONSOLE_LOG SHOTS QMP_SOCKET ACK_SOCKET TIMEOUT_S -- QEMU ARGS...
"""
import json
import os
import socket
import subprocess
import sys
import threading
import time


def connect(path, deadline):
    while True:
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            s.connect(path)
            return s
        except OSError:
            s.close()
            if time.time() > deadline:
                raise
            time.sleep(0.05)


class Qmp:
    def __init__(self, path, deadline):
        self.s = connect(path, deadline)
        self.f = self.s.makefile("r")
        self.reply()  # greeting
        self.cmd("qmp_capabilities")

    def reply(self):
        while True:
            msg = json.loads(self.f.readline())
            if "event" not in msg:
                return msg

    def cmd(self, name, **args):
        self.s.sendall(json.dumps({"execute": name, "arguments": args}).encode() + b"\n")
        r = self.reply()
        if "error" in r:
            raise RuntimeError("%s: %s" % (name, r["error"]))
        return r


def main():
    log_path, shots, qmp_path, ack_path, timeout = sys.argv[1:6]
    qemu = sys.argv[7:]
    os.makedirs(shots, exist_ok=True)
    for p in (qmp_path, ack_path):
        if os.path.exists(p):
            os.unlink(p)
    proc = subprocess.Popen(qemu, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    timer = threading.Timer(float(timeout), proc.kill)
    timer.start()
    deadline = time.time() + 30
    qmp = ack = None
    with open(log_path, "wb") as log:
        try:
            qmp = Qmp(qmp_path, deadline)
            ack = connect(ack_path, deadline)
            for raw in proc.stdout:
                log.write(raw)
                log.flush()
                line = raw.decode("latin-1").strip()
                if line.startswith("VMSHOT "):
                    _, name, k = line.split()[:3]
                    qmp.cmd("screendump", filename=os.path.abspath(os.path.join(shots, "%s-%s.ppm" % (name, k))))
                    ack.sendall(b"go\n")
        except Exception as e:  # the run fails by its missing VMTEST lines; say why here
            log.write(("qemu_capture: %s\n" % e).encode())
            proc.kill()
        finally:
            timer.cancel()
            proc.wait()
    return 0


if __name__ == "__main__":
    sys.exit(main())
