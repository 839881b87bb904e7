/*
 * checkasm_arm_main.c - the checkasm core (tests/checkasm/) on the emulated
 * Cortex-M boards: the same registry, families and inputs as the host run,
 * with the kernels this image can run (on a Helium board the MVE row
 * kernels of firmware/tdc_trm_mve.c against the portable C kernels, bit for
 * bit).  tests/arm/run_checkasm_qemu.sh runs it in qemu-system-arm.
 *
 * Arguments come from QEMU's -append (semihosting SYS_GET_CMDLINE gives
 * "IMAGE ARGS..."), so a failure printed as
 *     checkasm --seed 0x... trm_full_row_mve
 * replays with `-append "--seed 0x... trm_full_row_mve"`.  Output goes to
 * the host's stdout through semihosting; the exit status (0 all agreed,
 * 1 a kernel differed, 2 bad usage) is QEMU's exit status.
 */
#include <errno.h>
#include <stddef.h>
#include <stdint.h>

#include "checkasm/checkasm.h"
#include "tdc_semihost.h"

#define MAX_ARGS 16

void checkasm_write(const char *s, size_t n)
{
    tdc_semihost_write(1, s, n);
}

/* newlib nano's vsnprintf links its stream code, which names malloc (never
 * reached with a caller's buffer): the images have no heap, so the break
 * never moves and a call would fail with ENOMEM instead of writing past RAM. */
void *_sbrk(ptrdiff_t incr);
void *_sbrk(ptrdiff_t incr)
{
    (void)incr;
    errno = ENOMEM;
    return (void *)-1;
}

int main(void)
{
    static char cmd[512];
    static char *argv[MAX_ARGS + 1];
    int argc = 0;
    if (tdc_semihost_cmdline(cmd, sizeof cmd) < 0) {
        cmd[0] = 0;
    }
    /* split on spaces in place; the first word is the image (argv[0]) */
    for (char *p = cmd; *p && argc < MAX_ARGS;) {
        while (*p == ' ') {
            *p++ = 0;
        }
        if (!*p) {
            break;
        }
        argv[argc++] = p;
        while (*p && *p != ' ') {
            p++;
        }
    }
    if (argc == 0) {
        static char image[] = "checkasm";
        argv[argc++] = image;
    }
    argv[argc] = NULL;
    return checkasm_main(argc, argv);
}
