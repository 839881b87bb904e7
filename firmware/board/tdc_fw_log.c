/*
 * tdc_fw_log.c - the board frame loop's log lines (no printf in firmware):
 * the reset cause at start, the loop's counters at the end (each family,
 * the bands and the LCD inverse log their own).
 */
#include "tdc_fw_family.h"
#include "tdc_text.h"

void tdc_fw_log_kv(const char *what, uint32_t v)
{
    char line[96];
    char *end = line + sizeof line - 1;
    char *o = tdc_text_str(line, end, what);
    o = tdc_text_u32(o, end, v);
    *o = 0;
    tdc_board_log(line);
}

const char *tdc_fw_reset_name(tdc_reset_cause_t c)
{
    static const char *const names[] = {"unknown", "power-on", "pin", "software", "watchdog", "brown-out", "low-power"};
    return (unsigned)c < sizeof names / sizeof names[0] ? names[c] : "unknown";
}

void tdc_fw_log_loop(const tdc_link_counters_t *c)
{
    uint32_t errors = 0;
    for (unsigned i = 1; i < TDC_LINK_ERR_COUNT; i++) {
        errors += c->errors[i];
    }
    tdc_fw_log_kv("packets accepted: ", c->packets_ok);
    tdc_fw_log_kv("packets/bytes rejected: ", errors);
    tdc_fw_log_kv("frames shown: ", tdc_fw.frames_shown);
    tdc_fw_log_kv("eyes kept (incomplete): ", tdc_fw.eyes_incomplete);
    tdc_fw_log_kv("full packets unused (never unpacked): ", tdc_fw.unused_full);
    tdc_fw_log_kv("late packets (ignored): ", tdc_fw.late_packets);
    tdc_fw_log_kv("stage errors: ", tdc_fw.stage_errors);
    tdc_fw_log_kv("unsupported streams: ", tdc_fw.unsupported);
    tdc_fw_log_kv("repeated stream headers (no-op): ", tdc_fw.stream_repeats);
    tdc_fw_log_kv("late full packets processed: ", tdc_fw.late_full);
    tdc_fw_log_kv("packets skipped (unused kind): ", c->packets_skipped);
}
