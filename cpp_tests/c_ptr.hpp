// Owning pointers to the C API's objects, for the C++ tests and benchmarks that call the C API
// directly (bench/, decompose/; header-only: each is its own executable).
#pragma once

#include <memory>

#include "topoplex.h"

namespace topoplex_tests {

// Releases a T with its tpx_*_free (which accepts null).
template <class T, void (*Free)(T *)>
struct Freer {
  void operator()(T *p) const { Free(p); }
};

// The one owner of a T* the C API returned.
template <class T, void (*Free)(T *)>
using CPtr = std::unique_ptr<T, Freer<T, Free>>;

}  // namespace topoplex_tests
