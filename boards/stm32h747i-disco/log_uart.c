/*
 * log_uart.c - the DISCO's log: USART1 (TX PA9, RX PA10, AF7) reaches the
 * ST-LINK V3's virtual COM port on the CN14 USB connector (UM2411), 115200
 * 8N1.  And the fault handler, which logs there before resetting.
 *
 * USART1 kernel clock = rcc_pclk2 (RCC_D2CCIP2R.USART16SEL reset value 0),
 * 100 MHz after clocks.c: BRR = 100 MHz / 115200 = 868 (oversampling 16,
 * 0.006 % error; RM0399 chapter "USART baud rate generation").
 */
#include <stdint.h>

#include "board.h"
#include "disco.h"

#define RCC(off) TDC_REG32(TDC_STM32_RCC + (off))
#define USART1(off) TDC_REG32(TDC_STM32_USART1 + (off))
#define GPIOA(off) TDC_REG32(TDC_STM32_GPIO(0) + (off))
#define LOG_BAUD 115200u
/* TXE polls per byte: one byte takes 87 us = 35000 CPU cycles at 400 MHz;
 * 10^5 reads wait longer than that and bound a dead UART. */
#define TXE_TRIES 100000u

static int g_log_up;

void tdc_disco_log_init(void)
{
    RCC(0xE0) |= 1u << 0; /* RCC_AHB4ENR.GPIOAEN */
    RCC(0xF0) |= 1u << 4; /* RCC_APB2ENR.USART1EN */
    (void)RCC(0xF0);      /* read back: the clock is on before the first access */
    /* PA9, PA10: alternate function 7 (MODER 10, AFRH fields 1 and 2). */
    GPIOA(0x00) = (GPIOA(0x00) & ~(0xFu << 18)) | (0xAu << 18);
    GPIOA(0x24) = (GPIOA(0x24) & ~(0xFFu << 4)) | (0x77u << 4);
    USART1(0x00) = 0u; /* UE = 0 while configuring */
    USART1(0x0C) = (TDC_DISCO_PCLK_HZ + LOG_BAUD / 2u) / LOG_BAUD;
    USART1(0x00) = (1u << 3) | (1u << 2) | 1u; /* TE, RE, UE */
    g_log_up = 1;
}

static void put(char c)
{
    for (uint32_t i = 0; i < TXE_TRIES; i++) {
        if (USART1(0x1C) & (1u << 7)) { /* ISR.TXE */
            USART1(0x28) = (uint8_t)c;
            return;
        }
    }
}

static void puts_raw(const char *s)
{
    while (*s) {
        put(*s++);
    }
}

void tdc_disco_log(const char *msg)
{
    if (!g_log_up) {
        return;
    }
    puts_raw(msg);
    puts_raw("\r\n");
}

static void hex32(char *out, uint32_t v)
{
    out[0] = '0';
    out[1] = 'x';
    for (int i = 0; i < 8; i++) {
        out[2 + i] = "0123456789abcdef"[(v >> (28 - 4 * i)) & 0xFu];
    }
    out[10] = '\0';
}

void tdc_disco_log_hex(const char *label, uint32_t value)
{
    char h[11];
    if (!g_log_up) {
        return;
    }
    hex32(h, value);
    puts_raw(label);
    puts_raw(h);
    puts_raw("\r\n");
}

/* Stacked frame (ARMv7-M exception entry): r0 r1 r2 r3 r12 lr pc xpsr. */
__attribute__((naked)) void tdc_disco_fault_entry(void)
{
    __asm__ volatile("tst lr, #4\n\t"
                     "ite eq\n\t"
                     "mrseq r0, msp\n\t"
                     "mrsne r0, psp\n\t"
                     "mrs r1, ipsr\n\t"
                     "b tdc_disco_fault_report\n\t");
}

_Noreturn void tdc_disco_fault_report(const uint32_t *frame, uint32_t exception)
{
    if (!g_log_up) {
        tdc_disco_log_init(); /* a fault before the log came up: clocks may be HSI, the text garbled but present */
    }
    tdc_disco_log_hex("fault: exception ", exception & 0x1FFu);
    if (frame) {
        tdc_disco_log_hex("fault: pc ", frame[6]);
        tdc_disco_log_hex("fault: lr ", frame[5]);
        tdc_disco_log_hex("fault: xpsr ", frame[7]);
    }
    tdc_disco_log_hex("fault: cfsr ", TDC_REG32(0xE000ED28u));
    tdc_disco_log_hex("fault: hfsr ", TDC_REG32(0xE000ED2Cu));
    tdc_disco_log_hex("fault: mmfar ", TDC_REG32(0xE000ED34u));
    tdc_disco_log_hex("fault: bfar ", TDC_REG32(0xE000ED38u));
    /* Let the last byte leave the shift register (ISR.TC), bounded. */
    for (uint32_t i = 0; i < TXE_TRIES && !(USART1(0x1C) & (1u << 6)); i++) {
    }
    TDC_REG32(TDC_CM_SCB_AIRCR) = (0x5FAu << 16) | (1u << 2); /* SYSRESETREQ */
    for (;;) {
    }
}
