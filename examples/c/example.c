/* Three triangles on one edge (a non-manifold edge) in the mesh, the one object an application
 * keeps: read its lent arrays inline, ask by handles, edit it in place, write it. */
#include <stdio.h>
#include <topoplex.h>

static int fail(TpxComplex *complex, TpxLive *mesh) {
    fprintf(stderr, "topoplex: %s\n", tpx_last_error_message());
    tpx_live_free(mesh);
    tpx_complex_free(complex);
    return 1;
}

int main(void) {
    /*        2
     *   3 -- 0 -- 4      triangles 0 1 2, 0 1 3, 0 1 4 all contain edge 0-1
     *        1                                                              */
    const uint32_t ids[] = {0, 1, 2, 0, 1, 3, 0, 1, 4};
    const size_t offsets[] = {0, 3, 6, 9};
    const double xyz[] = {0, 0, 0, 0, -1, 0, 0, 1, 0, -1, 0, 0, 1, 0, 1};
    TpxComplex *complex = NULL;
    TpxLive *mesh = NULL; /* from a file: tpx_live_from_file("in.off", 0, &mesh) */
    if (tpx_complex_from_arrays(5, ids, offsets, 3, xyz, 3, &complex) != TPX_STATUS_OK ||
        tpx_live_from_complex(complex, &mesh) != TPX_STATUS_OK)
        return fail(complex, mesh);
    /* Inline: the mesh lends its arrays (valid until its next topological edit). Vertex 0's
     * star is a run of packed top ids, dimension << 28 | slot; a top's ids keep the winding. */
    TpxLiveArrays a;
    if (tpx_live_arrays(mesh, &a) != TPX_STATUS_OK) return fail(complex, mesh);
    const uint32_t *star = a.star_words + a.star_blocks[3 * 0], in_star = a.star_blocks[3 * 0 + 1];
    printf("topoplex %s: vertex 0 is in %u triangles:", tpx_version(), in_star);
    for (uint32_t i = 0; i < in_star; i++) {
        const uint32_t p = star[i] >> 28, slot = star[i] & 0x0fffffffu;
        const uint32_t *v = a.tops[p] + (size_t)slot * (p + 1);
        printf(" {%u %u %u}", v[0], v[1], v[2]);
    }
    /* By handles: locate edge {0, 1} once, then ask from the handle. */
    const TpxStructure *s = NULL;
    const uint32_t edge[] = {1, 0};
    TpxSimplex e;
    uint32_t before = 1, after = 0;
    if (tpx_live_structure(mesh, &s) != TPX_STATUS_OK ||
        tpx_locate(s, edge, 2, &e) != TPX_STATUS_OK ||
        tpx_simplex_test(s, &e, 1, &before) != TPX_STATUS_OK)
        return fail(complex, mesh);
    /* A handle out of range is a status, never a crash. */
    TpxSimplex bad = {99, 2, e.owner};
    size_t degree = 0;
    const TpxStatus st = tpx_degree(s, &bad, 0, &degree);
    /* Edit in place: contract vertex 2 into 0 where the link condition allows it (topology
     * kept); the triangle 0 1 2 goes, so edge 0-1 is left in two triangles. The handle lives. */
    if (tpx_live_contract(mesh, 0, 2, TPX_CONTRACT_PRESERVE_TOPOLOGY, NULL, 0, NULL) !=
            TPX_STATUS_OK ||
        tpx_simplex_test(s, &e, 1, &after) != TPX_STATUS_OK)
        return fail(complex, mesh);
    printf("\nedge 0-1 manifold? %s, after contracting 2 into 0: %s; bad handle -> status %d\n",
           before ? "yes" : "no", after ? "yes" : "no", (int)st);
    /* Write it (format from the extension): faces in order and winding, straight from the
     * mesh's tables. */
    if (tpx_live_write(mesh, "fan.off", TPX_FORMAT_FROM_EXTENSION) != TPX_STATUS_OK)
        return fail(complex, mesh);
    tpx_live_free(mesh);
    tpx_complex_free(complex);
    return in_star == 3 && !before && after && st == TPX_STATUS_INVALID_HANDLE ? 0 : 1;
}
