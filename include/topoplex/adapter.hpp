/*
 * Topoplex C++ adapters: what every peer adapter shares (no peer library needed).
 *
 * The adapters (topoplex/openmesh.hpp, topoplex/cgal.hpp, topoplex/cgal_tds3.hpp,
 * topoplex/gudhi.hpp) copy a peer's mesh into a topoplex::Complex and back, in memory, array
 * by array (one pass, storage reserved first). Each includes this header; include one only in
 * code that has its peer. docs/adapters.md lists what each keeps, costs and refuses.
 *
 *  - Refused: input a peer cannot hold (a wire edge for a half-edge mesh, a triangle a
 *    half-edge mesh rejects, a polygon for Topoplex) throws topoplex::Refused (a topoplex::Error
 *    with status TPX_STATUS_UNSUPPORTED_COMPLEX) naming the first offending element; nothing is
 *    returned half built.
 *  - Data: a property or attribute the other side cannot hold (a type or a place it has no
 *    counterpart for) is refused the same way unless the caller passes a `std::vector<Dropped>*`,
 *    which then receives one entry per thing left behind (name and reason): never a silent loss.
 */
#ifndef TOPOPLEX_ADAPTER_HPP
#define TOPOPLEX_ADAPTER_HPP

#include "../topoplex.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace topoplex {

/* What a peer cannot hold: thrown by the adapters, never a partial result. */
class Refused : public Error {
 public:
  explicit Refused(const std::string &message)
      : Error(TPX_STATUS_UNSUPPORTED_COMPLEX, message) {}
};

/* Something an adapter left behind at the caller's request (see the header comment). */
struct Dropped {
  std::string name; /* the property's or attribute's name ("" for a part of the mesh) */
  std::string why;
};

namespace adapt {

/* Leaves `name` behind: recorded in *dropped when the caller gave one, else refused. */
inline void drop(std::vector<Dropped> *dropped, const std::string &name, const std::string &why) {
  if (dropped == nullptr) {
    throw Refused("'" + name + "': " + why +
                  " (pass a std::vector<topoplex::Dropped>* to leave it behind)");
  }
  dropped->push_back(Dropped{name, why});
}

inline std::string ids_text(const std::uint32_t *ids, std::size_t n) {
  std::string s = "{";
  for (std::size_t i = 0; i < n; ++i) s += (i ? ", " : "") + std::to_string(ids[i]);
  return s + "}";
}

/* Calls f(i, ids, n, top) for every listed simplex of `c` in input order (ids as given, with
 * their winding; top: its top id, or UINT32_MAX when absorbed as a face of another listing).
 * One C call per listing into one reused buffer: O(listing), no allocation per simplex. */
template <class F>
void for_each_listed(const Complex &c, F &&f) {
  const std::size_t n = c.input_stats().input_simplices;
  std::uint32_t buf[16];
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t len = 0;
    std::uint32_t top = 0;
    detail::check(tpx_complex_input_simplex(c.get(), i, buf, 16, &len, &top));
    f(i, static_cast<const std::uint32_t *>(buf), len, top);
  }
}

/* The by-value form of an adapter that fills a caller's object: an `M` default-built, filled
 * by `fill`, returned. */
template <class M, class Fill>
M filled(Fill &&fill) {
  M m;
  fill(m);
  return m;
}

/* Calls f(view) with the attribute's AttributeView of its stored type. */
template <class F>
void with_values(const Complex &c, const AttributeInfo &a, F &&f) {
  switch (a.type) {
    case ValueType::I32: f(c.attribute<std::int32_t>(a.name, a.location)); break;
    case ValueType::I64: f(c.attribute<std::int64_t>(a.name, a.location)); break;
    case ValueType::F32: f(c.attribute<float>(a.name, a.location)); break;
    case ValueType::F64: f(c.attribute<double>(a.name, a.location)); break;
  }
}

/* Coordinates of `c` as 3 per vertex (0 to 3 given ones padded with zeros): refused above 3. */
inline std::vector<double> xyz3(const Complex &c, const char *peer) {
  const std::size_t dim = c.coord_dim();
  if (dim > 3) {
    throw Refused(std::string(peer) + " holds 3 coordinates per vertex; the complex has " +
                  std::to_string(dim));
  }
  if (dim == 3) return c.coords();
  const std::vector<double> given = c.coords();
  std::vector<double> out(3 * std::size_t(c.vertex_count()), 0.0);
  for (std::size_t v = 0; v < c.vertex_count(); ++v)
    for (std::size_t k = 0; k < dim; ++k) out[3 * v + k] = given[dim * v + k];
  return out;
}

/* The triangles of a complex of dimension <= 2, as a half-edge mesh is built from them: every
 * listed triangle in input order with its winding (a repeated listing once), the listing each
 * came from, and how many listings are no face of their own (edges and vertices listed beside
 * their triangles, repeats): their listed values have no face to go to. Refused: dimension above
 * 2, a wire edge (an edge in no triangle). O(listing). */
struct SurfaceListing {
  std::vector<std::uint32_t> triangles; /* 3 ids per face, as listed */
  std::vector<std::size_t> listing;     /* listing index of each face */
  std::size_t other_listings = 0;
};

inline SurfaceListing surface_listing(const Complex &c, const char *peer) {
  if (c.dimension() > 2) {
    throw Refused(std::string(peer) + " holds triangles; the complex has dimension " +
                  std::to_string(c.dimension()));
  }
  SurfaceListing out;
  const std::size_t n_tri = c.dimension() == 2 ? c.top_count(2) : 0;
  out.triangles.reserve(3 * n_tri);
  out.listing.reserve(n_tri);
  std::vector<bool> seen;
  for_each_listed(c, [&](std::size_t i, const std::uint32_t *ids, std::size_t n, std::uint32_t top) {
    if (n == 3) {
      if (top >= seen.size()) seen.resize(std::size_t(top) + 1, false);
      if (seen[top]) {
        ++out.other_listings;
        return;
      }
      seen[top] = true;
      out.triangles.insert(out.triangles.end(), ids, ids + 3);
      out.listing.push_back(i);
    } else if (n == 2 && top != UINT32_MAX) {
      throw Refused(std::string(peer) + " cannot hold the wire edge " + ids_text(ids, n) +
                    " (listed simplex " + std::to_string(i) +
                    "): a half-edge mesh has no edge outside a face; split the complex with "
                    "topoplex/manifold_parts.hpp");
    } else {
      ++out.other_listings;  // a face of a listed triangle, or a listed vertex
    }
  });
  return out;
}

/* The arrays of a peer mesh's complex (3 coordinates per vertex), built face after face with
 * storage reserved first: push a face's vertex ids onto `ids`, then end_face. */
struct TriangleArrays {
  std::vector<std::uint32_t> ids;
  std::vector<std::size_t> offsets;
  std::vector<double> xyz;

  TriangleArrays(std::size_t nv, std::size_t nf) {
    ids.reserve(3 * nf);
    offsets.reserve(nf + 1);
    offsets.push_back(0);
    xyz.reserve(3 * nv);
  }
  /* Ends the face whose ids were pushed since the last; refused unless it has 3 vertices,
   * named as `element` and its number ("OpenMesh face", 7). */
  void end_face(const char *element, std::size_t number) {
    const std::size_t n = ids.size() - offsets.back();
    if (n != 3) {
      throw Refused(std::string(element) + " " + std::to_string(number) + " has " +
                    std::to_string(n) +
                    " vertices: Topoplex holds simplices (triangulate the mesh first)");
    }
    offsets.push_back(ids.size());
  }
  Complex complex() const {
    return Complex::from_arrays(std::uint32_t(xyz.size() / 3), ids, offsets, xyz, 3);
  }
};

/* Adds the faces of `tris` (3 ids per face over vertex indices 0..) to a half-edge mesh of
 * `peer` through add(m, ids), false when the mesh rejects the face; then m is cleared and the
 * triangle refused, named by what(f). */
template <class Mesh, class Add, class What>
void add_triangles(Mesh &m, const char *peer, const std::vector<std::uint32_t> &tris, Add &&add,
                   What &&what) {
  for (std::size_t f = 0; 3 * f < tris.size(); ++f) {
    if (!add(m, &tris[3 * f])) {
      m.clear();
      throw Refused(std::string(peer) + " refused triangle " + ids_text(&tris[3 * f], 3) + " (" +
                    what(f) +
                    "): an edge in a third triangle, a vertex whose fan is already closed, or a "
                    "winding opposite to a neighbour's; topoplex/manifold_parts.hpp splits a "
                    "complex into parts a half-edge mesh holds");
    }
  }
}

/* Hands every attribute of `c` to a surface mesh built from `s`: copy(a, on_vertices) copies
 * it and says whether the mesh holds it; one it does not is left behind (reason `unheld`), and
 * so are the values of listings that are no face of the mesh. */
template <class Copy>
void attributes_to_mesh(const Complex &c, const SurfaceListing &s, const char *unheld,
                        std::vector<Dropped> *dropped, Copy &&copy) {
  for (const AttributeInfo &a : c.attributes()) {
    const bool vertices = a.location == Location::Vertices;
    if (!copy(a, vertices)) {
      drop(dropped, a.name, unheld);
    } else if (!vertices && s.other_listings != 0) {
      drop(dropped, a.name,
           "its values on " + std::to_string(s.other_listings) +
               " listed simplices that are no face of the mesh (edges or vertices listed "
               "beside their triangles, repeated listings)");
    }
  }
}

}  // namespace adapt
}  // namespace topoplex

#endif /* TOPOPLEX_ADAPTER_HPP */
