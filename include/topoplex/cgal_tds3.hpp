/*
 * CGAL Triangulation_3 and Mesh_complex_3_in_triangulation_3 <-> Topoplex, in memory. Include
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
 * Back (CGAL 5.5, whose Mesh_3 loader CGAL/Mesh_3/tet_soup_to_c3t3.h this uses; later CGAL
 * versions moved it, and complex_to_c3t3 is then not declared): complex_to_c3t3 fills a C3T3
 * from the listed tetrahedra (vertex order kept; a negatively oriented one has its first two
 * vertices swapped, as CGAL requires positive cells, counted in the return value) with
 * "c3t3:subdomain" as their subdomain (1 without it) and the listed triangles' "c3t3:patch" as
 * the surface patch of the facets they name, then rescans the complex. The tetrahedra must fill
 * a ball (every Triangulation_3 covers its convex hull: c3t3_to_complex(c3t3, true) gives such
 * a complex): otherwise, or with a flat tetrahedron, a triangle in three tetrahedra, a complex
 * that is not 3-dimensional or lacks 3 coordinates, it is refused (topoplex::Refused) and the
 * C3T3 cleared. Other attributes are refused unless left behind into a Dropped list. Cost:
 * CGAL's loader, O(C log C) with hash maps of facets.
 *
 * Refused: nothing beyond the triangulation's own dimension: a triangulation of dimension
 * below 3 gives its vertices only (no cells). Cost: one pass over the vertices (a hash map of
 * vertex handles, O(V)) and one over the cells (and facets), arrays reserved first; O(V + C).
 */
#ifndef TOPOPLEX_CGAL_TDS3_HPP
#define TOPOPLEX_CGAL_TDS3_HPP

#include "adapter.hpp"

#include <CGAL/Handle_hash_function.h>
#include <CGAL/version.h>
#if CGAL_VERSION_NR < CGAL_VERSION_NUMBER(5, 6, 0)
#include <CGAL/Mesh_3/tet_soup_to_c3t3.h>
#include <CGAL/enum.h>
#define TOPOPLEX_HAVE_COMPLEX_TO_C3T3 1
#endif

#include <algorithm>
#include <array>
#include <map>

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

template <class SPI>
bool patch_from(const std::int32_t *x, std::size_t k, SPI &out) {
  if constexpr (std::is_integral<SPI>::value) {
    if (k != 1) return false;
    out = SPI(x[0]);
  } else {
    if (k != 2) return false;
    out = SPI(x[0], x[1]);
  }
  return true;
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

#ifdef TOPOPLEX_HAVE_COMPLEX_TO_C3T3
/* Fills `out` (cleared first) with the complex's tetrahedra and labels (header comment).
 * Returns the number of tetrahedra given to CGAL with their first two vertices swapped. */
template <class C3T3>
std::size_t complex_to_c3t3(const Complex &c, C3T3 &out, std::vector<Dropped> *dropped = nullptr) {
  using Tr = typename C3T3::Triangulation;
  using SPI = typename Tr::Cell::Surface_patch_index;
  using P3 = typename Tr::Geom_traits::Point_3;
  out.clear();
  if (c.dimension() != 3) {
    throw Refused("a C3T3 holds a tetrahedral mesh; the complex has dimension " +
                  std::to_string(c.dimension()));
  }
  if (c.coord_dim() != 3) {
    throw Refused("a C3T3 needs 3 coordinates per vertex; the complex has " +
                  std::to_string(c.coord_dim()));
  }
  bool have_sub = false, have_patch = false;
  std::size_t patch_k = 0;
  for (const AttributeInfo &a : c.attributes()) {
    if (a.name == "c3t3:subdomain" && a.location == Location::Listed && a.type == ValueType::I32 &&
        a.components == 1) {
      have_sub = true;
    } else if (a.name == "c3t3:patch" && a.location == Location::Listed &&
               a.type == ValueType::I32) {
      have_patch = true;
      patch_k = a.components;
    } else {
      adapt::drop(dropped, a.name,
                  "a C3T3 holds the cells' subdomain (\"c3t3:subdomain\", i32) and the facets' "
                  "surface patch (\"c3t3:patch\", i32) only");
    }
  }
  const std::vector<double> xyz = c.coords();
  std::vector<typename Tr::Point> points;
  points.reserve(c.vertex_count());
  for (std::size_t v = 0; v < c.vertex_count(); ++v)
    points.push_back(typename Tr::Point(P3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2])));
  const AttributeView<std::int32_t> sub =
      have_sub ? c.attribute<std::int32_t>("c3t3:subdomain", Location::Listed)
               : AttributeView<std::int32_t>();
  const AttributeView<std::int32_t> patch =
      have_patch ? c.attribute<std::int32_t>("c3t3:patch", Location::Listed)
                 : AttributeView<std::int32_t>();
  std::vector<std::array<int, 5>> cells;
  cells.reserve(c.top_count(3));
  std::map<std::array<int, 3>, SPI> border;
  std::vector<bool> seen;
  std::size_t swapped = 0;
  adapt::for_each_listed(c, [&](std::size_t i, const std::uint32_t *ids, std::size_t n,
                                std::uint32_t top) {
    if (n == 4 && top != UINT32_MAX) {
      if (top >= seen.size()) seen.resize(std::size_t(top) + 1, false);
      if (seen[top]) return;
      seen[top] = true;
      std::array<int, 5> t{int(ids[0]), int(ids[1]), int(ids[2]), int(ids[3]),
                           have_sub ? int(sub[i]) : 1};
      auto pt = [&](int v) { return P3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]); };
      const auto o = CGAL::orientation(pt(t[0]), pt(t[1]), pt(t[2]), pt(t[3]));
      if (o == CGAL::COPLANAR) {
        throw Refused("tetrahedron " + adapt::ids_text(ids, 4) + " (listed simplex " +
                      std::to_string(i) + ") is flat: a C3T3 cell must have volume");
      }
      if (o == CGAL::NEGATIVE) {
        std::swap(t[0], t[1]);
        ++swapped;
      }
      cells.push_back(t);
    } else if (n == 3 && have_patch) {
      SPI value;
      if (!detail::patch_from(patch.element(i), patch_k, value)) {
        throw Refused("\"c3t3:patch\" has " + std::to_string(patch_k) +
                      " components; this C3T3's Surface_patch_index takes " +
                      (std::is_integral<SPI>::value ? "1" : "2"));
      }
      std::array<int, 3> f{int(ids[0]), int(ids[1]), int(ids[2])};
      std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
      border.emplace(f, value);
    }
  });
  if (points.empty() || cells.empty()) {
    throw Refused("a C3T3 needs at least one tetrahedron");
  }
  std::vector<typename Tr::Vertex_handle> handles;
  if (!CGAL::build_triangulation<Tr, false>(out.triangulation(), points, cells, border, handles)) {
    out.clear();
    throw Refused("CGAL could not build a triangulation from the tetrahedra: they must fill a "
                  "ball, each triangle in at most two of them (c3t3_to_complex(c3t3, true) gives "
                  "such a complex)");
  }
  out.rescan_after_load_of_triangulation();
  return swapped;
}
#endif

}  // namespace cgal
}  // namespace topoplex

#endif /* TOPOPLEX_CGAL_TDS3_HPP */
