/*
 * zeng_rng.h - counter-based random numbers for the Zeng reference: every
 * sample is a hash of (seed, frame, pixel, index), so a pixel's samples do
 * not depend on the order of evaluation or on threads (splitmix64 finaliser).
 */
#ifndef ZENG_RNG_H
#define ZENG_RNG_H

#include <math.h>
#include <stdint.h>

static inline uint64_t zr_mix(uint64_t z)
{
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static inline uint64_t zr_key(uint64_t seed, uint64_t frame, uint64_t pixel)
{
    return zr_mix(zr_mix(zr_mix(seed) ^ frame) ^ pixel);
}

/* uniform in (0, 1) */
static inline double zr_u01(uint64_t key, unsigned idx)
{
    return ((double)(zr_mix(key ^ ((uint64_t)idx * 0xd1b54a32d192ed03ull)) >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

static inline double zr_gauss(uint64_t key, unsigned idx)
{
    double u = zr_u01(key, 2 * idx + 100), v = zr_u01(key, 2 * idx + 101);
    return sqrt(-2.0 * log(u)) * cos(2 * M_PI * v);
}

#endif
