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
 * Usage: qemu-system-arm ... -plugin tdc-insn-count.so,mark=0xADDR,out=FILE
 * FILE gets one line per mark: "<index> <instructions so far>", and a last
 * line "total <instructions>".
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

static uint64_t g_insns;
static uint64_t g_mark_addr = UINT64_MAX;
static uint64_t g_marks[MAX_MARKS];
static unsigned g_nmarks;
static char g_out[1024];

static void on_mark(unsigned int vcpu, void *userdata)
{
    (void)vcpu;
    (void)userdata;
    if (g_nmarks < MAX_MARKS) {
        g_marks[g_nmarks++] = g_insns;
    }
}

static void on_tb_trans(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    (void)id;
    const size_t n = qemu_plugin_tb_n_insns(tb);
    qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &g_insns, n);
    for (size_t i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        if (qemu_plugin_insn_vaddr(insn) == g_mark_addr) {
            qemu_plugin_register_vcpu_insn_exec_cb(insn, on_mark, QEMU_PLUGIN_CB_NO_REGS, NULL);
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
        fprintf(f, "%u %llu\n", i, (unsigned long long)g_marks[i]);
    }
    fprintf(f, "total %llu\n", (unsigned long long)g_insns);
    fclose(f);
}

QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc, char **argv)
{
    (void)info;
    for (int i = 0; i < argc; i++) {
        if (!strncmp(argv[i], "mark=", 5)) {
            g_mark_addr = strtoull(argv[i] + 5, NULL, 0) & ~1ull; /* Thumb bit off */
        } else if (!strncmp(argv[i], "out=", 4)) {
            snprintf(g_out, sizeof g_out, "%s", argv[i] + 4);
        }
    }
    if (g_mark_addr == UINT64_MAX || !g_out[0]) {
        qemu_plugin_outs("tdc-insn-count: need mark=0xADDR,out=FILE\n");
        return -1;
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_tb_trans);
    qemu_plugin_register_atexit_cb(id, on_plugin_exit, NULL);
    return 0;
}
