/*
 * zeng_filter.h - the spatial filters and history operations of the Zeng
 * reference pipeline, in doubles (images are W*H*ch interleaved):
 *   - separable joint bilateral (Kopf et al. 2007, as Zeng §5 uses it: the
 *     31x31 shadow filter and the 9x9 clean-up, per-pixel sigma allowed);
 *   - a-trous wavelet (Dammertz et al. 2010; Zeng §5: 4 levels, ~32x32, for
 *     the other indirect light) and SVGF's variance-guided variant
 *     (Schied et al. 2017, 5 levels);
 *   - bilinear history fetch with optional per-tap id test, and the
 *     neighbourhood moments of a clamp window (Salvi 2016).
 * Edge-stopping guides: view depth (relative), normal, object id.
 */
#ifndef ZENG_FILTER_H
#define ZENG_FILTER_H

#include <stddef.h>

typedef struct {
    int w, h;
    const int *id;
    const double *depth, *nrm; /* W*H, W*H*3 */
} zf_guide_t;

typedef struct {
    double sigma_depth;  /* relative depth difference scale (0: off) */
    double normal_power; /* weight max(0, n.n')^power, a power of two (0: off) */
    int same_id;         /* taps on another object get weight 0 */
} zf_edges_t;

#define ZF_MAX_R 32

/* Separable joint bilateral of radius r (<= ZF_MAX_R): 1D Gaussian sigma (sigma_px[p] per
 * centre pixel when not NULL, else sigma) times the edge weights, rows then
 * columns, each pass normalised.  A centre sigma <= 0 copies the pixel.
 * tmp: W*H*ch doubles.  in may not alias out. */
void zf_bilateral(const double *in, int ch, const zf_guide_t *g, const zf_edges_t *e, int r, double sigma,
                  const double *sigma_px, double *out, double *tmp);

/* A-trous: `levels` passes of the 5-tap B3 spline at steps 1, 2, 4, ...,
 * edge weights from the guide and a colour weight exp(-|dc|^2 / sc^2) with
 * sc = sigma_c / 2^level (Dammertz); sigma_c <= 0: no colour weight. */
void zf_atrous(const double *in, int ch, const zf_guide_t *g, const zf_edges_t *e, int levels, double sigma_c,
               double *out, double *tmp);

/* SVGF's a-trous level (step 2^level): luminance weight
 * exp(-|l_p - l_q| / (4 sqrt(g3x3(var_p)) + eps)); filters colour and
 * variance (var' = sum w^2 var / (sum w)^2). */
void zf_svgf_level(const double *col, const double *var, int ch, const zf_guide_t *g, const zf_edges_t *e,
                   int level, double *col_out, double *var_out);

/* Bilinear sample of img (W*H*ch) at continuous position (x, y) (pixel
 * centres at i + 0.5).  ids != NULL: only taps whose ids[] equals want
 * count (renormalised).  Returns 0 when no tap is usable (outside). */
int zf_fetch(const double *img, int ch, int w, int h, double x, double y, const int *ids, int want, double *out);

/* Mean and standard deviation per channel over the (2r+1)^2 window
 * (clipped at the borders). */
void zf_moments(const double *img, int ch, int w, int h, int x, int y, int r, double *mu, double *sd);

#endif
