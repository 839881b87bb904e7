/*
 * tdc_board_linux_drm.c - the Linux board's panel out through DRM/KMS
 * (libdrm, atomic API):
 *   start-up  the connector (by name, or the first connected one), a mode
 *             of exactly the panel's size (eyes side by side), the CRTC
 *             and primary plane that can drive it, two dumb buffers
 *             (XRGB8888) allocated and mapped once, an atomic mode-set
 *             showing buffer 0 black
 *   show      the frame loop's RGB888 frame converted into the buffer not
 *             scanned out, then an atomic commit of that buffer with a
 *             page-flip event (non-blocking): the flip happens on vblank
 *   vsync     waits for that event (the flip is on screen when it
 *             arrives); with no flip pending, the next vblank
 *             (drmWaitVBlank; drivers without vblank interrupts, e.g.
 *             bochs, complete flips at commit and have none)
 * Failures are named: no DRM device, no atomic KMS, no such connector,
 * mode not available (the connector's modes listed), no flip event.
 */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>
#include <drm_fourcc.h>

#include "tdc_board.h"
#include "tdc_board_linux.h"

typedef struct {
    uint32_t handle, fb_id, pitch;
    uint64_t size;
    uint8_t *map;
} dumb_t;

static int g_fd = -1;
static uint32_t g_conn, g_crtc, g_plane, g_crtc_index, g_w, g_h;
static uint32_t p_conn_crtc, p_crtc_mode, p_crtc_active, p_fb, p_crtc, p_sx, p_sy, p_sw, p_sh, p_cx, p_cy, p_cw, p_ch;
static dumb_t g_buf[2];
static unsigned g_front; /* the buffer scanned out (or about to be, once its flip completes) */
static int g_flip_pending, g_no_vblank;
/* the USB connection whose frame the pending flip shows (tdc_lx_ffs_conn) */
static unsigned g_flip_conn;

/* A property of a KMS object by name: its id (0: none), and its value in *value. */
static uint32_t prop_find(uint32_t obj, uint32_t type, const char *name, uint64_t *value)
{
    drmModeObjectProperties *props = drmModeObjectGetProperties(g_fd, obj, type);
    uint32_t id = 0;
    for (uint32_t i = 0; props && i < props->count_props && !id; i++) {
        drmModePropertyRes *p = drmModeGetProperty(g_fd, props->props[i]);
        if (p && !strcmp(p->name, name)) {
            id = p->prop_id;
            if (value) *value = props->prop_values[i];
        }
        drmModeFreeProperty(p);
    }
    drmModeFreeObjectProperties(props);
    return id;
}

static void conn_name(const drmModeConnector *c, char *out, size_t cap)
{
    const char *t = drmModeGetConnectorTypeName(c->connector_type);
    snprintf(out, cap, "%s-%u", t ? t : "Unknown", c->connector_type_id);
}

static int make_dumb(dumb_t *b)
{
    struct drm_mode_create_dumb cd = {.width = g_w, .height = g_h, .bpp = 32};
    if (drmIoctl(g_fd, DRM_IOCTL_MODE_CREATE_DUMB, &cd) != 0) return -1;
    b->handle = cd.handle;
    b->pitch = cd.pitch;
    b->size = cd.size;
    uint32_t handles[4] = {b->handle}, pitches[4] = {b->pitch}, offsets[4] = {0};
    if (drmModeAddFB2(g_fd, g_w, g_h, DRM_FORMAT_XRGB8888, handles, pitches, offsets, &b->fb_id, 0) != 0) return -1;
    struct drm_mode_map_dumb md = {.handle = b->handle};
    if (drmIoctl(g_fd, DRM_IOCTL_MODE_MAP_DUMB, &md) != 0) return -1;
    void *m = mmap(NULL, (size_t)b->size, PROT_READ | PROT_WRITE, MAP_SHARED, g_fd, (off_t)md.offset);
    if (m == MAP_FAILED) return -1;
    b->map = m;
    memset(b->map, 0, (size_t)b->size);
    return 0;
}

static void plane_props(drmModeAtomicReq *req, uint32_t fb)
{
    drmModeAtomicAddProperty(req, g_plane, p_fb, fb);
    drmModeAtomicAddProperty(req, g_plane, p_crtc, g_crtc);
    drmModeAtomicAddProperty(req, g_plane, p_sx, 0);
    drmModeAtomicAddProperty(req, g_plane, p_sy, 0);
    drmModeAtomicAddProperty(req, g_plane, p_sw, (uint64_t)g_w << 16);
    drmModeAtomicAddProperty(req, g_plane, p_sh, (uint64_t)g_h << 16);
    drmModeAtomicAddProperty(req, g_plane, p_cx, 0);
    drmModeAtomicAddProperty(req, g_plane, p_cy, 0);
    drmModeAtomicAddProperty(req, g_plane, p_cw, g_w);
    drmModeAtomicAddProperty(req, g_plane, p_ch, g_h);
}

static int pick_connector(drmModeRes *res, drmModeConnector **out)
{
    char name[64], seen[512] = "";
    for (int i = 0; i < res->count_connectors; i++) {
        drmModeConnector *c = drmModeGetConnector(g_fd, res->connectors[i]);
        if (!c) continue;
        conn_name(c, name, sizeof name);
        const int want = tdc_lx_opts.connector ? !strcmp(name, tdc_lx_opts.connector)
                                               : c->connection == DRM_MODE_CONNECTED;
        if (want) {
            *out = c;
            return 0;
        }
        size_t l = strlen(seen);
        snprintf(seen + l, sizeof seen - l, "%s%s (%s)", l ? ", " : "", name,
                 c->connection == DRM_MODE_CONNECTED ? "connected" : "not connected");
        drmModeFreeConnector(c);
    }
    tdc_lx_fail(TDC_LX_EXIT_NO_DEVICE, "drm: no connector %s on %s (connectors: %s)",
                tdc_lx_opts.connector ? tdc_lx_opts.connector : "connected", tdc_lx_opts.drm_path,
                seen[0] ? seen : "none");
    return -1;
}

/* A mode of exactly w x h, the refresh nearest the panel's. */
static int pick_mode(const drmModeConnector *c, uint32_t refresh_hz, drmModeModeInfo *out)
{
    int best = -1;
    char modes[512] = "";
    for (int i = 0; i < c->count_modes; i++) {
        const drmModeModeInfo *m = &c->modes[i];
        if (m->hdisplay == g_w && m->vdisplay == g_h &&
            (best < 0 || (m->vrefresh > refresh_hz ? m->vrefresh - refresh_hz : refresh_hz - m->vrefresh) <
                             (c->modes[best].vrefresh > refresh_hz ? c->modes[best].vrefresh - refresh_hz
                                                                   : refresh_hz - c->modes[best].vrefresh))) {
            best = i;
        }
        size_t l = strlen(modes);
        if (l + 24 < sizeof modes) snprintf(modes + l, sizeof modes - l, "%s%ux%u@%u", l ? " " : "", m->hdisplay, m->vdisplay, m->vrefresh);
    }
    if (best < 0) {
        char name[64];
        conn_name(c, name, sizeof name);
        tdc_lx_fail(TDC_LX_EXIT_REFUSED, "drm: mode %ux%u not available on %s (modes: %s)", g_w, g_h, name,
                    modes[0] ? modes : "none");
        return -1;
    }
    *out = c->modes[best];
    if (c->modes[best].vrefresh != refresh_hz) {
        tdc_lx_logf("drm: mode %ux%u refreshes at %u Hz, the panel profile says %u Hz", g_w, g_h,
                    c->modes[best].vrefresh, refresh_hz);
    }
    return 0;
}

static int pick_crtc_plane(drmModeRes *res, const drmModeConnector *c)
{
    uint32_t crtcs = 0;
    for (int i = 0; i < c->count_encoders; i++) {
        drmModeEncoder *e = drmModeGetEncoder(g_fd, c->encoders[i]);
        if (e) crtcs |= e->possible_crtcs;
        drmModeFreeEncoder(e);
    }
    for (int i = 0; i < res->count_crtcs; i++) {
        if (crtcs & (1u << i)) {
            g_crtc = res->crtcs[i];
            g_crtc_index = (uint32_t)i;
            break;
        }
    }
    if (!g_crtc) return -1;
    drmModePlaneRes *pr = drmModeGetPlaneResources(g_fd);
    for (uint32_t i = 0; pr && i < pr->count_planes && !g_plane; i++) {
        drmModePlane *p = drmModeGetPlane(g_fd, pr->planes[i]);
        uint64_t type = 0;
        if (p && (p->possible_crtcs & (1u << g_crtc_index)) &&
            prop_find(p->plane_id, DRM_MODE_OBJECT_PLANE, "type", &type) && type == DRM_PLANE_TYPE_PRIMARY) {
            g_plane = p->plane_id;
        }
        drmModeFreePlane(p);
    }
    drmModeFreePlaneResources(pr);
    return g_plane ? 0 : -1;
}

int tdc_lx_drm_init(uint32_t width, uint32_t height, uint32_t refresh_hz)
{
    g_w = width;
    g_h = height;
    g_fd = open(tdc_lx_opts.drm_path, O_RDWR | O_CLOEXEC);
    if (g_fd < 0) {
        tdc_lx_fail(TDC_LX_EXIT_NO_DEVICE, "drm: no DRM device %s: %s", tdc_lx_opts.drm_path, strerror(errno));
        return -1;
    }
    if (drmSetClientCap(g_fd, DRM_CLIENT_CAP_UNIVERSAL_PLANES, 1) != 0 ||
        drmSetClientCap(g_fd, DRM_CLIENT_CAP_ATOMIC, 1) != 0) {
        tdc_lx_fail(TDC_LX_EXIT_REFUSED, "drm: %s has no atomic mode-setting: %s", tdc_lx_opts.drm_path, strerror(errno));
        return -1;
    }
    drmModeRes *res = drmModeGetResources(g_fd);
    if (!res) {
        tdc_lx_fail(TDC_LX_EXIT_REFUSED, "drm: %s is not a KMS device: %s", tdc_lx_opts.drm_path, strerror(errno));
        return -1;
    }
    drmModeConnector *c = NULL;
    drmModeModeInfo mode;
    int rc = pick_connector(res, &c);
    if (rc == 0 && (rc = pick_mode(c, refresh_hz, &mode)) == 0 && (rc = pick_crtc_plane(res, c)) != 0) {
        tdc_lx_fail(TDC_LX_EXIT_REFUSED, "drm: no CRTC with a primary plane can drive the connector");
    }
    char name[64] = "";
    if (c) {
        g_conn = c->connector_id;
        conn_name(c, name, sizeof name);
        drmModeFreeConnector(c);
    }
    drmModeFreeResources(res);
    if (rc != 0) return -1;
    const struct {
        uint32_t *id, obj, type;
        const char *name;
    } props[] = {{&p_conn_crtc, g_conn, DRM_MODE_OBJECT_CONNECTOR, "CRTC_ID"},
                 {&p_crtc_mode, g_crtc, DRM_MODE_OBJECT_CRTC, "MODE_ID"},
                 {&p_crtc_active, g_crtc, DRM_MODE_OBJECT_CRTC, "ACTIVE"},
                 {&p_fb, g_plane, DRM_MODE_OBJECT_PLANE, "FB_ID"},
                 {&p_crtc, g_plane, DRM_MODE_OBJECT_PLANE, "CRTC_ID"},
                 {&p_sx, g_plane, DRM_MODE_OBJECT_PLANE, "SRC_X"},
                 {&p_sy, g_plane, DRM_MODE_OBJECT_PLANE, "SRC_Y"},
                 {&p_sw, g_plane, DRM_MODE_OBJECT_PLANE, "SRC_W"},
                 {&p_sh, g_plane, DRM_MODE_OBJECT_PLANE, "SRC_H"},
                 {&p_cx, g_plane, DRM_MODE_OBJECT_PLANE, "CRTC_X"},
                 {&p_cy, g_plane, DRM_MODE_OBJECT_PLANE, "CRTC_Y"},
                 {&p_cw, g_plane, DRM_MODE_OBJECT_PLANE, "CRTC_W"},
                 {&p_ch, g_plane, DRM_MODE_OBJECT_PLANE, "CRTC_H"}};
    for (unsigned i = 0; i < sizeof props / sizeof props[0]; i++) {
        if (!(*props[i].id = prop_find(props[i].obj, props[i].type, props[i].name, NULL))) {
            tdc_lx_fail(TDC_LX_EXIT_REFUSED, "drm: no atomic property %s on %s", props[i].name, name);
            return -1;
        }
    }
    if (make_dumb(&g_buf[0]) != 0 || make_dumb(&g_buf[1]) != 0) {
        tdc_lx_fail(TDC_LX_EXIT_IO, "drm: cannot allocate two %ux%u XRGB8888 dumb buffers: %s", g_w, g_h,
                    strerror(errno));
        return -1;
    }
    uint32_t blob = 0;
    drmModeAtomicReq *req = drmModeAtomicAlloc();
    if (drmModeCreatePropertyBlob(g_fd, &mode, sizeof mode, &blob) != 0 || !req) {
        tdc_lx_fail(TDC_LX_EXIT_IO, "drm: mode blob: %s", strerror(errno));
        return -1;
    }
    drmModeAtomicAddProperty(req, g_conn, p_conn_crtc, g_crtc);
    drmModeAtomicAddProperty(req, g_crtc, p_crtc_mode, blob);
    drmModeAtomicAddProperty(req, g_crtc, p_crtc_active, 1);
    plane_props(req, g_buf[0].fb_id);
    rc = drmModeAtomicCommit(g_fd, req, DRM_MODE_ATOMIC_ALLOW_MODESET, NULL);
    drmModeAtomicFree(req);
    if (rc != 0) {
        tdc_lx_fail(TDC_LX_EXIT_IO, "drm: atomic mode-set %ux%u on %s refused: %s", g_w, g_h, name, strerror(errno));
        return -1;
    }
    g_front = 0;
    tdc_lx_logf("drm: %s on %s, mode %ux%u@%u, two dumb buffers (pitch %u)", name, tdc_lx_opts.drm_path, g_w, g_h,
                mode.vrefresh, g_buf[0].pitch);
    return 0;
}

static void on_flip(int fd, unsigned seq, unsigned sec, unsigned usec, unsigned crtc, void *data)
{
    (void)fd, (void)seq, (void)sec, (void)usec, (void)crtc, (void)data;
    g_flip_pending = 0;
    tdc_lx_ffs_frame_shown(g_flip_conn);
}

void tdc_lx_drm_wait(void)
{
    if (!g_flip_pending) {
        if (g_no_vblank) return;
        drmVBlank vb = {.request = {.type = DRM_VBLANK_RELATIVE | (g_crtc_index << DRM_VBLANK_HIGH_CRTC_SHIFT),
                                    .sequence = 1}};
        if (drmWaitVBlank(g_fd, &vb) != 0) {
            g_no_vblank = 1; /* e.g. bochs: flips complete at commit */
            tdc_lx_logf("drm: no vblank interrupts on this device (%s): vsync = page-flip completion",
                        strerror(errno));
        }
        return;
    }
    drmEventContext ev = {.version = 3, .page_flip_handler2 = on_flip};
    while (g_flip_pending) {
        struct pollfd p = {.fd = g_fd, .events = POLLIN};
        int n = poll(&p, 1, 1000);
        if (n == 0) {
            tdc_lx_logf("drm: no page-flip event within 1 s: the display pipe stalled");
            g_flip_pending = 0;
            return;
        }
        if (n < 0) {
            if (errno == EINTR) continue;
            tdc_lx_logf("drm: waiting for the flip: %s", strerror(errno));
            return;
        }
        drmHandleEvent(g_fd, &ev);
    }
}

/* The scan-out conversion RGB888 -> XRGB8888, rows in bands on the row
 * workers (at Vive size 4.7 % of a one-threaded TRM frame). */
typedef struct {
    const uint8_t *fb;
    uint32_t stride, w, h, n;
    uint8_t *dst;
    uint32_t pitch;
} xrgb_job_t;

static void xrgb_band(void *arg, uint32_t i)
{
    const xrgb_job_t *j = arg;
    const uint32_t y1 = (uint32_t)((uint64_t)j->h * (i + 1u) / j->n);
    for (uint32_t y = (uint32_t)((uint64_t)j->h * i / j->n); y < y1; y++) {
        const uint8_t *s = j->fb + (size_t)y * j->stride;
        uint32_t *d = (uint32_t *)(void *)(j->dst + (size_t)y * j->pitch);
        for (uint32_t x = 0; x < j->w; x++) {
            d[x] = (uint32_t)s[3 * x] << 16 | (uint32_t)s[3 * x + 1] << 8 | s[3 * x + 2];
        }
    }
}

void tdc_lx_xrgb(const uint8_t *fb, uint32_t stride, uint32_t w, uint32_t h, uint8_t *dst, uint32_t pitch)
{
    const xrgb_job_t j = {fb, stride, w, h, tdc_board_workers(), dst, pitch};
    tdc_board_run_bands(xrgb_band, (void *)&j, j.n);
}

int tdc_lx_drm_show(const uint8_t *fb, uint32_t stride, uint32_t width, uint32_t height)
{
    tdc_lx_drm_wait(); /* never write the buffer a pending flip will scan out */
    dumb_t *b = &g_buf[g_front ^ 1u];
    tdc_lx_xrgb(fb, stride, width < g_w ? width : g_w, height < g_h ? height : g_h, b->map, b->pitch);
    drmModeAtomicReq *req = drmModeAtomicAlloc();
    if (!req) return -1;
    drmModeAtomicAddProperty(req, g_plane, p_fb, b->fb_id);
    int rc = drmModeAtomicCommit(g_fd, req, DRM_MODE_PAGE_FLIP_EVENT | DRM_MODE_ATOMIC_NONBLOCK, NULL);
    drmModeAtomicFree(req);
    if (rc != 0) {
        tdc_lx_logf("drm: page flip refused: %s", strerror(errno));
        return -1;
    }
    g_flip_pending = 1;
    g_flip_conn = tdc_lx_ffs_conn();
    g_front ^= 1u;
    return 0;
}
