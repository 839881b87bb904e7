/*
 * tdc_sim_stage_lcd.c - the LCD output stage: with an LCD panel, the
 * firmware's overdrive-aware inverse (firmware/tdc_lcd.h) turns the codes a
 * mode wants shown into drive codes, adding the residual the mode carries
 * (TRM's rho) where the panel could not reach; the panel simulation uses
 * the physical LCD model of the profile (sim/lcd/panels/NAME.lcdsim).
 * Behind the same init / frame / reset / free table as the mode families.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "simulator/tdc_sim_mode.h"

#include "tdc_lcd.h"

typedef struct {
    tdc_lcd_t lcd;
    void *mem;
} lcd_state_t;

static int lcd_init(sim_mode_t *m, const tdc_sim_setup_t *s)
{
    if (s->lcd_panel) {
        const tdc_sim_config_t *cfg = s->cfg;
        tdc_lcd_config_t lc = {(uint16_t)m->w, (uint16_t)m->h, (uint16_t)m->hz, (uint8_t)cfg->lcd_mode,
                               (uint8_t)cfg->lcd_bits};
        size_t n = tdc_lcd_get_size(&lc);
        lcd_state_t *st = calloc(1, sizeof(*st));
        if (!st) {
            return -1;
        }
        st->mem = n ? malloc(n) : NULL;
        if (st->mem && tdc_lcd_init(&st->lcd, &lc, s->lcd_panel, st->mem, n) == TDC_OK) {
            static const char *const names[] = {"gamma", "exact", "od17", "od33", "state", "state-pair"};
            char b[96];
            snprintf(b, sizeof(b), "LCD inverse %s, %d-bit history", names[cfg->lcd_mode % 6], cfg->lcd_bits);
            tdc_sim_note(m, b);
            m->drive = st;
        } else {
            char b[160];
            free(st->mem);
            free(st);
            snprintf(b, sizeof(b), "LCD firmware stage refused mode %d at %d Hz on %s: drive = wanted code",
                     cfg->lcd_mode, m->hz, s->lcd_panel->name);
            tdc_sim_note(m, b);
        }
    } else {
        tdc_sim_note(m, "no LCD panel profile: LCD firmware stage skipped, drive = wanted code");
    }
    char path[512], err[256];
    snprintf(path, sizeof(path), "sim/lcd/panels/%s.lcdsim", s->lcd_panel ? s->lcd_panel->name : "pg279q");
    if (tdc_panel_sim_use_lcdsim(&m->panel, path, err, sizeof(err)) != 0) {
        tdc_sim_note(m, err);
    } else if (s->cfg->backlight >= 0 && tdc_panel_sim_lcd_backlight(&m->panel, s->cfg->backlight, s->cfg->strobe_duty,
                                                                     s->cfg->strobe_phase) != 0) {
        tdc_sim_note(m, "LCD backlight timing refused: the panel's own is used");
    }
    tdc_sim_note(m, m->panel.model);
    return 0;
}

/* wanted -> out (the driver has copied wanted into out already). */
static int lcd_frame(sim_mode_t *m, tdc_source_t *src, double t, int spp, uint32_t lf)
{
    (void)src, (void)t, (void)spp, (void)lf;
    lcd_state_t *st = m->drive;
    if (!st) {
        return 0;
    }
    int32_t *rho = m->residual ? m->residual(m) : NULL;
    double t0 = tdc_sim_now();
    int rc = tdc_lcd_frame(&st->lcd, m->wanted, (uint32_t)m->w * 3u, m->out, (uint32_t)m->w * 3u, rho);
    m->res->fw_s += tdc_sim_now() - t0;
    return tdc_sim_stage(m, "tdc_lcd_frame", rc);
}

static void lcd_reset(sim_mode_t *m)
{
    lcd_state_t *st = m->drive;
    if (st) {
        tdc_lcd_reset(&st->lcd);
    }
}

static void lcd_free(sim_mode_t *m)
{
    lcd_state_t *st = m->drive;
    if (st) {
        free(st->mem);
        free(st);
    }
    m->drive = NULL;
}

const tdc_sim_family_t tdc_sim_stage_lcd = {"lcd", NULL, 0, lcd_init, lcd_frame, lcd_reset, lcd_free};
