/*
 * Topoplex <-> GUDHI Simplex_tree (any dimension, any options), in memory. Include only where
 * GUDHI is found (its headers and Boost).
 *
 *   Gudhi::Simplex_tree<> st = ...;                       // a Rips complex, an alpha complex
 *   topoplex::Complex c = topoplex::gudhi::to_complex(st);  // every simplex, its filtration
 *   topoplex::Structure s(c, topoplex::Kind::IASTAR);       // co-faces, adjacencies, ...
 *   Gudhi::Simplex_tree<> st2 = topoplex::gudhi::to_simplex_tree<Gudhi::Simplex_tree<>>(c);
 *
 * Kept: the vertices, as ids 0..n-1 in ascending vertex-handle order (when the handles are not
 * exactly 0..n-1 the handles are kept in the i64 vertex attribute "gudhi:vertex" and given
 * back); every simplex, listed in the tree's own order (Simplex_tree::complex_simplex_range)
 * with its filtration value in the f64 listed attribute "gudhi:filtration". Back, every listed
 * simplex is inserted with its value (insert_simplex_and_subfaces, which keeps the least value
 * a simplex is given: a simplex gets its own value whenever the filtration is monotone, faces
 * not above cofaces, as GUDHI requires), or, without that attribute, the complex's top
 * simplices with filtration 0. Optional coordinates (`coords`, `coord_dim` per vertex in
 * vertex-id order) travel with the complex; a tree has none. Other attributes are refused on the
 * way back unless left behind into a `std::vector<Dropped>*`.
 *
 * Refused (topoplex::Refused): a vertex handle that is negative or above UINT32_MAX - 1; more
 * than 2^32 - 1 vertices.
 *
 * Cost: to a complex, one pass over every simplex (S simplices of total size Σ(p+1)): the ids,
 * offsets and filtration arrays reserved from num_simplices(), then Topoplex's normalisation,
 * which absorbs the faces (O(Σ(p+1) log S)); all simplices are listed because each carries a
 * value. Back, one insert_simplex_and_subfaces per listed simplex (GUDHI's cost).
 */
#ifndef TOPOPLEX_GUDHI_HPP
#define TOPOPLEX_GUDHI_HPP

#include "adapter.hpp"

#include <gudhi/Simplex_tree.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace topoplex {
namespace gudhi {

constexpr const char *filtration_attribute = "gudhi:filtration";
constexpr const char *vertex_attribute = "gudhi:vertex";

/* The complex of a simplex tree: every simplex listed with its filtration value. */
template <class ST>
Complex to_complex(const ST &tree, const std::vector<double> &coords = {},
                   std::size_t coord_dim = 0) {
  ST &st = const_cast<ST &>(tree);  // GUDHI's ranges are non-const members; nothing is written
  std::vector<std::int64_t> handles;
  handles.reserve(st.num_vertices());
  for (auto v : st.complex_vertex_range()) {
    const auto h = static_cast<std::int64_t>(v);
    if (h < 0 || h >= std::int64_t(UINT32_MAX)) {
      throw Refused("Simplex_tree vertex handle " + std::to_string(h) +
                    " is outside 0 .. 2^32 - 2");
    }
    handles.push_back(h);
  }
  std::sort(handles.begin(), handles.end());
  const bool dense = handles.empty() || handles.back() == std::int64_t(handles.size()) - 1;
  auto id = [&](std::int64_t h) {
    if (dense) return std::uint32_t(h);
    return std::uint32_t(std::lower_bound(handles.begin(), handles.end(), h) - handles.begin());
  };
  const std::size_t n = st.num_simplices();
  std::vector<std::uint32_t> ids;
  std::vector<std::size_t> offsets;
  std::vector<double> filtration;
  ids.reserve(n * std::size_t(std::max(1, st.dimension() + 1)));
  offsets.reserve(n + 1);
  filtration.reserve(n);
  offsets.push_back(0);
  for (auto sh : st.complex_simplex_range()) {
    for (auto v : st.simplex_vertex_range(sh)) ids.push_back(id(static_cast<std::int64_t>(v)));
    offsets.push_back(ids.size());
    filtration.push_back(double(st.filtration(sh)));
  }
  Complex c = Complex::from_arrays(std::uint32_t(handles.size()), ids, offsets, coords, coord_dim,
                                   UINT64_MAX);
  c.set_attribute<double>(filtration_attribute, Location::Listed, 1, filtration);
  if (!dense) c.set_attribute<std::int64_t>(vertex_attribute, Location::Vertices, 1, handles);
  return c;
}

/* Fills `st` (which should be empty) with the complex. */
template <class ST>
void to_simplex_tree(const Complex &c, ST &st, std::vector<Dropped> *dropped = nullptr) {
  using VH = typename ST::Vertex_handle;
  using FV = typename ST::Filtration_value;
  const std::uint32_t nv = c.vertex_count();
  std::vector<VH> handle(nv);
  bool have_filtration = false, have_handles = false;
  for (const AttributeInfo &a : c.attributes()) {
    if (a.name == filtration_attribute && a.location == Location::Listed &&
        a.type == ValueType::F64 && a.components == 1) {
      have_filtration = true;
    } else if (a.name == vertex_attribute && a.location == Location::Vertices &&
               a.type == ValueType::I64 && a.components == 1) {
      have_handles = true;
    } else {
      adapt::drop(dropped, a.name,
                  "a Simplex_tree holds one filtration value per simplex and nothing else");
    }
  }
  if (have_handles) {
    const AttributeView<std::int64_t> h = c.attribute<std::int64_t>(vertex_attribute, Location::Vertices);
    for (std::uint32_t v = 0; v < nv; ++v) handle[v] = VH(h[v]);
  } else {
    for (std::uint32_t v = 0; v < nv; ++v) handle[v] = VH(v);
  }
  for (std::uint32_t v = 0; v < nv; ++v) st.insert_simplex({handle[v]}, FV(0));
  std::vector<VH> s;
  s.reserve(16);
  if (have_filtration) {
    const AttributeView<double> f = c.attribute<double>(filtration_attribute, Location::Listed);
    // Vertices first got 0: give each listed vertex its own value, then insert the rest.
    adapt::for_each_listed(c, [&](std::size_t i, const std::uint32_t *ids, std::size_t n,
                                  std::uint32_t) {
      s.clear();
      for (std::size_t k = 0; k < n; ++k) s.push_back(handle[ids[k]]);
      if (n == 1) {
        st.assign_filtration(st.find(s), FV(f[i]));
      } else {
        st.insert_simplex_and_subfaces(s, FV(f[i]));
      }
    });
  } else {
    for (std::uint32_t p = 1; p <= c.dimension(); ++p) {
      const Rows tops = c.top_simplices(p);
      for (SimplexView t : tops) {
        s.clear();
        for (std::uint32_t v : t) s.push_back(handle[v]);
        st.insert_simplex_and_subfaces(s, FV(0));
      }
    }
  }
}

template <class ST>
ST to_simplex_tree(const Complex &c, std::vector<Dropped> *dropped = nullptr) {
  return adapt::filled<ST>([&](ST &st) { to_simplex_tree(c, st, dropped); });
}

}  // namespace gudhi
}  // namespace topoplex

#endif /* TOPOPLEX_GUDHI_HPP */
