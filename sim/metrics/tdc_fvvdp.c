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
 * Sharing: metrics judging several tests against one reference
 * (tdc_fvvdp_new_shared) hold and filter the reference once; a sharing
 * metric reads the owner's reference pyramids, so the owner must be fed each
 * frame first.  Metrics of the same size and rate (the modes and eyes of
 * one run, tdc_fvvdp_new_beside) work in one set of scratch planes in turn.
 *
 * Memory: the history is ceil(fps/4) frames of test and reference, 16-bit
 * codes (tdc_fvvdp_l16: relative rounding <= 2^-12), w*h each (4.6 MB a
 * frame of 1440x1600; at 90 Hz, 23 taps, 106 MB a stream); it grows with
 * the frames fed and stops at the filters' length (nothing older is kept),
 * so a run of n frames holds min(n, taps).  The
 * rest, once per workspace: the test signals' pyramids (2 x 4/3 frames of
 * doubles), four contrast planes (float), three planes of doubles and the
 * per-band magnification map; per reference, its two signals' pyramids.
 * tdc_fvvdp_bytes() reports what a metric holds itself.
 *
 * Threads: every pass runs over rows (sim/tdc_par.h); per-band sums are
 * per-row partial sums added in row order, so the JOD does not depend on
 * the thread count.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "metrics/tdc_fvvdp.h"
#include "tdc_par.h"

void tdc_fvvdp_csf_init(void);
void tdc_fvvdp_csf_lut_log2(const double *log2_rho, const double *log2_lum, const double *sqrt_ecc, int n,
                            double *s0, double *s1);

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
    tdc_fvvdp_t *owner; /* shares the owner's reference signals (tdc_fvvdp_new_shared) */
    tdc_fvvdp_t *ws;    /* works in ws's scratch (tdc_fvvdp_new_beside, _shared); NULL: its own */
    tdc_fvvdp_geometry_t g;
    double ppd, fps;
    int w, h, nch, taps, frames;
    double f[2][TDC_FVVDP_MAX_TAPS];
    tdc_fvvdp_pyr_t pyr;
    /* History: frame j of stream t (test, and the reference unless shared)
     * in hist[t][j % taps], allocated as frames arrive; taps older than the
     * first frame read the first frame ("replicate" padding), so a run of n
     * frames holds min(n, taps) of them. */
    unsigned short *hist[2][TDC_FVVDP_MAX_TAPS]; /* tdc_fvvdp_l16 codes */
    /* Gaussian pyramids of the signals: the reference's (odd) held by the
     * reference's owner, the test's (even) and the rest below by the
     * workspace's holder and used by every metric working in it in turn
     * (they never run frames at the same time): */
    double *gp[4][TDC_FVVDP_MAX_LEVELS];
    double *lresmag[TDC_FVVDP_MAX_LEVELS]; /* log2 of the off-axis magnification per band sample */
    double *bkg, *ex, *tmp, *rows, *colx;
    float *con[4];                         /* band contrasts: test, reference x sustained, transient */
    double fovea_deg;
    double *const *dmap; /* heat-map hook (tdc_fvvdp_set_dmap) or NULL */
    /* Q of the frame in progress and pooled over frames: [all, fovea, periphery]. */
    double qsc[3][2], qsum[3];
    int nq[3];
    tdc_fvvdp_jods_t last;
    size_t bytes;
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

static tdc_fvvdp_t *new_impl(const tdc_fvvdp_geometry_t *g, double fps, tdc_fvvdp_t *owner, tdc_fvvdp_t *ws,
                             char *why, size_t why_len)
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
    m->ws = ws;
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
    for (int s = 0; s < 2 * m->nch; s++) {
        for (int l = 0; l < m->pyr.levels && ((s & 1) ? !owner : !ws); l++) {
            ok &= (m->gp[s][l] = zalloc(m, (size_t)m->pyr.w[l] * m->pyr.h[l], sizeof(double))) != NULL;
        }
        ok &= ws || (m->con[s] = zalloc(m, n, sizeof(float))) != NULL;
    }
    if (!ws) {
        /* tmp: reduce needs w ceil(h/2), expand ceil(w/2) h */
        size_t nt = (size_t)(m->w > m->h ? m->w : m->h) * ((m->w < m->h ? m->w : m->h) + 1) / 2;
        ok &= (m->bkg = zalloc(m, n, sizeof(double))) != NULL;
        ok &= (m->ex = zalloc(m, n, sizeof(double))) != NULL;
        ok &= (m->tmp = zalloc(m, nt, sizeof(double))) != NULL;
        ok &= (m->rows = zalloc(m, 5 * (size_t)m->h, sizeof(double))) != NULL;
        ok &= (m->colx = zalloc(m, (size_t)m->w, sizeof(double))) != NULL;
    }
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
    return new_impl(g, fps, NULL, NULL, why, why_len);
}

tdc_fvvdp_t *tdc_fvvdp_new_shared(tdc_fvvdp_t *owner, char *why, size_t why_len)
{
    if (owner->owner) {
        snprintf(why, why_len, "the owner of a shared reference must own it");
        return NULL;
    }
    return new_impl(&owner->g, owner->fps, owner, owner->ws ? owner->ws : owner, why, why_len);
}

tdc_fvvdp_t *tdc_fvvdp_new_beside(tdc_fvvdp_t *other, char *why, size_t why_len)
{
    return new_impl(&other->g, other->fps, NULL, other->ws ? other->ws : other, why, why_len);
}

/* The metric holding the scratch m works in. */
static tdc_fvvdp_t *home(tdc_fvvdp_t *m)
{
    return m->ws ? m->ws : m;
}

/* Pyramid of signal s (odd: the reference's, held by its owner). */
static double **pyr(tdc_fvvdp_t *m, int s)
{
    return (s & 1) ? (m->owner ? m->owner : m)->gp[s] : home(m)->gp[s];
}

void tdc_fvvdp_free(tdc_fvvdp_t *m)
{
    if (!m) {
        return;
    }
    for (int t = 0; t < 2; t++) {
        for (int k = 0; k < TDC_FVVDP_MAX_TAPS; k++) {
            free(m->hist[t][k]);
        }
    }
    for (int s = 0; s < 4; s++) {
        for (int l = 0; l < TDC_FVVDP_MAX_LEVELS; l++) {
            free(m->gp[s][l]);
        }
        free(m->con[s]);
    }
    for (int l = 0; l < TDC_FVVDP_MAX_LEVELS; l++) {
        free(m->lresmag[l]);
    }
    free(m->colx);
    free(m->bkg);
    free(m->ex);
    free(m->tmp);
    free(m->rows);
    free(m);
}

void tdc_fvvdp_set_dmap(tdc_fvvdp_t *m, double *const *bands)
{
    m->dmap = bands;
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

int tdc_fvvdp_set_fovea(tdc_fvvdp_t *m, double deg)
{
    if (!(deg > 0.0 && deg <= 90.0)) {
        return -1;
    }
    m->fovea_deg = deg;
    return 0;
}

/* A row of luminance into the history's 16-bit codes. */
static TDC_SIMD_CLONES void encode_row(const float *in, unsigned short *out, int w)
{
    TDC_SIMD
    for (int x = 0; x < w; x++) {
        out[x] = tdc_fvvdp_l16(in[x]);
    }
}

/* Both channels' FIR of one row over the taps (rows[k] + off: the frame k
 * refreshes old): sustained into sus, transient into tr, in double, taps
 * added in order (the same bits in every clone and thread). */
static TDC_SIMD_CLONES void fir_row(const unsigned short *const *rows, size_t off, int taps, const double *f0,
                                    const double *f1, int w, double *sus, double *tr)
{
    for (int x = 0; x < w; x++) {
        sus[x] = 0.0;
        tr[x] = 0.0;
    }
    for (int k = 0; k < taps; k++) {
        const unsigned short *row = rows[k] + off;
        double a = f0[k], b = f1[k];
        TDC_SIMD
        for (int x = 0; x < w; x++) {
            double v = tdc_fvvdp_l16_value(row[x]);
            sus[x] += a * v;
            tr[x] += b * v;
        }
    }
}

/* Level 0 of the four signals: the frame itself (images) or the FIR of the
 * history (video; the frame enters it as 16-bit codes, tdc_fvvdp_l16, and
 * every tap, this frame's too, reads the codes).  -1: out of memory for the
 * history. */
static int signals(tdc_fvvdp_t *m, const float *test, const float *ref)
{
    size_t n = (size_t)m->w * m->h;
    int nt = m->owner ? 1 : 2; /* streams held: test, and the reference unless shared */
    if (m->nch == 1) {
        for (size_t i = 0; i < n; i++) {
            pyr(m, 0)[0][i] = test[i];
            if (nt == 2) {
                pyr(m, 1)[0][i] = ref[i];
            }
        }
        return 0;
    }
    const float *src[2] = { test, ref };
    const unsigned short *rows[2][TDC_FVVDP_MAX_TAPS];
    int taps = m->taps, cur = m->frames, w = m->w;
    for (int t = 0; t < nt; t++) {
        unsigned short **slot = &m->hist[t][cur % taps];
        if (!*slot && !(*slot = zalloc(m, n, sizeof(unsigned short)))) {
            return -1;
        }
        for (int k = 0; k < taps; k++) {
            /* Tap k weighs the frame k refreshes old (the first before it). */
            rows[t][k] = m->hist[t][(cur - k > 0 ? cur - k : 0) % taps];
        }
    }
    TDC_PAR_FOR((long)n * taps)
    for (int y = 0; y < m->h; y++) {
        for (int t = 0; t < nt; t++) {
            encode_row(src[t] + (size_t)y * w, m->hist[t][cur % taps] + (size_t)y * w, w);
            double *sus = pyr(m, t)[0] + (size_t)y * w, *tr = pyr(m, 2 + t)[0] + (size_t)y * w;
            fir_row(rows[t], (size_t)y * w, taps, m->f[0], m->f[1], w, sus, tr);
        }
    }
    return 0;
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

/* log2 and exp2 for the masking loop, in single precision and plain
 * arithmetic so that it vectorises (8 lanes in the AVX2 clone; libm's pow,
 * three per sample and channel, took 60 % of the metric's time at
 * 1440x1600) and gives the same bits in every clone and thread.  log2: the
 * exponent plus 2 atanh(s) / ln 2 of the mantissa m in [sqrt(1/2), sqrt(2)),
 * s = (m - 1) / (m + 1) <= 0.172, series to s^9 (truncation < 1e-8); x below
 * FLT_MIN (0, subnormals) gives -150, whose exp2 is 0 at the scale of every
 * sum here.  exp2: 2^k by the exponent bits times e^(f ln 2), f = x - k in
 * [-0.5, 0.5], Taylor to degree 7 (truncation < 1e-8); x clamped to
 * [-126, 126].  Float rounding moves the validation's JODs by < 1e-5. */
typedef union {
    float f;
    uint32_t u;
} bits_t;

static inline float fast_log2(float x)
{
    bits_t b = { .f = x }, mant;
    float e = (float)(int32_t)(b.u >> 23) - 127.0f;
    mant.u = (b.u & 0x007FFFFFu) | 0x3F800000u;
    int hi = mant.f > 1.41421356f;
    float m = hi ? 0.5f * mant.f : mant.f;
    e = hi ? e + 1.0f : e;
    float s = (m - 1.0f) / (m + 1.0f), z = s * s;
    float p = 1.0f / 9.0f;
    p = p * z + 1.0f / 7.0f;
    p = p * z + 1.0f / 5.0f;
    p = p * z + 1.0f / 3.0f;
    p = p * z + 1.0f;
    float r = e + 2.88539008f * s * p; /* 2 / ln 2 */
    return x >= 1.17549435e-38f ? r : -150.0f;
}

static inline float fast_exp2(float x)
{
    const float magic = 12582912.0f; /* 1.5 * 2^23: adding it rounds to an integer */
    x = x < -126.0f ? -126.0f : (x > 126.0f ? 126.0f : x);
    bits_t t = { .f = x + magic }, sc;
    float k = t.f - magic, y = (x - k) * 0.693147181f;
    sc.u = (t.u - 0x4B400000u + 127u) << 23;
    float p = 1.0f / 5040.0f;
    p = p * y + 1.0f / 720.0f;
    p = p * y + 1.0f / 120.0f;
    p = p * y + 1.0f / 24.0f;
    p = p * y + 1.0f / 6.0f;
    p = p * y + 0.5f;
    p = p * y + 1.0f;
    p = p * y + 1.0f;
    return p * sc.f;
}

/* Masking and the beta power of n samples of one channel: contrasts ct
 * (test) and cr (reference), lsens = log2 of the CSF sensitivity with its
 * correction, mq the channel's masking exponent; e receives
 * min(|T - R|^p / (1 + (10^c min(|T|, |R|))^q), 1e4)^beta, T = ct sens,
 * R = cr sens (steps 4-5 of the header, in log2). */
static TDC_SIMD_CLONES void mask_row(const float *ct, const float *cr, const float *lsens, float mq, int n, float *e)
{
    const float lmc = (float)(MASK_C * 3.3219280948873623); /* log2 10 */
    const float lcap = 13.2877124f;                         /* log2 1e4 */
    const float p = (float)MASK_P, beta = (float)BETA;
    TDC_SIMD
    for (int x = 0; x < n; x++) {
        float t = fabsf(ct[x]), r = fabsf(cr[x]);
        float dd = fabsf(ct[x] - cr[x]), mn = t < r ? t : r;
        float ld = fast_log2(dd) + lsens[x];
        float lm = lmc + fast_log2(mn) + lsens[x];
        float lq = p * ld - fast_log2(1.0f + fast_exp2(mq * lm));
        lq = lq < lcap ? lq : lcap;
        e[x] = dd > 0.0f ? fast_exp2(beta * lq) : 0.0f;
    }
}

#define CHUNK 256 /* samples of a row per masking call (stack buffers) */

/* Q of one band, both channels: the beta-mean of the masked,
 * CSF-normalised difference of the contrasts in con[] over the band
 * (q[c][0]) and, with a gaze, over its samples within fovea_deg of the gaze
 * (q[c][1]) and beyond (q[c][2]; -1 where the region has no sample).  The
 * regional means are tdc's, not the paper's: the same pooling restricted to
 * the region's samples.  The CSF's table position (frequency, adapting
 * luminance, eccentricity) is the same for both channels: found once. */
static void band_q(tdc_fvvdp_t *m, int l, const double *gaze, double q[2][3])
{
    tdc_fvvdp_t *o = home(m);
    int bw = m->pyr.w[l], bh = m->pyr.h[l], nch = m->nch;
    double lcorr = SENS_CORR_DB / 20.0 * 3.3219280948873623; /* log2 of the correction */
    double gd[2] = { 0.0, 0.0 };
    if (gaze) {
        tdc_fvvdp_view_dir(&m->g, m->w, m->h, gaze[0] + 0.5, gaze[1] + 0.5, gd);
    }
    const double *lrm = gaze ? o->lresmag[l] : NULL;
    double *dm = m->dmap ? m->dmap[l] : NULL; /* this metric's heat map, not the workspace's */
    double *rows = o->rows; /* per row: sum ch 0, ch 1, fovea ch 0, ch 1, fovea samples */
    double lrho = log2(m->pyr.rho[l]), fovea = m->fovea_deg;
    /* Horizontal view angles relative to the gaze, per column (the view
     * direction's x depends on the column only, its y on the row only). */
    for (int x = 0; x < bw; x++) {
        double d[2] = { 0.0, 0.0 };
        if (gaze) {
            tdc_fvvdp_view_dir(&m->g, bw, bh, x + 0.5, 0.5, d);
        }
        o->colx[x] = d[0] - gd[0];
    }
    TDC_PAR_FOR((long)bw * bh)
    for (int y = 0; y < bh; y++) {
        double acc[5] = { 0.0, 0.0, 0.0, 0.0, 0.0 }, vy = 0.0;
        if (gaze) {
            double d[2];
            tdc_fvvdp_view_dir(&m->g, bw, bh, 0.5, y + 0.5, d);
            vy = d[1] - gd[1];
        }
        for (int x0 = 0; x0 < bw; x0 += CHUNK) {
            int nx = bw - x0 < CHUNK ? bw - x0 : CHUNK;
            size_t i0 = (size_t)y * bw + x0;
            double a[2][CHUNK], lr[CHUNK], ly[CHUNK], se[CHUNK], in[CHUNK]; /* in: 1 within the fovea */
            float ls[2][CHUNK], e[CHUNK];
            const double *bkg = o->bkg + i0, *cx = o->colx + x0, *lm = lrm ? lrm + i0 : NULL;
            for (int x = 0; x < nx; x++) {
                lr[x] = lm ? lrho + lm[x] : lrho;
            }
            TDC_SIMD
            for (int x = 0; x < nx; x++) {
                double ecc = sqrt(cx[x] * cx[x] + vy * vy); /* 0 without a gaze */
                ly[x] = fast_log2((float)bkg[x]); /* the table axis: 1e-6 is plenty */
                se[x] = sqrt(ecc);
                in[x] = ecc < fovea ? 1.0 : 0.0;
            }
            tdc_fvvdp_csf_lut_log2(lr, ly, se, nx, a[0], a[1]);
            TDC_SIMD
            for (int x = 0; x < nx; x++) {
                ls[0][x] = (float)(a[0][x] + lcorr);
                ls[1][x] = (float)(a[1][x] + lcorr);
            }
            for (int c = 0; c < nch; c++) {
                mask_row(o->con[2 * c] + i0, o->con[2 * c + 1] + i0, ls[c], c ? (float)MASK_Q_TRANS : (float)MASK_Q_SUST, nx, e);
                for (int x = 0; x < nx; x++) {
                    acc[c] += e[x];
                    acc[2 + c] += in[x] * e[x];
                }
                /* The heat map takes the masked difference d itself: e = d^beta. */
                for (int x = 0; dm && x < nx; x++) {
                    dm[i0 + x] += (c ? W_TRANSIENT : 1.0) * pow(e[x], 1.0 / BETA);
                }
            }
            for (int x = 0; x < nx; x++) {
                acc[4] += in[x];
            }
        }
        for (int k = 0; k < 5; k++) {
            rows[(size_t)k * bh + y] = acc[k];
        }
    }
    double n = (double)bw * bh, n_in = tdc_par_sum_rows(rows + 4 * (size_t)bh, bh);
    for (int c = 0; c < nch; c++) {
        double sum = tdc_par_sum_rows(rows + (size_t)c * bh, bh);
        double sin_ = tdc_par_sum_rows(rows + (size_t)(2 + c) * bh, bh);
        q[c][0] = pow(sum / n, 1.0 / BETA);
        q[c][1] = n_in > 0.0 ? pow(sin_ / n_in, 1.0 / BETA) : -1.0;
        q[c][2] = n - n_in > 0.0 ? pow(fmax(sum - sin_, 0.0) / (n - n_in), 1.0 / BETA) : -1.0;
    }
}

/* Contrast of band l of signal s into con[s] (float: its rounding, 6e-8 of
 * the contrast, is far below any visible difference), given bkg. */
static void band_contrast(tdc_fvvdp_t *m, int s, int l, double mul)
{
    tdc_fvvdp_t *o = home(m);
    int bw = o->pyr.w[l], bh = o->pyr.h[l];
    const double *g = pyr(m, s)[l], *up = pyr(m, s)[l + 1], *bkg = o->bkg;
    double *ex = o->ex, *tmp = o->tmp;
    const int bw2 = (bw + 1) / 2;
    float *out = o->con[s];
    TDC_PAR_FOR((long)bw * bh)
    for (int y = 0; y < bh; y++) {
        tdc_fvvdp_expand_row(up, bw, bh, y, tmp + (size_t)y * bw2, ex + (size_t)y * bw);
        for (size_t i = (size_t)y * bw; i < (size_t)(y + 1) * bw; i++) {
            double c = (g[i] - ex[i]) / bkg[i];
            out[i] = (float)((c < 1000.0 ? c : 1000.0) * mul);
        }
    }
}

double tdc_fvvdp_frame(tdc_fvvdp_t *m, const float *test, const float *ref, const double *gaze)
{
    tdc_fvvdp_t *o = home(m);
    if (signals(m, test, ref)) {
        return NAN;
    }
    int nsig = 2 * m->nch, lv = m->pyr.levels;
    for (int s = 0; s < nsig; s++) {
        for (int l = 0; l + 1 < lv && !(m->owner && (s & 1)); l++) {
            tdc_fvvdp_reduce(pyr(m, s)[l], m->pyr.w[l], m->pyr.h[l], pyr(m, s)[l + 1], o->tmp);
        }
    }
    if (gaze) {
        resmag_maps(o);
    }
    /* Regions a band has no sample of are left out of that band's sum. */
    double qsc[3][2] = { { 0.0, 0.0 }, { 0.0, 0.0 }, { 0.0, 0.0 } };
    int have[3] = { 1, gaze != NULL, gaze != NULL };
    for (int l = 0; l + 1 < lv; l++) {
        int bw = m->pyr.w[l], bh = m->pyr.h[l];
        /* Local adaptation: the reference's sustained signal one level down. */
        const double *up = pyr(m, 1)[l + 1];
        double *bkg = o->bkg, *tmp = o->tmp;
        const int bw2 = (bw + 1) / 2;
        TDC_PAR_FOR((long)bw * bh)
        for (int y = 0; y < bh; y++) {
            tdc_fvvdp_expand_row(up, bw, bh, y, tmp + (size_t)y * bw2, bkg + (size_t)y * bw);
            for (size_t i = (size_t)y * bw; i < (size_t)(y + 1) * bw; i++) {
                bkg[i] = bkg[i] > 0.1 ? bkg[i] : 0.1;
            }
        }
        double mul = l == 0 ? 1.0 : 2.0;
        for (int s = 0; s < nsig; s++) {
            band_contrast(m, s, l, mul);
        }
        double q[2][3];
        band_q(m, l, gaze, q);
        for (int c = 0; c < m->nch; c++) {
            for (int r = 0; r < 3; r++) {
                qsc[r][c] += q[c][r] > 0.0 ? q[c][r] * (c ? W_TRANSIENT : 1.0) : 0.0;
                have[r] &= !(l == 0 && q[c][r] < 0.0);
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
    return m->last.all;
}
