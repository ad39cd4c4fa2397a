/*
 * CGAL's graph concepts on a Topoplex live triangle mesh: boost::graph_traits for
 * topoplex::cgal::SurfaceGraph, so that CGAL's BGL and Polygon_mesh_processing functions run on
 * the mesh itself, with no copy into a Surface_mesh. Include only where CGAL is found
 * (find_package(CGAL), link CGAL::CGAL).
 *
 *   topoplex::Live live = topoplex::Live::from_file("mesh.off");
 *   topoplex::cgal::SurfaceGraph g(live);           // refuses a non-manifold mesh
 *   namespace PMP = CGAL::Polygon_mesh_processing;
 *   double a = PMP::area(g);
 *   PMP::tangential_relaxation(g);                    // moves vertices through live.set_coords
 *
 * Models: VertexListGraph, EdgeListGraph, HalfedgeListGraph, FaceListGraph (and the BGL
 * IncidenceGraph / BidirectionalGraph that CGAL's iterators give), with the internal property
 * maps boost::vertex_point (CGAL::Epick::Point_3 read in place; writable: put moves the vertex with
 * tpx_live_set_coords, O(1), which keeps every lent view valid), boost::vertex_index,
 * boost::halfedge_index, boost::face_index (the identity on the dense ids below), and vector
 * backed dynamic property maps (CGAL::dynamic_*_property_t) for CGAL's scratch data. Not
 * MutableFaceGraph or MutableHalfedgeGraph: the connectivity is read-only through this graph,
 * so CGAL functions that edit the mesh (isotropic_remeshing, Euler operations,
 * triangulate_hole, ...) do not compile on it. Edit the Live itself, then build a new graph.
 *
 * Encoding (the mesh keeps no halfedges; the graph derives them):
 *  - vertex v: live vertex slot v (0 <= v < vertex_slots);
 *  - face f: triangle slot f, its live top TopRef(2, f), vertices (t0, t1, t2) in stored order;
 *  - halfedge 3f + i (i < 3): from t_i to t_(i+1 mod 3), in face f (so next/prev stay in f);
 *    its opposite is read from the live mesh's facet adjacency (Live::mesh_with_adjacency(),
 *    MeshView::across): the triangle across the edge and the local index of its reverse;
 *  - border halfedges: numbered 3F + k after the 3F interior ones (F triangles), one per
 *    boundary edge, in increasing order of the interior halfedge they are opposite to; face
 *    null_face(); next and prev along the boundary are tables built once;
 *  - edge: named by the smaller of its two halfedges (always an interior one), carrying the
 *    halfedge it was taken from (halfedge(edge(h)) == h, as CGAL's validity check asks);
 *  - halfedge(v): a halfedge with target v, the border one when v is on the boundary (CGAL's
 *    convention), null_halfedge() for an isolated vertex.
 *
 * Refused at construction (topoplex::Refused, naming the simplex; nothing is built): a mesh that
 * is not a consistently oriented 2-manifold with boundary made of triangles, that is any top
 * simplex of another dimension (a wire edge, a tetrahedron), an edge in three or more triangles
 * (MeshView::across gives TPX_ACROSS_MANY), two triangles winding their shared edge the same
 * way, a vertex whose triangles form several fans (a pinch, or two boundary fans: a bowtie),
 * coordinates other than 3 per vertex, and a removed vertex or tombstoned triangle slot (call
 * Live::compact() first: the ids must be dense for CGAL's index maps). For a non-manifold
 * complex cut it first into surface parts (topoplex/manifold_parts.hpp: SurfaceParts::iqm or
 * SurfaceParts::cut) and run CGAL on each part (cgal::part_to_surface_mesh in cgal.hpp).
 *
 * Cost: construction builds the live mesh's facet adjacency when it is not there yet
 * (tpx_live_adjacency: 12 bytes per triangle, kept by the Live until its next edit), then one
 * pass over the triangles (O(F)), one walk around every vertex (O(F) in all) and the boundary
 * tables (O(B log B) for B border halfedges). The graph holds 4 bytes per vertex
 * (halfedge(v)) and 12 bytes per border halfedge (its interior opposite, next, prev), plus 4
 * bytes per vertex while it is built. Queries: source, target, next, prev, face, halfedge(f),
 * halfedge(v) O(1); opposite O(1) inside, O(log B) from an interior halfedge on the boundary
 * to its border halfedge; halfedge(u, v) O(|star(u)|); degree(v) O(1).
 *
 * Validity: the graph reads the live mesh's arrays in place. It is valid while the Live is not
 * edited in its topology (insert, remove, contract, split, add_vertex, compact) and outlives
 * neither; moving vertices (put on the point map, Live::set_coords) keeps it valid. Many threads
 * may read one graph at once; writing points needs exclusive access, as Live::set_coords does.
 */
#ifndef TOPOPLEX_CGAL_GRAPH_TRAITS_HPP
#define TOPOPLEX_CGAL_GRAPH_TRAITS_HPP

#include "adapter.hpp"

#include <CGAL/Dynamic_property_map.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Iterator_range.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <boost/graph/graph_traits.hpp>
#include <boost/iterator/iterator_facade.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iterator>
#include <memory>
#include <ostream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace topoplex {
namespace cgal {

/* A descriptor: a dense id, UINT32_MAX for null. Kind tells the four apart (0 vertex,
 * 1 halfedge, 2 edge, 3 face) so that overloads on them differ. */
template <int Kind>
class GraphId {
 public:
  constexpr GraphId() noexcept = default;
  constexpr explicit GraphId(std::uint32_t i) noexcept : i_(i) {}
  constexpr std::uint32_t idx() const noexcept { return i_; }
  constexpr bool operator==(GraphId o) const noexcept { return i_ == o.i_; }
  constexpr bool operator!=(GraphId o) const noexcept { return i_ != o.i_; }
  constexpr bool operator<(GraphId o) const noexcept { return i_ < o.i_; }
  constexpr bool operator>(GraphId o) const noexcept { return i_ > o.i_; }
  constexpr bool operator<=(GraphId o) const noexcept { return i_ <= o.i_; }
  constexpr bool operator>=(GraphId o) const noexcept { return i_ >= o.i_; }
  friend std::size_t hash_value(GraphId h) noexcept { return h.i_; }
  friend std::ostream &operator<<(std::ostream &os, GraphId h) {
    static const char *const kinds[] = {"v", "h", "e", "f"};
    return os << kinds[Kind] << h.i_;
  }

 private:
  std::uint32_t i_ = UINT32_MAX;
};
using GraphVertex = GraphId<0>;
using GraphHalfedge = GraphId<1>;
using GraphFace = GraphId<3>;

/* An edge: named by the smaller of its two halfedges' ids (idx(), what it compares and hashes
 * by), and carrying the halfedge it was taken from, which halfedge(e, g) gives back (CGAL's
 * validity check asks halfedge(edge(h)) == h, as Surface_mesh's edges do). */
class GraphEdge {
 public:
  constexpr GraphEdge() noexcept = default;
  constexpr GraphEdge(std::uint32_t id, std::uint32_t h) noexcept : i_(id), h_(h) {}
  constexpr explicit GraphEdge(std::uint32_t id) noexcept : i_(id), h_(id) {}
  constexpr std::uint32_t idx() const noexcept { return i_; }
  constexpr GraphHalfedge halfedge() const noexcept { return GraphHalfedge(h_); }
  constexpr bool operator==(GraphEdge o) const noexcept { return i_ == o.i_; }
  constexpr bool operator!=(GraphEdge o) const noexcept { return i_ != o.i_; }
  constexpr bool operator<(GraphEdge o) const noexcept { return i_ < o.i_; }
  friend std::size_t hash_value(GraphEdge e) noexcept { return e.i_; }
  friend std::ostream &operator<<(std::ostream &os, GraphEdge e) { return os << "e" << e.i_; }

 private:
  std::uint32_t i_ = UINT32_MAX, h_ = UINT32_MAX;
};

/* Ids first, first + 1, ... as descriptors (vertices, halfedges, faces). */
template <class Id>
class GraphIdIterator
    : public boost::iterator_facade<GraphIdIterator<Id>, Id, std::random_access_iterator_tag, Id> {
 public:
  GraphIdIterator() = default;
  explicit GraphIdIterator(std::uint32_t i) noexcept : i_(i) {}

 private:
  friend class boost::iterator_core_access;
  Id dereference() const noexcept { return Id(i_); }
  bool equal(const GraphIdIterator &o) const noexcept { return i_ == o.i_; }
  void increment() noexcept { ++i_; }
  void decrement() noexcept { --i_; }
  void advance(std::ptrdiff_t n) noexcept { i_ = static_cast<std::uint32_t>(i_ + n); }
  std::ptrdiff_t distance_to(const GraphIdIterator &o) const noexcept {
    return static_cast<std::ptrdiff_t>(o.i_) - static_cast<std::ptrdiff_t>(i_);
  }
  std::uint32_t i_ = 0;
};

class SurfaceGraph;

/* The edges: the interior halfedges h with h < opposite(h). */
class GraphEdgeIterator
    : public boost::iterator_facade<GraphEdgeIterator, GraphEdge, std::forward_iterator_tag,
                                    GraphEdge> {
 public:
  GraphEdgeIterator() = default;
  inline GraphEdgeIterator(const SurfaceGraph *g, std::uint32_t h) noexcept;

 private:
  friend class boost::iterator_core_access;
  GraphEdge dereference() const noexcept { return GraphEdge(h_); }
  bool equal(const GraphEdgeIterator &o) const noexcept { return h_ == o.h_; }
  inline void increment() noexcept;
  inline void settle() noexcept;
  const SurfaceGraph *g_ = nullptr;
  std::uint32_t h_ = 0;
};

}  // namespace cgal
}  // namespace topoplex

namespace boost {

template <>
struct graph_traits<topoplex::cgal::SurfaceGraph> {
 private:
  struct traversal : public virtual boost::bidirectional_graph_tag,
                     public virtual boost::vertex_list_graph_tag,
                     public virtual boost::edge_list_graph_tag,
                     public virtual boost::adjacency_graph_tag {};
  using G = topoplex::cgal::SurfaceGraph;

 public:
  using vertex_descriptor = topoplex::cgal::GraphVertex;
  using halfedge_descriptor = topoplex::cgal::GraphHalfedge;
  using edge_descriptor = topoplex::cgal::GraphEdge;
  using face_descriptor = topoplex::cgal::GraphFace;
  using vertex_property_type = CGAL::Epick::Point_3;
  using directed_category = boost::undirected_tag;
  using edge_parallel_category = boost::disallow_parallel_edge_tag;
  using traversal_category = traversal;

  using vertex_iterator = topoplex::cgal::GraphIdIterator<vertex_descriptor>;
  using halfedge_iterator = topoplex::cgal::GraphIdIterator<halfedge_descriptor>;
  using face_iterator = topoplex::cgal::GraphIdIterator<face_descriptor>;
  using edge_iterator = topoplex::cgal::GraphEdgeIterator;
  using vertices_size_type = std::uint32_t;
  using halfedges_size_type = std::uint32_t;
  using edges_size_type = std::uint32_t;
  using faces_size_type = std::uint32_t;
  using degree_size_type = std::size_t;

  using in_edge_iterator = CGAL::In_edge_iterator<G>;
  using out_edge_iterator = CGAL::Out_edge_iterator<G>;
  using adjacency_iterator = CGAL::Vertex_around_target_iterator<G>;

  static vertex_descriptor null_vertex() { return vertex_descriptor(); }
  static halfedge_descriptor null_halfedge() { return halfedge_descriptor(); }
  static face_descriptor null_face() { return face_descriptor(); }
};
template <>
struct graph_traits<const topoplex::cgal::SurfaceGraph>
    : public graph_traits<topoplex::cgal::SurfaceGraph> {};

}  // namespace boost

namespace topoplex {
namespace cgal {

/* boost::vertex_point: the vertex's coordinates as a CGAL::Epick point, read in place (a
 * reference into the live mesh's coordinate array, as Surface_mesh's map hands out references
 * into its point array: it sees later moves of the vertex and lasts while the array does);
 * put moves the vertex in the live mesh (tpx_live_set_coords: finite numbers, O(1)).
 *
 * Reading 3 doubles as a Point_3: Epick's Point_3 is 3 doubles and nothing else (checked
 * below: size, alignment, trivially copyable, standard layout), an implicit-lifetime type, and
 * the array is heap memory written only by the library (never through this map), so the point
 * is read where it lies. A map returning the point by value measured 2x slower in
 * compute_face_normals on a cache-resident mesh (docs/adapters.md). */
class SurfaceGraphPointMap {
 public:
  using key_type = GraphVertex;
  using value_type = CGAL::Epick::Point_3;
  using reference = const value_type &;
  using category = boost::read_write_property_map_tag;
  SurfaceGraphPointMap() = default;
  explicit SurfaceGraphPointMap(const SurfaceGraph *g) noexcept : g_(g) {}
  inline friend const value_type &get(const SurfaceGraphPointMap &m, key_type v);
  inline friend void put(const SurfaceGraphPointMap &m, key_type v, const value_type &p);

 private:
  const SurfaceGraph *g_ = nullptr;
};

/* vertex_index, halfedge_index, face_index: the descriptor's dense id (read-only). */
template <class Id>
class SurfaceGraphIndexMap {
 public:
  using key_type = Id;
  using value_type = std::size_t;
  using reference = std::size_t;
  using category = boost::readable_property_map_tag;
  friend std::size_t get(SurfaceGraphIndexMap, Id k) noexcept { return k.idx(); }
};

/* The dynamic property maps CGAL makes for its scratch data: a vector indexed by the dense id
 * (edges by their halfedge id), shared by the copies of the map, default-initialised. */
template <class Id, class T>
class SurfaceGraphVectorMap {
 public:
  using key_type = Id;
  using value_type = T;
  using reference = std::conditional_t<std::is_same<T, bool>::value, T, T &>;
  using category = std::conditional_t<std::is_same<T, bool>::value,
                                      boost::read_write_property_map_tag,
                                      boost::lvalue_property_map_tag>;
  SurfaceGraphVectorMap() = default;
  explicit SurfaceGraphVectorMap(std::size_t n) : v_(std::make_shared<std::vector<Slot>>(n)) {}
  friend reference get(const SurfaceGraphVectorMap &m, Id k) { return (*m.v_)[k.idx()].x; }
  friend void put(const SurfaceGraphVectorMap &m, Id k, const T &x) { (*m.v_)[k.idx()].x = x; }
  reference operator[](Id k) const { return (*v_)[k.idx()].x; }

 private:
  struct Slot {  // not std::vector<bool>: every value addressable
    T x{};
  };
  std::shared_ptr<std::vector<Slot>> v_;
};

/* A Topoplex live triangle mesh seen as a CGAL halfedge graph (see the header comment). */
class SurfaceGraph {
 public:
  static constexpr std::uint32_t kNull = UINT32_MAX;
  using vertex_descriptor = GraphVertex;
  using halfedge_descriptor = GraphHalfedge;
  using edge_descriptor = GraphEdge;
  using face_descriptor = GraphFace;

  /* An empty graph (no vertices): what concept checks default-construct. */
  SurfaceGraph() = default;

  /* The graph of `live` (kept by pointer: it must outlive the graph and not be edited in its
   * topology meanwhile). Builds the facet adjacency and the boundary tables; throws
   * topoplex::Refused for a mesh that is not an oriented 2-manifold of triangles. */
  explicit SurfaceGraph(Live &live) : live_(&live) {
    if (live.coord_dim() != 3) {
      throw Refused("SurfaceGraph: the mesh has " + std::to_string(live.coord_dim()) +
                    " coordinates per vertex; CGAL's points need 3");
    }
    m_ = live.mesh_with_adjacency();
    tri_ = m_.arrays().tops[2];
    xyz_ = m_.arrays().coords;
    for (std::uint32_t p = 1; p < 16; ++p) {
      if (p == 2) continue;
      for (std::uint32_t s = 0; s < m_.slots(p); ++s)
        if (m_.is_top(TopRef(p, s))) {
          const SimplexView t = m_.vertices(TopRef(p, s));
          throw Refused("SurfaceGraph: top simplex " + adapt::ids_text(t.begin(), t.size()) +
                        " has dimension " + std::to_string(p) +
                        ": a CGAL face graph holds triangles only (" + refer_parts());
        }
    }
    nv_ = m_.vertex_slots();
    for (std::uint32_t v = 0; v < nv_; ++v)
      if (!m_.is_vertex(v)) {
        throw Refused("SurfaceGraph: vertex slot " + std::to_string(v) +
                      " is removed; call Live::compact() first (CGAL's index maps need dense ids)");
      }
    nf_ = m_.slots(2);
    if (nf_ >= (UINT32_MAX - 2) / 6) {
      throw Refused("SurfaceGraph: " + std::to_string(nf_) +
                    " triangles: too many for 32-bit halfedge ids");
    }
    for (std::uint32_t f = 0; f < nf_; ++f) {
      const TopRef t(2, f);
      if (!m_.is_top(t)) {
        throw Refused("SurfaceGraph: triangle slot " + std::to_string(f) +
                      " is removed; call Live::compact() first (CGAL's index maps need dense ids)");
      }
      const SimplexView a = m_.vertices(t);
      for (std::uint32_t i = 0; i < 3; ++i) {
        const std::uint32_t u = m_.across(t, (i + 2) % 3);
        const std::uint32_t s = a[i], d = a[(i + 1) % 3];
        if (u == TPX_ACROSS_MANY) {
          throw Refused("SurfaceGraph: edge {" + std::to_string(std::min(s, d)) + ", " +
                        std::to_string(std::max(s, d)) +
                        "} lies in three or more triangles (one is triangle " +
                        adapt::ids_text(a.begin(), 3) + "): not a 2-manifold (" + refer_parts());
        }
        if (u == TPX_ACROSS_NONE) {
          border_.push_back(3 * f + i);
          continue;
        }
        const SimplexView b = m_.vertices(TopRef(u));
        const std::uint32_t j = local(b, d);
        if (b[(j + 1) % 3] != s) {
          throw Refused("SurfaceGraph: triangles " + adapt::ids_text(a.begin(), 3) + " and " +
                        adapt::ids_text(b.begin(), 3) + " run their shared edge {" +
                        std::to_string(std::min(s, d)) + ", " + std::to_string(std::max(s, d)) +
                        "} the same way: the mesh is not consistently oriented (SurfaceParts in "
                        "topoplex/manifold_parts.hpp orients each part)");
        }
      }
    }
    if (border_.size() > UINT32_MAX - 2 - 3 * std::size_t(nf_)) {
      throw Refused("SurfaceGraph: too many halfedges for 32-bit ids");
    }
    border_.shrink_to_fit();
    nb_ = static_cast<std::uint32_t>(border_.size());
    // Border halfedge k runs from target(border_[k]) to source(border_[k]); its next leaves the
    // vertex it enters. One outgoing border halfedge per vertex, else two boundary fans meet.
    std::vector<std::uint32_t> out(nv_, kNull);
    for (std::uint32_t k = 0; k < nb_; ++k) {
      const std::uint32_t from = interior_target(border_[k]);
      if (out[from] != kNull) {
        throw Refused("SurfaceGraph: vertex " + std::to_string(from) +
                      " is on two boundary fans (a bowtie): not a 2-manifold (" + refer_parts());
      }
      out[from] = k;
    }
    border_next_.assign(nb_, kNull);
    border_prev_.assign(nb_, kNull);
    for (std::uint32_t k = 0; k < nb_; ++k) {
      const std::uint32_t n = out[interior_source(border_[k])];
      if (n == kNull) {  // cannot happen on an oriented manifold: fans enter and leave once
        throw Refused("SurfaceGraph: the boundary stops at vertex " +
                      std::to_string(interior_source(border_[k])) + ": not a 2-manifold (" +
                      refer_parts());
      }
      border_next_[k] = n;
      border_prev_[n] = k;
    }
    out = std::vector<std::uint32_t>();
    vertex_halfedge_.assign(nv_, kNull);
    for (std::uint32_t h = 0; h < 3 * nf_; ++h) {
      std::uint32_t &slot = vertex_halfedge_[interior_target(h)];
      if (slot == kNull) slot = h;
    }
    for (std::uint32_t k = 0; k < nb_; ++k)
      vertex_halfedge_[interior_source(border_[k])] = 3 * nf_ + k;
    // Every vertex's triangles in one fan: the walk around it meets all of its star.
    for (std::uint32_t v = 0; v < nv_; ++v) {
      const std::size_t k = m_.star(v).size();
      if (k == 0) continue;
      const GraphHalfedge start(vertex_halfedge_[v]);
      GraphHalfedge h = start;
      std::size_t met = 0;
      do {
        met += h.idx() < 3 * nf_;
        h = opposite(next(h));
      } while (h != start && met <= k);
      if (met != k) {
        throw Refused("SurfaceGraph: the " + std::to_string(k) + " triangles at vertex " +
                      std::to_string(v) +
                      " form more than one fan (a pinched vertex): not a 2-manifold (" +
                      refer_parts());
      }
    }
  }

  /* Counts. */
  std::uint32_t vertex_count() const noexcept { return nv_; }
  std::uint32_t face_count() const noexcept { return nf_; }
  std::uint32_t border_halfedge_count() const noexcept { return nb_; }
  std::uint32_t halfedge_count() const noexcept { return 3 * nf_ + nb_; }
  std::uint32_t edge_count() const noexcept { return (3 * nf_ + nb_) / 2; }
  /* Bytes the graph holds beyond the live mesh and its adjacency. */
  std::size_t bytes() const noexcept {
    return 4 * (vertex_halfedge_.capacity() + border_.capacity() + border_next_.capacity() +
                border_prev_.capacity());
  }
  const MeshView &mesh() const noexcept { return m_; }
  Live *live() const noexcept { return live_; }

  /* Navigation (descriptors must be valid, non-null ids of this graph). */
  GraphVertex source(GraphHalfedge h) const noexcept {
    const std::uint32_t i = h.idx();
    return GraphVertex(i < 3 * nf_ ? interior_source(i) : interior_target(border_[i - 3 * nf_]));
  }
  GraphVertex target(GraphHalfedge h) const noexcept {
    const std::uint32_t i = h.idx();
    return GraphVertex(i < 3 * nf_ ? interior_target(i) : interior_source(border_[i - 3 * nf_]));
  }
  GraphHalfedge next(GraphHalfedge h) const noexcept {
    const std::uint32_t i = h.idx();
    if (i < 3 * nf_) return GraphHalfedge(interior_next(i));
    return GraphHalfedge(3 * nf_ + border_next_[i - 3 * nf_]);
  }
  GraphHalfedge prev(GraphHalfedge h) const noexcept {
    const std::uint32_t i = h.idx();
    if (i < 3 * nf_) return GraphHalfedge(i % 3 == 0 ? i + 2 : i - 1);
    return GraphHalfedge(3 * nf_ + border_prev_[i - 3 * nf_]);
  }
  GraphHalfedge opposite(GraphHalfedge h) const noexcept {
    const std::uint32_t i = h.idx();
    if (i >= 3 * nf_) return GraphHalfedge(border_[i - 3 * nf_]);
    const std::uint32_t f = i / 3, c = i % 3;
    const std::uint32_t u = m_.across(TopRef(2, f), (c + 2) % 3);
    if (u == TPX_ACROSS_NONE) {
      const auto it = std::lower_bound(border_.begin(), border_.end(), i);
      return GraphHalfedge(3 * nf_ + static_cast<std::uint32_t>(it - border_.begin()));
    }
    const TopRef t(u);
    // The reverse runs from this halfedge's target: its local index in the other triangle.
    return GraphHalfedge(3 * t.slot() + local(m_.vertices(t), interior_target(i)));
  }
  GraphFace face(GraphHalfedge h) const noexcept {
    return h.idx() < 3 * nf_ ? GraphFace(h.idx() / 3) : GraphFace();
  }
  /* The halfedge entering the face's first vertex (3f + 2), as CGAL::Euler::add_face and
   * Surface_mesh set it: PMP's per-face sums then start where they do on a Surface_mesh. */
  GraphHalfedge halfedge(GraphFace f) const noexcept { return GraphHalfedge(3 * f.idx() + 2); }
  GraphHalfedge halfedge(GraphVertex v) const noexcept {
    return GraphHalfedge(vertex_halfedge_[v.idx()]);
  }
  /* The halfedge from u to v, if {u, v} is an edge. O(|star(u)|). */
  std::pair<GraphHalfedge, bool> halfedge(GraphVertex u, GraphVertex v) const noexcept {
    if (u.idx() >= nv_ || v.idx() >= nv_) return {GraphHalfedge(), false};
    for (TopRef t : m_.star(u.idx())) {
      const SimplexView a = m_.vertices(t);
      const std::uint32_t j = local(a, u.idx());
      if (a[(j + 1) % 3] == v.idx()) return {GraphHalfedge(3 * t.slot() + j), true};
      if (a[(j + 2) % 3] == v.idx())
        return {opposite(GraphHalfedge(3 * t.slot() + (j + 2) % 3)), true};
    }
    return {GraphHalfedge(), false};
  }
  GraphEdge edge(GraphHalfedge h) const noexcept {
    return GraphEdge(std::min(h.idx(), opposite(h).idx()), h.idx());
  }
  GraphHalfedge halfedge(GraphEdge e) const noexcept { return e.halfedge(); }
  /* Edges at v: its triangles, plus one on the boundary. O(1). */
  std::size_t degree(GraphVertex v) const noexcept {
    const std::uint32_t h = vertex_halfedge_[v.idx()];
    return m_.star(v.idx()).size() + (h != kNull && h >= 3 * nf_);
  }
  const double *coords(GraphVertex v) const noexcept { return xyz_ + 3 * std::size_t(v.idx()); }

 private:
  friend class GraphEdgeIterator;
  static std::string refer_parts() {
    return "cut it into surface parts with topoplex/manifold_parts.hpp, SurfaceParts::iqm or "
           "SurfaceParts::cut, and run CGAL on each part)";
  }
  static std::uint32_t local(const SimplexView &a, std::uint32_t v) noexcept {
    return a[0] == v ? 0 : a[1] == v ? 1 : 2;
  }
  // The triangle table holds slot f's vertices at 3f, 3f + 1, 3f + 2: halfedge 3f + i starts
  // at entry 3f + i and ends at the next entry of its triangle.
  static std::uint32_t interior_next(std::uint32_t h) noexcept { return h % 3 == 2 ? h - 2 : h + 1; }
  std::uint32_t interior_source(std::uint32_t h) const noexcept { return tri_[h]; }
  std::uint32_t interior_target(std::uint32_t h) const noexcept { return tri_[interior_next(h)]; }

  Live *live_ = nullptr;
  MeshView m_{};
  const std::uint32_t *tri_ = nullptr;  // the live mesh's triangle table (tops[2])
  const double *xyz_ = nullptr;         // its coordinates, 3 per vertex slot
  std::uint32_t nv_ = 0, nf_ = 0, nb_ = 0;
  std::vector<std::uint32_t> vertex_halfedge_;  // a halfedge with target v (border if any)
  std::vector<std::uint32_t> border_;           // border k's interior opposite, ascending
  std::vector<std::uint32_t> border_next_, border_prev_;  // along the boundary (border ids k)
};

GraphEdgeIterator::GraphEdgeIterator(const SurfaceGraph *g, std::uint32_t h) noexcept
    : g_(g), h_(h) {
  settle();
}
void GraphEdgeIterator::settle() noexcept {
  const std::uint32_t end = 3 * g_->nf_;
  while (h_ < end && g_->opposite(GraphHalfedge(h_)).idx() < h_) ++h_;
}
void GraphEdgeIterator::increment() noexcept {
  ++h_;
  settle();
}

static_assert(sizeof(CGAL::Epick::Point_3) == 3 * sizeof(double) &&
                  alignof(CGAL::Epick::Point_3) == alignof(double) &&
                  std::is_trivially_copyable<CGAL::Epick::Point_3>::value &&
                  std::is_standard_layout<CGAL::Epick::Point_3>::value,
              "SurfaceGraphPointMap reads 3 doubles as an Epick Point_3");
inline const SurfaceGraphPointMap::value_type &get(const SurfaceGraphPointMap &m, GraphVertex v) {
  return *reinterpret_cast<const SurfaceGraphPointMap::value_type *>(m.g_->coords(v));
}
inline void put(const SurfaceGraphPointMap &m, GraphVertex v,
                const SurfaceGraphPointMap::value_type &p) {
  const double x[3] = {p.x(), p.y(), p.z()};
  // The Live is the caller's non-const object (the graph keeps it by non-const pointer).
  topoplex::detail::check(
      tpx_live_set_coords(const_cast<TpxLive *>(m.g_->live()->get()), v.idx(), x, 3));
}

/* ---- the free functions CGAL's BGL calls (found by argument-dependent lookup) ---- */

using SurfaceGraphVertexRange = CGAL::Iterator_range<GraphIdIterator<GraphVertex>>;
using SurfaceGraphHalfedgeRange = CGAL::Iterator_range<GraphIdIterator<GraphHalfedge>>;
using SurfaceGraphFaceRange = CGAL::Iterator_range<GraphIdIterator<GraphFace>>;
using SurfaceGraphEdgeRange = CGAL::Iterator_range<GraphEdgeIterator>;

inline GraphVertex source(GraphHalfedge h, const SurfaceGraph &g) { return g.source(h); }
inline GraphVertex target(GraphHalfedge h, const SurfaceGraph &g) { return g.target(h); }
inline GraphVertex source(GraphEdge e, const SurfaceGraph &g) { return g.source(g.halfedge(e)); }
inline GraphVertex target(GraphEdge e, const SurfaceGraph &g) { return g.target(g.halfedge(e)); }
inline GraphHalfedge next(GraphHalfedge h, const SurfaceGraph &g) { return g.next(h); }
inline GraphHalfedge prev(GraphHalfedge h, const SurfaceGraph &g) { return g.prev(h); }
inline GraphHalfedge opposite(GraphHalfedge h, const SurfaceGraph &g) { return g.opposite(h); }
inline GraphFace face(GraphHalfedge h, const SurfaceGraph &g) { return g.face(h); }
inline GraphHalfedge halfedge(GraphFace f, const SurfaceGraph &g) { return g.halfedge(f); }
inline GraphHalfedge halfedge(GraphVertex v, const SurfaceGraph &g) { return g.halfedge(v); }
inline GraphHalfedge halfedge(GraphEdge e, const SurfaceGraph &g) { return g.halfedge(e); }
inline std::pair<GraphHalfedge, bool> halfedge(GraphVertex u, GraphVertex v,
                                               const SurfaceGraph &g) {
  return g.halfedge(u, v);
}
inline GraphEdge edge(GraphHalfedge h, const SurfaceGraph &g) { return g.edge(h); }
inline std::pair<GraphEdge, bool> edge(GraphVertex u, GraphVertex v, const SurfaceGraph &g) {
  const auto h = g.halfedge(u, v);
  return {h.second ? g.edge(h.first) : GraphEdge(), h.second};
}

inline SurfaceGraphVertexRange vertices(const SurfaceGraph &g) {
  return {GraphIdIterator<GraphVertex>(0), GraphIdIterator<GraphVertex>(g.vertex_count())};
}
inline SurfaceGraphHalfedgeRange halfedges(const SurfaceGraph &g) {
  return {GraphIdIterator<GraphHalfedge>(0), GraphIdIterator<GraphHalfedge>(g.halfedge_count())};
}
inline SurfaceGraphFaceRange faces(const SurfaceGraph &g) {
  return {GraphIdIterator<GraphFace>(0), GraphIdIterator<GraphFace>(g.face_count())};
}
inline SurfaceGraphEdgeRange edges(const SurfaceGraph &g) {
  const std::uint32_t end = 3 * g.face_count();
  return {GraphEdgeIterator(&g, 0), GraphEdgeIterator(&g, end)};
}
inline std::uint32_t num_vertices(const SurfaceGraph &g) { return g.vertex_count(); }
inline std::uint32_t num_halfedges(const SurfaceGraph &g) { return g.halfedge_count(); }
inline std::uint32_t num_edges(const SurfaceGraph &g) { return g.edge_count(); }
inline std::uint32_t num_faces(const SurfaceGraph &g) { return g.face_count(); }
inline std::size_t degree(GraphVertex v, const SurfaceGraph &g) { return g.degree(v); }
inline std::size_t out_degree(GraphVertex v, const SurfaceGraph &g) { return g.degree(v); }
inline std::size_t in_degree(GraphVertex v, const SurfaceGraph &g) { return g.degree(v); }
inline std::size_t degree(GraphFace, const SurfaceGraph &) { return 3; }

inline CGAL::Iterator_range<CGAL::Out_edge_iterator<SurfaceGraph>>
out_edges(GraphVertex v, const SurfaceGraph &g) {
  using It = CGAL::Out_edge_iterator<SurfaceGraph>;
  return {It(g.halfedge(v), g), It(g.halfedge(v), g, int(g.halfedge(v) != GraphHalfedge()))};
}
inline CGAL::Iterator_range<CGAL::In_edge_iterator<SurfaceGraph>>
in_edges(GraphVertex v, const SurfaceGraph &g) {
  using It = CGAL::In_edge_iterator<SurfaceGraph>;
  return {It(g.halfedge(v), g), It(g.halfedge(v), g, int(g.halfedge(v) != GraphHalfedge()))};
}
inline CGAL::Iterator_range<CGAL::Vertex_around_target_iterator<SurfaceGraph>>
adjacent_vertices(GraphVertex v, const SurfaceGraph &g) {
  using It = CGAL::Vertex_around_target_iterator<SurfaceGraph>;
  return {It(g.halfedge(v), g), It(g.halfedge(v), g, int(g.halfedge(v) != GraphHalfedge()))};
}

/* ---- internal property maps ---- */

inline SurfaceGraphPointMap get(boost::vertex_point_t, const SurfaceGraph &g) {
  return SurfaceGraphPointMap(&g);
}
inline const SurfaceGraphPointMap::value_type &get(boost::vertex_point_t, const SurfaceGraph &g,
                                                   GraphVertex v) {
  return get(SurfaceGraphPointMap(&g), v);
}
inline void put(boost::vertex_point_t, const SurfaceGraph &g, GraphVertex v,
                const SurfaceGraphPointMap::value_type &p) {
  put(SurfaceGraphPointMap(&g), v, p);
}
inline SurfaceGraphIndexMap<GraphVertex> get(boost::vertex_index_t, const SurfaceGraph &) {
  return {};
}
inline SurfaceGraphIndexMap<GraphHalfedge> get(boost::halfedge_index_t, const SurfaceGraph &) {
  return {};
}
inline SurfaceGraphIndexMap<GraphFace> get(boost::face_index_t, const SurfaceGraph &) {
  return {};
}
inline std::size_t get(boost::vertex_index_t, const SurfaceGraph &, GraphVertex v) {
  return v.idx();
}
inline std::size_t get(boost::halfedge_index_t, const SurfaceGraph &, GraphHalfedge h) {
  return h.idx();
}
inline std::size_t get(boost::face_index_t, const SurfaceGraph &, GraphFace f) { return f.idx(); }

/* Dynamic maps: sized by the ids (edges by the interior halfedge ids naming them). */
template <class T>
SurfaceGraphVectorMap<GraphVertex, T> get(const CGAL::dynamic_vertex_property_t<T> &,
                                          const SurfaceGraph &g) {
  return SurfaceGraphVectorMap<GraphVertex, T>(g.vertex_count());
}
template <class T>
SurfaceGraphVectorMap<GraphHalfedge, T> get(const CGAL::dynamic_halfedge_property_t<T> &,
                                            const SurfaceGraph &g) {
  return SurfaceGraphVectorMap<GraphHalfedge, T>(g.halfedge_count());
}
template <class T>
SurfaceGraphVectorMap<GraphEdge, T> get(const CGAL::dynamic_edge_property_t<T> &, const SurfaceGraph &g) {
  return SurfaceGraphVectorMap<GraphEdge, T>(3 * std::size_t(g.face_count()));
}
template <class T>
SurfaceGraphVectorMap<GraphFace, T> get(const CGAL::dynamic_face_property_t<T> &, const SurfaceGraph &g) {
  return SurfaceGraphVectorMap<GraphFace, T>(g.face_count());
}

/* boost::property_map's answer for property `Tag`: the map `get` above hands out for it (read
 * and written alike). */
template <class Tag>
struct PropertyMapOf {
  using type = decltype(get(std::declval<Tag>(), std::declval<const SurfaceGraph &>()));
  using const_type = type;
};

}  // namespace cgal
}  // namespace topoplex

namespace std {
template <int Kind>
struct hash<topoplex::cgal::GraphId<Kind>> {
  std::size_t operator()(topoplex::cgal::GraphId<Kind> h) const noexcept { return h.idx(); }
};
template <>
struct hash<topoplex::cgal::GraphEdge> {
  std::size_t operator()(topoplex::cgal::GraphEdge e) const noexcept { return e.idx(); }
};
}  // namespace std

namespace boost {

template <>
struct property_map<topoplex::cgal::SurfaceGraph, boost::vertex_point_t>
    : topoplex::cgal::PropertyMapOf<boost::vertex_point_t> {};
template <>
struct property_map<topoplex::cgal::SurfaceGraph, boost::vertex_index_t>
    : topoplex::cgal::PropertyMapOf<boost::vertex_index_t> {};
template <>
struct property_map<topoplex::cgal::SurfaceGraph, boost::halfedge_index_t>
    : topoplex::cgal::PropertyMapOf<boost::halfedge_index_t> {};
template <>
struct property_map<topoplex::cgal::SurfaceGraph, boost::face_index_t>
    : topoplex::cgal::PropertyMapOf<boost::face_index_t> {};
template <class T>
struct property_map<topoplex::cgal::SurfaceGraph, CGAL::dynamic_vertex_property_t<T>>
    : topoplex::cgal::PropertyMapOf<CGAL::dynamic_vertex_property_t<T>> {};
template <class T>
struct property_map<topoplex::cgal::SurfaceGraph, CGAL::dynamic_halfedge_property_t<T>>
    : topoplex::cgal::PropertyMapOf<CGAL::dynamic_halfedge_property_t<T>> {};
template <class T>
struct property_map<topoplex::cgal::SurfaceGraph, CGAL::dynamic_edge_property_t<T>>
    : topoplex::cgal::PropertyMapOf<CGAL::dynamic_edge_property_t<T>> {};
template <class T>
struct property_map<topoplex::cgal::SurfaceGraph, CGAL::dynamic_face_property_t<T>>
    : topoplex::cgal::PropertyMapOf<CGAL::dynamic_face_property_t<T>> {};

}  // namespace boost

namespace CGAL {
template <>
struct graph_has_property<topoplex::cgal::SurfaceGraph, boost::vertex_point_t> : CGAL::Tag_true {};
template <>
struct graph_has_property<topoplex::cgal::SurfaceGraph, boost::vertex_index_t> : CGAL::Tag_true {};
template <>
struct graph_has_property<topoplex::cgal::SurfaceGraph, boost::halfedge_index_t>
    : CGAL::Tag_true {};
template <>
struct graph_has_property<topoplex::cgal::SurfaceGraph, boost::face_index_t> : CGAL::Tag_true {};
}  // namespace CGAL

#endif /* TOPOPLEX_CGAL_GRAPH_TRAITS_HPP */
