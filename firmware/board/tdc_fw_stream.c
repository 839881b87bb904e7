/*
 * tdc_fw_stream.c - stream set-up for the board frame loop: the families of
 * this build (tdc_fw_family.h), and for each stream header the decoder
 * accepts, the family its flags name, set up for the panel's rate, or a
 * refusal that says why (nothing of that stream is shown).
 */
#include "tdc_board.h"
#include "tdc_fw_family.h"

const tdc_fw_family_t *const tdc_fw_families[] = {TDC_FW_FAMILIES};
const size_t tdc_fw_family_count = sizeof tdc_fw_families / sizeof tdc_fw_families[0];

/* The refresh rate the panel runs a stream at: the stream's if the panel
 * has that rate, else the panel's nominal one. */
static uint16_t panel_hz(uint16_t stream_hz)
{
    const tdc_panel_t *panel = &TDC_PANEL_SYMBOL;
    uint16_t hz = panel->refresh_hz;
    for (unsigned i = 0; i < TDC_PANEL_MAX_RATES && panel->rates_hz[i]; i++) {
        if (panel->rates_hz[i] == stream_hz) {
            hz = stream_hz;
        }
    }
    return hz;
}

/* Why no family of this build plays a stream with these family flags. */
static const char *refusal(uint32_t sel)
{
    if (sel & TDC_LINK_STREAM_LAYERS) {
        return "stream sends layered subframes: this build has no layered assembly (STAGES=layers)";
    }
    if (sel & TDC_LINK_STREAM_SUBFRAMES) {
        return (sel & TDC_LINK_STREAM_FOVEATED)
                   ? "stream foveates assembly frames: not supported by this build"
                   : "stream uses TRM and tile assembly together: not supported by this build";
    }
    if (sel == (TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_FOVEATED)) {
        return "stream foveates TRM frames: not in this build (TDC_CFG_FOV_TRM)";
    }
    /* (the decoder, which has no buffers for a stage not built, refused
     * such a stream header already) */
    return (sel & TDC_LINK_STREAM_FOVEATED) ? "stream is foveated: this build has no foveation stage (STAGES=fov)"
                                            : "stream needs a stage this build does not have";
}

const tdc_fw_family_t *tdc_fw_stream_start(void)
{
    const tdc_link_stream_info_t *si = tdc_link_stream(&tdc_fw.dec);
    tdc_fw.have_stream = 0;
    if (!si) {
        return NULL;
    }
    tdc_fw.stream = *si;
    tdc_fw.stream_id = tdc_fw.dec.stream_id;
    tdc_fw.have_stream = 1;
    const int bands = (si->flags & TDC_LINK_STREAM_BANDS) != 0;
    if (bands != TDC_CFG_BANDS && (bands || FW_STAGING_RGB888 > sizeof tdc_fw_staging)) {
        /* bands need the front/back pair (a single buffer would show a
         * dropped picture's first bands); a build staging one band cannot
         * take whole pictures */
        tdc_board_log(bands ? "stream sends row bands: this build has no back buffer (TDC_CFG_BANDS)"
                            : "stream sends whole pictures: this build stages one row band (TDC_CFG_BANDS)");
        tdc_fw.unsupported++;
        return NULL;
    }
    const uint32_t sel = si->flags & FW_FAMILY_FLAGS;
    const tdc_fw_family_t *fam = NULL;
    for (size_t i = 0; i < tdc_fw_family_count; i++) {
        fam = tdc_fw_families[i]->flags == sel ? tdc_fw_families[i] : fam;
    }
    const uint16_t hz = panel_hz(si->refresh_hz);
    if (!fam) {
        tdc_board_log(refusal(sel));
        tdc_fw.unsupported++;
        return NULL;
    }
    if (fam->configure && fam->configure(si, hz) != 0) {
        tdc_fw.unsupported++;
        return NULL;
    }
    tdc_fw_lcd_configure(hz);
    return fam;
}

/* The stream header just accepted repeats the configured one (a copy for
 * late joiners). */
int tdc_fw_stream_repeat(const tdc_link_event_t *ev)
{
    const tdc_link_stream_info_t *si = tdc_link_stream(&tdc_fw.dec);
    return tdc_fw.have_stream && si && ev->stream_id == tdc_fw.stream_id && tdc_fw.stream.flags == si->flags &&
           tdc_fw.stream.r_num == si->r_num && tdc_fw.stream.r_den == si->r_den && tdc_fw.stream.width == si->width &&
           tdc_fw.stream.height == si->height && tdc_fw.stream.eyes == si->eyes &&
           tdc_fw.stream.refresh_hz == si->refresh_hz;
}
