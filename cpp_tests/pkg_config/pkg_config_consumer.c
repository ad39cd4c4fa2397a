/* Built with only `pkg-config --cflags --libs topoplex`: the edges of a triangle's vertex. */
#include <topoplex.h>

#include <stdio.h>

int main(void) {
  static const uint32_t ids[] = {0, 1, 2};
  static const size_t offsets[] = {0, 3};
  static const uint32_t v0[] = {0};
  static const uint32_t want[] = {0, 1, 0, 2};
  uint32_t buf[8];
  size_t len = 0, i;
  TpxComplex *c = NULL;
  TpxStructure *s = NULL;
  int ok = tpx_complex_from_arrays(3, ids, offsets, 1, NULL, 0, &c) == TPX_STATUS_OK &&
           tpx_structure_build(c, TPX_KIND_IG, &s) == TPX_STATUS_OK &&
           tpx_relation(s, v0, 1, 1, buf, 8, &len) == TPX_STATUS_OK && len == 4;
  for (i = 0; ok && i < 4; ++i) ok = buf[i] == want[i];
  if (!ok) fprintf(stderr, "pkg-config consumer failed: %s\n", tpx_last_error_message());
  tpx_structure_free(s);
  tpx_complex_free(c);
  printf("%s\n", ok ? "1 passed, 0 failed" : "0 passed, 1 failed");
  return ok ? 0 : 1;
}
