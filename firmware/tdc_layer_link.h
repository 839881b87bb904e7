/*
 * tdc_layer_link.h - the layered subframe packet (link kind LAYERS,
 * docs/link-protocol.md "Layered subframes"): per traced sample of a
 * tile-ordered subframe, the components the controller reuses separately
 * (Zeng et al., temporally reliable motion vectors, §4), each with its own
 * motion vector, plus the eq. 4 falloff weight of the shadow layer.
 *
 * Layer types (at most one of each; on the wire in this order):
 *   1 SHADING     unshadowed direct shading, RGB888 panel codes
 *   2 VISIBILITY  fraction of the light seen (combined over lights), 1 byte,
 *                 linear, 0 = in shadow .. 255 = lit; multiplies SHADING
 *   3 GLOSSY      reflection / glossy layer, RGB888 panel codes, added
 *   4 INDIRECT    other indirect light, RGB888 panel codes, added
 * Displayed linear light = lin(SHADING) * VIS / 255 + lin(GLOSSY) +
 * lin(INDIRECT) (a missing layer is 1 for VISIBILITY, 0 for the others).
 *
 * Packet header (tdc_wire.h): kind TDC_LINK_KIND_LAYERS, format 0, width x
 * height = the panel, flags = which layers follow (bit t-1 for type t) and
 * TDC_LAYER_PKT_FALLOFF; the payload length follows from the flags (so the
 * decoder checks it before collecting the payload):
 *
 *   16-byte layer header, little-endian:
 *     0  uint8  layout version, 1
 *     1  uint8  layer count n, 1..4 (must equal the popcount of the flags)
 *     2  uint8  type of layer 0..3 (1..4 ascending; 0 for i >= n)
 *     6  uint8  vector kind of layer 0..3 (TDC_LAYER_MV_*; 0 for i >= n)
 *    10  uint8  flags: bit 0 falloff plane follows (= TDC_LAYER_PKT_FALLOFF)
 *    11  uint8  reserved, 0
 *    12  uint16 tiles_x = ceil(width / 2)
 *    14  uint16 tiles_y = ceil(height / 2)
 *   then for each layer i: its value plane (tiles x 3 or 1 bytes, tile rows
 *   packed, the SUBFRAME order), then its vector plane (tiles x int16 (dx, dy)
 *   LE, Q4, backward, as MOTION);
 *   then with FALLOFF: tiles x uint16 LE, Q15 in [0, 32768]: G of eq. 4,
 *   G(theta - pi/2; 0, 0.1), 32768 = the shadow vector is fully trusted.
 *
 * A one-layer packet (SHADING with SURFACE vectors) carries exactly the
 * bytes of SUBFRAME + per-sample MOTION (7 per tile) plus the 16-byte layer
 * header, in one packet instead of two.  A stream without shadows or
 * reflections does not announce layers at all and sends SUBFRAME + MOTION
 * as before (stage elision: nothing of this file runs).
 *
 * Refused (TDC_LINK_ERR_LAYERS, the reason counted per tdc_layer_err_t, the
 * pipeline buffers untouched, the last good frame kept): a layer header that
 * disagrees with the packet header, vector kinds not defined for a layer
 * type, sentinel vectors (an int16 -32768 component, the "no vector" value
 * some renderers write), falloff weights above 1.
 */
#ifndef TDC_LAYER_LINK_H
#define TDC_LAYER_LINK_H

#include <stddef.h>
#include <stdint.h>

#include "tdc_geom.h"

#define TDC_LAYER_MAX 4
#define TDC_LAYER_HDR_BYTES 16u
#define TDC_LAYER_LAYOUT_VERSION 1u

/* Layer types (1-based; 0 = no layer). */
enum {
    TDC_LAYER_SHADING = 1,
    TDC_LAYER_VISIBILITY = 2,
    TDC_LAYER_GLOSSY = 3,
    TDC_LAYER_INDIRECT = 4,
};

/* Vector kinds (Zeng §4; 0 = none, only for absent layers). */
enum {
    TDC_LAYER_MV_SURFACE = 1, /* the visible surface point (ordinary) */
    TDC_LAYER_MV_SHADOW = 2,  /* shadow vector, eq. 3 (splatted into lit pixels, §4.1) */
    TDC_LAYER_MV_MIRROR = 3,  /* virtual image of a mirror reflection */
    TDC_LAYER_MV_GLOSSY = 4,  /* stochastic glossy vector, eq. 5 */
    TDC_LAYER_MV_DUAL = 5,    /* dual vector for disocclusions, eq. 6 */
    TDC_LAYER_MV_LAST = 5
};

/* Packet-header flags of a LAYERS packet. */
#define TDC_LAYER_PKT_TYPE(t) (1u << ((t)-1u)) /* layer type t follows */
#define TDC_LAYER_PKT_TYPES 0x000Fu
#define TDC_LAYER_PKT_FALLOFF 0x0010u /* falloff plane follows (needs VISIBILITY) */
#define TDC_LAYER_PKT_KNOWN 0x001Fu

/* Sentinel component refused in vectors. */
#define TDC_LAYER_MV_SENTINEL (-32768)
/* Falloff weight one (Q15). */
#define TDC_LAYER_W_ONE 32768u

/* Why a layered payload was refused (a counter index: 0 = accepted). */
typedef enum {
    TDC_LAYER_OK = 0,
    TDC_LAYER_ERR_VERSION,  /* unknown layout version */
    TDC_LAYER_ERR_COUNT,    /* layer count 0, > 4, or not the number of layers the packet flags announce */
    TDC_LAYER_ERR_TYPE,     /* layer types not the flags' set in ascending order, or set for absent layers */
    TDC_LAYER_ERR_VECTOR,   /* vector kind not defined for its layer type, or set for absent layers */
    TDC_LAYER_ERR_SIZE,     /* tiles_x / tiles_y disagree with the packet's width x height */
    TDC_LAYER_ERR_RESERVED, /* flags disagree with the packet's, or a reserved byte not 0 */
    TDC_LAYER_ERR_SENTINEL, /* a vector component is the sentinel -32768 */
    TDC_LAYER_ERR_WEIGHT,   /* a falloff weight above 32768 (1.0) */
    TDC_LAYER_ERR_N
} tdc_layer_err_t;

/* Bytes per sample of a layer type's value (0 for an unknown type). */
static inline uint32_t tdc_layer_value_bytes(uint32_t type)
{
    return type == TDC_LAYER_VISIBILITY ? 1u : (type >= 1u && type <= 4u ? 3u : 0u);
}

/* 1 if packet flags describe a valid layer set: at least one layer, known
 * bits only, FALLOFF only with VISIBILITY, VISIBILITY only with SHADING. */
static inline int tdc_layer_flags_valid(uint32_t flags)
{
    const uint32_t vis = TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY), sh = TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING);
    return (flags & ~TDC_LAYER_PKT_KNOWN) == 0 && (flags & TDC_LAYER_PKT_TYPES) != 0 &&
           (!(flags & TDC_LAYER_PKT_FALLOFF) || (flags & vis)) && (!(flags & vis) || (flags & sh));
}

/* Payload bytes of a LAYERS packet with these flags over `tiles` samples
 * (0 for invalid flags).  Scaling: at most 16 + tiles * (3 * 3 + 1 + 16 + 2)
 * = 16 + 28 tiles < 2^32 for tiles < 2^27 (the decoder compares the size
 * with the panel first). */
static inline uint32_t tdc_layer_payload_bytes(uint32_t flags, uint32_t tiles)
{
    if (!tdc_layer_flags_valid(flags)) {
        return 0;
    }
    uint32_t per = (flags & TDC_LAYER_PKT_FALLOFF) ? 2u : 0u;
    for (uint32_t t = 1; t <= TDC_LAYER_MAX; t++) {
        if (flags & TDC_LAYER_PKT_TYPE(t)) {
            per += tdc_layer_value_bytes(t) + 4u;
        }
    }
    return TDC_LAYER_HDR_BYTES + per * tiles;
}

/* The layer header. */
typedef struct {
    uint8_t version;
    uint8_t count;
    uint8_t type[TDC_LAYER_MAX];
    uint8_t mv_kind[TDC_LAYER_MAX];
    uint8_t flags; /* bit 0: falloff */
    uint8_t reserved;
    uint16_t tiles_x, tiles_y;
} tdc_layer_hdr_t;

/*
 * Where the decoder unpacks an accepted layered payload (caller-owned, one
 * per eye): the header and, per layer type t (index t - 1, not the wire
 * order), its value plane and vector plane, each with room for the panel's
 * tiles; falloff: tiles Q15 weights.  A NULL plane means this build does not
 * take that layer type (its packets are TDC_LINK_ERR_UNEXPECTED).
 * `present` = the packet flags of the last accepted packet.
 */
typedef struct tdc_layer_frame {
    tdc_layer_hdr_t hdr;
    uint16_t present;
    uint8_t *value[TDC_LAYER_MAX]; /* type t: tiles * tdc_layer_value_bytes(t) */
    int16_t *mv[TDC_LAYER_MAX];    /* type t: tiles * 2, (dx, dy) Q4 */
    uint16_t *falloff;             /* tiles, Q15 (NULL: falloff packets refused) */
} tdc_layer_frame_t;

/* Writes the layer header of packet flags `flags` with the vector kinds
 * mv_kind[t - 1] of the present types, for a width x height panel.
 * Returns 0, or -1 for invalid flags or vector kinds. */
int tdc_layer_hdr_pack(uint8_t out[TDC_LAYER_HDR_BYTES], uint32_t flags, const uint8_t mv_kind[TDC_LAYER_MAX],
                       uint32_t width, uint32_t height);

/* Parses a layer header; TDC_LAYER_OK when it agrees with the packet's
 * flags and width x height. */
tdc_layer_err_t tdc_layer_hdr_parse(const uint8_t in[TDC_LAYER_HDR_BYTES], uint32_t pkt_flags, uint32_t width,
                                    uint32_t height, tdc_layer_hdr_t *h);

/* Checks a whole payload (len = tdc_layer_payload_bytes, already checked by
 * the decoder): header, then every vector and weight.  Reads only. */
tdc_layer_err_t tdc_layer_payload_check(const uint8_t *payload, uint32_t len, uint32_t pkt_flags, uint32_t width,
                                        uint32_t height);

/* 1 if `dst` can take every plane a packet with these flags carries. */
int tdc_layer_frame_accepts(const tdc_layer_frame_t *dst, uint32_t pkt_flags);

/* Unpacks a checked payload into dst (planes by type). */
void tdc_layer_unpack(const uint8_t *payload, uint32_t pkt_flags, uint32_t width, uint32_t height,
                      tdc_layer_frame_t *dst);

/* Whether vector kind k is defined for layer type t. */
int tdc_layer_mv_valid(uint32_t type, uint32_t kind);

/* "TDC_LAYER_ERR_SENTINEL"; "TDC_LAYER_ERR_?" outside the enum. */
const char *tdc_layer_err_name(tdc_layer_err_t e);

#endif /* TDC_LAYER_LINK_H */
