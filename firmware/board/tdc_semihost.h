/*
 * tdc_semihost.h - ARM semihosting for the emulated boards (QEMU runs the
 * image with -semihosting-config enable=on,target=native).  Output goes to
 * the host's stdout / stderr, the exit status to QEMU's exit status.
 *
 * Only used by emulated boards and the ARM golden runner: a real board has
 * no debugger attached and would stop at the BKPT.
 */
#ifndef TDC_SEMIHOST_H
#define TDC_SEMIHOST_H

#include <stddef.h>
#include <stdint.h>

/* Writes n bytes to the host's stdout (fd 1) or stderr (fd 2). */
void tdc_semihost_write(int fd, const char *s, size_t n);

/* Writes a NUL-terminated string to the host's stdout / stderr. */
void tdc_semihost_puts(int fd, const char *s);

/* Host time in centiseconds since the program started (SYS_CLOCK). */
uint32_t tdc_semihost_clock_cs(void);

/* Copies the command line QEMU was given with -append into buf (NUL
 * terminated); returns its length, or -1 when there is none. */
int tdc_semihost_cmdline(char *buf, uint32_t size);

/* Host files (target=native): opens path for binary reading; returns a
 * handle >= 0, or -1. */
int32_t tdc_semihost_open_read(const char *path);

/* Reads up to n bytes; returns the number read (0 at end of file), -1 on error. */
int32_t tdc_semihost_read(int32_t handle, void *buf, uint32_t n);

void tdc_semihost_close(int32_t handle);

/* Ends the emulation with exit status `code` (SYS_EXIT_EXTENDED, so the
 * status reaches the shell: a failing run fails the test). */
_Noreturn void tdc_semihost_exit(uint32_t code);

#endif
