/*
 * tdc_fvvdp.c - FovVideoVDP's frame loop, masking, pooling and JOD
 * regression (paper sections 3.2-3.6).  The stages it calls are in the
 * sibling files (tdc_fvvdp.h lists them).
 *
 * Per frame:
 *   1. the frame enters the history of test and reference luminance; the
 *      sustained and transient signals are the FIR of that history with the
 *      channel filters (tdc_fvvdp_temporal.c; the first frame fills the
 *      whole history, "replicate" padding);
 *   2. each signal is decomposed into a Laplacian pyramid; a band's contrast
 *      is the band divided by the local mean of the reference's sustained
 *      signal (the expanded next Gaussian level, floored at 0.1 cd/m^2),
 *      capped at 1000, and doubled for every band but the first (the
 *      reference's band_mul);
 *   3. contrasts are scaled by the CSF (tdc_fvvdp_csf.c) at the band
 *      frequency (times the off-axis resolution magnification), the local
 *      luminance and the pixel's eccentricity from the gaze, with the
 *      sensitivity correction of 16.2596 dB;
 *   4. masking (eq. 5-6, "min mutual masking"): D = |T - R|^p / (1 +
 *      (10^c * min(|T|, |R|))^q) with p = 2.4, c = -0.973838, q = 2.43685
 *      (sustained) or 4.946 (transient), capped at 1e4;
 *   5. pooling (eq. 7-8): a band's D is pooled with a beta = 1.52134 mean,
 *      bands are summed (beta_sch 1) with the transient channel weighted
 *      0.25, channels combined with a beta_tch = 0.666092 norm, frames
 *      averaged (beta_t 1);
 *   6. JOD (eq. 9): 10 - (|a|^(1/b) Q)^b, a = -0.0161713, b = 10^-0.228.
 * All values: fvvdp_parameters.json "version 1.2.3" of the reference.
 *
 * Sharing (tdc_fvvdp_new_shared): metrics judging several tests against one
 * reference hold and filter the reference once; a sharing metric reads the
 * owner's reference pyramids, so the owner must be fed each frame first.
 *
 * Memory: the history is ceil(fps/4) frames of test and reference, float,
 * w*h each (22.1 MB a 1440x1600 eye at 90 Hz, 23 taps: 23*2*4*2.3 M = 424
 * MB); the rest is O(w*h) doubles (the four signals' pyramids, 4/3 of a
 * frame each, plus four frame-sized scratch planes).  tdc_fvvdp_bytes()
 * reports the total.
 *
 * Threads: every pass runs over rows (sim/tdc_par.h); per-band sums are
 * per-row partial sums added in row order, so the JOD does not depend on
 * the thread count.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "metrics/tdc_fvvdp.h"
#include "tdc_par.h"

void tdc_fvvdp_csf_init(void);
double tdc_fvvdp_csf_lut_q(int ch, double log2_rho, double lum, double sqrt_ecc);

#define MASK_P 2.4
#define MASK_C (-0.973838)
#define MASK_Q_SUST 2.43685
#define MASK_Q_TRANS 4.946
#define W_TRANSIENT 0.25
#define BETA 1.52134
#define BETA_TCH 0.666092
#define SENS_CORR_DB 16.2596
#define JOD_A (-0.0161713)
#define LOG_JOD_EXP (-0.2280)

struct tdc_fvvdp {
    const tdc_fvvdp_t *owner; /* shares the owner's reference signals (tdc_fvvdp_new_shared) */
    tdc_fvvdp_geometry_t g;
    double ppd, fps;
    int w, h, nch, taps, frames, head;
    double f[2][TDC_FVVDP_MAX_TAPS];
    tdc_fvvdp_pyr_t pyr;
    float *hist;                          /* [streams][taps][w*h], ring at head: test, reference
                                             (the reference only without an owner) */
    double *gp[4][TDC_FVVDP_MAX_LEVELS];  /* Gaussian pyramids of the signals */
    double *lresmag[TDC_FVVDP_MAX_LEVELS]; /* log2 of the off-axis magnification per band sample */
    double *bkg, *ct, *cr, *tmp, *rows, *colx;
    double fovea_deg;
    /* Q of the frame in progress and pooled over frames: [all, fovea, periphery]. */
    double qsc[3][2], qsum[3];
    int nq[3];
    tdc_fvvdp_jods_t last;
    size_t bytes;
    double *const *dmap; /* heat-map hook (tdc_fvvdp_set_dmap) or NULL */
};

double tdc_fvvdp_q2jod(double q)
{
    double b = pow(10.0, LOG_JOD_EXP);
    return 10.0 - pow(pow(fabs(JOD_A), 1.0 / b) * q, b);
}

static void *zalloc(tdc_fvvdp_t *m, size_t n, size_t sz)
{
    m->bytes += n * sz;
    return calloc(n, sz);
}

static tdc_fvvdp_t *new_impl(const tdc_fvvdp_geometry_t *g, double fps, const tdc_fvvdp_t *owner, char *why,
                             size_t why_len)
{
    if (g->width < 4 || g->height < 4 || g->width > 16384 || g->height > 16384) {
        snprintf(why, why_len, "size %dx%d outside 4..16384", g->width, g->height);
        return NULL;
    }
    if (!(g->width_m > 0.0) || !(g->distance_m > 0.0)) {
        snprintf(why, why_len, "display width %g m, distance %g m: must be positive", g->width_m, g->distance_m);
        return NULL;
    }
    if (!(fps == 0.0 || (fps >= 8.0 && fps <= 1000.0))) {
        snprintf(why, why_len, "frame rate %g Hz outside 8..1000 (0 for images)", fps);
        return NULL;
    }
    tdc_fvvdp_t *m = calloc(1, sizeof *m);
    if (!m) {
        snprintf(why, why_len, "out of memory");
        return NULL;
    }
    m->owner = owner;
    m->g = *g;
    m->w = g->width;
    m->h = g->height;
    m->ppd = tdc_fvvdp_ppd(g);
    m->fps = fps;
    m->fovea_deg = 5.0;
    if (tdc_fvvdp_pyr_layout(&m->pyr, m->w, m->h, m->ppd) != 0) {
        snprintf(why, why_len, "no pyramid for %dx%d at %g px/deg", m->w, m->h, m->ppd);
        free(m);
        return NULL;
    }
    m->nch = 1;
    m->taps = 1;
    if (fps > 0.0) {
        m->nch = 2;
        m->taps = tdc_fvvdp_temporal_filters(fps, m->f);
    }
    size_t n = (size_t)m->w * m->h;
    int ok = 1;
    if (m->nch == 2) {
        ok &= (m->hist = zalloc(m, (owner ? 1 : 2) * (size_t)m->taps * n, sizeof(float))) != NULL;
    }
    for (int s = 0; s < 2 * m->nch; s++) {
        for (int l = 0; l < m->pyr.levels && !(owner && (s & 1)); l++) {
            ok &= (m->gp[s][l] = zalloc(m, (size_t)m->pyr.w[l] * m->pyr.h[l], sizeof(double))) != NULL;
        }
    }
    ok &= (m->bkg = zalloc(m, n, sizeof(double))) != NULL;
    ok &= (m->ct = zalloc(m, n, sizeof(double))) != NULL;
    ok &= (m->cr = zalloc(m, n, sizeof(double))) != NULL;
    ok &= (m->tmp = zalloc(m, n, sizeof(double))) != NULL;
    ok &= (m->rows = zalloc(m, 3 * (size_t)m->h, sizeof(double))) != NULL;
    ok &= (m->colx = zalloc(m, (size_t)m->w, sizeof(double))) != NULL;
    if (!ok) {
        snprintf(why, why_len, "out of memory (%zu bytes)", m->bytes);
        tdc_fvvdp_free(m);
        return NULL;
    }
    tdc_fvvdp_csf_init();
    return m;
}

tdc_fvvdp_t *tdc_fvvdp_new(const tdc_fvvdp_geometry_t *g, double fps, char *why, size_t why_len)
{
    return new_impl(g, fps, NULL, why, why_len);
}

tdc_fvvdp_t *tdc_fvvdp_new_shared(const tdc_fvvdp_t *owner, char *why, size_t why_len)
{
    if (owner->owner) {
        snprintf(why, why_len, "the owner of a shared reference must own it");
        return NULL;
    }
    return new_impl(&owner->g, owner->fps, owner, why, why_len);
}

/* Pyramid level l of signal s (odd s: the reference's, the owner's when
 * shared). */
static const double *sig(const tdc_fvvdp_t *m, int s, int l)
{
    return (s & 1) && m->owner ? m->owner->gp[s][l] : m->gp[s][l];
}

void tdc_fvvdp_free(tdc_fvvdp_t *m)
{
    if (!m) {
        return;
    }
    free(m->hist);
    for (int s = 0; s < 4; s++) {
        for (int l = 0; l < TDC_FVVDP_MAX_LEVELS; l++) {
            free(m->gp[s][l]);
        }
    }
    for (int l = 0; l < TDC_FVVDP_MAX_LEVELS; l++) {
        free(m->lresmag[l]);
    }
    free(m->colx);
    free(m->bkg);
    free(m->ct);
    free(m->cr);
    free(m->tmp);
    free(m->rows);
    free(m);
}

int tdc_fvvdp_frames(const tdc_fvvdp_t *m)
{
    return m->frames;
}

size_t tdc_fvvdp_bytes(const tdc_fvvdp_t *m)
{
    return m->bytes + sizeof *m;
}

static double pooled(const tdc_fvvdp_t *m, int r)
{
    return m->nq[r] ? tdc_fvvdp_q2jod(m->qsum[r] / m->nq[r]) : NAN;
}

double tdc_fvvdp_jod(const tdc_fvvdp_t *m)
{
    return m->nq[0] ? pooled(m, 0) : 10.0;
}

void tdc_fvvdp_pooled(const tdc_fvvdp_t *m, tdc_fvvdp_jods_t *j)
{
    j->all = pooled(m, 0);
    j->fovea = pooled(m, 1);
    j->periphery = pooled(m, 2);
}

void tdc_fvvdp_last(const tdc_fvvdp_t *m, tdc_fvvdp_jods_t *j)
{
    *j = m->last;
}

void tdc_fvvdp_reset_pool(tdc_fvvdp_t *m)
{
    for (int r = 0; r < 3; r++) {
        m->qsum[r] = 0.0;
        m->nq[r] = 0;
    }
}

void tdc_fvvdp_set_dmap(tdc_fvvdp_t *m, double *const *bands)
{
    m->dmap = bands;
}

int tdc_fvvdp_set_fovea(tdc_fvvdp_t *m, double deg)
{
    if (!(deg > 0.0 && deg <= 90.0)) {
        return -1;
    }
    m->fovea_deg = deg;
    return 0;
}

/* Level 0 of the four signals: the frame itself (images) or the FIR of the
 * history (video). */
static void signals(tdc_fvvdp_t *m, const float *test, const float *ref)
{
    size_t n = (size_t)m->w * m->h;
    int nt = m->owner ? 1 : 2; /* streams held: test, and the reference unless shared */
    if (m->nch == 1) {
        for (size_t i = 0; i < n; i++) {
            m->gp[0][0][i] = test[i];
            if (nt == 2) {
                m->gp[1][0][i] = ref[i];
            }
        }
        return;
    }
    const float *src[2] = { test, ref };
    for (int t = 0; t < nt; t++) {
        float *h = m->hist + (size_t)t * m->taps * n;
        if (m->frames == 0) {
            for (int k = 0; k < m->taps; k++) {
                memcpy(h + (size_t)k * n, src[t], n * sizeof(float));
            }
        } else {
            memcpy(h + (size_t)m->head * n, src[t], n * sizeof(float));
        }
    }
    int taps = m->taps, head = m->head, w = m->w;
    TDC_PAR_FOR((long)n * taps)
    for (int y = 0; y < m->h; y++) {
        for (int t = 0; t < nt; t++) {
            const float *h = m->hist + (size_t)t * taps * n + (size_t)y * w;
            double *sus = m->gp[t][0] + (size_t)y * w, *tr = m->gp[2 + t][0] + (size_t)y * w;
            for (int x = 0; x < w; x++) {
                sus[x] = 0.0;
                tr[x] = 0.0;
            }
            for (int k = 0; k < taps; k++) {
                /* Tap k weighs the frame k refreshes old. */
                const float *row = h + (size_t)((head - k + taps) % taps) * n;
                double f0 = m->f[0][k], f1 = m->f[1][k];
                TDC_SIMD
                for (int x = 0; x < w; x++) {
                    sus[x] += f0 * row[x];
                    tr[x] += f1 * row[x];
                }
            }
        }
    }
}

static void resmag_maps(tdc_fvvdp_t *m)
{
    for (int l = 0; l + 1 < m->pyr.levels; l++) {
        int bw = m->pyr.w[l], bh = m->pyr.h[l];
        if (m->lresmag[l]) {
            continue;
        }
        m->lresmag[l] = zalloc(m, (size_t)bw * bh, sizeof(double));
        if (!m->lresmag[l]) {
            continue; /* falls back to on-axis magnification 1 */
        }
        for (int y = 0; y < bh; y++) {
            for (int x = 0; x < bw; x++) {
                double d[2];
                tdc_fvvdp_view_dir(&m->g, bw, bh, x + 0.5, y + 0.5, d);
                m->lresmag[l][(size_t)y * bw + x] = log2(tdc_fvvdp_res_mag(&m->g, d));
            }
        }
    }
}

/* Q of one band and channel: the beta-mean of the masked, CSF-normalised
 * difference of the contrasts in m->ct (test) and m->cr (reference), over
 * the band (q[0]) and, with a gaze, over its samples within fovea_deg of the
 * gaze (q[1]) and beyond (q[2]; -1 where the region has no sample).  The
 * regional means are tdc's, not the paper's: the same pooling restricted to
 * the region's samples. */
static void band_q(tdc_fvvdp_t *m, int l, int ch, const double *gaze, double q[3])
{
    int bw = m->pyr.w[l], bh = m->pyr.h[l];
    double rho = m->pyr.rho[l];
    double corr = pow(10.0, SENS_CORR_DB / 20.0);
    double mc = pow(10.0, MASK_C);
    double mq = ch ? MASK_Q_TRANS : MASK_Q_SUST;
    double gd[2] = { 0.0, 0.0 };
    if (gaze) {
        tdc_fvvdp_view_dir(&m->g, m->w, m->h, gaze[0] + 0.5, gaze[1] + 0.5, gd);
    }
    const double *lrm = gaze ? m->lresmag[l] : NULL;
    double *dm = m->dmap ? m->dmap[l] : NULL, wch = ch ? W_TRANSIENT : 1.0;
    double *rin = m->rows + m->h, *nin = m->rows + 2 * (size_t)m->h;
    double lrho = log2(rho);
    /* Horizontal view angles relative to the gaze, per column (the view
     * direction's x depends on the column only, its y on the row only). */
    for (int x = 0; gaze && x < bw; x++) {
        double d[2];
        tdc_fvvdp_view_dir(&m->g, bw, bh, x + 0.5, 0.5, d);
        m->colx[x] = d[0] - gd[0];
    }
    TDC_PAR_FOR((long)bw * bh)
    for (int y = 0; y < bh; y++) {
        double s = 0.0, si = 0.0, ni = 0.0, vy = 0.0;
        if (gaze) {
            double d[2];
            tdc_fvvdp_view_dir(&m->g, bw, bh, 0.5, y + 0.5, d);
            vy = d[1] - gd[1];
        }
        for (int x = 0; x < bw; x++) {
            size_t i = (size_t)y * bw + x;
            double ecc = 0.0, lr = lrho;
            if (gaze) {
                double vx = m->colx[x];
                ecc = sqrt(vx * vx + vy * vy);
                lr = lrho + (lrm ? lrm[i] : 0.0);
            }
            double sens = tdc_fvvdp_csf_lut_q(ch, lr, m->bkg[i], sqrt(ecc)) * corr;
            double t = m->ct[i] * sens, rr = m->cr[i] * sens;
            double mk = mc * fmin(fabs(t), fabs(rr));
            double d = pow(fabs(t - rr), MASK_P) / (1.0 + pow(mk, mq));
            d = d < 1e4 ? d : 1e4;
            if (dm) {
                dm[i] += wch * d;
            }
            double e = pow(d, BETA);
            s += e;
            if (ecc < m->fovea_deg) {
                si += e;
                ni += 1.0;
            }
        }
        m->rows[y] = s;
        rin[y] = si;
        nin[y] = ni;
    }
    double n = (double)bw * bh;
    double sum = tdc_par_sum_rows(m->rows, bh);
    double sin_ = tdc_par_sum_rows(rin, bh), n_in = tdc_par_sum_rows(nin, bh);
    q[0] = pow(sum / n, 1.0 / BETA);
    q[1] = n_in > 0.0 ? pow(sin_ / n_in, 1.0 / BETA) : -1.0;
    q[2] = n - n_in > 0.0 ? pow(fmax(sum - sin_, 0.0) / (n - n_in), 1.0 / BETA) : -1.0;
}

/* Contrast of band l of signal s into out, given bkg of that band. */
static void band_contrast(tdc_fvvdp_t *m, int s, int l, double mul, double *out)
{
    int bw = m->pyr.w[l], bh = m->pyr.h[l];
    tdc_fvvdp_expand(sig(m, s, l + 1), bw, bh, out, m->tmp);
    const double *g = sig(m, s, l);
    TDC_PAR_FOR((long)bw * bh)
    for (int y = 0; y < bh; y++) {
        for (int x = 0; x < bw; x++) {
            size_t i = (size_t)y * bw + x;
            double c = (g[i] - out[i]) / m->bkg[i];
            out[i] = (c < 1000.0 ? c : 1000.0) * mul;
        }
    }
}

double tdc_fvvdp_frame(tdc_fvvdp_t *m, const float *test, const float *ref, const double *gaze)
{
    signals(m, test, ref);
    int nsig = 2 * m->nch, lv = m->pyr.levels;
    for (int s = 0; s < nsig; s++) {
        for (int l = 0; l + 1 < lv && !(m->owner && (s & 1)); l++) {
            tdc_fvvdp_reduce(m->gp[s][l], m->pyr.w[l], m->pyr.h[l], m->gp[s][l + 1], m->tmp);
        }
    }
    if (gaze) {
        resmag_maps(m);
    }
    /* Regions a band has no sample of are left out of that band's sum. */
    double qsc[3][2] = { { 0.0, 0.0 }, { 0.0, 0.0 }, { 0.0, 0.0 } };
    int have[3] = { 1, gaze != NULL, gaze != NULL };
    for (int l = 0; l + 1 < lv; l++) {
        int bw = m->pyr.w[l], bh = m->pyr.h[l];
        /* Local adaptation: the reference's sustained signal one level down. */
        tdc_fvvdp_expand(sig(m, 1, l + 1), bw, bh, m->bkg, m->tmp);
        for (size_t i = 0; i < (size_t)bw * bh; i++) {
            m->bkg[i] = m->bkg[i] > 0.1 ? m->bkg[i] : 0.1;
        }
        double mul = l == 0 ? 1.0 : 2.0;
        for (int c = 0; c < m->nch; c++) {
            double q[3];
            band_contrast(m, 2 * c, l, mul, m->ct);
            band_contrast(m, 2 * c + 1, l, mul, m->cr);
            band_q(m, l, c, gaze, q);
            for (int r = 0; r < 3; r++) {
                qsc[r][c] += q[r] > 0.0 ? q[r] * (c ? W_TRANSIENT : 1.0) : 0.0;
                have[r] &= !(l == 0 && q[r] < 0.0);
            }
        }
    }
    double qtc[3];
    for (int r = 0; r < 3; r++) {
        qtc[r] = pow(qsc[r][0], BETA_TCH);
        if (m->nch == 2) {
            qtc[r] += pow(qsc[r][1], BETA_TCH);
        }
        qtc[r] = pow(qtc[r], 1.0 / BETA_TCH);
        if (have[r]) {
            m->qsum[r] += qtc[r];
            m->nq[r]++;
        }
    }
    m->last.all = tdc_fvvdp_q2jod(qtc[0]);
    m->last.fovea = have[1] ? tdc_fvvdp_q2jod(qtc[1]) : NAN;
    m->last.periphery = have[2] ? tdc_fvvdp_q2jod(qtc[2]) : NAN;
    m->frames++;
    if (m->nch == 2) {
        m->head = (m->head + 1) % m->taps;
    }
    return m->last.all;
}
