/* Built only with TOPOPLEX_SANITIZE=ON and expected to FAIL: it drops a handle the Rust
 * library allocated, so LeakSanitizer must report it. Proves the sanitizer run sees the
 * library's heap (a pass here would mean the other tests' clean runs prove nothing). */
#include "topoplex.h"

static void drop_a_complex(void) {
  static const uint32_t ids[] = {0, 1, 2};
  static const size_t offsets[] = {0, 3};
  TpxComplex *c = NULL;
  (void)tpx_complex_from_arrays(3, ids, offsets, 1, NULL, 0, &c);
  c = NULL; /* the only pointer to it, so nothing on the stack keeps it reachable */
  (void)c;
}

int main(void) {
  drop_a_complex();
  return 0;
}
