// topoplex.h included from C++ on its own: extern "C" guards, no C-only constructs.
#include "topoplex.h"

#include <type_traits>

static_assert(std::is_same<std::underlying_type<TpxStatus>::type, uint32_t>::value,
              "TpxStatus is a uint32_t enum in C++");
static_assert(sizeof(TpxStorage) == 3 * sizeof(uint64_t), "TpxStorage is three uint64_t");

int main() { return tpx_version()[0] != '\0' && TPX_STATUS_PANIC == 14 ? 0 : 1; }
