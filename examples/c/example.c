/* Three triangles on one edge (a non-manifold edge), queried through the C ABI. */
#include <stdio.h>
#include <topoplex.h>

int main(void) {
    /*        2
     *   3 -- 0 -- 4      triangles 0 1 2, 0 1 3, 0 1 4 all contain edge 0-1
     *        1                                                              */
    const uint32_t ids[] = {0, 1, 2, 0, 1, 3, 0, 1, 4};
    const size_t offsets[] = {0, 3, 6, 9};
    TpxComplex *complex = NULL;
    TpxStructure *ig = NULL;
    if (tpx_complex_from_arrays(5, ids, offsets, 3, NULL, 0, &complex) != TPX_STATUS_OK ||
        tpx_structure_build(complex, TPX_KIND_IG, &ig) != TPX_STATUS_OK) {
        fprintf(stderr, "topoplex: %s\n", tpx_last_error_message());
        tpx_complex_free(complex);
        return 1;
    }
    /* R_{1,2}: the triangles around edge {0, 1}, rows of 3 ids in lexicographic order. */
    const uint32_t edge[] = {1, 0};
    uint32_t out[64];
    size_t len = 0;
    if (tpx_relation(ig, edge, 2, 2, out, 64, &len) != TPX_STATUS_OK) {
        fprintf(stderr, "topoplex: %s\n", tpx_last_error_message());
        return 1;
    }
    printf("topoplex %s: edge 0-1 is in %zu triangles:", tpx_version(), len / 3);
    for (size_t i = 0; i < len; i += 3) printf(" {%u %u %u}", out[i], out[i + 1], out[i + 2]);
    printf("\n");
    /* Write the complex as OFF (format from the extension): triangles in input order and
     * winding; without coordinates the vertices are written at the origin. */
    TpxStatus written = tpx_complex_write(complex, "fan.off", TPX_FORMAT_FROM_EXTENSION);
    if (written != TPX_STATUS_OK) fprintf(stderr, "topoplex: %s\n", tpx_last_error_message());
    tpx_structure_free(ig);
    tpx_complex_free(complex);
    return len == 9 && written == TPX_STATUS_OK ? 0 : 1;
}
