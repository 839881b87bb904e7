/*
 * tdc_semihost.c - ARM semihosting calls (see tdc_semihost.h).
 *
 * On M-profile cores a semihosting request is "BKPT 0xAB" with the
 * operation number in r0 and the parameter block address in r1; the result
 * comes back in r0 (ARM "Semihosting for AArch32 and AArch64", v3).
 */
#include "tdc_semihost.h"

enum {
    SYS_OPEN = 0x01,
    SYS_CLOSE = 0x02,
    SYS_WRITE = 0x05,
    SYS_READ = 0x06,
    SYS_CLOCK = 0x10,
    SYS_GET_CMDLINE = 0x15,
    SYS_EXIT_EXTENDED = 0x20
};

#define ADP_STOPPED_APPLICATION_EXIT 0x20026u

static uint32_t semihost_call(uint32_t op, const void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

static uint32_t str_len(const char *s)
{
    uint32_t n = 0;
    while (s[n]) {
        n++;
    }
    return n;
}

/* Host handles of ":tt" opened for writing: mode 4 ("w") is stdout,
 * mode 8 ("a") is stderr.  Opened once, on first use. */
static uint32_t g_handle[3];
static uint8_t g_opened[3];

static uint32_t tt_handle(int fd)
{
    unsigned i = fd == 2 ? 2u : 1u;
    if (!g_opened[i]) {
        static const char tt[] = ":tt";
        uint32_t args[3] = {(uint32_t)(uintptr_t)tt, i == 2u ? 8u : 4u, 3u};
        g_handle[i] = semihost_call(SYS_OPEN, args);
        g_opened[i] = 1;
    }
    return g_handle[i];
}

void tdc_semihost_write(int fd, const char *s, size_t n)
{
    uint32_t args[3] = {tt_handle(fd), (uint32_t)(uintptr_t)s, (uint32_t)n};
    (void)semihost_call(SYS_WRITE, args);
}

void tdc_semihost_puts(int fd, const char *s)
{
    tdc_semihost_write(fd, s, str_len(s));
}

uint32_t tdc_semihost_clock_cs(void)
{
    return semihost_call(SYS_CLOCK, NULL);
}

int32_t tdc_semihost_open_read(const char *path)
{
    uint32_t args[3] = {(uint32_t)(uintptr_t)path, 1u /* "rb" */, str_len(path)};
    return (int32_t)semihost_call(SYS_OPEN, args);
}

int32_t tdc_semihost_read(int32_t handle, void *buf, uint32_t n)
{
    uint32_t args[3] = {(uint32_t)handle, (uint32_t)(uintptr_t)buf, n};
    const uint32_t not_read = semihost_call(SYS_READ, args); /* bytes NOT read */
    return not_read > n ? -1 : (int32_t)(n - not_read);
}

void tdc_semihost_close(int32_t handle)
{
    uint32_t args[1] = {(uint32_t)handle};
    (void)semihost_call(SYS_CLOSE, args);
}

int tdc_semihost_cmdline(char *buf, uint32_t size)
{
    if (size == 0u) {
        return -1;
    }
    uint32_t args[2] = {(uint32_t)(uintptr_t)buf, size};
    buf[0] = 0;
    if (semihost_call(SYS_GET_CMDLINE, args) != 0u) {
        return -1;
    }
    buf[size - 1u] = 0;
    return (int)str_len(buf);
}

_Noreturn void tdc_semihost_exit(uint32_t code)
{
    uint32_t args[2] = {ADP_STOPPED_APPLICATION_EXIT, code};
    (void)semihost_call(SYS_EXIT_EXTENDED, args);
    for (;;) {
        /* not reached under QEMU; a real core without debugger stops at the BKPT */
    }
}
