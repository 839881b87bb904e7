#!/usr/bin/python3
"""disco_cost.py - instructions the DISCO's own board code executes per unit
of work, counted on the emulated Cortex-M7 (python3-unicorn, one count per
executed instruction; instructions, not cycles: no pipeline, cache, SDRAM
or AHB wait model).  The stage rows of docs/boards.md's DISCO real-time
table come from `make bench-arm` (QEMU plugin counts of the same code
compiled the same way); this adds what only this board has: the USB HS
interrupt and ring, transport_read, and the scan-out flip with its D-cache
clean.  Usage: disco_cost.py ELF   (make bench-disco)
"""
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from unicorn import UC_HOOK_CODE  # noqa: E402
from disco_emu import Disco  # noqa: E402

BUF, GOT = 0x24060000, 0x24070000


def counted(b, fn):
    n = [0]

    def hook(_uc, _addr, _size, _data):
        n[0] += 1
    h = b.uc.hook_add(UC_HOOK_CODE, hook)
    b.uc.ctl_flush_tb()  # blocks translated before the hook would run uncounted
    try:
        fn()
    finally:
        b.uc.hook_del(h)
        b.uc.ctl_flush_tb()
    return n[0]


def enumerate_board(b):
    b.usb.bus_reset()
    for setup in ((0x00, 5, 7, 0, 0), (0x00, 9, 1, 0, 0)):  # SET_ADDRESS, SET_CONFIGURATION
        b.usb.setup(struct.pack("<BBHHH", *setup))


def main(elf):
    b = Disco(elf)
    b.run_reset()
    enumerate_board(b)
    pkts = 16
    data = [bytes((k + i) & 0xFF for i in range(512)) for k in range(pkts)]
    irq = counted(b, lambda: [b.usb.out(1, d) for d in data])
    read = counted(b, lambda: [b.call("tdc_board_transport_read", BUF, 4096, GOT) for _ in range(2)])
    got = struct.unpack("<I", bytes(b.uc.mem_read(GOT, 4)))[0]
    assert got == 4096, got
    w, h = 800, 480
    show = counted(b, lambda: b.call("tdc_board_panel_show", 0xD0100000, w * 3, w, h, 0))
    nbytes = pkts * 512
    print("DISCO board code, instructions (python3-unicorn, Cortex-M7, this ELF):")
    print("%-52s %12s %14s" % ("work", "instructions", "per unit"))
    print("%-52s %12d %11.2f /B" % ("USB HS interrupt: %d bulk OUT packets into the ring" % pkts, irq, irq / nbytes))
    print("%-52s %12d %11.2f /B" % ("transport_read: %d bytes out of the ring" % nbytes, read, read / nbytes))
    print("%-52s %12d %11.3f /px" % ("panel_show 800x480 RGB888 (D-cache clean + flip)", show, show / (w * h)))


if __name__ == "__main__":
    if len(sys.argv) != 2 or not os.path.exists(sys.argv[1]):
        sys.exit("disco_cost: run: no firmware ELF given (make BOARD=stm32h747i-disco PANEL=disco-dsi)")
    main(sys.argv[1])
