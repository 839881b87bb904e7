/* tdc_crt0.c - memory set-up before main() on the Cortex-M boards. */
#include "tdc_crt0.h"

extern uint32_t __data_load[], __data_start[], __data_end[];
extern uint32_t __bss_start[], __bss_end[];
extern uint32_t __ext_start[], __ext_end[];

int main(void);

/* Plain word loops.  gcc may turn them into memcpy/memset calls, which is
 * fine: those need no initialised data of their own. */
static void zero_words(uint32_t *p, const uint32_t *end)
{
    while (p < end) {
        *p++ = 0u;
    }
}

int tdc_crt0_start(void)
{
    const uint32_t *src = __data_load;
    for (uint32_t *dst = __data_start; dst < __data_end;) {
        *dst++ = *src++;
    }
    zero_words(__bss_start, __bss_end);
    zero_words(__ext_start, __ext_end);
    return main();
}

void tdc_crt0_default_handler(void)
{
    uint32_t ipsr;
    __asm__ volatile("mrs %0, ipsr" : "=r"(ipsr));
    tdc_board_fault(ipsr & 0x1ffu);
}
