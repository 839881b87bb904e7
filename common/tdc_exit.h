/*
 * tdc_exit.h - the exit codes of every tdc program, written once.
 *
 *   X(code, NAME, "meaning", "programs")
 *
 * Read by tdc_tool.h (the TDC_EXIT_* enum) and tdc_tool.c (tdc_exit_name),
 * by common/tdc_exit.py for the Python tools (tdc_sweep.py,
 * tdc_experiments.py) and the docs: `python3 common/tdc_exit.py
 * markdown` prints the table of docs/tools.md, `... short` the README line;
 * tests/unit/test_exit_table.sh fails when either differs from this list or
 * when a program's --help names a code otherwise.
 *
 * Rules: codes are 0..N-1 without gaps; a code never changes its number or
 * meaning (scripts test them); one entry per line in exactly this form (the
 * Python reader parses it).  0..12 are the numbers tdc-usb has always used.
 */
#ifndef TDC_EXIT_H
#define TDC_EXIT_H

/* clang-format off */
#define TDC_EXIT_TABLE(X) \
    X(0, OK, "success", "all") \
    X(1, ARGS, "bad command line: unknown option, bad value, missing argument", "all") \
    X(2, NO_DEVICE, "no board (USB), GPIO chip, DRM device or connector matches", "tdc-usb, tdc-gpio, tdc-board") \
    X(3, AMBIGUOUS, "more than one board matches: select one", "tdc-usb") \
    X(4, IO, "device I/O error (libusb: access, stall, I/O; GPIO request/read; USB gadget set-up)", "tdc-usb, tdc-gpio, tdc-board") \
    X(5, TIMEOUT, "a transfer or an expected edge timed out", "tdc-usb, tdc-gpio") \
    X(6, DISCONNECTED, "the board went away mid-operation", "tdc-usb") \
    X(7, FILE, "cannot open, read, write or create a file or folder (a folder named as a file included)", "all but tdc-gpio") \
    X(8, IMAGE, "firmware image malformed: magic, size, CRC, DFU suffix", "tdc-usb") \
    X(9, INCOMPATIBLE, "image for another board, or larger than its slot", "tdc-usb") \
    X(10, DFU, "the board's DFU reported an error", "tdc-usb") \
    X(11, VERIFY, "read-back or received-data check failed", "tdc-usb") \
    X(12, PROTOCOL, "the board's reply is malformed", "tdc-usb") \
    X(13, INPUT, "an input file's contents are malformed: PNG, CSV, scene, OBJ, panel profile, .tdcs stream, sweep or experiment group", "tdc-run, tdc-sim, tdc-render, tdc-linkdump, tdc-tablegen, tdc-calib, tdc-lcd-measure, tdc_sweep.py, tdc_experiments.py, tdc-fvvdp-validate") \
    X(14, REFUSED, "the firmware (a stage) or the renderer refused the input or configuration: the run is not a result", "tdc-run, tdc-sim, tdc-render, tdc-fvvdp-validate, tdc-board (no display mode for the panel)") \
    X(15, NO_LINE, "no such GPIO line on the chip", "tdc-gpio") \
    X(16, BUSY, "the GPIO line is held by another consumer", "tdc-gpio") \
    X(17, NOMEM, "out of memory", "tdc-run, tdc-sim, tdc-render, tdc-zeng") \
    X(18, JOBS, "a job of a sweep or experiment failed, or a result it needs is missing (each job's own code is in its log)", "tdc_sweep.py, tdc_experiments.py") \
    X(19, ENGINE, "the job engine (GNU parallel, Slurm sbatch) is missing or failed", "tdc_sweep.py") \
    X(20, RESTART, "the board installed a new program by DFU and ended so that its launcher starts it (not an error)", "tdc-board")
/* clang-format on */

#endif
