/*
 * fuzz_panel.c - libFuzzer harness of the panel-profile parser of the table
 * generator (hosttools/tablegen/tdc_tablegen.c, built into this harness
 * with its main() left out): any bytes as a profile.  The generator's
 * failure path (one message, exit) returns here instead of exiting.
 * Aborts (besides the sanitizers) when a profile is accepted that breaks
 * what the generator then relies on: a name of [A-Za-z0-9-] only, sizes,
 * bits and rates within their ranges, 1..3 rates with the nominal one
 * first-class, every lcd_p_hz rate among them, gamma within [1, 4].
 * Run with -close_fd_mask=2: every rejected profile prints its one line.
 */
#include <setjmp.h>
#include <stdio.h>

#define TDC_TABLEGEN_NO_MAIN
#define TDC_TABLEGEN_FAIL_HOOK fuzz_tablegen_failed
static jmp_buf g_fail;
void fuzz_tablegen_failed(int code);
void fuzz_tablegen_failed(int code)
{
    longjmp(g_fail, code ? code : 1);
}
#include "../../hosttools/tablegen/tdc_tablegen.c"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static profile_t p;
    g_path = "fuzz.panel";
    g_in = fmemopen((void *)data, size ? size : 1, "r");
    if (g_in == NULL) return 0;
    if (size == 0) {
        fclose(g_in);
        return 0;
    }
    if (setjmp(g_fail) != 0) {
        fclose(g_in);
        g_in = NULL;
        return 0;
    }
    parse_profile_stream(g_in, &p);
    fclose(g_in);
    g_in = NULL;
    /* accepted: check what the generator and the firmware rely on */
    for (const char *c = p.name; *c; c++)
        if (!(isalnum((unsigned char)*c) || *c == '-')) abort();
    if (!p.name[0] || p.width < 1 || p.width > 8192 || p.height < 1 || p.height > 8192 || p.eyes < 1 || p.eyes > 2 ||
        p.bits < 6 || p.bits > 10 || p.refresh_hz < 1 || p.refresh_hz > 1000 || p.nrates < 1 ||
        p.nrates >= TDC_PANEL_MAX_RATES)
        abort();
    for (int c = 0; c < 3; c++)
        if (!(p.gamma[c] >= 1.0 && p.gamma[c] <= 4.0)) abort();
    for (int i = 0; i < p.n_lcd_rate_p; i++) {
        int found = 0;
        for (int r = 0; r < p.nrates; r++) found |= p.rates[r] == p.lcd_rate_hz[i];
        if (!found) abort();
    }
    return 0;
}
