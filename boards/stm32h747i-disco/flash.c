/*
 * flash.c - the STM32H747's embedded flash as the tdc DFU target
 * (tdc_usbp_flash_t in firmware/tdc_usbproto.h): two 1 MiB banks, the
 * running image in the bank mapped at 0x08000000, the update written to the
 * other bank at 0x08100000, then the banks swapped by option byte.
 *
 * RM0399 chapter "Embedded flash memory (FLASH)": 128 KiB sectors, 8 per
 * bank; programming in 256-bit flash words (8 consecutive 32-bit writes
 * with FLASH_CRx.PG set; the word is committed when the write buffer is
 * full and FLASH_SRx.QW clears); an erased word reads all ones and cannot
 * be programmed twice (ECC); sector erase = SER + SNB + START, busy until
 * QW clears.  The register set of bank 2 is bank 1's plus 0x100.
 *
 * A/B: the running bank is never written (a download aimed at it is
 * refused), so a power cut during an update leaves the running image
 * intact; the swap (FLASH_OPTSR_PRG.SWAP_BANK_OPT, OPTSTART) is the last
 * step and takes effect at the next reset.
 *
 * Erase time: a sector erase takes up to seconds (DS12930 flash
 * characteristics); polls here are bounded by TDC_DISCO_FLASH_ERASE_MS by
 * the DWT cycle counter.  A download block that starts a sector is
 * therefore too slow for its DNLOAD request: tdc_disco_flash_busy_ms()
 * makes the DFU state machine answer dfuDNBUSY with that bound as
 * bwPollTimeout and write the block after the reply (usb_hs.c), so the
 * host's next GETSTATUS arrives once the erase is over.
 *
 * Executed in tests/disco against a flash model that enforces these rules
 * and cuts power mid-update; not yet run on a board.
 */
#include <stdint.h>

#include "board.h"
#include "disco.h"

#define FLASH_R(off) TDC_REG32(TDC_STM32_FLASH_R + (off))
#define BANK_BYTES TDC_DISCO_FLASH_BANK_BYTES
#define SECTOR_BYTES (128u * 1024u)
#define WORD_BYTES 32u /* 256-bit flash word */
#define FLASH_BASE 0x08000000u

/* Per-bank register offsets (bank 2: + 0x100). */
#define KEYR 0x04u
#define CR 0x0Cu
#define SR 0x10u
#define CCR 0x14u
#define OPTKEYR 0x08u
#define OPTCR 0x18u
#define OPTSR_CUR 0x1Cu
#define OPTSR_PRG 0x20u
#define CR_LOCK (1u << 0)
#define CR_PG (1u << 1)
#define CR_SER (1u << 2)
#define CR_PSIZE_X64 (3u << 4)
#define CR_START (1u << 7)
#define SR_BSY (1u << 0)
#define SR_QW (1u << 2)
#define SR_ERRORS 0x07EE0000u /* WRPERR PGSERR STRBERR INCERR OPERR RDPERR RDSERR SNECCERR DBECCERR */
#define OPT_SWAP_BANK (1u << 31)

static int wait_idle(uint32_t bank_off, uint32_t ms)
{
    const uint32_t cycles_per_ms = TDC_BOARD_CPU_HZ / 1000u;
    const uint32_t t0 = TDC_REG32(TDC_CM_DWT_CYCCNT);
    uint32_t elapsed_ms = 0u, last = t0;
    while (FLASH_R(bank_off + SR) & (SR_QW | SR_BSY)) {
        const uint32_t now = TDC_REG32(TDC_CM_DWT_CYCCNT);
        while (now - last >= cycles_per_ms) { /* count whole ms: no 32-bit wrap over seconds */
            last += cycles_per_ms;
            elapsed_ms++;
        }
        if (elapsed_ms > ms) {
            return 0;
        }
    }
    const uint32_t err = FLASH_R(bank_off + SR) & SR_ERRORS;
    FLASH_R(bank_off + CCR) = err | (1u << 16); /* clear the error flags and EOP */
    return err == 0u;
}

static void unlock(uint32_t bank_off)
{
    if (FLASH_R(bank_off + CR) & CR_LOCK) {
        FLASH_R(bank_off + KEYR) = 0x45670123u;
        FLASH_R(bank_off + KEYR) = 0xCDEF89ABu;
    }
}

static int erase_sector(uint32_t bank_off, uint32_t sector)
{
    if (!wait_idle(bank_off, TDC_DISCO_FLASH_ERASE_MS)) {
        return 0;
    }
    FLASH_R(bank_off + CR) = CR_SER | CR_PSIZE_X64 | (sector << 8);
    FLASH_R(bank_off + CR) = CR_SER | CR_PSIZE_X64 | (sector << 8) | CR_START;
    const int ok = wait_idle(bank_off, TDC_DISCO_FLASH_ERASE_MS);
    FLASH_R(bank_off + CR) = 0u;
    return ok;
}

/* One 256-bit word from src (len <= 32 bytes; the rest of the word stays
 * erased, all ones). */
static int program_word(uint32_t bank_off, uint32_t addr, const uint8_t *src, uint32_t len)
{
    uint32_t w[8];
    for (uint32_t i = 0; i < 8u; i++) {
        uint32_t v = 0xFFFFFFFFu;
        for (uint32_t b = 0; b < 4u; b++) {
            const uint32_t k = 4u * i + b;
            if (k < len) {
                v = (v & ~(0xFFu << (8u * b))) | ((uint32_t)src[k] << (8u * b));
            }
        }
        w[i] = v;
    }
    FLASH_R(bank_off + CR) = CR_PG | CR_PSIZE_X64;
    __asm__ volatile("dsb" ::: "memory");
    for (uint32_t i = 0; i < 8u; i++) {
        TDC_REG32(addr + 4u * i) = w[i];
    }
    __asm__ volatile("dsb" ::: "memory");
    const int ok = wait_idle(bank_off, TDC_DISCO_FLASH_PROGRAM_MS);
    FLASH_R(bank_off + CR) = 0u;
    return ok;
}

/* Offsets 0 .. 1 MiB: the running bank (refused); 1 .. 2 MiB: the other
 * bank, mapped at 0x08100000.  A write starting a sector erases it first;
 * writes are in whole flash words except a download's last block. */
int tdc_disco_flash_write(void *ctx, uint32_t offset, const uint8_t *data, uint32_t len)
{
    (void)ctx;
    if (offset < BANK_BYTES || offset - BANK_BYTES > BANK_BYTES || len > 2u * BANK_BYTES - offset ||
        (offset % WORD_BYTES) != 0u) {
        return 1;
    }
    /* Registers follow the physical bank, the swap moves addresses only:
     * with SWAP_BANK clear bank 2 sits at 0x08100000 (register set 2),
     * with it set bank 1 does (set 1). */
    const uint32_t bank_off = (FLASH_R(OPTSR_CUR) & OPT_SWAP_BANK) ? 0u : 0x100u;
    unlock(bank_off);
    int ok = 1;
    for (uint32_t done = 0; ok && done < len; done += WORD_BYTES) {
        const uint32_t off = offset - BANK_BYTES + done;
        if (off % SECTOR_BYTES == 0u) {
            ok = erase_sector(bank_off, off / SECTOR_BYTES);
        }
        if (ok) {
            ok = program_word(bank_off, FLASH_BASE + BANK_BYTES + off, data + done,
                              len - done < WORD_BYTES ? len - done : WORD_BYTES);
        }
    }
    FLASH_R(bank_off + CR) = CR_LOCK;
    return ok ? 0 : 1;
}

uint32_t tdc_disco_flash_busy_ms(void *ctx, uint32_t offset, uint32_t len)
{
    (void)ctx;
    if (offset < BANK_BYTES || len == 0u) {
        return 0u; /* refused by the write at once */
    }
    const uint32_t first = (offset - BANK_BYTES + SECTOR_BYTES - 1u) / SECTOR_BYTES; /* sectors starting */
    const uint32_t end = (offset - BANK_BYTES + len - 1u) / SECTOR_BYTES;            /* in [offset, +len) */
    return end >= first ? (end - first + 1u) * TDC_DISCO_FLASH_ERASE_MS : 0u;
}

int tdc_disco_flash_read(void *ctx, uint32_t offset, uint8_t *data, uint32_t len)
{
    (void)ctx;
    if (offset > 2u * BANK_BYTES || len > 2u * BANK_BYTES - offset) {
        return 1;
    }
    const volatile uint8_t *src = (const volatile uint8_t *)(uintptr_t)(FLASH_BASE + offset);
    for (uint32_t i = 0; i < len; i++) {
        data[i] = src[i];
    }
    return 0;
}

/* Boot the other bank from the next reset: toggle SWAP_BANK_OPT, start the
 * option-byte programming, wait for it, reset. */
int tdc_disco_flash_activate_other_bank(void)
{
    if (FLASH_R(OPTCR) & 1u) { /* OPTLOCK */
        FLASH_R(OPTKEYR) = 0x08192A3Bu;
        FLASH_R(OPTKEYR) = 0x4C5D6E7Fu;
    }
    const uint32_t cur = FLASH_R(OPTSR_CUR);
    FLASH_R(OPTSR_PRG) = (cur & ~OPT_SWAP_BANK) | (~cur & OPT_SWAP_BANK);
    FLASH_R(OPTCR) = (FLASH_R(OPTCR) & ~1u) | (1u << 1); /* OPTSTART */
    for (uint32_t i = 0; i < 100000000u && (FLASH_R(OPTSR_CUR) & 1u); i++) { /* OPT_BUSY */
    }
    if ((FLASH_R(OPTSR_CUR) ^ cur) != OPT_SWAP_BANK) {
        return 0;
    }
    FLASH_R(OPTCR) |= 1u; /* OPTLOCK */
    TDC_REG32(TDC_CM_SCB_AIRCR) = (0x5FAu << 16) | (1u << 2);
    for (;;) {
    }
}
