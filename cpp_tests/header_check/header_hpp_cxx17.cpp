// topoplex.hpp is self-contained and warning-free under the strict flags.
#include "topoplex.hpp"

int main() { return topoplex::version().empty() ? 1 : 0; }
