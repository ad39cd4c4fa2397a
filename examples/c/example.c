/* Three triangles on one edge (a non-manifold edge): locate the edge once, then navigate
 * from handles through the C ABI. */
#include <stdio.h>
#include <topoplex.h>

static int fail(TpxComplex *complex, TpxStructure *s) {
    fprintf(stderr, "topoplex: %s\n", tpx_last_error_message());
    tpx_structure_free(s);
    tpx_complex_free(complex);
    return 1;
}

int main(void) {
    /*        2
     *   3 -- 0 -- 4      triangles 0 1 2, 0 1 3, 0 1 4 all contain edge 0-1
     *        1                                                              */
    const uint32_t ids[] = {0, 1, 2, 0, 1, 3, 0, 1, 4};
    const size_t offsets[] = {0, 3, 6, 9};
    TpxComplex *complex = NULL;
    TpxStructure *ts = NULL;
    if (tpx_complex_from_arrays(5, ids, offsets, 3, NULL, 0, &complex) != TPX_STATUS_OK ||
        tpx_structure_build(complex, TPX_KIND_TS, &ts) != TPX_STATUS_OK)
        return fail(complex, ts);
    /* Locate edge {0, 1} once: a handle (dense index, dimension, owner stamp). */
    const uint32_t edge[] = {1, 0};
    TpxSimplex e;
    if (tpx_locate(ts, edge, 2, &e) != TPX_STATUS_OK) return fail(complex, ts);
    /* R_{1,2}: its triangles, as dense triangle indices, in the structure's radial order. */
    uint32_t tris[16];
    size_t n = 0;
    if (tpx_related(ts, &e, 2, TPX_ORDER_NATURAL, tris, 16, &n) != TPX_STATUS_OK)
        return fail(complex, ts);
    printf("topoplex %s: edge 0-1 is in %zu triangles:", tpx_version(), n);
    for (size_t i = 0; i < n; i++) {
        /* Any index is a handle again: {index, dimension, owner}. */
        TpxSimplex t = {tris[i], 2, e.owner};
        uint32_t v[3];
        size_t len = 0;
        if (tpx_simplex_vertices(ts, &t, v, 3, &len) != TPX_STATUS_OK) return fail(complex, ts);
        printf(" {%u %u %u}", v[0], v[1], v[2]);
    }
    /* A handle of another structure, or out of range, is a status, never a crash. */
    TpxSimplex bad = {99, 2, e.owner};
    size_t degree = 0;
    TpxStatus st = tpx_degree(ts, &bad, 0, &degree);
    printf("\nmanifold edge? ");
    uint32_t manifold = 0;
    if (tpx_simplex_test(ts, &e, 1, &manifold) != TPX_STATUS_OK) return fail(complex, ts);
    printf("%s; bad handle -> status %d\n", manifold ? "yes" : "no", (int)st);
    /* Write the complex as OFF (format from the extension): triangles in input order and
     * winding; without coordinates the vertices are written at the origin. */
    TpxStatus written = tpx_complex_write(complex, "fan.off", TPX_FORMAT_FROM_EXTENSION);
    if (written != TPX_STATUS_OK) return fail(complex, ts);
    tpx_structure_free(ts);
    tpx_complex_free(complex);
    return n == 3 && !manifold && st == TPX_STATUS_INVALID_HANDLE ? 0 : 1;
}
