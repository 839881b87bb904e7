/*
 * startup.c - STM32H747I-DISCO, Cortex-M7 core: vector table, clocks,
 * memories, then crt0 and main().
 *
 * Clock tree (RM0399 section 8): direct SMPS supply, VOS0 (VOS1 + ODEN),
 * HSE 25 MHz -> PLL1 (M = 5, N = 192, P = 2) = 480 MHz SYSCLK; AXI/AHB
 * 240 MHz, APBs 120 MHz; flash 4 wait states.  Then the FMC SDRAM
 * (sdram.c) and the MPU region that makes it Normal memory, before crt0
 * zeroes the buffers placed there.
 *
 * Written from the reference manual; builds and links in CI, NOT yet run on
 * hardware (no board in CI).  Bring-up order and values follow RM0399 and
 * the DISCO user manual UM2411.
 */
#include <stdint.h>

#include "board.h"
#include "sdram.h"
#include "tdc_crt0.h"
#include "tdc_vectors.h"

#define STM32H747_IRQS 150
TDC_VECTORS(STM32H747_IRQS);

#define RCC(off) TDC_REG32(TDC_STM32_RCC + (off))
#define PWR(off) TDC_REG32(TDC_STM32_PWR + (off))
#define SYSCFG_PWRCR TDC_REG32(0x58000400u + 0x2Cu)
#define FLASH_ACR TDC_REG32(TDC_STM32_FLASH_R + 0x00u)

static void wait_set(volatile uint32_t *reg, uint32_t mask)
{
    while ((*reg & mask) != mask) {
    }
}

static void clocks_init(void)
{
    /* Supply: direct SMPS (the DISCO's default wiring), LDO off. */
    PWR(0x0C) = (PWR(0x0C) & ~0x7u) | (1u << 2); /* PWR_CR3: SMPSEN */
    wait_set(&PWR(0x04), 1u << 13);              /* PWR_CSR1: ACTVOSRDY */
    /* VOS1, then overdrive (VOS0) for 480 MHz. */
    PWR(0x18) = (PWR(0x18) & ~(3u << 14)) | (3u << 14); /* PWR_D3CR: VOS = 11 (VOS1) */
    wait_set(&PWR(0x18), 1u << 13);                     /* VOSRDY */
    RCC(0xF4) |= 1u << 1;                               /* RCC_APB4ENR: SYSCFGEN */
    SYSCFG_PWRCR |= 1u;                                 /* ODEN */
    wait_set(&PWR(0x18), 1u << 13);
    /* HSE on. */
    RCC(0x00) |= 1u << 16;          /* RCC_CR: HSEON */
    wait_set(&RCC(0x00), 1u << 17); /* HSERDY */
    /* PLL1: HSE / 5 = 5 MHz in (range 4-8 MHz), x192 = 960 MHz VCO, /2 = 480 MHz. */
    RCC(0x28) = (RCC(0x28) & ~((0x3Fu << 4) | 3u)) | (5u << 4) | 2u;                    /* PLLCKSELR */
    RCC(0x2C) = (RCC(0x2C) & ~0xFu) | (2u << 2) | (1u << 16) | (1u << 17) | (1u << 18); /* PLLCFGR */
    RCC(0x30) = (191u << 0) | (1u << 9) | (3u << 16) | (1u << 24);                      /* PLL1DIVR N P Q R */
    RCC(0x00) |= 1u << 24;                                                              /* PLL1ON */
    wait_set(&RCC(0x00), 1u << 25);                                                     /* PLL1RDY */
    /* Bus dividers: HPRE /2 (240 MHz), APB3 /2; APB1, APB2 /2; APB4 /2. */
    RCC(0x18) = (8u << 0) | (4u << 4); /* RCC_D1CFGR */
    RCC(0x1C) = (4u << 4) | (4u << 8); /* RCC_D2CFGR */
    RCC(0x20) = (4u << 4);             /* RCC_D3CFGR */
    /* Flash: 4 wait states, programming delay 2 for 240 MHz AXI at VOS0. */
    FLASH_ACR = (4u << 0) | (2u << 4);
    while ((FLASH_ACR & 0xFu) != 4u) {
    }
    /* SYSCLK = PLL1. */
    RCC(0x10) = (RCC(0x10) & ~7u) | 3u;     /* RCC_CFGR: SW = PLL1 */
    while (((RCC(0x10) >> 3) & 7u) != 3u) { /* SWS */
    }
}

/* MPU region 0: SDRAM as Normal, non-cacheable memory (the default map
 * makes 0xC0000000-0xDFFFFFFF Device memory, where unaligned accesses
 * fault and LTDC coherence would need cache maintenance), execute never. */
static void mpu_sdram(void)
{
    TDC_REG32(0xE000ED98u) = 0u;                                  /* MPU_RNR */
    TDC_REG32(0xE000ED9Cu) = TDC_STM32_SDRAM_BASE;                /* MPU_RBAR */
    TDC_REG32(0xE000EDA0u) = (1u << 28) | (3u << 24) | (1u << 19) /* XN, AP full, TEX=001 */
                             | (24u << 1) | 1u;                   /* 2^(24+1) = 32 MiB, enable */
    TDC_REG32(0xE000ED94u) = (1u << 2) | 1u;                      /* MPU_CTRL: PRIVDEFENA | ENABLE */
    __asm__ volatile("dsb\n\tisb" ::: "memory");
}

/* Instruction cache on (data cache left off: frame buffers are shared with
 * the LTDC, and SDRAM is non-cacheable anyway). */
static void icache_on(void)
{
    __asm__ volatile("dsb\n\tisb" ::: "memory");
    TDC_REG32(0xE000EF50u) = 0u; /* ICIALLU */
    __asm__ volatile("dsb\n\tisb" ::: "memory");
    TDC_REG32(0xE000ED14u) |= 1u << 17; /* SCB_CCR.IC */
    __asm__ volatile("dsb\n\tisb" ::: "memory");
}

void Reset_Handler(void)
{
    clocks_init();
    icache_on();
    tdc_stm32_sdram_init();
    mpu_sdram();
    (void)tdc_crt0_start();
    /* main() returns only when the transport fails (today: the USB stub);
     * keep the last image on the panel and sleep. */
    for (;;) {
        __asm__ volatile("wfi");
    }
}

_Noreturn void tdc_board_fault(uint32_t exception)
{
    (void)exception;
    /* No debugger output on the board: reset (the reset cause register
     * then reads "software reset", which main reports over USB). */
    TDC_REG32(TDC_CM_SCB_AIRCR) = (0x5FAu << 16) | (1u << 2);
    for (;;) {
    }
}
