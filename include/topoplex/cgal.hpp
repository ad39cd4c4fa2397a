/*
 * Topoplex <-> CGAL Surface_mesh and Polyhedron_3, in memory. Include only where CGAL is found
 * (find_package(CGAL), link CGAL::CGAL). Tetrahedral meshes: cgal_tds3.hpp.
 *
 *   CGAL::Surface_mesh<K::Point_3> sm = ...;
 *   topoplex::Complex c = topoplex::cgal::to_complex(sm);            // vertices, faces, maps
 *   auto sm2 = topoplex::cgal::to_surface_mesh<CGAL::Surface_mesh<K::Point_3>>(c);
 *   CGAL::Polyhedron_3<K> P = topoplex::cgal::to_polyhedron<CGAL::Polyhedron_3<K>>(c);
 *
 * Kept: vertex i is the i-th vertex of the mesh's vertex range; listed simplex f is the f-th
 * face, its vertices as the halfedges around the face run from halfedge(f) (both CGAL meshes
 * keep the order they were given, so each direction gives the other's order and winding back);
 * coordinates through CGAL::to_double (bit for bit with an inexact double kernel such as Epick;
 * an exact kernel gives its double approximation). Surface_mesh property maps <-> attributes,
 * names kept: vertex maps <-> Location::Vertices, face maps <-> Location::Listed, for the value
 * types std::int32_t, std::int64_t, float, double and the kernel's Vector_3 (3 reals; on the
 * way back 3 reals become a Vector_3 map). Its own maps ("v:point", "v:connectivity",
 * "*:removed", ...) are not data. Polyhedron_3 has no named maps: geometry and connectivity only
 * (a complex's attributes are refused for it unless left behind into a Dropped list).
 *
 * Refused (topoplex::Refused): a face of more than 3 vertices; a Surface_mesh with removed
 * elements not yet collected (collect_garbage()); a complex of dimension > 2, with a wire edge
 * or more than 3 coordinates; a triangle the mesh rejects (Surface_mesh::add_face returning
 * null_face(), Polyhedron_incremental_builder_3::test_facet false: an edge in a third triangle,
 * a vertex whose fan is already closed, a winding opposite to a neighbour's), named in the
 * exception; the output is cleared then. A vertex joining several open fans (a bowtie) is
 * accepted where the mesh accepts it (Surface_mesh does: a non-manifold vertex its algorithms
 * may not expect; SurfaceParts splits it). Left behind only into a caller's `std::vector<Dropped>*`, refused
 * otherwise: a map of another value type, an edge or halfedge map, listed values on listings
 * that are no face. Label names are not carried.
 *
 * Cost: one pass over the vertices and one over the faces each way, arrays reserved first,
 * O(V + F) time, plus O(V + F) per carried map; Polyhedron_3 to a complex: one hash map of its
 * vertex handles (O(V) memory). For non-manifold complexes see manifold_parts.hpp and
 * part_to_surface_mesh below.
 */
#ifndef TOPOPLEX_CGAL_HPP
#define TOPOPLEX_CGAL_HPP

#include "adapter.hpp"
#include "manifold_parts.hpp"

#include <CGAL/Handle_hash_function.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/Modifier_base.h>
#include <CGAL/Polyhedron_incremental_builder_3.h>
#include <CGAL/boost/graph/iterator.h>

#include <cstdint>
#include <string>
#include <typeinfo>
#include <unordered_map>
#include <vector>

namespace topoplex {
namespace cgal {
namespace detail {

inline bool internal_map(const std::string &n) {
  return n == "v:point" || n == "v:connectivity" || n == "v:removed" || n == "f:connectivity" ||
         n == "f:removed" || n == "h:connectivity" || n == "e:removed";
}

template <class SM>
using Vector_3 = typename CGAL::Kernel_traits<typename SM::Point>::Kernel::Vector_3;

template <class SM, class I, class T, class Range>
bool map_to_attribute(Complex &c, SM &m, const std::string &name, const Range &range,
                      Location loc) {
  if (m.template property_type<I>(name) != typeid(T)) return false;
  auto pm = m.template property_map<I, T>(name).first;
  if constexpr (std::is_arithmetic<T>::value) {
    std::vector<T> flat;
    flat.reserve(range.size());
    for (I i : range) flat.push_back(pm[i]);
    c.set_attribute<T>(name, loc, 1, flat);
  } else {
    std::vector<double> flat;
    flat.reserve(3 * range.size());
    for (I i : range)
      for (int k = 0; k < 3; ++k) flat.push_back(CGAL::to_double(pm[i][k]));
    c.set_attribute<double>(name, loc, 3, flat);
  }
  return true;
}

template <class SM, class I, class Range>
void maps_to_attributes(Complex &c, SM &m, const Range &range, Location loc, const char *where,
                        std::vector<Dropped> *dropped) {
  for (const std::string &name : m.template properties<I>()) {
    if (internal_map(name)) continue;
    const bool ok = map_to_attribute<SM, I, std::int32_t>(c, m, name, range, loc) ||
                    map_to_attribute<SM, I, std::int64_t>(c, m, name, range, loc) ||
                    map_to_attribute<SM, I, float>(c, m, name, range, loc) ||
                    map_to_attribute<SM, I, double>(c, m, name, range, loc) ||
                    map_to_attribute<SM, I, Vector_3<SM>>(c, m, name, range, loc);
    if (!ok) {
      adapt::drop(dropped, name,
                  std::string("Surface_mesh ") + where +
                      " map of a value type Topoplex attributes do not hold (int32_t, int64_t, "
                      "float, double, Vector_3)");
    }
  }
}

template <class SM, class I>
void refuse_maps(SM &m, const char *where, std::vector<Dropped> *dropped) {
  for (const std::string &name : m.template properties<I>()) {
    if (internal_map(name)) continue;
    adapt::drop(dropped, name,
                std::string("Surface_mesh ") + where +
                    " map: Topoplex attributes are on vertices and listed simplices");
  }
}

template <class SM, class I, class X, class T>
bool fill_map(SM &m, const std::string &name, const AttributeView<T> &v,
              const std::vector<std::size_t> *index, std::size_t n) {
  auto added = m.template add_property_map<I, X>(name, X());
  if (!added.second && m.template property_type<I>(name) != typeid(X)) return false;
  auto pm = added.first;
  for (std::size_t e = 0; e < n; ++e) {
    const T *x = v.element(index ? (*index)[e] : e);
    if constexpr (std::is_arithmetic<X>::value) {
      pm[I(typename I::size_type(e))] = x[0];
    } else {
      pm[I(typename I::size_type(e))] = X(x[0], x[1], x[2]);
    }
  }
  return true;
}

/* Adds the faces of `tris` (3 ids per face over vertex indices 0..) to m; on a rejected face,
 * clears m and throws naming it. */
template <class SM, class What>
void add_faces(SM &m, const std::vector<std::uint32_t> &tris, What what) {
  using V = typename SM::Vertex_index;
  adapt::add_triangles(
      m, "Surface_mesh", tris,
      [](SM &mesh, const std::uint32_t *t) {
        return mesh.add_face(V(t[0]), V(t[1]), V(t[2])) != SM::null_face();
      },
      what);
}

template <class HDS>
class PolyhedronBuilder : public CGAL::Modifier_base<HDS> {
 public:
  PolyhedronBuilder(const std::vector<double> &xyz, const adapt::SurfaceListing &s)
      : xyz_(xyz), s_(s) {}
  void operator()(HDS &hds) override {
    using Point = typename HDS::Vertex::Point;
    CGAL::Polyhedron_incremental_builder_3<HDS> b(hds, false);
    const std::size_t nv = xyz_.size() / 3, nf = s_.listing.size();
    b.begin_surface(nv, nf, 3 * nf);
    for (std::size_t v = 0; v < nv; ++v)
      b.add_vertex(Point(xyz_[3 * v], xyz_[3 * v + 1], xyz_[3 * v + 2]));
    std::vector<std::size_t> f3(3);
    for (std::size_t f = 0; f < nf; ++f) {
      for (int k = 0; k < 3; ++k) f3[k] = s_.triangles[3 * f + k];
      if (!b.test_facet(f3.begin(), f3.end())) {
        refused = f;
        b.rollback();  // ends the surface, the polyhedron as before
        return;
      }
      b.add_facet(f3.begin(), f3.end());
    }
    b.end_surface();
  }
  std::size_t refused = SIZE_MAX;

 private:
  const std::vector<double> &xyz_;
  const adapt::SurfaceListing &s_;
};

}  // namespace detail

/* ---- Surface_mesh ---- */

/* The complex of a Surface_mesh (triangles; isolated vertices kept), with its vertex and face
 * property maps as attributes. See the header comment for what is refused. */
template <class P>
Complex to_complex(const CGAL::Surface_mesh<P> &mesh, std::vector<Dropped> *dropped = nullptr) {
  using SM = CGAL::Surface_mesh<P>;
  // Reading a map by name is a non-const member of Surface_mesh; nothing here writes.
  SM &m = const_cast<SM &>(mesh);
  if (m.has_garbage()) {
    throw Refused("the Surface_mesh has removed elements: call collect_garbage() first");
  }
  adapt::TriangleArrays t(m.number_of_vertices(), m.number_of_faces());
  for (auto f : m.faces()) {
    for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) t.ids.push_back(std::uint32_t(v));
    t.end_face("Surface_mesh face", std::size_t(f));
  }
  for (auto v : m.vertices()) {
    const P &p = m.point(v);
    t.xyz.insert(t.xyz.end(),
                 {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
  }
  Complex c = t.complex();
  detail::maps_to_attributes<SM, typename SM::Vertex_index>(c, m, m.vertices(),
                                                            Location::Vertices, "vertex", dropped);
  detail::maps_to_attributes<SM, typename SM::Face_index>(c, m, m.faces(), Location::Listed,
                                                          "face", dropped);
  detail::refuse_maps<SM, typename SM::Edge_index>(m, "edge", dropped);
  detail::refuse_maps<SM, typename SM::Halfedge_index>(m, "halfedge", dropped);
  return c;
}

/* Fills `m` (cleared first) with the complex: vertex i, face f = the f-th listed triangle (a
 * repeated listing once), attributes as property maps. See the header comment for refusals. */
template <class P>
void to_surface_mesh(const Complex &c, CGAL::Surface_mesh<P> &m,
                     std::vector<Dropped> *dropped = nullptr) {
  using SM = CGAL::Surface_mesh<P>;
  const adapt::SurfaceListing s = adapt::surface_listing(c, "Surface_mesh");
  const std::vector<double> xyz = adapt::xyz3(c, "Surface_mesh");
  const std::size_t nv = c.vertex_count(), nf = s.listing.size();
  m.clear();
  m.reserve(typename SM::size_type(nv), typename SM::size_type(nv + nf + 2),
            typename SM::size_type(nf));
  for (std::size_t v = 0; v < nv; ++v) m.add_vertex(P(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]));
  detail::add_faces(m, s.triangles,
                    [&](std::size_t f) { return "listed simplex " + std::to_string(s.listing[f]); });
  using VI = typename SM::Vertex_index;
  using FI = typename SM::Face_index;
  adapt::attributes_to_mesh(
      c, s,
      "no Surface_mesh map holds it (1 number or 3 reals per element; a map of that name and "
      "another type exists)",
      dropped, [&](const AttributeInfo &a, bool vertices) {
        bool ok = false;
        adapt::with_values(c, a, [&](const auto &view) {
          using T = typename std::decay<decltype(view[0])>::type;
          const std::vector<std::size_t> *index = vertices ? nullptr : &s.listing;
          const std::size_t n = vertices ? nv : nf;
          if (a.components == 1) {
            ok = vertices ? detail::fill_map<SM, VI, T>(m, a.name, view, index, n)
                          : detail::fill_map<SM, FI, T>(m, a.name, view, index, n);
          } else if (a.components == 3 && std::is_floating_point<T>::value) {
            using V3 = detail::Vector_3<SM>;
            ok = vertices ? detail::fill_map<SM, VI, V3>(m, a.name, view, index, n)
                          : detail::fill_map<SM, FI, V3>(m, a.name, view, index, n);
          }
        });
        return ok;
      });
}

template <class SM>
SM to_surface_mesh(const Complex &c, std::vector<Dropped> *dropped = nullptr) {
  return adapt::filled<SM>([&](SM &m) { to_surface_mesh(c, m, dropped); });
}

/* Part `p` (manifold_parts.hpp) as a Surface_mesh: local vertex i at its original vertex's
 * coordinates (`xyz`: 3 per original vertex), face f the part's face f. O(part). */
template <class P>
void part_to_surface_mesh(const SurfacePart &p, const std::vector<double> &xyz,
                          CGAL::Surface_mesh<P> &m) {
  using SM = CGAL::Surface_mesh<P>;
  if (!p.problem.empty()) throw Refused("Surface_mesh cannot hold it: " + p.problem);
  m.clear();
  m.reserve(typename SM::size_type(p.vertex_count()),
            typename SM::size_type(p.vertex_count() + p.face_count() + 2),
            typename SM::size_type(p.face_count()));
  for (std::uint32_t o : p.original_vertex) m.add_vertex(P(xyz[3 * o], xyz[3 * o + 1], xyz[3 * o + 2]));
  detail::add_faces(m, p.triangles, [&](std::size_t f) { return p.face_name(f); });
}

template <class SM>
SM part_to_surface_mesh(const SurfacePart &p, const std::vector<double> &xyz) {
  return adapt::filled<SM>([&](SM &m) { part_to_surface_mesh(p, xyz, m); });
}

/* The vertex coordinates, 3 per vertex of the vertex range (for SurfaceParts::gather_coords). */
template <class P>
std::vector<double> coordinates(const CGAL::Surface_mesh<P> &m) {
  std::vector<double> out;
  out.reserve(3 * m.number_of_vertices());
  for (auto v : m.vertices()) {
    const P &p = m.point(v);
    out.insert(out.end(), {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
  }
  return out;
}

/* ---- Polyhedron_3 ---- */

/* The complex of a Polyhedron_3 (vertices and facets in iteration order). */
template <class Poly>
Complex polyhedron_to_complex(const Poly &poly) {
  using VH = typename Poly::Vertex_const_handle;
  const std::size_t nv = poly.size_of_vertices(), nf = poly.size_of_facets();
  std::unordered_map<VH, std::uint32_t, CGAL::Handle_hash_function> id;
  id.reserve(nv);
  adapt::TriangleArrays t(nv, nf);
  std::uint32_t next = 0;
  for (auto v = poly.vertices_begin(); v != poly.vertices_end(); ++v) {
    id.emplace(VH(v), next++);
    const auto &p = v->point();
    t.xyz.insert(t.xyz.end(),
                 {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
  }
  std::size_t f_no = 0;
  for (auto f = poly.facets_begin(); f != poly.facets_end(); ++f, ++f_no) {
    auto h = f->facet_begin();
    do {
      t.ids.push_back(id.at(VH(h->vertex())));
    } while (++h != f->facet_begin());
    t.end_face("Polyhedron_3 facet", f_no);
  }
  return t.complex();
}

/* Fills `poly` (cleared first) with the complex through Polyhedron_incremental_builder_3:
 * vertex i, facet f = the f-th listed triangle. The complex's attributes have no place in a
 * Polyhedron_3: refused unless left behind into `dropped`. */
template <class Poly>
void to_polyhedron(const Complex &c, Poly &poly, std::vector<Dropped> *dropped = nullptr) {
  const adapt::SurfaceListing s = adapt::surface_listing(c, "Polyhedron_3");
  const std::vector<double> xyz = adapt::xyz3(c, "Polyhedron_3");
  for (const AttributeInfo &a : c.attributes())
    adapt::drop(dropped, a.name, "Polyhedron_3 has no named property maps");
  poly.clear();
  detail::PolyhedronBuilder<typename Poly::HalfedgeDS> b(xyz, s);
  poly.delegate(b);
  if (b.refused != SIZE_MAX) {
    poly.clear();
    throw Refused("Polyhedron_3 refused triangle " +
                  adapt::ids_text(&s.triangles[3 * b.refused], 3) + " (listed simplex " +
                  std::to_string(s.listing[b.refused]) +
                  "): an edge in a third triangle, a vertex whose fan is already closed, or a "
                  "winding opposite to a neighbour's; topoplex/manifold_parts.hpp splits a complex into "
                  "parts a half-edge mesh holds");
  }
}

template <class Poly>
Poly to_polyhedron(const Complex &c, std::vector<Dropped> *dropped = nullptr) {
  return adapt::filled<Poly>([&](Poly &p) { to_polyhedron(c, p, dropped); });
}

}  // namespace cgal
}  // namespace topoplex

#endif /* TOPOPLEX_CGAL_HPP */
