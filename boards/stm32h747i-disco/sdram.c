/*
 * sdram.c - FMC SDRAM bank 2 of the STM32H747I-DISCO: IS42S32800J-6, 32-bit
 * bus, 4 banks x 4096 rows x 512 columns = 32 MiB at 0xD0000000 (UM2411:
 * SDNE1/SDCKE1, hence bank 2).
 *
 * FMC kernel clock = HCLK3 = 200 MHz (clocks.c), SDCLK = HCLK / 2 = 100 MHz
 * (10 ns).  Timings from the IS42S32800J data sheet (-6 speed grade),
 * rounded up to SDCLK cycles: tMRD 2 tCK, tXSR 70 ns -> 7, tRAS 42 ns -> 5,
 * tRC 60 ns -> 6, tRP 18 ns -> 2, tRCD 18 ns -> 2; TWR = max(tWR 2 tCK,
 * TRAS - TRCD, TRC - TRCD - TRP) = 3 (RM0399 FMC_SDTRx: TWR must also cover
 * those differences).  CAS latency 3 (2 would do at 100 MHz; 3 is legal at
 * every SDCLK this board can run).  Refresh: 4096 rows per 64 ms ->
 * 15.625 us x 100 MHz - 20 = 1542 (RM0399 FMC_SDRTR formula).
 *
 * Pins (UM2411 schematics, AF12 = FMC): the 32-bit data, address, bank,
 * control lines on ports D, E, F, G, H, I.
 *
 * Sequence: RM0399 FMC "SDRAM initialization" steps 1-8.  Executed in
 * tests/disco against an FMC model; not yet run on a board.
 */
#include <stdint.h>

#include "board.h"
#include "sdram.h"

#define RCC(off) TDC_REG32(TDC_STM32_RCC + (off))
#define FMC(off) TDC_REG32(TDC_STM32_FMC + (off))
#define GPIO(port, off) TDC_REG32(TDC_STM32_GPIO(port) + (off))

enum { PORT_D = 3, PORT_E = 4, PORT_F = 5, PORT_G = 6, PORT_H = 7, PORT_I = 8 };

static const struct {
    uint8_t port;
    uint16_t pins;
} k_fmc_pins[] = {
    {PORT_D, 0xC703u}, /* PD0 1 8 9 10 14 15 */
    {PORT_E, 0xFF83u}, /* PE0 1 7..15 */
    {PORT_F, 0xF83Fu}, /* PF0..5 11..15 */
    {PORT_G, 0x8137u}, /* PG0 1 2 4 5 8 15 */
    {PORT_H, 0xFFE0u}, /* PH5..15 */
    {PORT_I, 0x06FFu}, /* PI0..7 9 10 */
};

static void pins_fmc(void)
{
    RCC(0xE0) |= 0x1F8u; /* RCC_AHB4ENR: GPIOD..GPIOI */
    (void)RCC(0xE0);
    for (unsigned i = 0; i < sizeof k_fmc_pins / sizeof k_fmc_pins[0]; i++) {
        const uint32_t port = k_fmc_pins[i].port;
        for (uint32_t pin = 0; pin < 16u; pin++) {
            if (!(k_fmc_pins[i].pins & (1u << pin))) {
                continue;
            }
            GPIO(port, 0x00) = (GPIO(port, 0x00) & ~(3u << (2u * pin))) | (2u << (2u * pin)); /* MODER: AF */
            GPIO(port, 0x08) |= 3u << (2u * pin);                                             /* OSPEEDR: very high */
            GPIO(port, 0x0C) = (GPIO(port, 0x0C) & ~(3u << (2u * pin))) | (1u << (2u * pin)); /* PUPDR: up */
            const uint32_t afr = pin < 8u ? 0x20u : 0x24u;                                    /* AFRL / AFRH */
            const uint32_t sh = 4u * (pin & 7u);
            GPIO(port, afr) = (GPIO(port, afr) & ~(0xFu << sh)) | (12u << sh); /* AF12 = FMC */
        }
    }
}

static void sdram_command(uint32_t mode, uint32_t refresh_count, uint32_t mode_reg)
{
    while (FMC(0x158) & (1u << 5)) { /* FMC_SDSR: BUSY */
    }
    /* FMC_SDCMR: MODE, CTB2 (bank 2), NRFS, MRD */
    FMC(0x150) = mode | (1u << 3) | ((refresh_count - 1u) << 5) | (mode_reg << 9);
    while (FMC(0x158) & (1u << 5)) {
    }
}

static void delay_cycles(uint32_t n)
{
    for (volatile uint32_t i = 0; i < n; i++) {
    }
}

void tdc_stm32_sdram_init(void)
{
    RCC(0xD4) |= 1u << 12; /* RCC_AHB3ENR: FMCEN */
    (void)RCC(0xD4);
    pins_fmc();
    /* SDCR1 holds SDCLK, RBURST, RPIPE for both banks; SDCR2 the geometry. */
    const uint32_t common = (2u << 10) | (1u << 12); /* SDCLK = HCLK/2, read burst */
    const uint32_t geometry =
        (1u << 0) | (1u << 2) | (2u << 4) | (1u << 6) | (3u << 7); /* 9 col, 12 row, 32 bit, 4 banks, CAS 3 */
    FMC(0x140) = common | geometry;
    FMC(0x144) = common | geometry;
    /* SDTR: TMRD, TXSR, TRAS, TRC, TWR, TRP, TRCD (each minus one); TRC and
     * TRP are taken from SDTR1. */
    const uint32_t timing = (1u << 0) | (6u << 4) | (4u << 8) | (5u << 12) | (2u << 16) | (1u << 20) | (1u << 24);
    FMC(0x148) = timing;
    FMC(0x14C) = timing;
    TDC_REG32(TDC_STM32_FMC + 0x00u) |= 1u << 31; /* FMC_BCR1: FMCEN */
    sdram_command(1u, 1u, 0u);                    /* clock configuration enable */
    delay_cycles(100000u);                        /* >= 100 us: >= 4 cycles per iteration, 400 MHz */
    sdram_command(2u, 1u, 0u);                    /* precharge all */
    sdram_command(3u, 8u, 0u);                    /* 8 auto-refresh cycles */
    sdram_command(4u, 1u, 0x230u);                /* mode: burst 1, sequential, CAS 3, single write */
    FMC(0x154) = 1542u << 1;                      /* FMC_SDRTR: refresh count */
}
