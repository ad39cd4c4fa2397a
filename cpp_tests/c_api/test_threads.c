/* Eight threads query one shared const structure at once, for every kind that encodes the
 * complex, and every answer equals the serial answer from tpx_relation_table. */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <topoplex.h>

#define THREADS 8

typedef struct {
    const TpxStructure *s;
    uint32_t d;
    TpxRelationTable *tables[4][4]; /* serial answers, [p][q] */
    const uint32_t *simplices[4];
    size_t counts[4];
    int thread;
    long mismatches;
    long queries;
} Job;

static void *worker(void *arg) {
    Job *job = (Job *)arg;
    uint32_t buf[4096];
    for (uint32_t p = 0; p <= job->d; p++) {
        for (uint32_t q = 0; q <= job->d; q++) {
            size_t olen = 0, ilen = 0;
            const size_t *off = tpx_relation_table_offsets(job->tables[p][q], &olen);
            const uint32_t *ids = tpx_relation_table_ids(job->tables[p][q], &ilen);
            for (size_t i = (size_t)job->thread; i < job->counts[p]; i += THREADS) {
                size_t len = 0;
                const uint32_t *sigma = job->simplices[p] + i * (p + 1);
                if (tpx_relation(job->s, sigma, p + 1, q, buf, 4096, &len) != TPX_STATUS_OK ||
                    len != off[i + 1] - off[i] ||
                    (len > 0 && memcmp(buf, ids + off[i], len * sizeof(uint32_t)) != 0)) {
                    job->mismatches++;
                }
                job->queries++;
            }
        }
    }
    return NULL;
}

static int check_complex(const char *name, TpxComplex *c) {
    int failures = 0;
    for (uint32_t kind = TPX_KIND_IG; kind <= TPX_KIND_DE; kind++) {
        TpxStructure *s = NULL;
        TpxStatus st = tpx_structure_build(c, kind, &s);
        if (st == TPX_STATUS_UNSUPPORTED_COMPLEX) continue;
        if (st != TPX_STATUS_OK) {
            fprintf(stderr, "%s kind %u: build: %s\n", name, kind, tpx_last_error_message());
            return 1;
        }
        Job jobs[THREADS];
        Job base;
        memset(&base, 0, sizeof base);
        base.s = s;
        tpx_structure_dimension(s, &base.d);
        uint32_t *owned[4] = {NULL, NULL, NULL, NULL};
        for (uint32_t p = 0; p <= base.d; p++) {
            size_t len = 0;
            tpx_structure_simplices(s, p, NULL, 0, &len); /* BUFFER_TOO_SMALL gives the size */
            owned[p] = malloc((len ? len : 1) * sizeof(uint32_t));
            if (tpx_structure_simplices(s, p, owned[p], len, &len) != TPX_STATUS_OK) return 1;
            base.simplices[p] = owned[p];
            base.counts[p] = len / (p + 1);
            for (uint32_t q = 0; q <= base.d; q++) {
                if (tpx_relation_table(s, p, q, &base.tables[p][q]) != TPX_STATUS_OK) return 1;
            }
        }
        pthread_t th[THREADS];
        for (int t = 0; t < THREADS; t++) {
            jobs[t] = base;
            jobs[t].thread = t;
            pthread_create(&th[t], NULL, worker, &jobs[t]);
        }
        long mismatches = 0, queries = 0;
        for (int t = 0; t < THREADS; t++) {
            pthread_join(th[t], NULL);
            mismatches += jobs[t].mismatches;
            queries += jobs[t].queries;
        }
        printf("%s kind %u: %ld concurrent queries, %ld mismatches\n", name, kind, queries, mismatches);
        if (mismatches != 0 || queries == 0) failures++;
        for (uint32_t p = 0; p <= base.d; p++) {
            for (uint32_t q = 0; q <= base.d; q++) tpx_relation_table_free(base.tables[p][q]);
            free(owned[p]);
        }
        tpx_structure_free(s);
    }
    return failures;
}

static TpxComplex *from_list(uint32_t n, const uint32_t *ids, const size_t *offsets, size_t count) {
    TpxComplex *c = NULL;
    if (tpx_complex_from_arrays(n, ids, offsets, count, NULL, 0, &c) != TPX_STATUS_OK) {
        fprintf(stderr, "complex: %s\n", tpx_last_error_message());
        exit(1);
    }
    return c;
}

int main(void) {
    enum { K = 12 };
    /* A K×K grid of triangles (a manifold disk), three more triangles on its edge 0-1 (a
     * non-manifold edge), and a wire edge: every 2D structure that accepts it is checked. */
    static uint32_t ids[2 * K * K * 3 + 3 * 3 + 2];
    static size_t offsets[2 * K * K + 3 + 1 + 1];
    size_t n = 0, m = 0; /* offsets[0] = 0 (static) */
    uint32_t extra = (K + 1) * (K + 1);
    for (uint32_t y = 0; y < K; y++) {
        for (uint32_t x = 0; x < K; x++) {
            uint32_t a = y * (K + 1) + x;
            uint32_t tri[6] = {a, a + 1, a + K + 2, a, a + K + 2, a + K + 1};
            for (int i = 0; i < 6; i++) {
                ids[n++] = tri[i];
                if (i % 3 == 2) offsets[++m] = n;
            }
        }
    }
    for (uint32_t i = 0; i < 3; i++) {
        ids[n++] = 0;
        ids[n++] = 1;
        ids[n++] = extra + i;
        offsets[++m] = n;
    }
    ids[n++] = extra + 3;
    ids[n++] = extra + 4;
    offsets[++m] = n;
    int failures = 0;
    TpxComplex *grid = from_list(extra + 5, ids, offsets, m);
    failures += check_complex("grid+fin+wire", grid);
    tpx_complex_free(grid);

    /* Tetrahedra: a strip of cubes, six tetrahedra each, with a dangling triangle. */
    static uint32_t tids[4 * 6 * 4 + 3];
    static size_t toff[4 * 6 + 2];
    size_t tn = 0, tm = 0;
    toff[0] = 0;
    for (uint32_t cube = 0; cube < 4; cube++) {
        uint32_t v[8];
        for (uint32_t i = 0; i < 8; i++) v[i] = 4 * (cube + (i >> 2)) + (i & 3);
        /* Kuhn subdivision of the cube along its 0-7 diagonal. */
        static const int perm[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
        for (int t = 0; t < 6; t++) {
            for (int k = 0; k < 4; k++) tids[tn++] = v[perm[t][k]];
            toff[++tm] = tn;
        }
    }
    tids[tn++] = 0;
    tids[tn++] = 1;
    tids[tn++] = 20;
    toff[++tm] = tn;
    TpxComplex *tets = from_list(21, tids, toff, tm);
    failures += check_complex("cubes+dangling", tets);
    tpx_complex_free(tets);
    return failures == 0 ? 0 : 1;
}
