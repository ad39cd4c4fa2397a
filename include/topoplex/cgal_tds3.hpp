/*
 * CGAL Triangulation_3 and Mesh_complex_3_in_triangulation_3 -> Topoplex, in memory. Include
 * only where CGAL is found (find_package(CGAL), link CGAL::CGAL).
 *
 *   topoplex::Complex c = topoplex::cgal::triangulation_to_complex(tr);   // finite cells
 *   topoplex::Complex m = topoplex::cgal::c3t3_to_complex(c3t3);          // the mesh, labelled
 *
 * Kept: vertex i is the i-th finite vertex of the triangulation's vertex range; the listed
 * tetrahedra are the finite cells (triangulation_to_complex) or the cells in the complex
 * (c3t3_to_complex; all finite cells with all_cells), in iteration order, each with the vertex
 * order vertex(0..3) (CGAL's positive orientation); coordinates through CGAL::to_double of the
 * point (a weighted point's bare point). c3t3_to_complex lists after the cells the facets in the
 * complex, each facet (c, i) as Triangulation_utils_3::vertex_triple_index(i, 0..2) orders it:
 * wound so that its normal (right-hand rule) points into c, the cell the C3T3 iterates it from
 * (which side that is, CGAL does not fix), and carries the labels as listed attributes: "c3t3:subdomain" (i32; the cell's
 * Subdomain_index, 0 on the facets) and "c3t3:patch" (i32, 1 component for an integral
 * Surface_patch_index, 2 for a pair; 0 on the cells). Feature edges and corners (edges and
 * vertices in complex) are not listed.
 *
 * Not done (left for later): the way back (a Triangulation_3 or C3T3 from a complex); CGAL
 * 5.5 builds one from a tetrahedron soup only through Mesh_3's internal loader.
 *
 * Refused: nothing beyond the triangulation's own dimension: a triangulation of dimension
 * below 3 gives its vertices only (no cells). Cost: one pass over the vertices (a hash map of
 * vertex handles, O(V)) and one over the cells (and facets), arrays reserved first; O(V + C).
 */
#ifndef TOPOPLEX_CGAL_TDS3_HPP
#define TOPOPLEX_CGAL_TDS3_HPP

#include "adapter.hpp"

#include <CGAL/Handle_hash_function.h>

#include <cstdint>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace topoplex {
namespace cgal {
namespace detail {

template <class Tr>
struct TdsVertices {
  std::unordered_map<typename Tr::Vertex_handle, std::uint32_t, CGAL::Handle_hash_function> id;
  std::vector<double> xyz;
  explicit TdsVertices(const Tr &tr) {
    const std::size_t n = tr.number_of_vertices();
    id.reserve(n);
    xyz.reserve(3 * n);
    std::uint32_t next = 0;
    for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v) {
      id.emplace(v, next++);
      const auto p = tr.geom_traits().construct_point_3_object()(v->point());
      xyz.insert(xyz.end(), {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
    }
  }
};

inline void patch_numbers(int x, std::vector<std::int32_t> &out, std::size_t &k) {
  out.push_back(x);
  k = 1;
}
template <class A, class B>
void patch_numbers(const std::pair<A, B> &x, std::vector<std::int32_t> &out, std::size_t &k) {
  out.push_back(std::int32_t(x.first));
  out.push_back(std::int32_t(x.second));
  k = 2;
}

}  // namespace detail

/* Every finite cell of a Triangulation_3 (any vertex and cell base) as a listed tetrahedron. */
template <class Tr>
Complex triangulation_to_complex(const Tr &tr) {
  const detail::TdsVertices<Tr> vs(tr);
  const std::size_t nc = tr.dimension() == 3 ? tr.number_of_finite_cells() : 0;
  std::vector<std::uint32_t> ids;
  std::vector<std::size_t> offsets;
  ids.reserve(4 * nc);
  offsets.reserve(nc + 1);
  offsets.push_back(0);
  if (tr.dimension() == 3) {
    for (auto c = tr.finite_cells_begin(); c != tr.finite_cells_end(); ++c) {
      for (int k = 0; k < 4; ++k) ids.push_back(vs.id.at(c->vertex(k)));
      offsets.push_back(ids.size());
    }
  }
  return Complex::from_arrays(std::uint32_t(vs.id.size()), ids, offsets, vs.xyz, 3);
}

/* The mesh of a Mesh_complex_3_in_triangulation_3: its cells (all finite cells with
 * all_cells) then its facets, with "c3t3:subdomain" and "c3t3:patch" (header comment). */
template <class C3T3>
Complex c3t3_to_complex(const C3T3 &c3t3, bool all_cells = false) {
  const auto &tr = c3t3.triangulation();
  using Tr = typename std::decay<decltype(tr)>::type;
  const detail::TdsVertices<Tr> vs(tr);
  const std::size_t nc = all_cells ? tr.number_of_finite_cells() : c3t3.number_of_cells_in_complex();
  const std::size_t nf = c3t3.number_of_facets_in_complex();
  std::vector<std::uint32_t> ids;
  std::vector<std::size_t> offsets;
  std::vector<std::int32_t> subdomain, patch;
  ids.reserve(4 * nc + 3 * nf);
  offsets.reserve(nc + nf + 1);
  subdomain.reserve(nc + nf);
  patch.reserve(2 * (nc + nf));
  offsets.push_back(0);
  auto add_cell = [&](typename Tr::Cell_handle c) {
    for (int k = 0; k < 4; ++k) ids.push_back(vs.id.at(c->vertex(k)));
    offsets.push_back(ids.size());
    subdomain.push_back(std::int32_t(c3t3.subdomain_index(c)));
  };
  if (all_cells) {
    for (auto c = tr.finite_cells_begin(); c != tr.finite_cells_end(); ++c) add_cell(c);
  } else {
    for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) add_cell(c);
  }
  std::vector<std::int32_t> facet_patch;
  std::size_t k = 1;
  for (auto f = c3t3.facets_in_complex_begin(); f != c3t3.facets_in_complex_end(); ++f) {
    const auto c = f->first;
    const int i = f->second;
    for (int j = 0; j < 3; ++j) ids.push_back(vs.id.at(c->vertex(Tr::vertex_triple_index(i, j))));
    offsets.push_back(ids.size());
    subdomain.push_back(0);
    detail::patch_numbers(c3t3.surface_patch_index(*f), facet_patch, k);
  }
  patch.assign(k * (offsets.size() - 1 - nf), 0);
  patch.insert(patch.end(), facet_patch.begin(), facet_patch.end());
  Complex out = Complex::from_arrays(std::uint32_t(vs.id.size()), ids, offsets, vs.xyz, 3);
  out.set_attribute<std::int32_t>("c3t3:subdomain", Location::Listed, 1, subdomain);
  out.set_attribute<std::int32_t>("c3t3:patch", Location::Listed, k, patch);
  return out;
}

}  // namespace cgal
}  // namespace topoplex

#endif /* TOPOPLEX_CGAL_TDS3_HPP */
