/*
 * tdc_insn_plugin.c - QEMU TCG plugin that counts executed guest
 * instructions and records the count every time the guest calls a marker
 * function (tdc_bench_mark, address given as mark=0x...).  make bench-arm
 * turns consecutive marks into instructions per output pixel.
 *
 * Debian's qemu-system-arm is built with plugin support but ships neither
 * plugins nor qemu-plugin.h, so the few declarations used are written out
 * below from the documented plugin API (QEMU 7.2, plugin API version 1:
 * docs/devel/tcg-plugins.rst).  Counting: every translated block adds its
 * instruction count to a 64-bit counter when it starts executing (inline
 * add, no callback); the marker's own block is counted before the mark is
 * taken, the same for every mark, so differences between marks are exact
 * instruction counts of the code in between.
 *
 * Usage: qemu-system-arm ... -plugin tdc-insn-count.so,mark=0xADDR[+0xADDR2...],out=FILE[,tbprof=FILE2]
 * FILE gets one line per mark: "<index> <instructions so far> <which mark
 * address, 0-based>", and a last line "total <instructions>".  FILE2 (optional profile) gets one line per
 * translated block: "<vaddr hex> <instructions in block> <executions>";
 * tests/arm/profile_arm.sh sums them per function.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- plugin API declarations (QEMU 7.2, version 1) ---- */
typedef uint64_t qemu_plugin_id_t;
struct qemu_plugin_tb;
struct qemu_plugin_insn;
typedef struct qemu_info_t qemu_info_t;
enum qemu_plugin_cb_flags { QEMU_PLUGIN_CB_NO_REGS = 0 };
enum qemu_plugin_op { QEMU_PLUGIN_INLINE_ADD_U64 = 0 };
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);
typedef void (*qemu_plugin_vcpu_udata_cb_t)(unsigned int vcpu_index, void *userdata);
typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *userdata);
void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb, size_t idx);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
void qemu_plugin_register_vcpu_tb_exec_inline(struct qemu_plugin_tb *tb, enum qemu_plugin_op op, void *ptr,
                                              uint64_t imm);
void qemu_plugin_register_vcpu_insn_exec_cb(struct qemu_plugin_insn *insn, qemu_plugin_vcpu_udata_cb_t cb,
                                            enum qemu_plugin_cb_flags flags, void *userdata);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb, void *userdata);
void qemu_plugin_outs(const char *string);
#define QEMU_PLUGIN_EXPORT __attribute__((visibility("default")))
/* ---- end of API declarations ---- */

QEMU_PLUGIN_EXPORT int qemu_plugin_version = 1;

#define MAX_MARKS 4096
#define MAX_MARK_ADDRS 8

static uint64_t g_insns;
static uint64_t g_mark_addr[MAX_MARK_ADDRS];
static unsigned g_nmark_addr;
static uint64_t g_marks[MAX_MARKS];
static unsigned g_mark_id[MAX_MARKS];
static unsigned g_nmarks;
static char g_out[1024];
static char g_prof[1024];

/* Profile records live in fixed blocks, so the counters the inline adds
 * point at never move. */
typedef struct {
    uint64_t vaddr;
    uint64_t count;
    uint32_t n;
} tb_rec_t;
#define RECS_PER_BLOCK 4096
typedef struct rec_block {
    struct rec_block *next;
    unsigned used;
    tb_rec_t rec[RECS_PER_BLOCK];
} rec_block_t;
static rec_block_t *g_blocks;

static tb_rec_t *new_rec(void)
{
    if (!g_blocks || g_blocks->used == RECS_PER_BLOCK) {
        rec_block_t *b = calloc(1, sizeof *b);
        if (!b) {
            return NULL;
        }
        b->next = g_blocks;
        g_blocks = b;
    }
    return &g_blocks->rec[g_blocks->used++];
}

static void on_mark(unsigned int vcpu, void *userdata)
{
    (void)vcpu;
    if (g_nmarks < MAX_MARKS) {
        g_mark_id[g_nmarks] = (unsigned)(uintptr_t)userdata;
        g_marks[g_nmarks++] = g_insns;
    }
}

static void on_tb_trans(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    (void)id;
    const size_t n = qemu_plugin_tb_n_insns(tb);
    qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &g_insns, n);
    if (g_prof[0] && n) {
        tb_rec_t *r = new_rec();
        if (r) {
            r->vaddr = qemu_plugin_insn_vaddr(qemu_plugin_tb_get_insn(tb, 0));
            r->n = (uint32_t)n;
            qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &r->count, 1);
        }
    }
    for (size_t i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        const uint64_t va = qemu_plugin_insn_vaddr(insn);
        for (unsigned m = 0; m < g_nmark_addr; m++) {
            if (va == g_mark_addr[m]) {
                qemu_plugin_register_vcpu_insn_exec_cb(insn, on_mark, QEMU_PLUGIN_CB_NO_REGS, (void *)(uintptr_t)m);
            }
        }
    }
}

static void on_plugin_exit(qemu_plugin_id_t id, void *userdata)
{
    (void)id;
    (void)userdata;
    FILE *f = g_out[0] ? fopen(g_out, "w") : NULL;
    if (!f) {
        qemu_plugin_outs("tdc-insn-count: no out= file, or cannot create it\n");
        return;
    }
    for (unsigned i = 0; i < g_nmarks; i++) {
        fprintf(f, "%u %llu %u\n", i, (unsigned long long)g_marks[i], g_mark_id[i]);
    }
    fprintf(f, "total %llu\n", (unsigned long long)g_insns);
    fclose(f);
    FILE *p = g_prof[0] ? fopen(g_prof, "w") : NULL;
    for (rec_block_t *b = g_blocks; p && b; b = b->next) {
        for (unsigned i = 0; i < b->used; i++) {
            if (b->rec[i].count) {
                fprintf(p, "%llx %u %llu\n", (unsigned long long)b->rec[i].vaddr, b->rec[i].n,
                        (unsigned long long)b->rec[i].count);
            }
        }
    }
    if (p) {
        fclose(p);
    }
}

QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc, char **argv)
{
    (void)info;
    for (int i = 0; i < argc; i++) {
        if (!strncmp(argv[i], "mark=", 5)) {
            const char *p = argv[i] + 5;
            while (*p && g_nmark_addr < MAX_MARK_ADDRS) {
                char *end;
                g_mark_addr[g_nmark_addr++] = strtoull(p, &end, 0) & ~1ull; /* Thumb bit off */
                p = *end == '+' ? end + 1 : end;
                if (end == p && *p) {
                    break;
                }
            }
        } else if (!strncmp(argv[i], "out=", 4)) {
            snprintf(g_out, sizeof g_out, "%s", argv[i] + 4);
        } else if (!strncmp(argv[i], "tbprof=", 7)) {
            snprintf(g_prof, sizeof g_prof, "%s", argv[i] + 7);
        }
    }
    if (!g_nmark_addr || !g_out[0]) {
        qemu_plugin_outs("tdc-insn-count: need mark=0xADDR,out=FILE\n");
        return -1;
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_tb_trans);
    qemu_plugin_register_atexit_cb(id, on_plugin_exit, NULL);
    return 0;
}
