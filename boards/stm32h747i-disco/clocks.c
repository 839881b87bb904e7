/*
 * clocks.c - STM32H747I-DISCO supply, voltage scale and clock tree, then the
 * Cortex-M7 caches and the MPU region of the SDRAM.
 *
 * Supply and scale (RM0399 chapter "Power control"): the DISCO wires
 * VCORE to the internal SMPS directly (UM2411), so PWR_CR3 gets SDEN = 1,
 * LDOEN = 0, BYPASS = 0 in ONE write (the supply bits are write-once after
 * power-on) and ACTVOSRDY is awaited; then VOS1, the highest scale on that
 * supply, and VOSRDY before any clock is raised.
 *
 * Clocks (RM0399 chapter "RCC"): HSE 25 MHz -> PLL1 (board.h) 400 MHz
 * SYSCLK; D1CPRE /1, HPRE /2 (AXI/AHB 200 MHz), all APB prescalers /2
 * (100 MHz): the VOS1 maxima of DS12930.  Flash (RM0399 chapter wait-state
 * table, VOS1, AXI 185-210 MHz): LATENCY 2, WRHIGHFREQ 2, read back before
 * the switch.
 *
 * Executed in tests/disco (register models enforce these rules); not yet run
 * on a board.
 */
#include <stdint.h>

#include "board.h"
#include "disco.h"

#define RCC(off) TDC_REG32(TDC_STM32_RCC + (off))
#define PWR(off) TDC_REG32(TDC_STM32_PWR + (off))
#define FLASH_ACR TDC_REG32(TDC_STM32_FLASH_R + 0x00u)

/* Bounded polls: a bit that never comes is reported, not hung on.
 * 10^6 reads are > 2 ms at any clock here, far above the longest documented
 * wait (HSE start-up, 2 ms typical for the crystal). */
#define POLL_TRIES 1000000u

static int wait_bits(volatile uint32_t *reg, uint32_t mask, uint32_t want)
{
    for (uint32_t i = 0; i < POLL_TRIES; i++) {
        if ((*reg & mask) == want) {
            return 1;
        }
    }
    return 0;
}

int tdc_disco_clocks_init(void)
{
    int ok = 1;
    /* PWR_CR3: SDEN only (direct SMPS), every supply field in one write. */
    PWR(0x0C) = (PWR(0x0C) & ~0x3Fu) | (1u << 2);
    ok &= wait_bits(&PWR(0x04), 1u << 13, 1u << 13); /* PWR_CSR1.ACTVOSRDY */
    /* PWR_D3CR.VOS = 11 (VOS1), then VOSRDY. */
    PWR(0x18) = (PWR(0x18) & ~(3u << 14)) | (3u << 14);
    ok &= wait_bits(&PWR(0x18), 1u << 13, 1u << 13);

    RCC(0x00) |= 1u << 16;                           /* RCC_CR.HSEON */
    ok &= wait_bits(&RCC(0x00), 1u << 17, 1u << 17); /* HSERDY */
    /* RCC_PLLCKSELR: PLLSRC = HSE (2), DIVM1. */
    RCC(0x28) = (RCC(0x28) & ~((0x3Fu << 4) | 3u)) | (TDC_DISCO_PLL1_M << 4) | 2u;
    /* RCC_PLLCFGR: PLL1RGE = 2 (4-8 MHz input), VCOSEL = 0 (wide), integer
     * mode, DIVP1EN DIVQ1EN DIVR1EN. */
    RCC(0x2C) = (RCC(0x2C) & ~0xFu & ~(7u << 16)) | (2u << 2) | (7u << 16);
    /* RCC_PLL1DIVR: each field holds the factor minus one. */
    RCC(0x30) = (TDC_DISCO_PLL1_N - 1u) | ((TDC_DISCO_PLL1_P - 1u) << 9) | ((TDC_DISCO_PLL1_Q - 1u) << 16) |
                ((TDC_DISCO_PLL1_R - 1u) << 24);
    RCC(0x00) |= 1u << 24;                           /* PLL1ON */
    ok &= wait_bits(&RCC(0x00), 1u << 25, 1u << 25); /* PLL1RDY */

    /* Flash wait states before the clock goes up, read back (RM0399). */
    FLASH_ACR = (2u << 0) | (2u << 4);
    ok &= wait_bits(&FLASH_ACR, 0x3Fu, (2u << 0) | (2u << 4));
    /* RCC_D1CFGR: D1CPRE /1, D1PPRE /2, HPRE /2; D2: D2PPRE1, D2PPRE2 /2;
     * D3: D3PPRE /2. */
    RCC(0x18) = (4u << 4) | 8u;
    RCC(0x1C) = (4u << 4) | (4u << 8);
    RCC(0x20) = (4u << 4);
    if (!ok) {
        return 0; /* stay on HSI 64 MHz rather than switch to a clock not ready */
    }
    RCC(0x10) = (RCC(0x10) & ~7u) | 3u;                 /* RCC_CFGR.SW = PLL1 */
    return wait_bits(&RCC(0x10), 7u << 3, 3u << 3); /* SWS */
}

/* MPU region 0 = the 32 MiB SDRAM as Normal memory, write-back
 * read/write-allocate (TEX 001, C 1, B 1), execute-never (ARMv7-M ARM
 * B3.5).  The default map makes 0xC0000000-0xDFFFFFFF Device memory, where
 * unaligned accesses fault and nothing is cached.  The LTDC reads the
 * frame buffers behind the cache's back: tdc_disco_dcache_clean() runs
 * before every flip (tdc_board_panel_show). */
static void mpu_sdram(void)
{
    TDC_REG32(0xE000ED98u) = 0u;                                             /* MPU_RNR */
    TDC_REG32(0xE000ED9Cu) = TDC_STM32_SDRAM_BASE;                           /* MPU_RBAR */
    TDC_REG32(0xE000EDA0u) = (1u << 28) | (3u << 24) | (1u << 19) | (1u << 17) /* XN, AP full, TEX 001, C */
                             | (1u << 16) | (24u << 1) | 1u;                   /* B, 2^(24+1) = 32 MiB, enable */
    TDC_REG32(0xE000ED94u) = (1u << 2) | 1u;                                 /* MPU_CTRL: PRIVDEFENA, ENABLE */
    __asm__ volatile("dsb\n\tisb" ::: "memory");
}

/* Both caches invalidated, then enabled (Cortex-M7 TRM: the caches come
 * out of reset with unknown contents).  The D-cache geometry is read from
 * CCSIDR (16 KiB, 4 ways, 128 sets, 32-byte lines on the H747). */
void tdc_disco_caches_on(void)
{
    mpu_sdram();
    __asm__ volatile("dsb\n\tisb" ::: "memory");
    TDC_REG32(0xE000EF50u) = 0u; /* ICIALLU */
    TDC_REG32(0xE000ED84u) = 0u; /* CSSELR: level 1 data */
    __asm__ volatile("dsb" ::: "memory");
    const uint32_t ccsidr = TDC_REG32(0xE000ED80u);
    const uint32_t sets = ((ccsidr >> 13) & 0x7FFFu) + 1u;
    const uint32_t ways = ((ccsidr >> 3) & 0x3FFu) + 1u;
    for (uint32_t set = 0; set < sets; set++) {
        for (uint32_t way = 0; way < ways; way++) {
            TDC_REG32(0xE000EF60u) = (way << 30) | (set << 5); /* DCISW (4 ways: way in bits 31:30) */
        }
    }
    __asm__ volatile("dsb" ::: "memory");
    TDC_REG32(0xE000ED14u) |= (1u << 16) | (1u << 17); /* SCB_CCR: DC, IC */
    __asm__ volatile("dsb\n\tisb" ::: "memory");
}

void tdc_disco_dcache_clean(const void *p, uint32_t bytes)
{
    uint32_t a = (uint32_t)(uintptr_t)p & ~31u;
    const uint32_t end = (uint32_t)(uintptr_t)p + bytes;
    __asm__ volatile("dsb" ::: "memory");
    for (; a < end; a += 32u) {
        TDC_REG32(0xE000EF68u) = a; /* DCCMVAC */
    }
    __asm__ volatile("dsb" ::: "memory");
}
