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

uint32_t tdc_fw_time_stage(unsigned stage, uint32_t since)
{
    const uint32_t now = tdc_board_cycles();
    tdc_fw.stage_cycles[stage] += now - since; /* modulo 2^32: a stage under 10 s at 400 MHz */
    return now;
}

void tdc_fw_time_frame(void)
{
    static const char *const names[FW_STAGE_COUNT] = {"cycles/frame: decode ", " family ", " lcd ", " show "};
    if (++tdc_fw.timed_frames < (1u << FW_TIMING_LOG2)) {
        return;
    }
    uint64_t any = 0;
    char line[128];
    char *end = line + sizeof line - 1, *o = line;
    for (unsigned s = 0; s < FW_STAGE_COUNT; s++) {
        any |= tdc_fw.stage_cycles[s];
        o = tdc_text_str(o, end, names[s]);
        o = tdc_text_u32(o, end, (uint32_t)(tdc_fw.stage_cycles[s] >> FW_TIMING_LOG2));
        tdc_fw.stage_cycles[s] = 0;
    }
    *o = 0;
    tdc_fw.timed_frames = 0;
    if (any != 0u) {
        tdc_board_log(line);
    }
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
