/*
 * tdc_sim_codes.h - what every simulator source does with a sample: panel
 * drive code from linear light, Q4 motion vector, the stratified grid of
 * spp rays (shared by the procedural scenes and the photograph source).
 * In ref/ because the references encode their outputs the same way
 * (ref_fov_lr.c): below both the references and the simulator.
 */
#ifndef TDC_SIM_CODES_H
#define TDC_SIM_CODES_H

#include <math.h>
#include <stdint.h>

/* Drive code of linear light lin under panel gamma: round(255 lin^(1/gamma)), lin clamped to [0, 1]. */
static inline uint8_t tdc_sim_encode_code(double lin, double gamma)
{
    lin = lin < 0.0 ? 0.0 : (lin > 1.0 ? 1.0 : lin);
    double c = 255.0 * pow(lin, 1.0 / gamma) + 0.5;
    return (uint8_t)(c >= 255.0 ? 255 : (int)c);
}

/* Drive codes by table: the code of lin is the number of decision levels
 * level[1..255] at or below lin, counted up from the bucket of lin (lo[]:
 * the count at the bucket's lower bound; about 6 steps in the darkest
 * bucket at gamma 2.2, 0-1 elsewhere) instead of a pow per channel. */
#define TDC_SIM_CODE_BUCKETS 4096
typedef struct {
    double gamma;                         /* 0: not filled yet */
    double level[256];                    /* level[0] = -1 */
    uint8_t lo[TDC_SIM_CODE_BUCKETS + 1]; /* the count at i / TDC_SIM_CODE_BUCKETS */
} tdc_sim_code_table_t;

typedef enum {
    /* level[k] = ((k - 0.5) / 255)^gamma: the procedural scenes' encoder;
     * 100-240 of its 255 levels lie an ulp or so off EXACT's (gamma
     * 1.8-2.6), so a sample that close to a level can get the next code */
    TDC_SIM_CODES_MIDPOINT,
    TDC_SIM_CODES_EXACT /* the least lin that tdc_sim_encode_code takes to k or above: its codes */
} tdc_sim_code_levels_t;

/* Fills t for gamma (nothing to do if it holds gamma already).  EXACT finds
 * each level by bisection over the bit patterns of the doubles in [0, 1]
 * (ordered as the values; 62 pows a level, ~16 k a table): the same codes
 * as tdc_sim_encode_code for every lin, tdc_sim_encode_code being monotone
 * in lin (test_sim_eye checks both sides of every level). */
static inline void tdc_sim_code_table_init(tdc_sim_code_table_t *t, double gamma, tdc_sim_code_levels_t how)
{
    if (t->gamma == gamma) {
        return;
    }
    t->level[0] = -1.0;
    for (int k = 1; k < 256; k++) {
        if (how == TDC_SIM_CODES_MIDPOINT) {
            t->level[k] = pow((k - 0.5) / 255.0, gamma);
            continue;
        }
        union {
            double d;
            uint64_t u;
        } lo = {0.0}, hi = {1.0}, mid;
        while (lo.u < hi.u) {
            mid.u = lo.u + (hi.u - lo.u) / 2;
            if (tdc_sim_encode_code(mid.d, gamma) >= k) {
                hi.u = mid.u;
            } else {
                lo.u = mid.u + 1;
            }
        }
        t->level[k] = lo.d;
    }
    int k = 0;
    for (int i = 0; i <= TDC_SIM_CODE_BUCKETS; i++) {
        while (k < 255 && t->level[k + 1] <= (double)i / TDC_SIM_CODE_BUCKETS) {
            k++;
        }
        t->lo[i] = (uint8_t)k;
    }
    t->gamma = gamma;
}

/* The code of lin by table t (0 for negative or NaN lin). */
static inline uint8_t tdc_sim_code_lookup(const tdc_sim_code_table_t *t, double lin)
{
    if (!(lin >= 0.0)) {
        return 0;
    }
    int k = t->lo[lin >= 1.0 ? TDC_SIM_CODE_BUCKETS : (int)(lin * TDC_SIM_CODE_BUCKETS)];
    while (k < 255 && t->level[k + 1] <= lin) {
        k++;
    }
    return (uint8_t)k;
}

/* A displacement in pixels as a Q4 motion vector component, saturated to +-32767. */
static inline int16_t tdc_sim_mv_q4(double d)
{
    double q = floor(d * 16.0 + 0.5);
    return (int16_t)(q > 32767.0 ? 32767 : (q < -32767.0 ? -32767 : q));
}

/* Side g of the g x g stratified grid used for spp rays per pixel (g^2 <= spp). */
static inline int tdc_sim_spp_grid(int spp)
{
    int g = 1;
    while ((g + 1) * (g + 1) <= spp) {
        g++;
    }
    return g;
}

#endif
