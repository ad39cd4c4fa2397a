/*
 * CGAL Triangulation_3 and Mesh_complex_3_in_triangulation_3 <-> Topoplex, in memory. Include
 * only where CGAL is found (find_package(CGAL), link CGAL::CGAL).
 *
 *   topoplex::Complex c = topoplex::cgal::triangulation_to_complex(tr);   // finite cells
 *   topoplex::Complex m = topoplex::cgal::c3t3_to_complex(c3t3);          // the mesh, labelled
 *   topoplex::cgal::complex_to_triangulation(c, tr);                      // and back (plain T3)
 *   topoplex::cgal::complex_to_c3t3(m, c3t3);                             // and back (C3T3)
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
 * Back: complex_to_c3t3 fills a C3T3 from the listed tetrahedra (vertex order kept; a
 * negatively oriented one has its first two vertices swapped, as CGAL requires positive cells,
 * counted in the return value) with "c3t3:subdomain" as their subdomain (1 without it) and the
 * listed triangles' "c3t3:patch" as the surface patch of the facets they name, then rescans the
 * complex. It builds the triangulation through the TDS's public calls (detail::build_tds: the
 * vertices and cells in order, neighbours from the facets' sorted ids, an infinite cell over
 * each boundary facet, joined around the infinite vertex), the same triangulation CGAL 5.5's
 * tetrahedron-soup loader (Mesh_3/tet_soup_to_c3t3.h, which read_MEDIT uses) builds, cell for
 * cell; so it needs no CGAL version's loader (tested with CGAL 5.5). The tetrahedra must fill a
 * ball (every Triangulation_3 covers its convex hull: c3t3_to_complex(c3t3, true) gives such a
 * complex): otherwise (Euler's relation fails, a triangle in three tetrahedra, two on the same
 * side of their shared triangle, a vertex in none), or with a flat tetrahedron, a complex that
 * is not 3-dimensional or lacks 3 coordinates, it is refused (topoplex::Refused) and the C3T3
 * cleared. Other attributes are refused unless left behind into a Dropped list. Cost:
 * O(C log C) (sorts of the 4C facets and the boundary edges) plus O(C·degree) for counting
 * edges; no hash map, no walk of CGAL's is_valid().
 *
 * Refused: nothing beyond the triangulation's own dimension: a triangulation of dimension
 * below 3 gives its vertices only (no cells). Cost: one pass over the vertices (a hash map of
 * vertex handles, O(V)) and one over the cells (and facets), arrays reserved first; O(V + C).
 */
#ifndef TOPOPLEX_CGAL_TDS3_HPP
#define TOPOPLEX_CGAL_TDS3_HPP

#include "adapter.hpp"

#include <CGAL/Handle_hash_function.h>
#include <CGAL/enum.h>
/* complex_to_c3t3 is declared (it was only with CGAL < 5.6 while it used CGAL's Mesh_3 loader). */
#define TOPOPLEX_HAVE_COMPLEX_TO_C3T3 1

#include <algorithm>
#include <array>
#include <map>

#include <cstdint>
#include <string>
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

/* Whether cell type C carries Mesh_3's subdomain and surface patch indices (a C3T3's cells do,
 * a plain Triangulation_3's do not): build_tds sets them only then. */
template <class C, class = void>
struct has_mesh_indices : std::false_type {};
template <class C>
struct has_mesh_indices<C, std::void_t<typename C::Subdomain_index, typename C::Surface_patch_index>>
    : std::true_type {};

/* Whether vertex type V carries Mesh_3's dimension in the complex (set to -1 before the build,
 * 3 once in a cell, as CGAL's loader does): a plain Triangulation_3's vertices do not. */
template <class V, class = void>
struct has_vertex_dimension : std::false_type {};
template <class V>
struct has_vertex_dimension<V, std::void_t<decltype(std::declval<V &>().set_dimension(0))>>
    : std::true_type {};

/* The surface patch index type of cell type C, int for a cell without one. */
template <class C, bool = has_mesh_indices<C>::value>
struct patch_index {
  using type = int;
};
template <class C>
struct patch_index<C, true> {
  using type = typename C::Surface_patch_index;
};

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

namespace detail {

/* Builds tr (a Mesh_3 triangulation) from positively oriented cells (4 vertex ids and the
 * subdomain) through the TDS's public calls: the infinite vertex, the points' vertices in order,
 * the cells in order, each cell's neighbour across each facet from the facets' sorted ids, an
 * infinite cell (infinite vertex first, wound against the finite cell) over each facet in one
 * cell, and those joined across their edges around the infinite vertex. `border` gives facets
 * their surface patch (on both sides; a triple that is no facet is passed over). False (tr left
 * to be cleared) when a triangle is in three cells, a boundary edge not in exactly two boundary
 * facets, a facet wound alike in its two cells, a vertex in no cell, or Euler's relation fails
 * (the cells fill no ball): what the TDS's is_valid() would find, without its O(C) walks
 * around every edge. O(C log C) for the sorts, O(C·degree) for the edges. */
template <class Tr, class SPI>
bool build_tds(Tr &tr, const std::vector<typename Tr::Point> &points,
               const std::vector<std::array<int, 5>> &cells,
               std::vector<std::pair<std::array<std::uint32_t, 3>, SPI>> &border) {
  using VH = typename Tr::Vertex_handle;
  using CH = typename Tr::Cell_handle;
  using Key = std::array<std::uint32_t, 4>;  // 3 sorted ids, then 4 * cell + facet
  auto &tds = tr.tds();
  tds.clear();  // not tr.clear(): that would make a new triangulation of dimension -1
  const VH infinite = tds.create_vertex();
  tr.set_infinite_vertex(infinite);
  constexpr bool vdim = has_vertex_dimension<typename Tr::Vertex>::value;
  if constexpr (vdim) infinite->set_dimension(-1);
  std::vector<VH> vh(points.size());
  for (std::size_t v = 0; v < points.size(); ++v) {
    vh[v] = tds.create_vertex();
    vh[v]->set_point(points[v]);
    if constexpr (vdim) vh[v]->set_dimension(-1);
  }
  const std::size_t nc = cells.size();
  std::vector<CH> ch(nc);
  std::vector<Key> facets;
  facets.reserve(4 * nc);
  for (std::size_t k = 0; k < nc; ++k) {
    const auto &t = cells[k];
    ch[k] = tds.create_cell(vh[t[0]], vh[t[1]], vh[t[2]], vh[t[3]]);
    if constexpr (has_mesh_indices<typename Tr::Cell>::value) ch[k]->set_subdomain_index(t[4]);
    for (int j = 0; j < 4; ++j) {
      const VH v = vh[t[j]];
      if constexpr (vdim) v->set_dimension(3);
      if (v->cell() == CH()) v->set_cell(ch[k]);
      Key f{std::uint32_t(t[(j + 1) % 4]), std::uint32_t(t[(j + 2) % 4]),
            std::uint32_t(t[(j + 3) % 4]), std::uint32_t(4 * k + j)};
      std::sort(f.begin(), f.begin() + 3);
      facets.push_back(f);
    }
  }
  std::sort(facets.begin(), facets.end());
  const auto same = [](const Key &a, const Key &b) {
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
  };
  // Patches first (on the finite side; the infinite cells copy theirs below).
  std::sort(border.begin(), border.end(),
            [](const auto &a, const auto &b) { return a.first < b.first; });
  std::size_t b = 0;
  std::vector<std::size_t> open;  // indices into facets of the boundary facets
  std::vector<std::array<std::uint32_t, 3>> edges;  // 2 sorted ids, 4 * infinite cell + index
  for (std::size_t i = 0; i < facets.size();) {
    std::size_t e = i + 1;
    while (e < facets.size() && same(facets[e], facets[i])) ++e;
    if (e - i > 2) return false;
    const std::array<std::uint32_t, 3> ids{facets[i][0], facets[i][1], facets[i][2]};
    while (b < border.size() && border[b].first < ids) ++b;
    if constexpr (has_mesh_indices<typename Tr::Cell>::value) {
      for (std::size_t x = i; x < e; ++x) {
        if (b < border.size() && border[b].first == ids)
          ch[facets[x][3] / 4]->set_surface_patch_index(int(facets[x][3] % 4), border[b].second);
      }
    }
    if (e - i == 2) {
      const CH c0 = ch[facets[i][3] / 4], c1 = ch[facets[i + 1][3] / 4];
      c0->set_neighbor(int(facets[i][3] % 4), c1);
      c1->set_neighbor(int(facets[i + 1][3] % 4), c0);
    } else {
      open.push_back(i);
    }
    i = e;
  }
  // An infinite cell over each boundary facet (c, j): c's vertices with vertex j made the
  // infinite one, moved to the front (j transpositions), and for even j vertices 1 and 2
  // swapped: an odd permutation of c, so the shared facet is wound against c's.
  std::vector<CH> inf_cells;
  inf_cells.reserve(open.size());
  edges.reserve(3 * open.size());
  for (std::size_t i : open) {
    const std::size_t k = facets[i][3] / 4;
    const int j = int(facets[i][3] % 4);
    std::array<int, 3> w;
    for (int x = 0, y = 0; x < 4; ++x)
      if (x != j) w[y++] = cells[k][x];
    if (j % 2 == 0) std::swap(w[0], w[1]);
    const CH n = tds.create_cell(infinite, vh[w[0]], vh[w[1]], vh[w[2]]);
    n->set_neighbor(0, ch[k]);
    ch[k]->set_neighbor(j, n);
    if constexpr (has_mesh_indices<typename Tr::Cell>::value)
      n->set_surface_patch_index(0, ch[k]->surface_patch_index(j));
    if (infinite->cell() == CH()) infinite->set_cell(n);
    const std::uint32_t m = std::uint32_t(inf_cells.size());
    inf_cells.push_back(n);
    for (int x = 1; x <= 3; ++x) {  // the facet opposite vertex x: the infinite vertex and an edge
      std::uint32_t a = std::uint32_t(w[x % 3]), c = std::uint32_t(w[(x + 1) % 3]);
      if (c < a) std::swap(a, c);
      edges.push_back({a, c, 4 * m + std::uint32_t(x)});
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size(); i += 2) {
    const auto pair = [&](std::size_t x, std::size_t y) {
      return y < edges.size() && edges[x][0] == edges[y][0] && edges[x][1] == edges[y][1];
    };
    if (!pair(i, i + 1) || pair(i, i + 2)) return false;
    const CH c0 = inf_cells[edges[i][2] / 4], c1 = inf_cells[edges[i + 1][2] / 4];
    c0->set_neighbor(int(edges[i][2] % 4), c1);
    c1->set_neighbor(int(edges[i + 1][2] % 4), c0);
  }
  tds.set_dimension(nc == 0 ? -1 : 3);
  // The checks of the TDS's is_valid() that the input can fail, in O(C) and O(C·degree):
  // every vertex in a cell; each facet shared by two cells wound against itself in them;
  // Euler's relation V - E + F - C = 0 with the infinite vertex (F = 2C: the 3-sphere's).
  for (const VH &v : vh)
    if (v->cell() == CH()) return false;
  for (std::size_t i = 0; i + 1 < facets.size(); ++i) {
    if (!same(facets[i], facets[i + 1])) continue;
    const auto &c0 = cells[facets[i][3] / 4], &c1 = cells[facets[i + 1][3] / 4];
    const int j0 = int(facets[i][3] % 4), j1 = int(facets[i + 1][3] % 4);
    // c0 as (its vertex j0, then its others in order) is a permutation of parity j0; c1 as
    // (its vertex j1, then c0's others in c0's order) must have the other parity.
    int at[4], y = 1, inversions = 0;
    at[0] = j1;
    for (int x = 0; x < 4; ++x) {
      if (x == j0) continue;
      int k = 0;
      while (c1[k] != c0[x]) ++k;
      at[y++] = k;
    }
    for (int p = 0; p < 4; ++p)
      for (int q = p + 1; q < 4; ++q) inversions += at[p] > at[q];
    if ((inversions + j0) % 2 == 0) return false;
  }
  std::vector<std::uint32_t> first(points.size() + 1, 0), star(4 * nc);
  for (const auto &t : cells)
    for (int j = 0; j < 4; ++j) ++first[std::size_t(t[j]) + 1];
  for (std::size_t v = 0; v < points.size(); ++v) first[v + 1] += first[v];
  {
    std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
    for (std::size_t k = 0; k < nc; ++k)
      for (int j = 0; j < 4; ++j) star[fill[std::size_t(cells[k][j])]++] = std::uint32_t(k);
  }
  std::vector<bool> on_boundary(points.size(), false);
  for (std::size_t i : open)
    for (int x = 0; x < 3; ++x) on_boundary[facets[i][x]] = true;
  std::size_t edge_count = 0;
  std::vector<int> ends;
  for (std::size_t v = 0; v < points.size(); ++v) {
    ends.clear();
    for (std::uint32_t i = first[v]; i < first[v + 1]; ++i)
      for (int j = 0; j < 4; ++j)
        if (cells[star[i]][j] > int(v)) ends.push_back(cells[star[i]][j]);
    std::sort(ends.begin(), ends.end());
    edge_count += std::size_t(std::unique(ends.begin(), ends.end()) - ends.begin());
    edge_count += on_boundary[v];  // its edge to the infinite vertex
  }
  const std::size_t all_cells = nc + inf_cells.size();
  return points.size() + 1 + all_cells == edge_count;
}

}  // namespace detail

#ifdef TOPOPLEX_HAVE_COMPLEX_TO_C3T3
namespace detail {

/* The one body of complex_to_c3t3 and complex_to_triangulation: the listed tetrahedra (a
 * negatively oriented one with its first two vertices swapped, counted in the return value)
 * into `tr` through build_tds; with `Labels` (a C3T3's triangulation) "c3t3:subdomain" and
 * "c3t3:patch" as its cells' indices, without them every attribute left behind or refused.
 * `what` names the target in refusals; `tr` is left cleared on a refusal. */
template <bool Labels, class Tr>
std::size_t complex_to_tds(const Complex &c, Tr &tr, std::vector<Dropped> *dropped,
                           const std::string &what) {
  using SPI = typename patch_index<typename Tr::Cell>::type;
  using P3 = typename Tr::Geom_traits::Point_3;
  if (c.dimension() != 3) {
    throw Refused(what + " holds a tetrahedral mesh; the complex has dimension " +
                  std::to_string(c.dimension()));
  }
  if (c.coord_dim() != 3) {
    throw Refused(what + " needs 3 coordinates per vertex; the complex has " +
                  std::to_string(c.coord_dim()));
  }
  bool have_sub = false, have_patch = false;
  std::size_t patch_k = 0;
  for (const AttributeInfo &a : c.attributes()) {
    if (Labels && a.name == "c3t3:subdomain" && a.location == Location::Listed &&
        a.type == ValueType::I32 && a.components == 1) {
      have_sub = true;
    } else if (Labels && a.name == "c3t3:patch" && a.location == Location::Listed &&
               a.type == ValueType::I32) {
      have_patch = true;
      patch_k = a.components;
    } else {
      adapt::drop(dropped, a.name,
                  Labels ? "a C3T3 holds the cells' subdomain (\"c3t3:subdomain\", i32) and the "
                           "facets' surface patch (\"c3t3:patch\", i32) only"
                         : "a Triangulation_3 holds no values (complex_to_c3t3 keeps "
                           "\"c3t3:subdomain\" and \"c3t3:patch\")");
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
  std::vector<std::pair<std::array<std::uint32_t, 3>, SPI>> border;  // sorted ids, patch
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
                      std::to_string(i) + ") is flat: " + what + "'s cell must have volume");
      }
      if (o == CGAL::NEGATIVE) {
        std::swap(t[0], t[1]);
        ++swapped;
      }
      cells.push_back(t);
    } else if (n == 3 && have_patch) {
      SPI value;
      if (!patch_from(patch.element(i), patch_k, value)) {
        throw Refused("\"c3t3:patch\" has " + std::to_string(patch_k) +
                      " components; this C3T3's Surface_patch_index takes " +
                      (std::is_integral<SPI>::value ? "1" : "2"));
      }
      std::array<std::uint32_t, 3> f{ids[0], ids[1], ids[2]};
      std::sort(f.begin(), f.end());
      border.emplace_back(f, value);
    }
  });
  if (points.empty() || cells.empty()) {
    throw Refused(what + " needs at least one tetrahedron");
  }
  if (!build_tds(tr, points, cells, border)) {
    tr.clear();
    throw Refused("CGAL's triangulation cannot hold the tetrahedra: they must fill a ball, each "
                  "triangle in at most two of them, every vertex in one (c3t3_to_complex(c3t3, "
                  "true) gives such a complex)");
  }
  return swapped;
}

}  // namespace detail

/* Fills `out` (cleared first) with the complex's tetrahedra and labels (header comment).
 * Returns the number of tetrahedra given to CGAL with their first two vertices swapped. */
template <class C3T3>
std::size_t complex_to_c3t3(const Complex &c, C3T3 &out, std::vector<Dropped> *dropped = nullptr) {
  out.clear();
  std::size_t swapped = 0;
  try {
    swapped = detail::complex_to_tds<true>(c, out.triangulation(), dropped, "a C3T3");
  } catch (...) {
    out.clear();
    throw;
  }
  out.rescan_after_load_of_triangulation();
  return swapped;
}

/* Fills the plain Triangulation_3 `out` (any vertex and cell base without Mesh_3's indices;
 * cleared first) with the complex's listed tetrahedra, built as complex_to_c3t3 builds a C3T3's
 * (header comment): vertex i is the i-th finite vertex and the finite cells come in listing order
 * (triangulation_to_complex(out) gives the complex back), a negatively oriented tetrahedron with
 * its first two vertices swapped (counted in the return value). Refused as complex_to_c3t3, and
 * every attribute unless left behind into `dropped` (a Triangulation_3 holds no values). The
 * cells are not made Delaunay: `out` holds the complex's own tetrahedra, so Delaunay-specific
 * calls (insert, is_valid's empty-sphere test) assume what the complex gives. Cost as
 * complex_to_c3t3. */
template <class Tr>
std::size_t complex_to_triangulation(const Complex &c, Tr &out, std::vector<Dropped> *dropped = nullptr) {
  static_assert(!detail::has_mesh_indices<typename Tr::Cell>::value,
                "a Mesh_3 triangulation: use complex_to_c3t3, which sets its cells' indices");
  out.clear();
  return detail::complex_to_tds<false>(c, out, dropped, "a Triangulation_3");
}
#endif

}  // namespace cgal
}  // namespace topoplex

#endif /* TOPOPLEX_CGAL_TDS3_HPP */
