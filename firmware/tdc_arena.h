/*
 * tdc_arena.h - the one way a stage lays out its caller-owned memory
 * (libopus / CMSIS-DSP style get_size() + init()).
 *
 * Every stage with state (TRM, LCD inverse, tile assembly, foveated remap) writes its arena
 * layout ONCE, as a list of blocks in its header:
 *
 *     #define TDC_XXX_ARENA(X, <geometry>)      \
 *         X(member, element type, element count) \
 *         ...
 *
 * and expands that one list twice:
 *   - at run time, with the configuration's geometry, through the carver
 *     below (TDC_ARENA_CARVE): get_size() carves into a dry-run arena (no
 *     memory, only the byte count), init() carves the caller's memory, so
 *     get_size() is exactly the layout init() uses;
 *   - at compile time, with the build's largest geometry, through
 *     TDC_ARENA_BLOCK_BYTES: the stage's TDC_XXX_MEM_BYTES(...) bound that
 *     boards size their static buffers with.
 * tests/unit/test_arena.c checks all three against each other for every stage,
 * every panel and the extreme sizes (get_size <= bound, equality at the
 * bound's geometry, init's pointers inside and disjoint, nothing written
 * past get_size bytes).
 *
 * Alignment, the one rule for every stage: the arena passed to init() must
 * be aligned to TDC_ARENA_ALIGN = 8 bytes (init() returns TDC_ERR_ARG
 * otherwise, it never realigns a pointer).  Every block starts at a multiple
 * of 8 from the base and is rounded up to 8 bytes, so get_size() and every
 * _MEM_BYTES bound are multiples of 8, and a static arena is simply
 *     static uint64_t arena[TDC_XXX_MEM_BYTES(...) / 8u];
 * Why 8: the widest element a stage keeps is 8 bytes (the assembly's
 * uint64_t box sums, Cortex-M7 LDRD/STRD of 64-bit values), and malloc and
 * every linker section the boards use give at least 8.  An empty layout
 * (e.g. TRM pass-through) still reports TDC_ARENA_ALIGN bytes: get_size()
 * returns 0 only for an invalid configuration.
 *
 * Integer-only, no heap, header-only (inline).
 */
#ifndef TDC_ARENA_H
#define TDC_ARENA_H

#include <stddef.h>
#include <stdint.h>

#define TDC_ARENA_ALIGN 8u

/* n rounded up to a multiple of TDC_ARENA_ALIGN (a constant expression). */
#define TDC_ARENA_ROUND(n) ((((size_t)(n)) + (TDC_ARENA_ALIGN - 1u)) & ~(size_t)(TDC_ARENA_ALIGN - 1u))

/* Compile-time expansion of a layout list: "+ bytes of the block". */
#define TDC_ARENA_BLOCK_BYTES(member, type, count) +TDC_ARENA_ROUND(sizeof(type) * (size_t)(count))

/* Run-time expansion of a layout list: carves `member` of the state `st`
 * from the arena `arena` (both names in scope where the list is expanded).
 * In a dry run the member becomes NULL. */
#define TDC_ARENA_CARVE(member, type, count) st->member = (type *)tdc_arena_take(arena, sizeof(type) * (size_t)(count));

typedef struct {
    uint8_t *base; /* caller's memory; NULL in a dry run (get_size) */
    size_t cap;    /* bytes at base (SIZE_MAX in a dry run) */
    size_t used;   /* bytes carved so far, a multiple of TDC_ARENA_ALIGN */
    int overflow;  /* a block size did not fit size_t: the layout is invalid */
} tdc_arena_t;

/* A dry run: counts bytes, hands out NULL. */
static inline void tdc_arena_dry(tdc_arena_t *a)
{
    a->base = NULL;
    a->cap = SIZE_MAX;
    a->used = 0;
    a->overflow = 0;
}

/* Carving `cap` bytes at mem.  0 when mem is NULL or not aligned to
 * TDC_ARENA_ALIGN (the stage returns TDC_ERR_ARG), else 1. */
static inline int tdc_arena_over(tdc_arena_t *a, void *mem, size_t cap)
{
    tdc_arena_dry(a);
    if (!mem || ((uintptr_t)mem & (TDC_ARENA_ALIGN - 1u)) != 0u) {
        return 0;
    }
    a->base = (uint8_t *)mem;
    a->cap = cap;
    return 1;
}

/* The next block of `bytes` (rounded up to TDC_ARENA_ALIGN), or NULL in a
 * dry run, for an empty block (0 bytes: e.g. the AVX2 table on a board) or
 * when it does not fit (init() compares the caller's size with get_size(),
 * the same carve as a dry run, before it touches anything). */
static inline void *tdc_arena_take(tdc_arena_t *a, size_t bytes)
{
    const size_t r = TDC_ARENA_ROUND(bytes);
    if (r < bytes || a->used > SIZE_MAX - r) {
        a->overflow = 1;
        return NULL;
    }
    void *p = (a->base && r != 0u && a->used + r <= a->cap) ? (void *)(a->base + a->used) : NULL;
    a->used += r;
    return p;
}

/* Bytes the layout needs: what get_size() returns (0 on overflow; an empty
 * layout needs TDC_ARENA_ALIGN so that 0 keeps meaning "invalid"). */
static inline size_t tdc_arena_size(const tdc_arena_t *a)
{
    if (a->overflow) {
        return 0;
    }
    return a->used ? a->used : TDC_ARENA_ALIGN;
}

#endif /* TDC_ARENA_H */
