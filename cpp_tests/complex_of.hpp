// A complex from a list of simplices with coordinates, for the C++ tests (header-only: each
// test is its own executable).
#pragma once

#include <topoplex.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace topoplex_tests {

// The complex of `n` vertices listing `rows` (each any range of vertex ids), 3 coordinates each.
template <class Rows>
topoplex::Complex complex_of(std::uint32_t n, const Rows &rows, const std::vector<double> &xyz) {
  std::vector<std::uint32_t> ids;
  std::vector<std::size_t> off{0};
  for (const auto &r : rows) {
    ids.insert(ids.end(), r.begin(), r.end());
    off.push_back(ids.size());
  }
  return topoplex::Complex::from_arrays(n, ids, off, xyz, 3);
}

}  // namespace topoplex_tests
