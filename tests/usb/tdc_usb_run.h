/*
 * tdc_usb_run.h - shared harness of the umockdev tests (test_usb_emul.c:
 * tdc-usb; test_usb_clients.c: Debian's dfu-util and lsusb).  Programs run
 * as children with LD_PRELOAD=libumockdev-preload.so.0 inside the testbed,
 * so the program, libusb and its Linux backend are all unmodified.  A child
 * that runs longer than CHILD_DEADLINE_S is killed and the test fails.
 */
#ifndef TDC_USB_RUN_H
#define TDC_USB_RUN_H

#include <stddef.h>
#include <stdint.h>

#include "tdc_usb_emul.h"

#ifndef TDC_USB_BIN
#error "TDC_USB_BIN (path of the tdc-usb binary) must be defined by the build"
#endif

#define CHILD_DEADLINE_S 30.0
#define SLOT_BYTES 65536u

typedef struct {
    int status; /* exit code, or 128+signal, or -1 if killed for hanging */
    double secs;
    char out[16384], err[16384];
} run_t;

typedef struct {
    UMockdevTestbed *tb;
    emul_board_t *board[2];
} fixture_t;

extern char tmpdir[]; /* scratch folder of the test program (mkdtemp'ed by main) */

void run_prog_in(run_t *r, const char *prog, const char *const *args, const char *in_path);
void run_tool_in(run_t *r, const char *const *args, const char *in_path); /* tdc-usb */
void run_tool(run_t *r, const char *const *args);
/* exit code status, in_out in stdout and in_err in stderr (NULL: any) */
void expect(const run_t *r, int status, const char *in_out, const char *in_err);
uint32_t ref_crc32(const uint8_t *p, size_t n); /* table-driven, independent of the firmware's */
void write_file(const char *path, const uint8_t *data, size_t n);
uint8_t *random_bytes(size_t n, uint32_t seed);
int setup_none(void **state);
int setup_one(void **state);
int setup_two(void **state);
int teardown(void **state);
/* An image made by tdc-usb mkimage (header + payload; the file also has a
 * DFU suffix); returns header + payload (caller frees). */
uint8_t *make_image(const char *board, size_t payload, const char *img_path, size_t *len);
/* tmpdir/name into out. */
void tmp_path(char *out, size_t cap, const char *name);
/* The slow-erase case every flashing client (tdc-usb flash, dfu-util)
 * must pass: board 0's flash answers dfuDNBUSY (40 ms bwPollTimeout) for
 * each block that starts a 4 KiB erase unit; flash(r, img_path) downloads
 * a 9000-byte image without a reset and must exit 0 printing want_out, the
 * image must land and each of the three timeouts (blocks at 0, 4096, 8192)
 * be waited out, none polled early. */
void check_busy_erase(const fixture_t *f, void (*flash)(run_t *r, const char *img_path), const char *want_out);

#endif
