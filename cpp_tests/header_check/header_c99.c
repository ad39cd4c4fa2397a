/* topoplex.h is the only include: it must bring everything it uses (size_t, uint32_t). */
#include "topoplex.h"

int main(void) {
  TpxStatus st = TPX_STATUS_OK;
  TpxStorage storage = {0, 0, 0};
  uint32_t kind = TPX_KIND_DE;
  (void)storage;
  (void)kind;
  return st == 0 && tpx_version()[0] != '\0' ? 0 : 1;
}
