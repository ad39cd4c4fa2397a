/*
 * The Topoplex C ABI from plain C99: lifecycle, every reachable status, the buffer protocol,
 * file loading and the relation table, on one drawn fixture with hand-derived answers.
 *
 *          3 ------ 4 ------ 5        tetrahedron 0 1 2 3
 *         /|\      /                  dangling triangle 2 3 4 on edge 2-3
 *        / | \    /                   wire edge 4-5
 *       0--|--2--/
 *        \ | /
 *         \|/
 *          1
 *
 * TPX_STATUS_PANIC is not reachable from C without a bug; the Rust unit tests cover the panic
 * boundary itself.
 */
#include "topoplex.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

static int g_passed = 0;
static int g_failed = 0;

static void check(int ok, const char *what, const char *file, int line) {
  if (ok) {
    ++g_passed;
  } else {
    ++g_failed;
    fprintf(stderr, "%s:%d: FAILED: %s (last error: \"%s\")\n", file, line, what,
            tpx_last_error_message());
  }
}

#define CHECK(cond) check((cond) ? 1 : 0, #cond, __FILE__, __LINE__)
#define CHECK_STATUS(call, expected) check((call) == (expected), #call " == " #expected, __FILE__, __LINE__)

static int message_contains(const char *needle) {
  return strstr(tpx_last_error_message(), needle) != NULL;
}

static int same_u32(const uint32_t *a, const uint32_t *b, size_t n) {
  size_t i;
  for (i = 0; i < n; ++i) {
    if (a[i] != b[i]) return 0;
  }
  return 1;
}

static TpxComplex *fixture(void) {
  static const uint32_t ids[] = {3, 2, 1, 0, 4, 2, 3, 5, 4};
  static const size_t offsets[] = {0, 4, 7, 9};
  TpxComplex *c = NULL;
  CHECK_STATUS(tpx_complex_from_arrays(6, ids, offsets, 3, NULL, 0, &c), TPX_STATUS_OK);
  CHECK(c != NULL);
  return c;
}

static TpxStructure *build_ig(const TpxComplex *c) {
  TpxStructure *s = NULL;
  CHECK_STATUS(tpx_structure_build(c, TPX_KIND_IG, &s), TPX_STATUS_OK);
  CHECK(s != NULL);
  return s;
}

static void test_version(void) {
  CHECK(strcmp(tpx_version(), TPX_EXPECTED_VERSION) == 0);
  CHECK(tpx_last_error_message() != NULL);
}

static void test_complex_lifecycle(void) {
  static const double coords[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2};
  static const uint32_t ids[] = {3, 2, 1, 0, 4, 2, 3, 5, 4};
  static const size_t offsets[] = {0, 4, 7, 9};
  TpxComplex *c = NULL;
  uint32_t d = 99, n = 99;
  size_t tops[5];
  uint32_t p;

  CHECK_STATUS(tpx_complex_from_arrays(6, ids, offsets, 3, coords, 3, &c), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_dimension(c, &d), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_vertex_count(c, &n), TPX_STATUS_OK);
  CHECK(d == 3 && n == 6);
  for (p = 0; p < 5; ++p) {
    tops[p] = 99;
    CHECK_STATUS(tpx_complex_top_count(c, p, &tops[p]), TPX_STATUS_OK);
  }
  /* One top edge (4-5), one top triangle (2 3 4), one tetrahedron; none above. */
  CHECK(tops[0] == 0 && tops[1] == 1 && tops[2] == 1 && tops[3] == 1 && tops[4] == 0);
  CHECK(strcmp(tpx_last_error_message(), "") == 0);
  tpx_complex_free(c);

  /* Only isolated vertices, no arrays at all. */
  c = NULL;
  CHECK_STATUS(tpx_complex_from_arrays(3, NULL, NULL, 0, NULL, 0, &c), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_dimension(c, &d), TPX_STATUS_OK);
  CHECK(d == 0);
  tpx_complex_free(c);
}

/* The complex handed back: top simplices per dimension (sorted rows, sorted lexicographically)
   and the coordinates as given, with the buffer protocol of the structure queries. */
static void test_complex_contents(void) {
  static const double coords[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2};
  static const uint32_t ids[] = {3, 2, 1, 0, 4, 2, 3, 5, 4};
  static const size_t offsets[] = {0, 4, 7, 9};
  static const uint32_t tet[] = {0, 1, 2, 3}, tri[] = {2, 3, 4}, wire[] = {4, 5};
  TpxComplex *c = NULL;
  uint32_t buf[8];
  double xyz[18];
  size_t len = 99, dim = 99;
  size_t i;

  CHECK_STATUS(tpx_complex_from_arrays(6, ids, offsets, 3, coords, 3, &c), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_top_simplices(c, 3, buf, 8, &len), TPX_STATUS_OK);
  CHECK(len == 4 && same_u32(buf, tet, 4));
  CHECK_STATUS(tpx_complex_top_simplices(c, 2, buf, 8, &len), TPX_STATUS_OK);
  CHECK(len == 3 && same_u32(buf, tri, 3));
  CHECK_STATUS(tpx_complex_top_simplices(c, 1, buf, 8, &len), TPX_STATUS_OK);
  CHECK(len == 2 && same_u32(buf, wire, 2));
  CHECK_STATUS(tpx_complex_top_simplices(c, 0, NULL, 0, &len), TPX_STATUS_OK);
  CHECK(len == 0);
  len = 99;
  CHECK_STATUS(tpx_complex_top_simplices(c, 3, buf, 3, &len), TPX_STATUS_BUFFER_TOO_SMALL);
  CHECK(len == 4);
  len = 99;
  CHECK_STATUS(tpx_complex_top_simplices(c, 4, buf, 8, &len), TPX_STATUS_DIMENSION_OUT_OF_RANGE);
  CHECK(len == 99);

  CHECK_STATUS(tpx_complex_coord_dim(c, &dim), TPX_STATUS_OK);
  CHECK(dim == 3);
  CHECK_STATUS(tpx_complex_coords(c, NULL, 0, &len), TPX_STATUS_BUFFER_TOO_SMALL);
  CHECK(len == 18);
  CHECK_STATUS(tpx_complex_coords(c, xyz, 18, &len), TPX_STATUS_OK);
  CHECK(len == 18);
  for (i = 0; i < 18; ++i) CHECK(xyz[i] == coords[i]);
  CHECK_STATUS(tpx_complex_coords(c, NULL, 0, NULL), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_complex_coord_dim(NULL, &dim), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_complex_top_simplices(NULL, 0, buf, 8, &len), TPX_STATUS_NULL_ARGUMENT);
  tpx_complex_free(c);

  /* No coordinates: dimension 0, empty answer. */
  c = fixture();
  CHECK_STATUS(tpx_complex_coord_dim(c, &dim), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_coords(c, NULL, 0, &len), TPX_STATUS_OK);
  CHECK(dim == 0 && len == 0);
  tpx_complex_free(c);
}

static void test_structure_queries(void) {
  TpxComplex *c = fixture();
  TpxStructure *s = build_ig(c);
  uint32_t kind = 99, d = 99;
  size_t counts[4], len = 0;
  TpxStorage storage = {0, 0, 0};
  uint32_t buf[32];
  uint32_t p;
  static const uint32_t edge_32[] = {3, 2};
  static const uint32_t triangles_on_23[] = {0, 2, 3, 1, 2, 3, 2, 3, 4};
  static const uint32_t v4[] = {4};
  static const uint32_t edges_at_4[] = {2, 4, 3, 4, 4, 5};
  static const uint32_t tri_432[] = {4, 3, 2};
  static const uint32_t edges_of_234[] = {2, 3, 2, 4, 3, 4};
  static const uint32_t v2[] = {2};
  static const uint32_t neighbours_of_2[] = {0, 1, 3, 4};
  static const uint32_t tet[] = {0, 1, 2, 3};
  static const uint32_t adjacent_to_123[] = {0, 1, 2, 0, 1, 3, 0, 2, 3, 2, 3, 4};
  static const uint32_t triangles[] = {0, 1, 2, 0, 1, 3, 0, 2, 3, 1, 2, 3, 2, 3, 4};

  /* The structure owns its data: the complex may go first. */
  tpx_complex_free(c);

  CHECK_STATUS(tpx_structure_kind(s, &kind), TPX_STATUS_OK);
  CHECK_STATUS(tpx_structure_dimension(s, &d), TPX_STATUS_OK);
  CHECK(kind == TPX_KIND_IG && d == 3);
  for (p = 0; p < 4; ++p) {
    CHECK_STATUS(tpx_structure_count(s, p, &counts[p]), TPX_STATUS_OK);
  }
  /* 6 vertices; 6 tetrahedron edges + 2-4, 3-4, 4-5; 4 faces + 2 3 4; one tetrahedron. */
  CHECK(counts[0] == 6 && counts[1] == 9 && counts[2] == 5 && counts[3] == 1);
  CHECK_STATUS(tpx_structure_count(s, 7, &len), TPX_STATUS_OK);
  CHECK(len == 0);
  CHECK_STATUS(tpx_structure_top_count(s, 2, &len), TPX_STATUS_OK);
  CHECK(len == 1);
  CHECK_STATUS(tpx_structure_storage(s, &storage), TPX_STATUS_OK);
  CHECK(storage.integers > 0 && storage.bytes > 0);

  CHECK_STATUS(tpx_structure_simplices(s, 2, buf, 32, &len), TPX_STATUS_OK);
  CHECK(len == 15 && same_u32(buf, triangles, 15));

  CHECK_STATUS(tpx_relation(s, edge_32, 2, 2, buf, 32, &len), TPX_STATUS_OK);
  CHECK(len == 9 && same_u32(buf, triangles_on_23, 9));
  CHECK_STATUS(tpx_relation(s, v4, 1, 1, buf, 32, &len), TPX_STATUS_OK);
  CHECK(len == 6 && same_u32(buf, edges_at_4, 6));
  CHECK_STATUS(tpx_relation(s, tri_432, 3, 1, buf, 32, &len), TPX_STATUS_OK);
  CHECK(len == 6 && same_u32(buf, edges_of_234, 6));
  CHECK_STATUS(tpx_relation(s, v2, 1, 0, buf, 32, &len), TPX_STATUS_OK);
  CHECK(len == 4 && same_u32(buf, neighbours_of_2, 4));
  /* Triangles sharing an edge with 1 2 3. */
  CHECK_STATUS(tpx_relation(s, tet + 1, 3, 2, buf, 32, &len), TPX_STATUS_OK);
  CHECK(len == 12 && same_u32(buf, adjacent_to_123, 12));
  /* The tetrahedron has no adjacent tetrahedron: an empty answer, NULL buffer allowed. */
  len = 77;
  CHECK_STATUS(tpx_relation(s, tet, 4, 3, NULL, 0, &len), TPX_STATUS_OK);
  CHECK(len == 0);

  tpx_structure_free(s);
}

static void test_buffer_too_small(void) {
  TpxComplex *c = fixture();
  TpxStructure *s = build_ig(c);
  uint32_t small[4] = {7, 7, 7, 7};
  size_t len = 0;
  static const uint32_t edge_23[] = {2, 3};

  /* Size query: NULL buffer of length 0 gives the needed length. */
  CHECK_STATUS(tpx_relation(s, edge_23, 2, 2, NULL, 0, &len), TPX_STATUS_BUFFER_TOO_SMALL);
  CHECK(len == 9);
  len = 0;
  CHECK_STATUS(tpx_relation(s, edge_23, 2, 2, small, 4, &len), TPX_STATUS_BUFFER_TOO_SMALL);
  CHECK(len == 9);
  CHECK(small[0] == 7 && small[1] == 7 && small[2] == 7 && small[3] == 7);
  CHECK(message_contains("9"));
  len = 0;
  CHECK_STATUS(tpx_structure_simplices(s, 1, small, 4, &len), TPX_STATUS_BUFFER_TOO_SMALL);
  CHECK(len == 18);
  CHECK(small[0] == 7);
  /* A NULL buffer that claims room is a NULL argument. */
  CHECK_STATUS(tpx_relation(s, edge_23, 2, 2, NULL, 9, &len), TPX_STATUS_NULL_ARGUMENT);

  tpx_structure_free(s);
  tpx_complex_free(c);
}

static void test_null_arguments(void) {
  TpxComplex *c = fixture();
  TpxStructure *s = build_ig(c);
  TpxComplex *cout = NULL;
  TpxStructure *sout = NULL;
  TpxRelationTable *tout = NULL;
  uint32_t u = 42;
  size_t z = 42;
  TpxStorage storage = {1, 2, 3};
  static const uint32_t v0[] = {0};
  static const size_t offsets[] = {0, 1};

  CHECK_STATUS(tpx_complex_from_arrays(1, v0, offsets, 1, NULL, 0, NULL), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_complex_from_arrays(1, NULL, offsets, 1, NULL, 0, &cout), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_complex_from_arrays(1, v0, NULL, 1, NULL, 0, &cout), TPX_STATUS_NULL_ARGUMENT);
  CHECK(message_contains("offsets"));
  CHECK_STATUS(tpx_complex_from_file(NULL, &cout), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_complex_from_file("x.off", NULL), TPX_STATUS_NULL_ARGUMENT);
  CHECK(cout == NULL);
  CHECK_STATUS(tpx_complex_dimension(NULL, &u), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_complex_dimension(c, NULL), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_complex_vertex_count(NULL, &u), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_complex_top_count(NULL, 0, &z), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_structure_build(NULL, TPX_KIND_IG, &sout), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_structure_build(c, TPX_KIND_IG, NULL), TPX_STATUS_NULL_ARGUMENT);
  CHECK(sout == NULL);
  CHECK_STATUS(tpx_structure_kind(NULL, &u), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_structure_dimension(s, NULL), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_structure_count(NULL, 0, &z), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_structure_top_count(s, 0, NULL), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_structure_storage(NULL, &storage), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_structure_simplices(s, 0, NULL, 0, NULL), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_relation(NULL, v0, 1, 0, NULL, 0, &z), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_relation(s, NULL, 1, 0, NULL, 0, &z), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_relation(s, v0, 1, 0, NULL, 0, NULL), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_relation_table(NULL, 0, 0, &tout), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_relation_table(s, 0, 0, NULL), TPX_STATUS_NULL_ARGUMENT);
  CHECK(tout == NULL);
  CHECK(tpx_relation_table_offsets(NULL, &z) == NULL);
  CHECK(tpx_relation_table_ids(NULL, &z) == NULL);
  /* Outputs untouched by every failure above. */
  CHECK(u == 42 && z == 42 && storage.integers == 1 && storage.bits == 2 && storage.bytes == 3);

  tpx_complex_free(NULL);
  tpx_structure_free(NULL);
  tpx_relation_table_free(NULL);
  tpx_structure_free(s);
  tpx_complex_free(c);
}

static void test_invalid_inputs(void) {
  TpxComplex *c = NULL;
  static const uint32_t ids[] = {0, 1, 2, 2};
  static const size_t decreasing[] = {0, 2, 1};
  static const size_t two[] = {0, 2, 4};
  static const uint32_t out_of_range[] = {0, 3};
  static const size_t one[] = {0, 2};
  static const double coords[] = {0.0, 1.0};

  CHECK_STATUS(tpx_complex_from_arrays(3, ids, decreasing, 2, NULL, 0, &c), TPX_STATUS_INVALID_ARGUMENT);
  CHECK(message_contains("offsets"));
  CHECK_STATUS(tpx_complex_from_arrays(2, NULL, NULL, 0, coords, 0, &c), TPX_STATUS_INVALID_ARGUMENT);
  /* Simplex #1 is [2 2]. */
  CHECK_STATUS(tpx_complex_from_arrays(3, ids, two, 2, NULL, 0, &c), TPX_STATUS_INVALID_COMPLEX);
  CHECK(message_contains("#1") && message_contains("[2 2]"));
  CHECK_STATUS(tpx_complex_from_arrays(3, out_of_range, one, 1, NULL, 0, &c), TPX_STATUS_INVALID_COMPLEX);
  CHECK(message_contains("[0 3]"));
  CHECK_STATUS(tpx_complex_from_arrays(0, NULL, NULL, 0, NULL, 0, &c), TPX_STATUS_INVALID_COMPLEX);
  /* Sizes that cannot be addressed. */
  CHECK_STATUS(tpx_complex_from_arrays(1, ids, one, SIZE_MAX, NULL, 0, &c), TPX_STATUS_TOO_LARGE);
  CHECK_STATUS(tpx_complex_from_arrays(UINT32_MAX, NULL, NULL, 0, coords, SIZE_MAX, &c), TPX_STATUS_TOO_LARGE);
  CHECK(c == NULL);
}

/* Issue 16: closure bombs and absent vertices are TOO_LARGE (never an abort), the budget can be
 * raised, a NULL buffer with a length is NULL_ARGUMENT even for an empty answer, the absorbed
 * counts are visible, and messages are bounded. */
static void test_hardening(void) {
  static const uint32_t simplex4[] = {0, 1, 2, 3, 4};
  static const size_t one[] = {0, 5};
  static const uint32_t dup_ids[] = {0, 1, 2, 2, 1, 0, 1, 2, 3, 4};
  static const size_t dup_offsets[] = {0, 3, 6, 8, 10};
  static const uint32_t wire[] = {4, 5};
  TpxComplex *c = NULL;
  TpxStructure *s = NULL;
  TpxInputStats stats;
  size_t len = 42;
  char name[600];

  CHECK_STATUS(tpx_complex_from_arrays(UINT32_MAX, NULL, NULL, 0, NULL, 0, &c), TPX_STATUS_TOO_LARGE);
  CHECK(c == NULL && message_contains("budget"));
  /* One 4-simplex: 31 simplices by the closure bound. */
  CHECK_STATUS(tpx_complex_from_arrays_budget(5, simplex4, one, 1, NULL, 0, 30, &c), TPX_STATUS_TOO_LARGE);
  CHECK(c == NULL);
  CHECK_STATUS(tpx_complex_from_arrays_budget(5, simplex4, one, 1, NULL, 0, 31, &c), TPX_STATUS_OK);
  tpx_complex_free(c);
  c = NULL;

  CHECK_STATUS(tpx_complex_from_arrays(5, dup_ids, dup_offsets, 4, NULL, 0, &c), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_input_stats(c, &stats), TPX_STATUS_OK);
  CHECK(stats.input_simplices == 4 && stats.absorbed_duplicates == 1 && stats.absorbed_faces == 1);
  tpx_complex_free(c);

  c = fixture();
  s = build_ig(c);
  /* R_{1,2} of the wire edge 4-5 is empty; a NULL buffer with a length is still refused. */
  CHECK_STATUS(tpx_relation(s, wire, 2, 2, NULL, 8, &len), TPX_STATUS_NULL_ARGUMENT);
  CHECK(len == 42);
  CHECK_STATUS(tpx_relation(s, wire, 2, 2, NULL, 0, &len), TPX_STATUS_OK);
  CHECK(len == 0);
  tpx_structure_free(s);
  tpx_complex_free(c);

  /* A long path with a control character: the message is one bounded line. */
  memset(name, 'x', sizeof name);
  name[0] = '\v';
  memcpy(name + sizeof name - 5, ".off", 5);
  c = NULL;
  CHECK(tpx_complex_from_file(name, &c) != TPX_STATUS_OK);
  CHECK(c == NULL && strlen(tpx_last_error_message()) < 500);
  /* The path is echoed escaped (\x0b), never raw. */
  CHECK(strchr(tpx_last_error_message(), '\v') == NULL && message_contains("\\x0b"));
}

static void test_kinds(void) {
  TpxComplex *c = fixture();
  TpxStructure *ig = build_ig(c);
  TpxStructure *s = NULL;
  uint32_t kind, got;
  unsigned not_implemented = 0, built = 0, unsupported = 0;
  static const uint32_t edge_23[] = {2, 3};
  uint32_t want[16], buf[16];
  size_t want_len = 0, len = 0;

  CHECK_STATUS(tpx_structure_build(c, 10, &s), TPX_STATUS_UNKNOWN_KIND);
  CHECK(message_contains("10") && message_contains("0..=9"));
  CHECK_STATUS(tpx_structure_build(c, UINT32_MAX, &s), TPX_STATUS_UNKNOWN_KIND);
  CHECK(message_contains("4294967295"));
  CHECK(s == NULL);

  CHECK_STATUS(tpx_relation(ig, edge_23, 2, 2, want, 16, &want_len), TPX_STATUS_OK);
  /* Each kind either builds and answers as the IG does, or says why it cannot. */
  for (kind = TPX_KIND_IG; kind <= TPX_KIND_IASTAR; ++kind) {
    TpxStatus st = tpx_structure_build(c, kind, &s);
    if (st == TPX_STATUS_OK) {
      ++built;
      CHECK_STATUS(tpx_structure_kind(s, &got), TPX_STATUS_OK);
      CHECK(got == kind);
      CHECK_STATUS(tpx_relation(s, edge_23, 2, 2, buf, 16, &len), TPX_STATUS_OK);
      CHECK(len == want_len && same_u32(buf, want, len));
      tpx_structure_free(s);
      s = NULL;
    } else if (st == TPX_STATUS_NOT_IMPLEMENTED) {
      ++not_implemented;
      CHECK(message_contains("not implemented"));
      CHECK(s == NULL);
    } else if (st == TPX_STATUS_UNSUPPORTED_COMPLEX) {
      ++unsupported;
      CHECK(message_contains("["));
      CHECK(s == NULL);
    } else {
      check(0, "kind builds, is NOT_IMPLEMENTED or UNSUPPORTED_COMPLEX", __FILE__, __LINE__);
    }
  }
  CHECK(built >= 2); /* the IG and the live complex take any complex */
  printf("kinds: %u built, %u not implemented, %u unsupported on the fixture\n", built,
         not_implemented, unsupported);

  tpx_structure_free(ig);
  tpx_complex_free(c);
}

static void test_query_errors(void) {
  TpxComplex *c = fixture();
  TpxStructure *s = build_ig(c);
  TpxRelationTable *t = NULL;
  uint32_t buf[16];
  size_t len = 55;
  static const uint32_t not_in[] = {4, 0};
  static const uint32_t repeated[] = {1, 1};
  static const uint32_t out_of_range[] = {6};
  static const uint32_t seventeen[17] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
  static const uint32_t v0[] = {0};

  CHECK_STATUS(tpx_relation(s, not_in, 2, 0, buf, 16, &len), TPX_STATUS_NOT_IN_COMPLEX);
  CHECK(message_contains("[0 4]"));
  CHECK_STATUS(tpx_relation(s, v0, 0, 0, buf, 16, &len), TPX_STATUS_INVALID_SIMPLEX);
  CHECK_STATUS(tpx_relation(s, repeated, 2, 0, buf, 16, &len), TPX_STATUS_INVALID_SIMPLEX);
  CHECK(message_contains("repeats vertex 1"));
  CHECK_STATUS(tpx_relation(s, out_of_range, 1, 0, buf, 16, &len), TPX_STATUS_INVALID_SIMPLEX);
  CHECK_STATUS(tpx_relation(s, seventeen, 17, 0, buf, 16, &len), TPX_STATUS_INVALID_SIMPLEX);
  CHECK_STATUS(tpx_relation(s, v0, 1, 4, buf, 16, &len), TPX_STATUS_DIMENSION_OUT_OF_RANGE);
  CHECK_STATUS(tpx_structure_simplices(s, 4, buf, 16, &len), TPX_STATUS_DIMENSION_OUT_OF_RANGE);
  CHECK_STATUS(tpx_relation_table(s, 4, 0, &t), TPX_STATUS_DIMENSION_OUT_OF_RANGE);
  CHECK_STATUS(tpx_relation_table(s, 0, 4, &t), TPX_STATUS_DIMENSION_OUT_OF_RANGE);
  CHECK(len == 55 && t == NULL);
  /* A success clears the message. */
  CHECK_STATUS(tpx_relation(s, v0, 1, 1, buf, 16, &len), TPX_STATUS_OK);
  CHECK(strcmp(tpx_last_error_message(), "") == 0);

  tpx_structure_free(s);
  tpx_complex_free(c);
}

static void test_relation_table(void) {
  TpxComplex *c = fixture();
  TpxStructure *s = build_ig(c);
  TpxRelationTable *t = NULL;
  const size_t *offsets;
  const uint32_t *ids;
  size_t n_offsets = 0, n_ids = 0;
  /* Edges at each vertex, rows in lexicographic order. */
  static const size_t want_offsets[] = {0, 6, 12, 20, 28, 34, 36};
  static const uint32_t want_ids[] = {
      0, 1, 0, 2, 0, 3,       /* vertex 0 */
      0, 1, 1, 2, 1, 3,       /* vertex 1 */
      0, 2, 1, 2, 2, 3, 2, 4, /* vertex 2 */
      0, 3, 1, 3, 2, 3, 3, 4, /* vertex 3 */
      2, 4, 3, 4, 4, 5,       /* vertex 4 */
      4, 5,                   /* vertex 5 */
  };
  /* Triangles on each edge (edges in lexicographic order: 01 02 03 12 13 23 24 34 45). */
  static const size_t want_offsets_12[] = {0, 6, 12, 18, 24, 30, 39, 42, 45, 45};
  static const uint32_t want_ids_12[] = {
      0, 1, 2, 0, 1, 3,          /* 0 1 */
      0, 1, 2, 0, 2, 3,          /* 0 2 */
      0, 1, 3, 0, 2, 3,          /* 0 3 */
      0, 1, 2, 1, 2, 3,          /* 1 2 */
      0, 1, 3, 1, 2, 3,          /* 1 3 */
      0, 2, 3, 1, 2, 3, 2, 3, 4, /* 2 3 */
      2, 3, 4,                   /* 2 4 */
      2, 3, 4,                   /* 3 4 */
                                 /* 4 5: none */
  };
  size_t i;
  int offsets_ok = 1;

  CHECK_STATUS(tpx_relation_table(s, 0, 1, &t), TPX_STATUS_OK);
  offsets = tpx_relation_table_offsets(t, &n_offsets);
  ids = tpx_relation_table_ids(t, &n_ids);
  CHECK(offsets != NULL && ids != NULL);
  CHECK(n_offsets == 7 && n_ids == 36);
  if (n_offsets == 7 && n_ids == 36) {
    for (i = 0; i < 7; ++i) offsets_ok &= offsets[i] == want_offsets[i];
    CHECK(offsets_ok);
    CHECK(same_u32(ids, want_ids, 36));
  }
  CHECK(tpx_relation_table_offsets(t, NULL) == NULL);
  tpx_relation_table_free(t);

  t = NULL;
  CHECK_STATUS(tpx_relation_table(s, 1, 2, &t), TPX_STATUS_OK);
  offsets = tpx_relation_table_offsets(t, &n_offsets);
  ids = tpx_relation_table_ids(t, &n_ids);
  CHECK(n_offsets == 10 && n_ids == 45);
  if (n_offsets == 10 && n_ids == 45) {
    offsets_ok = 1;
    for (i = 0; i < 10; ++i) offsets_ok &= offsets[i] == want_offsets_12[i];
    CHECK(offsets_ok);
    CHECK(same_u32(ids, want_ids_12, 45));
  }
  tpx_relation_table_free(t);

  tpx_structure_free(s);
  tpx_complex_free(c);
}

static void test_files(void) {
  TpxComplex *c = NULL;
  uint32_t d = 0, n = 0;
  size_t top = 0;

  CHECK_STATUS(tpx_complex_from_file(TPX_TEST_DATA_DIR "/tet_triangle_wire.simplices", &c), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_dimension(c, &d), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_vertex_count(c, &n), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_top_count(c, 1, &top), TPX_STATUS_OK);
  CHECK(d == 3 && n == 6 && top == 1);
  tpx_complex_free(c);

  c = NULL;
  CHECK_STATUS(tpx_complex_from_file(TPX_TEST_DATA_DIR "/does_not_exist.off", &c), TPX_STATUS_IO_ERROR);
  CHECK(message_contains("does_not_exist.off"));
  CHECK_STATUS(tpx_complex_from_file(TPX_TEST_DATA_DIR "/garbage.off", &c), TPX_STATUS_PARSE_ERROR);
  CHECK(message_contains("garbage.off:"));
  CHECK_STATUS(tpx_complex_from_file(TPX_TEST_DATA_DIR "/mesh.unknown", &c), TPX_STATUS_PARSE_ERROR);
  /* The repeated vertex is on line 3; the message names file, line and simplex. */
  CHECK_STATUS(tpx_complex_from_file(TPX_TEST_DATA_DIR "/repeated_vertex.simplices", &c), TPX_STATUS_INVALID_COMPLEX);
  CHECK(message_contains("repeated_vertex.simplices:3") && message_contains("[0 0 1]"));
  CHECK_STATUS(tpx_complex_from_file("bad\xff.off", &c), TPX_STATUS_INVALID_ARGUMENT);
  CHECK(c == NULL);
}

/* tpx_complex_write: the fixture written as Gmsh (format from the extension) reads back with the
 * same top simplices; OFF cannot hold its tetrahedron and writes nothing. */
static void test_write(void) {
  TpxComplex *c = fixture();
  TpxComplex *back = NULL;
  uint32_t buf[8];
  size_t len = 0, n = 0;
  FILE *f;
  CHECK_STATUS(tpx_complex_write(c, "tpx_c_write.msh", TPX_FORMAT_FROM_EXTENSION), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_from_file("tpx_c_write.msh", &back), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_top_simplices(back, 3, buf, 8, &len), TPX_STATUS_OK);
  CHECK(len == 4 && buf[0] == 0 && buf[1] == 1 && buf[2] == 2 && buf[3] == 3);
  CHECK_STATUS(tpx_complex_top_count(back, 1, &n), TPX_STATUS_OK);
  CHECK(n == 1);
  CHECK_STATUS(tpx_complex_write(c, "tpx_c_write.off", TPX_FORMAT_FROM_EXTENSION),
               TPX_STATUS_FORMAT_CANNOT_HOLD);
  CHECK(message_contains("simplex #0 [3 2 1 0] has dimension 3"));
  f = fopen("tpx_c_write.off", "r");
  CHECK(f == NULL);
  if (f) fclose(f);
  CHECK_STATUS(tpx_complex_write(c, "tpx_c_write.txt", 999), TPX_STATUS_UNKNOWN_FORMAT);
  CHECK_STATUS(tpx_complex_write(c, NULL, TPX_FORMAT_VTK), TPX_STATUS_NULL_ARGUMENT);
  remove("tpx_c_write.msh");
  tpx_complex_free(back);
  tpx_complex_free(c);
}

/* The live complex navigates through the handle functions (tpx_live_structure): on the fixture,
 * edge 2-3 bounds triangles 0 2 3, 1 2 3 and 2 3 4; after removing 2 3 4 the triangle's handle
 * is stale, edge 2-3's (named through it) still names the edge; many handles at once answer in
 * one CSR; after compaction every older handle is STALE_GENERATION. */
static void test_live_handles(void) {
  TpxComplex *c = fixture();
  TpxLive *l = NULL;
  const TpxStructure *s = NULL;
  TpxSimplex e, t, tri[8], star[32];
  uint32_t ids[16], offsets[9], flags[8], v = 0;
  static const uint32_t edge[] = {3, 2}, dangling[] = {4, 2, 3};
  size_t len = 0, ni = 0, ng = 0, deg = 0, n2 = 0, i;
  int seen_234 = 0;
  CHECK_STATUS(tpx_live_from_complex(c, &l), TPX_STATUS_OK);
  CHECK_STATUS(tpx_live_structure(l, &s), TPX_STATUS_OK);
  CHECK_STATUS(tpx_locate(s, edge, 2, &e), TPX_STATUS_OK);
  CHECK_STATUS(tpx_related_handles(s, &e, 2, TPX_ORDER_NATURAL, tri, 8, &len), TPX_STATUS_OK);
  CHECK(len == 3);
  for (i = 0; i < len; ++i) {
    size_t n = 0;
    CHECK_STATUS(tpx_simplex_vertices(s, &tri[i], ids, 16, &n), TPX_STATUS_OK);
    if (n == 3 && ids[0] == 2 && ids[1] == 3 && ids[2] == 4) seen_234 = 1;
  }
  CHECK(seen_234);
  CHECK_STATUS(tpx_degree(s, &e, 3, &deg), TPX_STATUS_OK);
  CHECK(deg == 1);
  /* Dense indices above vertices: triangles 012 013 023 123 234, so 023 123 234 are 2 3 4. */
  CHECK_STATUS(tpx_related(s, &e, 2, TPX_ORDER_NATURAL, ids, 16, &len), TPX_STATUS_OK);
  CHECK(len == 3 && ids[0] == 2 && ids[1] == 3 && ids[2] == 4);
  CHECK_STATUS(tpx_star(s, &e, 0, TPX_ORDER_NATURAL, star, 32, &len), TPX_STATUS_OK);
  CHECK(len == 4); /* three triangles and the tetrahedron */
  CHECK_STATUS(tpx_simplex_test(s, &e, 1, &v), TPX_STATUS_OK);
  CHECK(v == 0); /* not manifold */
  CHECK_STATUS(tpx_cyclic_handles(s, &e, 2, tri, 8, offsets, flags, 8, &ni, &ng), TPX_STATUS_OK);
  CHECK(ni == 3 && ng == 2);
  {
    /* The same groups as indices: each item the index of the handle written above. */
    uint32_t want_idx[3];
    for (i = 0; i < 3; ++i) CHECK_STATUS(tpx_simplex_index(s, &tri[i], &want_idx[i]), TPX_STATUS_OK);
    CHECK_STATUS(tpx_cyclic(s, &e, 2, ids, 16, offsets, flags, 8, &ni, &ng), TPX_STATUS_OK);
    CHECK(ni == 3 && ng == 2 && same_u32(ids, want_idx, 3));
  }
  /* Handles named through the dangling triangle (the lowest top slot holding them: the triangle
   * itself and edge 2-3): the triangle's goes stale with it; edge 2-3 lives on in the
   * tetrahedron, and its handle keeps naming it (located again on each use). */
  CHECK_STATUS(tpx_locate(s, dangling, 3, &t), TPX_STATUS_OK);
  CHECK_STATUS(tpx_live_remove_top(l, dangling, 3), TPX_STATUS_OK);
  CHECK_STATUS(tpx_degree(s, &t, 0, &deg), TPX_STATUS_STALE_HANDLE);
  CHECK_STATUS(tpx_degree(s, &e, 2, &deg), TPX_STATUS_OK);
  CHECK(deg == 2);
  CHECK_STATUS(tpx_simplex_vertices(s, &e, ids, 16, &len), TPX_STATUS_OK);
  CHECK(len == 2 && ids[0] == 2 && ids[1] == 3);
  CHECK_STATUS(tpx_locate(s, edge, 2, &e), TPX_STATUS_OK);
  CHECK_STATUS(tpx_degree(s, &e, 2, &deg), TPX_STATUS_OK);
  CHECK(deg == 2);
  {
    /* Edge 2-3 and vertex 5 at once: triangles 0 2 3 and 1 2 3 / none; edges 2-3 / 4-5. */
    TpxSimplex asked[2], ans[8];
    uint32_t boff[3] = {9, 9, 9};
    static const uint32_t five = 5;
    asked[0] = e;
    CHECK_STATUS(tpx_handle(s, 0, five, &asked[1]), TPX_STATUS_OK);
    CHECK_STATUS(tpx_related_handles_batch(s, asked, 2, 2, TPX_ORDER_NATURAL, boff, ans, 8, &len),
                 TPX_STATUS_OK);
    CHECK(len == 2 && boff[0] == 0 && boff[1] == 2 && boff[2] == 2);
    CHECK_STATUS(tpx_simplex_vertices(s, &ans[1], ids, 16, &n2), TPX_STATUS_OK);
    CHECK(n2 == 3 && ids[0] == 1 && ids[1] == 2 && ids[2] == 3);
    CHECK_STATUS(tpx_related_handles_batch(s, asked, 2, 1, TPX_ORDER_NATURAL, boff, ans, 1, &len),
                 TPX_STATUS_BUFFER_TOO_SMALL);
    CHECK(len == 5 && boff[2] == 2); /* 4 edges at 2-3 and 4-5: nothing written */
    CHECK_STATUS(tpx_related_handles_batch(s, asked, 2, 1, TPX_ORDER_NATURAL, NULL, ans, 8, &len),
                 TPX_STATUS_NULL_ARGUMENT);
    CHECK_STATUS(tpx_related_handles_batch(s, asked, 2, 7, TPX_ORDER_NATURAL, boff, ans, 8, &len),
                 TPX_STATUS_DIMENSION_OUT_OF_RANGE);
    CHECK(message_contains("batch entry 0"));
    /* Edges now 01 02 03 12 13 23 45 (2-4 and 3-4 went with the triangle): 4-5 is edge 6. */
    CHECK_STATUS(tpx_related_batch(s, 0, &five, 1, 1, TPX_ORDER_NATURAL, boff, ids, 16, &len),
                 TPX_STATUS_OK);
    CHECK(len == 1 && ids[0] == 6 && boff[0] == 0 && boff[1] == 1);
  }
  CHECK_STATUS(tpx_live_compact(l, NULL, 0, NULL), TPX_STATUS_OK);
  CHECK_STATUS(tpx_degree(s, &e, 2, &deg), TPX_STATUS_STALE_GENERATION);
  CHECK(message_contains("compaction"));
  CHECK_STATUS(tpx_locate(s, edge, 2, &e), TPX_STATUS_OK);
  CHECK_STATUS(tpx_degree(s, &e, 2, &deg), TPX_STATUS_OK);
  tpx_live_free(l);
  tpx_complex_free(c);
}

/* Names to kinds: every CLI name in any ASCII case; unknown names, NULL refused, out untouched. */
static void test_kind_names(void) {
  static const char *names[] = {"ig", "sig", "ia", "iqm", "nmia", "ts", "pe", "le", "de", "iastar"};
  uint32_t k, out = 99;
  const char *name = NULL;
  for (k = 0; k < 10; ++k) {
    CHECK_STATUS(tpx_kind_from_name(names[k], &out), TPX_STATUS_OK);
    CHECK(out == k);
    CHECK_STATUS(tpx_kind_name(k, &name), TPX_STATUS_OK);
    CHECK(name != NULL && strcmp(name, names[k]) == 0);
  }
  name = NULL;
  CHECK_STATUS(tpx_kind_name(10, &name), TPX_STATUS_UNKNOWN_KIND);
  CHECK(name == NULL);
  CHECK_STATUS(tpx_kind_from_name("IaStar", &out), TPX_STATUS_OK);
  CHECK(out == TPX_KIND_IASTAR);
  CHECK_STATUS(tpx_kind_from_name("PE", &out), TPX_STATUS_OK);
  CHECK(out == TPX_KIND_PE);
  out = 99;
  CHECK_STATUS(tpx_kind_from_name("openmesh", &out), TPX_STATUS_UNKNOWN_KIND);
  CHECK(message_contains("openmesh") && message_contains("iastar"));
  CHECK_STATUS(tpx_kind_from_name("", &out), TPX_STATUS_UNKNOWN_KIND);
  CHECK_STATUS(tpx_kind_from_name("ig ", &out), TPX_STATUS_UNKNOWN_KIND);
  CHECK_STATUS(tpx_kind_from_name("\xff", &out), TPX_STATUS_INVALID_ARGUMENT);
  CHECK_STATUS(tpx_kind_from_name(NULL, &out), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_kind_from_name("ig", NULL), TPX_STATUS_NULL_ARGUMENT);
  CHECK(out == 99);
}

/* The sets of two views' rows equal (natural orders may differ between kinds). */
static int same_rows_as_sets(const TpxRelationView *a, const TpxRelationView *b) {
  size_t i, j, k;
  if (a->count != b->count) return 0;
  for (i = 0; i < a->count; ++i) {
    size_t na = a->offsets[i + 1] - a->offsets[i], nb = b->offsets[i + 1] - b->offsets[i];
    if (na != nb) return 0;
    for (j = 0; j < na; ++j) {
      int found = 0;
      for (k = 0; k < nb; ++k) found |= a->ids[a->offsets[i] + j] == b->ids[b->offsets[i] + k];
      if (!found) return 0;
    }
  }
  return 1;
}

/* TPX_KIND_IASTAR built as a structure answers every shared function as the IG does (views,
 * degree batches, handle(p, i) and its index), and saves and opens as its own kind. */
static void test_iastar_structure(void) {
  TpxComplex *c = fixture();
  TpxStructure *ig = build_ig(c), *ia = NULL, *back = NULL;
  uint32_t p, q, kind = 0, i, idx = 0;
  size_t n_ig = 0, n_ia = 0;
  CHECK_STATUS(tpx_structure_build(c, TPX_KIND_IASTAR, &ia), TPX_STATUS_OK);
  CHECK_STATUS(tpx_structure_kind(ia, &kind), TPX_STATUS_OK);
  CHECK(kind == TPX_KIND_IASTAR);
  for (p = 0; p <= 3; ++p) {
    CHECK_STATUS(tpx_structure_count(ig, p, &n_ig), TPX_STATUS_OK);
    CHECK_STATUS(tpx_structure_count(ia, p, &n_ia), TPX_STATUS_OK);
    CHECK(n_ig == n_ia);
    for (i = 0; i < n_ia; ++i) {
      TpxSimplex a, b;
      uint32_t va[16], vb[16];
      size_t la = 0, lb = 0;
      CHECK_STATUS(tpx_handle(ig, p, i, &a), TPX_STATUS_OK);
      CHECK_STATUS(tpx_handle(ia, p, i, &b), TPX_STATUS_OK);
      CHECK_STATUS(tpx_simplex_vertices(ig, &a, va, 16, &la), TPX_STATUS_OK);
      CHECK_STATUS(tpx_simplex_vertices(ia, &b, vb, 16, &lb), TPX_STATUS_OK);
      CHECK(la == lb && same_u32(va, vb, la));
      CHECK_STATUS(tpx_simplex_index(ia, &b, &idx), TPX_STATUS_OK);
      CHECK(idx == i);
    }
    for (q = 0; q <= 3; ++q) {
      TpxRelationView vi, va;
      uint32_t all[16], di[16], da[16];
      CHECK_STATUS(tpx_relation_view(ig, p, q, &vi), TPX_STATUS_OK);
      CHECK_STATUS(tpx_relation_view(ia, p, q, &va), TPX_STATUS_OK);
      CHECK(same_rows_as_sets(&vi, &va));
      for (i = 0; i < n_ia; ++i) all[i] = i;
      CHECK_STATUS(tpx_degree_batch(ig, p, all, n_ia, q, di), TPX_STATUS_OK);
      CHECK_STATUS(tpx_degree_batch(ia, p, all, n_ia, q, da), TPX_STATUS_OK);
      CHECK(same_u32(di, da, n_ia));
    }
  }
  CHECK_STATUS(tpx_save(c, ia, "tpx_c_iastar.tpx"), TPX_STATUS_OK);
  CHECK_STATUS(tpx_structure_open("tpx_c_iastar.tpx", TPX_KIND_IASTAR, TPX_OPEN_VERIFY, &back),
               TPX_STATUS_OK);
  CHECK_STATUS(tpx_structure_kind(back, &kind), TPX_STATUS_OK);
  CHECK_STATUS(tpx_structure_count(back, 1, &n_ia), TPX_STATUS_OK);
  CHECK(kind == TPX_KIND_IASTAR && n_ia == 9);
  remove("tpx_c_iastar.tpx");
  tpx_structure_free(back);
  tpx_structure_free(ia);
  tpx_structure_free(ig);
  tpx_complex_free(c);
}

/* Coordinates set on a complex and on a live complex (one vertex, all at once), refused when
 * NaN, of the wrong length or of a removed vertex (nothing changed); windings lent. */
static void test_coordinates_and_windings(void) {
  TpxComplex *c = fixture();
  TpxLive *l = NULL;
  const TpxStructure *s = NULL;
  double xyz[18], got[18], nan_xyz[3] = {0.0, 0.0, 0.0};
  const double *lent = NULL;
  const uint32_t *row = NULL;
  static const uint32_t tri[] = {2, 3, 4};
  uint32_t top = 0;
  size_t i, len = 0, dim = 0;
  TpxSimplex t;
  for (i = 0; i < 18; ++i) xyz[i] = 0.5 * (double)i;
  /* The complex: no coordinates, then 3 per vertex; a NaN or a short array changes nothing. */
  CHECK_STATUS(tpx_complex_set_coords(c, 3, xyz, 18), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_coord_dim(c, &dim), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_coords(c, got, 18, &len), TPX_STATUS_OK);
  CHECK(dim == 3 && len == 18 && memcmp(got, xyz, sizeof xyz) == 0);
  nan_xyz[1] = NAN;
  memcpy(got, xyz, sizeof xyz);
  got[7] = nan_xyz[1];
  CHECK_STATUS(tpx_complex_set_coords(c, 3, got, 18), TPX_STATUS_INVALID_ARGUMENT);
  CHECK(message_contains("coordinate 1 of vertex 2"));
  CHECK_STATUS(tpx_complex_set_coords(c, 3, xyz, 17), TPX_STATUS_INVALID_ARGUMENT);
  CHECK_STATUS(tpx_complex_set_coords(c, 0, xyz, 0), TPX_STATUS_INVALID_ARGUMENT);
  CHECK_STATUS(tpx_complex_set_coords(NULL, 3, xyz, 18), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_complex_coords(c, got, 18, &len), TPX_STATUS_OK);
  CHECK(memcmp(got, xyz, sizeof xyz) == 0);
  /* Windings lent by the complex: the tetrahedron and the triangle as listed. */
  CHECK_STATUS(tpx_complex_top_oriented(c, 3, 0, &row, &len), TPX_STATUS_OK);
  CHECK(len == 4 && row[0] == 3 && row[1] == 2 && row[2] == 1 && row[3] == 0);
  CHECK_STATUS(tpx_complex_top_oriented(c, 2, 0, &row, &len), TPX_STATUS_OK);
  CHECK(len == 3 && row[0] == 4 && row[1] == 2 && row[2] == 3);
  CHECK_STATUS(tpx_complex_top_oriented(c, 2, 1, &row, &len), TPX_STATUS_INVALID_ARGUMENT);
  CHECK_STATUS(tpx_complex_top_oriented(c, 4, 0, &row, &len), TPX_STATUS_DIMENSION_OUT_OF_RANGE);

  /* The live complex: the whole array lent, written through by both setters. */
  CHECK_STATUS(tpx_live_from_complex(c, &l), TPX_STATUS_OK);
  CHECK_STATUS(tpx_live_structure(l, &s), TPX_STATUS_OK);
  CHECK_STATUS(tpx_live_all_coords(l, &lent, &len), TPX_STATUS_OK);
  CHECK(len == 18 && memcmp(lent, xyz, sizeof xyz) == 0);
  for (i = 0; i < 18; ++i) got[i] = -1.0 - (double)i;
  CHECK_STATUS(tpx_live_set_all_coords(l, got, 18), TPX_STATUS_OK);
  CHECK(memcmp(lent, got, sizeof got) == 0);
  CHECK_STATUS(tpx_live_set_coords(l, 5, xyz, 3), TPX_STATUS_OK);
  CHECK(lent[15] == xyz[0] && lent[16] == xyz[1] && lent[17] == xyz[2]);
  CHECK_STATUS(tpx_live_set_coords(l, 5, nan_xyz, 3), TPX_STATUS_INVALID_ARGUMENT);
  CHECK(message_contains("vertex 5") && message_contains("NaN"));
  CHECK_STATUS(tpx_live_set_coords(l, 5, xyz, 2), TPX_STATUS_INVALID_ARGUMENT);
  CHECK_STATUS(tpx_live_set_all_coords(l, got, 17), TPX_STATUS_INVALID_ARGUMENT);
  CHECK(lent[15] == xyz[0]);
  /* Contract 5 into 4 (a wire end): 5 is gone, 4 keeps its place. */
  CHECK_STATUS(tpx_live_contract(l, 4, 5, TPX_CONTRACT_FREE, NULL, 0, NULL), TPX_STATUS_OK);
  CHECK_STATUS(tpx_live_set_coords(l, 5, xyz, 3), TPX_STATUS_DEAD_VERTEX);
  CHECK_STATUS(tpx_live_coords(l, 4, got, 3, &len), TPX_STATUS_OK);
  CHECK(len == 3 && got[0] == -13.0 && got[2] == -15.0);
  /* The triangle's winding, lent from the live complex's top table. */
  CHECK_STATUS(tpx_locate(s, tri, 3, &t), TPX_STATUS_OK);
  CHECK_STATUS(tpx_top_id(s, &t, &top), TPX_STATUS_OK);
  CHECK_STATUS(tpx_live_top_vertices(l, top, &row, &len), TPX_STATUS_OK);
  CHECK(len == 3 && row[0] == 4 && row[1] == 2 && row[2] == 3);
  CHECK_STATUS(tpx_live_top_vertices(l, UINT32_MAX, &row, &len), TPX_STATUS_INVALID_HANDLE);
  CHECK_STATUS(tpx_live_top_vertices(l, top, NULL, &len), TPX_STATUS_NULL_ARGUMENT);
  tpx_live_free(l);
  tpx_complex_free(c);
}

/* Attributes on the fixture, set from arrays: per vertex a 3-vector of doubles (a NaN payload and
 * a negative zero among them), per listing (tetrahedron, triangle, edge) an int32 label and a
 * float. Enumerated, found, lent; written to legacy VTK (ASCII and binary) and read back, each
 * attribute is the same name, location, type, shape and bytes (ASCII: a NaN reads back as a
 * NaN, its payload lost to the text). OFF cannot hold them; a name with
 * a blank is refused by VTK; wrong counts and unknown names are refused with their status. */
/* Whether numbers k of a and b are the same bits; with `nan_payloads` 0, any two NaNs are the
 * same (text cannot carry a NaN's payload). */
static int same_number(const void *a, const void *b, uint32_t type, size_t k, int nan_payloads) {
  if (type == TPX_VALUE_F64 && !nan_payloads && isnan(((const double *)a)[k]))
    return isnan(((const double *)b)[k]);
  if (type == TPX_VALUE_F32 && !nan_payloads && isnan(((const float *)a)[k]))
    return isnan(((const float *)b)[k]);
  if (type == TPX_VALUE_I32 || type == TPX_VALUE_F32)
    return memcmp((const char *)a + 4 * k, (const char *)b + 4 * k, 4) == 0;
  return memcmp((const char *)a + 8 * k, (const char *)b + 8 * k, 8) == 0;
}

static void check_same_attributes(const TpxComplex *a, const TpxComplex *b, int nan_payloads) {
  size_t n = 0, m = 0, i;
  CHECK_STATUS(tpx_complex_attribute_count(a, &n), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_attribute_count(b, &m), TPX_STATUS_OK);
  CHECK(n == m);
  for (i = 0; i < n; ++i) {
    TpxAttributeInfo x, y;
    char name[64];
    size_t j = SIZE_MAX, len_x = 0, len_y = 0, k, same = 0;
    const void *px = NULL, *py = NULL;
    CHECK_STATUS(tpx_complex_attribute_info(a, i, &x), TPX_STATUS_OK);
    CHECK(x.name_len < sizeof name);
    memcpy(name, x.name, x.name_len);
    name[x.name_len] = '\0';
    CHECK_STATUS(tpx_complex_attribute_find(b, name, x.location, &j), TPX_STATUS_OK);
    if (j == SIZE_MAX) continue;
    CHECK_STATUS(tpx_complex_attribute_info(b, j, &y), TPX_STATUS_OK);
    CHECK(y.value_type == x.value_type && y.components == x.components && y.elements == x.elements);
    CHECK_STATUS(tpx_complex_attribute_data(a, i, &px, &len_x), TPX_STATUS_OK);
    CHECK_STATUS(tpx_complex_attribute_data(b, j, &py, &len_y), TPX_STATUS_OK);
    CHECK(len_x == len_y && len_x == x.elements * x.components);
    for (k = 0; k < len_x && k < len_y; ++k) same += (size_t)same_number(px, py, x.value_type, k, nan_payloads);
    CHECK(same == len_x);
  }
}

/* What a caller's merge saw: its calls, the last attribute's name, a and b. */
typedef struct {
  int calls;
  char last_name[32];
  uint32_t a, b;
} MergeLog;

/* Labels ("material"): the larger; reals: 1/4 of a's plus 3/4 of b's. */
static void merge_max_and_mix(void *user, const char *name, uint32_t a, uint32_t b, double *row_a,
                              const double *row_b, size_t components) {
  MergeLog *log = (MergeLog *)user;
  size_t k;
  log->calls++;
  strncpy(log->last_name, name, sizeof log->last_name - 1);
  log->a = a;
  log->b = b;
  for (k = 0; k < components; ++k) {
    if (strcmp(name, "material") == 0) {
      row_a[k] = row_a[k] > row_b[k] ? row_a[k] : row_b[k];
    } else {
      row_a[k] = 0.25 * row_a[k] + 0.75 * row_b[k];
    }
  }
}

/* A caller's merge of vertex values at a contraction (a C function and user data), against the
 * values before; the split restores them; one vertex's values set by handle, bad rows refused;
 * the policy set again replaces the merge. */
static void test_live_vertex_merge(void) {
  TpxComplex *c = fixture();
  TpxLive *l = NULL;
  TpxUndo *undo = NULL;
  double velocity[12], got[9], a_before[2], b_before[2];
  const int32_t material[6] = {10, 11, 12, 13, 14, 15};
  const double set[2] = {1.5, -2.0}, fraction = 2.5;
  size_t len = 0, k;
  MergeLog log;
  memset(&log, 0, sizeof log);
  for (k = 0; k < 12; ++k) velocity[k] = (double)k * 0.5 - 1.0;
  CHECK_STATUS(tpx_complex_set_attribute(c, "velocity", TPX_LOCATION_VERTICES, TPX_VALUE_F64, 2, velocity, 12),
               TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_set_attribute(c, "material", TPX_LOCATION_VERTICES, TPX_VALUE_I32, 1, material, 6),
               TPX_STATUS_OK);
  CHECK_STATUS(tpx_live_from_complex(c, &l), TPX_STATUS_OK);
  CHECK_STATUS(tpx_live_set_vertex_merge(l, NULL, &log), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_live_set_vertex_merge(NULL, merge_max_and_mix, &log), TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_live_set_vertex_merge(l, merge_max_and_mix, &log), TPX_STATUS_OK);
  memcpy(a_before, &velocity[8], sizeof a_before);
  memcpy(b_before, &velocity[10], sizeof b_before);
  CHECK_STATUS(tpx_live_contract(l, 4, 5, TPX_CONTRACT_FREE, NULL, 0, &undo), TPX_STATUS_OK);
  CHECK(log.calls == 2 && log.a == 4 && log.b == 5 && strcmp(log.last_name, "material") == 0);
  CHECK_STATUS(tpx_live_vertex_values(l, "velocity", 4, got, 9, &len), TPX_STATUS_OK);
  CHECK(len == 2 && got[0] == 0.25 * a_before[0] + 0.75 * b_before[0] &&
        got[1] == 0.25 * a_before[1] + 0.75 * b_before[1]);
  CHECK_STATUS(tpx_live_vertex_values(l, "material", 4, got, 9, &len), TPX_STATUS_OK);
  CHECK(len == 1 && got[0] == 15.0);
  CHECK_STATUS(tpx_live_split(l, undo), TPX_STATUS_OK);
  tpx_undo_free(undo);
  CHECK_STATUS(tpx_live_vertex_values(l, "velocity", 4, got, 9, &len), TPX_STATUS_OK);
  CHECK(len == 2 && got[0] == a_before[0] && got[1] == a_before[1]);
  CHECK_STATUS(tpx_live_vertex_values(l, "material", 4, got, 9, &len), TPX_STATUS_OK);
  CHECK(got[0] == 14.0);
  /* One vertex's row by handle. */
  CHECK_STATUS(tpx_live_set_vertex_values(l, "velocity", 2, set, 2), TPX_STATUS_OK);
  CHECK_STATUS(tpx_live_vertex_values(l, "velocity", 2, got, 9, &len), TPX_STATUS_OK);
  CHECK(len == 2 && got[0] == 1.5 && got[1] == -2.0);
  CHECK_STATUS(tpx_live_set_vertex_values(l, "velocity", 2, set, 1), TPX_STATUS_INVALID_ARGUMENT);
  CHECK_STATUS(tpx_live_set_vertex_values(l, "material", 2, &fraction, 1), TPX_STATUS_INVALID_ARGUMENT);
  CHECK_STATUS(tpx_live_set_vertex_values(l, "absent", 2, set, 2), TPX_STATUS_NO_SUCH_ATTRIBUTE);
  CHECK_STATUS(tpx_live_set_vertex_values(l, "velocity", 99, set, 2), TPX_STATUS_DEAD_VERTEX);
  CHECK_STATUS(tpx_live_set_vertex_values(l, NULL, 2, set, 2), TPX_STATUS_NULL_ARGUMENT);
  /* The survivor policy replaces the merge: no call, a keeps its own. */
  CHECK_STATUS(tpx_live_set_vertex_policy(l, TPX_VERTEX_SURVIVOR), TPX_STATUS_OK);
  CHECK_STATUS(tpx_live_contract(l, 4, 5, TPX_CONTRACT_FREE, NULL, 0, NULL), TPX_STATUS_OK);
  CHECK(log.calls == 2);
  CHECK_STATUS(tpx_live_vertex_values(l, "velocity", 4, got, 9, &len), TPX_STATUS_OK);
  CHECK(got[0] == a_before[0] && got[1] == a_before[1]);
  tpx_live_free(l);
  tpx_complex_free(c);
}

static void test_attributes(void) {
  TpxComplex *c = fixture();
  TpxComplex *back = NULL;
  double velocity[18];
  const int32_t ref[3] = {7, -2, 2147483647};
  const float quality[3] = {0.25f, -1.5f, 3e38f};
  uint64_t nan_bits = 0x7ff80000deadbeefULL;
  size_t n = 99, i, len = 0, at = 0;
  TpxAttributeInfo info;
  const void *data = NULL;
  const uint32_t tet[] = {1, 0, 3, 2}, edge23[] = {3, 2}, edge01[] = {0, 1}, repeated[] = {4, 4};
  for (i = 0; i < 18; ++i) velocity[i] = (double)i / 3.0 - 2.0;
  memcpy(&velocity[4], &nan_bits, sizeof nan_bits);
  velocity[7] = -0.0;

  CHECK_STATUS(tpx_complex_attribute_count(c, &n), TPX_STATUS_OK);
  CHECK(n == 0);
  CHECK_STATUS(tpx_complex_set_attribute(c, "velocity", TPX_LOCATION_VERTICES, TPX_VALUE_F64, 3, velocity, 18),
               TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_set_attribute(c, "ref", TPX_LOCATION_LISTED, TPX_VALUE_I32, 1, ref, 3), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_set_attribute(c, "quality", TPX_LOCATION_LISTED, TPX_VALUE_F32, 1, quality, 3),
               TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_attribute_count(c, &n), TPX_STATUS_OK);
  CHECK(n == 3);
  CHECK_STATUS(tpx_complex_attribute_info(c, 1, &info), TPX_STATUS_OK);
  CHECK(info.name_len == 3 && memcmp(info.name, "ref", 3) == 0);
  CHECK(info.location == TPX_LOCATION_LISTED && info.value_type == TPX_VALUE_I32);
  CHECK(info.components == 1 && info.elements == 3);
  CHECK_STATUS(tpx_complex_attribute_data(c, 0, &data, &len), TPX_STATUS_OK);
  CHECK(len == 18 && memcmp(data, velocity, sizeof velocity) == 0);
  CHECK_STATUS(tpx_complex_attribute_find(c, "quality", TPX_LOCATION_LISTED, &at), TPX_STATUS_OK);
  CHECK(at == 2);

  /* The listing of a simplex: the tetrahedron is listing 0, edge 2-3 only a face (never listed). */
  CHECK_STATUS(tpx_complex_listed_index(c, tet, 4, &at), TPX_STATUS_OK);
  CHECK(at == 0);
  CHECK_STATUS(tpx_complex_listed_index(c, edge23, 2, &at), TPX_STATUS_OK);
  CHECK(at == TPX_NOT_LISTED);
  CHECK_STATUS(tpx_complex_listed_index(c, edge01, 2, &at), TPX_STATUS_OK);
  CHECK(at == TPX_NOT_LISTED);
  CHECK_STATUS(tpx_complex_listed_index(c, repeated, 2, &at), TPX_STATUS_INVALID_SIMPLEX);

  /* Refusals: nothing changes. */
  at = 12345;
  CHECK_STATUS(tpx_complex_attribute_find(c, "ref", TPX_LOCATION_VERTICES, &at), TPX_STATUS_NO_SUCH_ATTRIBUTE);
  CHECK(at == 12345 && message_contains("'ref'"));
  CHECK_STATUS(tpx_complex_set_attribute(c, "ref", TPX_LOCATION_LISTED, TPX_VALUE_I32, 1, ref, 2),
               TPX_STATUS_INVALID_ARGUMENT);
  CHECK(message_contains("'ref'") && message_contains("2 numbers"));
  CHECK_STATUS(tpx_complex_set_attribute(c, "v", TPX_LOCATION_VERTICES, TPX_VALUE_F64, 10, velocity, 18),
               TPX_STATUS_INVALID_ARGUMENT);
  CHECK_STATUS(tpx_complex_set_attribute(c, "v", TPX_LOCATION_VERTICES, TPX_VALUE_F64, 3, NULL, 18),
               TPX_STATUS_NULL_ARGUMENT);
  CHECK_STATUS(tpx_complex_remove_attribute(c, "nothing"), TPX_STATUS_NO_SUCH_ATTRIBUTE);
  CHECK_STATUS(tpx_complex_attribute_info(c, 3, &info), TPX_STATUS_INVALID_ARGUMENT);
  CHECK_STATUS(tpx_complex_attribute_count(c, &n), TPX_STATUS_OK);
  CHECK(n == 3);

  /* Written and read back, bit for bit. */
  CHECK_STATUS(tpx_complex_write(c, "tpx_c_attributes.vtk", TPX_FORMAT_VTK), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_from_file("tpx_c_attributes.vtk", &back), TPX_STATUS_OK);
  if (back) check_same_attributes(c, back, 0);
  tpx_complex_free(back);
  back = NULL;
  CHECK_STATUS(tpx_complex_write(c, "tpx_c_attributes_bin.vtk", TPX_FORMAT_VTK_BINARY), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_from_file("tpx_c_attributes_bin.vtk", &back), TPX_STATUS_OK);
  if (back) check_same_attributes(c, back, 1);
  tpx_complex_free(back);
  remove("tpx_c_attributes.vtk");
  remove("tpx_c_attributes_bin.vtk");

  /* A format that cannot hold them refuses; so does VTK for a name with a blank. */
  CHECK_STATUS(tpx_complex_write(c, "tpx_c_attributes.msh", TPX_FORMAT_MSH), TPX_STATUS_FORMAT_CANNOT_HOLD);
  CHECK(message_contains("velocity") || message_contains("ref") || message_contains("quality"));
  CHECK_STATUS(tpx_complex_set_attribute(c, "two words", TPX_LOCATION_LISTED, TPX_VALUE_I32, 1, ref, 3),
               TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_write(c, "tpx_c_attributes.vtk", TPX_FORMAT_VTK), TPX_STATUS_FORMAT_CANNOT_HOLD);
  CHECK(message_contains("two words"));
  CHECK_STATUS(tpx_complex_remove_attribute(c, "two words"), TPX_STATUS_OK);
  CHECK_STATUS(tpx_complex_attribute_count(c, &n), TPX_STATUS_OK);
  CHECK(n == 3);
  remove("tpx_c_attributes.msh");
  remove("tpx_c_attributes.vtk");
  tpx_complex_free(c);
}

int main(void) {
  test_version();
  test_complex_lifecycle();
  test_complex_contents();
  test_structure_queries();
  test_buffer_too_small();
  test_null_arguments();
  test_invalid_inputs();
  test_hardening();
  test_kinds();
  test_query_errors();
  test_relation_table();
  test_files();
  test_write();
  test_live_handles();
  test_kind_names();
  test_iastar_structure();
  test_coordinates_and_windings();
  test_attributes();
  test_live_vertex_merge();
  printf("%d passed, %d failed\n", g_passed, g_failed);
  return g_failed == 0 ? 0 : 1;
}
