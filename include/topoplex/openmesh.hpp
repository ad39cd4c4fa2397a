/*
 * Topoplex <-> OpenMesh (TriMesh_ArrayKernelT, PolyMesh_ArrayKernelT, any traits), in memory.
 * Include only where OpenMesh is found (find_package(OpenMesh), link OpenMeshCore).
 *
 *   OpenMesh::TriMesh_ArrayKernelT<> m = ...;
 *   topoplex::Complex c = topoplex::openmesh::to_complex(m);          // vertices, faces, props
 *   auto m2 = topoplex::openmesh::to_openmesh<OpenMesh::TriMesh_ArrayKernelT<>>(c);
 *
 * Kept: vertex i is OpenMesh vertex i; listed simplex f is face f with the vertices its
 * circulator gives from the face's halfedge (OpenMesh keeps the order add_face was given, so
 * each direction gives the other's order and winding back); coordinates as the mesh's Point
 * scalars (double points: bit for bit; float points: a double is rounded to float on the way in).
 * Properties <-> attributes, names kept: vertex properties <-> Location::Vertices, face
 * properties <-> Location::Listed; types int (i32), int64_t (i64), float (f32), double (f64),
 * and OpenMesh::VectorT<float|double, 2..4> (2 to 4 components), the standard "v:normals" and
 * "f:normals" included (requested on the way back). Internal properties ("v:points", status
 * bits, the "<vprop>"-style connectivity) are not data and are not copied.
 *
 * Refused (topoplex::Refused): a polygon of more than 3 vertices; deleted elements not yet
 * garbage-collected; a complex of dimension > 2, with a wire edge, or more than 3 coordinates;
 * a triangle OpenMesh's add_face rejects (an edge in a third triangle, a vertex whose fan is
 * already closed, a winding opposite to a neighbour's): the exception names it, and the mesh is
 * cleared. A vertex joining several open fans (a bowtie) is accepted, as OpenMesh accepts it:
 * a non-manifold vertex its algorithms may not expect; SurfaceParts splits it. Left behind only into a caller's `std::vector<Dropped>*`, refused otherwise: a
 * property of another type, an edge, halfedge or mesh property, listed values on listings that
 * are no face (edges listed beside their triangles, repeats). Label names are not carried.
 *
 * Towards OpenMesh, a mesh whose every vertex is plain (one fan of triangles, closed or with one
 * boundary edge in and one out; each directed edge in one triangle) is written straight into the
 * mesh's arrays (detail::build_plain: the same edges, halfedges and links add_face, called
 * triangle by triangle, makes); any other goes through add_face, with its acceptances and
 * refusals.
 *
 * Cost: one pass over the vertices and one over the faces each way, arrays reserved first
 * (O(V + F) time; the complex's arrays plus one copy of the ids and coordinates while building,
 * and towards OpenMesh 5 ids per face corner and 4 per vertex of scratch), plus O(V + F) per
 * carried property. For non-manifold complexes see manifold_parts.hpp and
 * part_to_openmesh below.
 */
#ifndef TOPOPLEX_OPENMESH_HPP
#define TOPOPLEX_OPENMESH_HPP

#include "adapter.hpp"
#include "manifold_parts.hpp"

#include <OpenMesh/Core/Geometry/VectorT.hh>
#include <OpenMesh/Core/Utils/Property.hh>

#include <cstdint>
#include <string>
#include <vector>

namespace topoplex {
namespace openmesh {
namespace detail {

inline bool internal_property(const std::string &n) {
  return n.empty() || n.front() == '<' || n == "v:points" ||
         (n.size() > 7 && n.compare(n.size() - 7, 7, ":status") == 0);
}

/* Copies property `p` (n elements) into attribute p->name() when it holds T (one of the four
 * scalars) or VectorT<S, N>; false when it holds another type. */
template <class T>
bool scalar_to_attribute(Complex &c, const OpenMesh::BaseProperty *p, Location loc) {
  auto *q = dynamic_cast<const OpenMesh::PropertyT<T> *>(p);
  if (q == nullptr) return false;
  const auto &d = q->data_vector();
  c.set_attribute<T>(p->name(), loc, 1, d.data(), d.size());
  return true;
}

template <class S, int N>
bool vector_to_attribute(Complex &c, const OpenMesh::BaseProperty *p, Location loc) {
  auto *q = dynamic_cast<const OpenMesh::PropertyT<OpenMesh::VectorT<S, N>> *>(p);
  if (q == nullptr) return false;
  const auto &d = q->data_vector();
  std::vector<S> flat;
  flat.reserve(d.size() * N);
  for (const auto &x : d)
    for (int k = 0; k < N; ++k) flat.push_back(x[k]);
  c.set_attribute<S>(p->name(), loc, N, flat);
  return true;
}

inline bool property_to_attribute(Complex &c, const OpenMesh::BaseProperty *p, Location loc) {
  return scalar_to_attribute<std::int32_t>(c, p, loc) ||
         scalar_to_attribute<std::int64_t>(c, p, loc) || scalar_to_attribute<float>(c, p, loc) ||
         scalar_to_attribute<double>(c, p, loc) || vector_to_attribute<float, 2>(c, p, loc) ||
         vector_to_attribute<float, 3>(c, p, loc) || vector_to_attribute<float, 4>(c, p, loc) ||
         vector_to_attribute<double, 2>(c, p, loc) || vector_to_attribute<double, 3>(c, p, loc) ||
         vector_to_attribute<double, 4>(c, p, loc);
}

template <class It>
void properties_to_attributes(Complex &c, It first, It last, Location loc, const char *where,
                              std::vector<Dropped> *dropped) {
  for (; first != last; ++first) {
    const OpenMesh::BaseProperty *p = *first;
    if (p == nullptr || internal_property(p->name())) continue;
    if (!property_to_attribute(c, p, loc)) {
      adapt::drop(dropped, p->name(),
                  std::string("OpenMesh ") + where +
                      " property of a type Topoplex attributes do not hold (int, int64_t, float, "
                      "double, VectorT<float|double, 2..4>)");
    }
  }
}

template <class It>
void refuse_properties(It first, It last, const char *where, std::vector<Dropped> *dropped) {
  for (; first != last; ++first) {
    const OpenMesh::BaseProperty *p = *first;
    if (p == nullptr || internal_property(p->name())) continue;
    adapt::drop(dropped, p->name(),
                std::string("OpenMesh ") + where +
                    " property: Topoplex attributes are on vertices and listed simplices");
  }
}

/* Has the mesh a property called `name` (of any type) at the elements of `Handle`? */
template <class Mesh, class Handle>
bool has_named(const Mesh &m, const std::string &name) {
  if constexpr (std::is_same<Handle, OpenMesh::VertexHandle>::value) {
    for (auto it = m.vprops_begin(); it != m.vprops_end(); ++it)
      if (*it && (*it)->name() == name) return true;
  } else {
    for (auto it = m.fprops_begin(); it != m.fprops_end(); ++it)
      if (*it && (*it)->name() == name) return true;
  }
  return false;
}

/* Writes `values` (element e of the property = element index[e] of the view, or e when index is
 * null) into the property `name` of type X at the elements of Handle, adding it when absent. */
template <class X, class Mesh, class Handle, class T>
bool fill_property(Mesh &m, const std::string &name, const AttributeView<T> &values,
                   const std::vector<std::size_t> *index, std::size_t n, Handle) {
  using PH = typename std::conditional<std::is_same<Handle, OpenMesh::VertexHandle>::value,
                                       OpenMesh::VPropHandleT<X>, OpenMesh::FPropHandleT<X>>::type;
  PH ph;
  if (!m.get_property_handle(ph, name)) {
    if (has_named<Mesh, Handle>(m, name)) return false;  // held with another type
    m.add_property(ph, name);
  }
  auto &d = m.property(ph).data_vector();
  const std::size_t k = values.components();
  for (std::size_t e = 0; e < n; ++e) {
    const T *x = values.element(index ? (*index)[e] : e);
    if constexpr (std::is_arithmetic<X>::value) {
      d[e] = x[0];
    } else {
      for (std::size_t j = 0; j < k; ++j) d[e][int(j)] = x[j];
    }
  }
  return true;
}

template <class Mesh, class Handle, class T>
bool attribute_to_property(Mesh &m, const std::string &name, const AttributeView<T> &v,
                           const std::vector<std::size_t> *index, std::size_t n, Handle h) {
  const std::size_t k = v.components();
  if (k == 1) return fill_property<T>(m, name, v, index, n, h);
  if constexpr (std::is_floating_point<T>::value) {
    if (k == 2) return fill_property<OpenMesh::VectorT<T, 2>>(m, name, v, index, n, h);
    if (k == 3) return fill_property<OpenMesh::VectorT<T, 3>>(m, name, v, index, n, h);
    if (k == 4) return fill_property<OpenMesh::VectorT<T, 4>>(m, name, v, index, n, h);
  }
  return false;
}

/* Adds the faces of `tris` (3 ids per face over vertex handles 0..) to m through add_face, one
 * by one; on a rejected face, clears m and throws naming it (`what(f)` describes it). */
template <class Mesh, class What>
void add_faces_one_by_one(Mesh &m, const std::vector<std::uint32_t> &tris, What what) {
  std::vector<typename Mesh::VertexHandle> fv(3);
  adapt::add_triangles(
      m, "OpenMesh", tris,
      [&fv](Mesh &mesh, const std::uint32_t *t) {
        for (int k = 0; k < 3; ++k) fv[k] = typename Mesh::VertexHandle(int(t[k]));
        return mesh.add_face(fv).is_valid();
      },
      what);
}

/* Writes the half-edge connectivity of `tris` (3 ids per face over the nv vertices m holds, and
 * nothing else yet) straight into m's arrays through ArrayKernel's public resize and setters,
 * exactly as OpenMesh's add_face, face after face, would leave it: face f is triangle f with its
 * halfedge from its third vertex to its first (so the face circulator gives the listed order);
 * edge e is the e-th edge met in face order, its halfedge 0 in the direction of the face that
 * met it first; a boundary halfedge's next is the boundary halfedge leaving its target vertex; a
 * boundary vertex's halfedge is its outgoing boundary halfedge (an interior vertex's: its first
 * face's outgoing halfedge, where add_face may leave another outgoing one).
 * Done only when every vertex is plain, which add_face takes without a question: triangles of
 * three distinct vertices, each directed edge in one triangle, each vertex's triangles one fan
 * (closed, or open with one boundary edge in and one out). Else false, m untouched, and the
 * caller adds the faces one by one (add_face accepts a bowtie and refuses what it refuses).
 * O(V + F) time (and the squared degree at each vertex), 5 ids per face halfedge and 4 per
 * vertex of scratch, no allocation per face. */
template <class Mesh>
bool build_plain(Mesh &m, const std::vector<std::uint32_t> &tris) {
  using VH = typename Mesh::VertexHandle;
  using HH = typename Mesh::HalfedgeHandle;
  using FH = typename Mesh::FaceHandle;
  constexpr std::uint32_t none = UINT32_MAX;
  const std::size_t nv = m.n_vertices(), nh = tris.size(), nf = nh / 3;
  if (m.n_edges() != 0 || m.n_faces() != 0 || nh >= std::size_t(INT32_MAX) / 2) return false;
  // Face halfedge h = 3f + k runs from tris[h] to tris[next(h)].
  const auto next = [](std::size_t h) { return h - h % 3 + (h % 3 + 1) % 3; };
  const auto prev = [](std::size_t h) { return h - h % 3 + (h % 3 + 2) % 3; };
  for (std::size_t f = 0; f < nf; ++f) {
    const std::uint32_t *t = &tris[3 * f];
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv || t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      return false;
  }
  // The face halfedges leaving each vertex, in face order (counting sort), with their targets
  // and their triangles' third vertices beside them (the searches below read ranges only).
  std::vector<std::uint32_t> first(nv + 1, 0), out(nh), to(nh), third(nh);
  for (std::size_t h = 0; h < nh; ++h) ++first[tris[h] + 1];
  for (std::size_t v = 0; v < nv; ++v) first[v + 1] += first[v];
  {
    std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
    for (std::size_t h = 0; h < nh; ++h) {
      const std::uint32_t i = fill[tris[h]]++;
      out[i] = std::uint32_t(h);
      to[i] = tris[next(h)];
      third[i] = tris[prev(h)];
    }
  }
  // Each face halfedge's opposite face halfedge (none on the boundary), paired from the end of
  // lower id; a directed edge twice is for add_face to refuse.
  std::vector<std::uint32_t> opp(nh, none);
  for (std::uint32_t a = 0; a < nv; ++a) {
    for (std::uint32_t i = first[a]; i < first[a + 1]; ++i) {
      const std::uint32_t b = to[i];
      for (std::uint32_t j = i + 1; j < first[a + 1]; ++j)
        if (to[j] == b) return false;
      if (b < a) continue;
      for (std::uint32_t j = first[b]; j < first[b + 1]; ++j) {
        if (to[j] == a) {
          opp[out[i]] = out[j];
          opp[out[j]] = out[i];
          break;
        }
      }
    }
  }
  // At each vertex: its one boundary face halfedge in and out (or none), and its triangles one
  // fan, walked from the boundary one out (or the first): from the halfedge to b in triangle
  // (v, b, c) on to the one to c, within v's range.
  std::vector<std::uint32_t> bin(nv, none), bout(nv, none);
  for (std::size_t h = 0; h < nh; ++h) {
    if (opp[h] != none) continue;
    std::uint32_t &i = bin[tris[next(h)]], &o = bout[tris[h]];
    if (i != none || o != none) return false;
    i = o = std::uint32_t(h);
  }
  for (std::size_t v = 0; v < nv; ++v) {
    const std::uint32_t degree = first[v + 1] - first[v];
    if (degree == 0) continue;
    if ((bin[v] == none) != (bout[v] == none)) return false;
    std::uint32_t start = first[v];
    while (bout[v] != none && out[start] != bout[v]) ++start;
    std::uint32_t i = start, seen = 1;
    while (seen <= degree) {
      std::uint32_t j = first[v];
      while (j < first[v + 1] && to[j] != third[i]) ++j;
      if (j == first[v + 1] || j == start) break;
      i = j;
      ++seen;
    }
    if (seen != degree) return false;
  }
  // OpenMesh halfedge of each face halfedge: edges numbered as add_face creates them.
  std::vector<std::uint32_t> he(nh);
  std::size_t ne = 0;
  for (std::size_t h = 0; h < nh; ++h) {
    if (opp[h] != none && opp[h] < h) continue;
    he[h] = std::uint32_t(2 * ne);
    if (opp[h] != none) he[opp[h]] = std::uint32_t(2 * ne + 1);
    ++ne;
  }
  m.resize(nv, ne, nf);
  for (std::size_t f = 0; f < nf; ++f) {
    const FH fh{int(f)};
    for (std::size_t h = 3 * f; h < 3 * f + 3; ++h) {
      const HH hh{int(he[h])};
      m.set_vertex_handle(hh, VH(int(tris[next(h)])));
      m.set_face_handle(hh, fh);
      m.set_next_halfedge_handle(hh, HH(int(he[next(h)])));
      if (opp[h] == none) {  // its boundary twin, to the boundary halfedge leaving tris[h]
        const HH b{int(he[h] ^ 1u)};
        m.set_vertex_handle(b, VH(int(tris[h])));
        m.set_next_halfedge_handle(b, HH(int(he[bin[tris[h]]] ^ 1u)));
      }
    }
    m.set_halfedge_handle(fh, HH(int(he[3 * f + 2])));
  }
  for (std::size_t v = 0; v < nv; ++v) {
    if (first[v + 1] == first[v]) continue;
    const std::uint32_t h = bin[v] != none ? he[bin[v]] ^ 1u : he[out[first[v]]];
    m.set_halfedge_handle(VH(int(v)), HH(int(h)));
  }
  return true;
}

/* Adds the faces of `tris` (3 ids per face over vertex handles 0.., which m holds, and nothing
 * else yet) to m: at once when every vertex is plain (build_plain), else through add_face; on a
 * rejected face, clears m and throws naming it (`what(f)` describes face f for the message). */
template <class Mesh, class What>
void add_faces(Mesh &m, const std::vector<std::uint32_t> &tris, What what) {
  if (build_plain(m, tris)) return;
  add_faces_one_by_one(m, tris, what);
}

}  // namespace detail

/* The complex of an OpenMesh mesh (triangles; isolated vertices kept), with its vertex and face
 * properties as attributes. See the header comment for what is refused. */
template <class Mesh>
Complex to_complex(const Mesh &m, std::vector<Dropped> *dropped = nullptr) {
  const std::size_t nv = m.n_vertices(), nf = m.n_faces();
  if ((m.has_vertex_status() && nv != 0) || (m.has_face_status() && nf != 0)) {
    for (auto v : m.all_vertices())
      if (m.has_vertex_status() && m.status(v).deleted())
        throw Refused("OpenMesh vertex " + std::to_string(v.idx()) +
                      " is deleted: call garbage_collection() first");
    for (auto f : m.all_faces())
      if (m.has_face_status() && m.status(f).deleted())
        throw Refused("OpenMesh face " + std::to_string(f.idx()) +
                      " is deleted: call garbage_collection() first");
  }
  adapt::TriangleArrays t(nv, nf);
  for (auto f : m.all_faces()) {
    for (auto v : m.fv_range(f)) t.ids.push_back(std::uint32_t(v.idx()));
    t.end_face("OpenMesh face", std::size_t(f.idx()));
  }
  for (auto v : m.all_vertices()) {
    const auto &p = m.point(v);
    for (int k = 0; k < 3; ++k) t.xyz.push_back(double(p[k]));
  }
  Complex c = t.complex();
  detail::properties_to_attributes(c, m.vprops_begin(), m.vprops_end(), Location::Vertices,
                                   "vertex", dropped);
  detail::properties_to_attributes(c, m.fprops_begin(), m.fprops_end(), Location::Listed, "face",
                                   dropped);
  detail::refuse_properties(m.eprops_begin(), m.eprops_end(), "edge", dropped);
  detail::refuse_properties(m.hprops_begin(), m.hprops_end(), "halfedge", dropped);
  detail::refuse_properties(m.mprops_begin(), m.mprops_end(), "mesh", dropped);
  return c;
}

/* Fills `m` (cleared first) with the complex: vertex i, face f = the f-th listed triangle (a
 * repeated listing once), attributes as properties. See the header comment for refusals. */
template <class Mesh>
void to_openmesh(const Complex &c, Mesh &m, std::vector<Dropped> *dropped = nullptr) {
  const adapt::SurfaceListing s = adapt::surface_listing(c, "OpenMesh");
  const std::vector<double> xyz = adapt::xyz3(c, "OpenMesh");
  const std::size_t nv = c.vertex_count(), nf = s.listing.size();
  m.clear();
  m.reserve(nv, nv + nf + 2, nf);  // Euler: E ~ V + F for a closed surface
  using Scalar = typename Mesh::Point::value_type;
  for (std::size_t v = 0; v < nv; ++v) {
    m.add_vertex(typename Mesh::Point(Scalar(xyz[3 * v]), Scalar(xyz[3 * v + 1]),
                                      Scalar(xyz[3 * v + 2])));
  }
  detail::add_faces(m, s.triangles, [&](std::size_t f) {
    return "listed simplex " + std::to_string(s.listing[f]);
  });
  adapt::attributes_to_mesh(
      c, s,
      "no OpenMesh property holds it (1 number, or 2 to 4 reals per element; a property of that "
      "name and another type exists)",
      dropped, [&](const AttributeInfo &a, bool vertices) {
        if (a.name == "v:normals" && vertices) m.request_vertex_normals();
        if (a.name == "f:normals" && !vertices) m.request_face_normals();
        bool ok = false;
        adapt::with_values(c, a, [&](const auto &view) {
          ok = vertices ? detail::attribute_to_property(m, a.name, view, nullptr, nv,
                                                        OpenMesh::VertexHandle())
                        : detail::attribute_to_property(m, a.name, view, &s.listing, nf,
                                                        OpenMesh::FaceHandle());
        });
        return ok;
      });
}

template <class Mesh>
Mesh to_openmesh(const Complex &c, std::vector<Dropped> *dropped = nullptr) {
  return adapt::filled<Mesh>([&](Mesh &m) { to_openmesh(c, m, dropped); });
}

/* ---- manifold parts (manifold_parts.hpp) as OpenMesh meshes ---- */

/* Part `p` as a mesh: local vertex i is mesh vertex i at its original vertex's coordinates
 * (`xyz`: 3 per original vertex, e.g. adapt::xyz3(c)), face f is the part's face f (oriented:
 * Part::flipped says which were turned). Refused: a non-orientable part. O(part). */
template <class Mesh>
void part_to_openmesh(const SurfacePart &p, const std::vector<double> &xyz, Mesh &m) {
  if (!p.problem.empty()) throw Refused("OpenMesh cannot hold it: " + p.problem);
  m.clear();
  m.reserve(p.original_vertex.size(), p.original_vertex.size() + p.face_count() + 2,
            p.face_count());
  using Scalar = typename Mesh::Point::value_type;
  for (std::uint32_t o : p.original_vertex) {
    m.add_vertex(typename Mesh::Point(Scalar(xyz[3 * o]), Scalar(xyz[3 * o + 1]),
                                      Scalar(xyz[3 * o + 2])));
  }
  detail::add_faces(m, p.triangles, [&](std::size_t f) { return p.face_name(f); });
}

template <class Mesh>
Mesh part_to_openmesh(const SurfacePart &p, const std::vector<double> &xyz) {
  return adapt::filled<Mesh>([&](Mesh &m) { part_to_openmesh(p, xyz, m); });
}

/* The mesh's vertex coordinates, 3 per vertex (to give back with SurfaceParts::gather). */
template <class Mesh>
std::vector<double> coordinates(const Mesh &m) {
  std::vector<double> out;
  out.reserve(3 * m.n_vertices());
  for (auto v : m.all_vertices()) {
    const auto &p = m.point(v);
    for (int k = 0; k < 3; ++k) out.push_back(double(p[k]));
  }
  return out;
}

}  // namespace openmesh
}  // namespace topoplex

#endif /* TOPOPLEX_OPENMESH_HPP */
