/*
 * fuzz_scene.c - libFuzzer harness of the renderer's text inputs: the
 * scene-file parser (render/tdc_scene_parse.c) and the OBJ mesh loader
 * (load_obj() of render/tdc_render_geom.c, built into this harness).
 * Byte 0 chooses: even = the rest is a scene file, odd = an OBJ file (a
 * memfd).  Aborts (besides the sanitizers) when:
 *   - the parser accepts a scene whose counts exceed its arrays, whose name
 *     could not name a file (tdc-render --png DIR/<name>-...: no '/', not
 *     '..'), or whose resolution is outside 1..16384, or reports failure
 *     without a message;
 *   - the OBJ loader accepts a mesh with a face index outside its vertices
 *     or an index count that is not whole triangles, or fails without a
 *     message.
 * Run with -close_fd_mask=2.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "../../render/tdc_render_geom.c"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static tdc_scene_t sc;
    static char text[1 << 16];
    static int fd = -1;
    static char path[64];
    char err[512];
    if (size < 1 || size - 1 >= sizeof text) return 0;
    if ((data[0] & 1u) == 0) {
        memcpy(text, data + 1, size - 1);
        text[size - 1] = '\0';
        err[0] = '\0';
        tdc_scene_status_t st = tdc_scene_parse(text, "fuzz.scene", NULL, &sc, err, sizeof err);
        if (st != TDC_SCENE_OK) {
            if (err[0] == '\0') abort();
            return 0;
        }
        if (sc.nmaterials < 0 || sc.nmaterials > TDC_SCENE_MAX_MATERIALS || sc.nobjects < 0 ||
            sc.nobjects > TDC_SCENE_MAX_OBJECTS || sc.nlights < 0 || sc.nlights > TDC_SCENE_MAX_LIGHTS ||
            sc.width < 1 || sc.width > 16384 || sc.height < 1 || sc.height > 16384)
            abort();
        size_t n = strlen(sc.name);
        if (n == 0 || n >= sizeof sc.name || strchr(sc.name, '/') || !strcmp(sc.name, "..") || !strcmp(sc.name, "."))
            abort();
        for (int i = 0; i < sc.nobjects; i++)
            if (sc.objects[i].material < 0 || sc.objects[i].material >= sc.nmaterials) abort();
        return 0;
    }
    if (fd < 0) {
        fd = memfd_create("fuzz.obj", 0);
        if (fd < 0) abort();
        snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
    }
    if (ftruncate(fd, 0) != 0 || pwrite(fd, data + 1, size - 1, 0) != (ssize_t)(size - 1)) abort();
    meshbuf_t m;
    memset(&m, 0, sizeof m);
    err[0] = '\0';
    if (load_obj(path, &m, err, sizeof err) == 0) {
        if (m.ni == 0 || m.ni % 3u != 0) abort();
        for (unsigned i = 0; i < m.ni; i++)
            if (m.ix[i] >= m.nv) abort();
    } else if (err[0] == '\0') {
        abort();
    }
    free(m.v);
    free(m.ix);
    return 0;
}
