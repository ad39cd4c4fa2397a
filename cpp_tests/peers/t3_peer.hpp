// CGAL's 3D triangulations (Delaunay, Mesh_3's C3T3, alpha shapes) as peers. The complex is a
// subcomplex of the triangulation chosen by a membership policy; every relation R_{p,q},
// p, q <= 3, is answered with the triangulation's own incidence queries (incident_cells /
// incident_facets / incident_edges of a vertex, the cell and facet circulators around an edge,
// cell neighbours), keeping only members of the subcomplex.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "peer_check.hpp"

namespace peers {

// The subcomplex of a triangulation made of some cells and all their faces.
template <class Tr, class CellPredicate>
struct CellsAndFaces {
  const Tr& tr;
  CellPredicate in_cell;

  bool cell(typename Tr::Cell_handle c) const { return !tr.is_infinite(c) && in_cell(c); }
  bool facet(const typename Tr::Facet& f) const {
    return cell(f.first) || cell(f.first->neighbor(f.second));
  }
  bool edge(const typename Tr::Edge& e) const {
    auto c = tr.incident_cells(e), done = c;
    do {
      if (cell(c)) return true;
    } while (++c != done);
    return false;
  }
  bool vertex(typename Tr::Vertex_handle v) const {
    std::vector<typename Tr::Cell_handle> cells;
    tr.incident_cells(v, std::back_inserter(cells));
    for (auto c : cells)
      if (cell(c)) return true;
    return false;
  }
};

// The finite part of a triangulation, in CGAL's own terms (is_infinite of each simplex).
template <class Tr>
struct FiniteSimplices {
  const Tr& tr;
  bool cell(typename Tr::Cell_handle c) const { return !tr.is_infinite(c); }
  bool facet(const typename Tr::Facet& f) const { return !tr.is_infinite(f); }
  bool edge(const typename Tr::Edge& e) const { return !tr.is_infinite(e); }
  bool vertex(typename Tr::Vertex_handle v) const { return !tr.is_infinite(v); }
};

// Numbers the member vertices in the triangulation's iteration order, hands the complex to
// `cx` (the member cells, plus lower-dimensional members when `with_all_faces`, which the
// complex absorbs unless they are top simplices), sets `cx.expected_tops` from the
// triangulation's incidences, and appends the 16 relations R_{p,q}, p, q <= 3, to `rels`.
template <class Tr, class Member, class PointOf>
void t3_peer(const Tr& tr, const Member& in, PointOf point_of, const std::string& peer, bool with_all_faces,
             PeerComplex& cx, std::vector<Relation>& rels) {
  using Vh = typename Tr::Vertex_handle;
  using Ch = typename Tr::Cell_handle;
  using Edge = typename Tr::Edge;
  using Facet = typename Tr::Facet;

  std::map<Vh, uint32_t> id;
  for (auto v : tr.finite_vertex_handles())
    if (in.vertex(v)) {
      const uint32_t i = uint32_t(id.size());
      id.emplace(v, i);
      const auto p = point_of(v);
      cx.coords.insert(cx.coords.end(), {double(p.x()), double(p.y()), double(p.z())});
    }
  cx.n_vertices = uint32_t(id.size());
  cx.coord_dim = 3;

  auto vid = [&](Vh v) { return id.at(v); };
  auto edge_ids = [&](const Edge& e) { return Ids{vid(e.first->vertex(e.second)), vid(e.first->vertex(e.third))}; };
  auto facet_ids = [&](const Facet& f) {
    Ids s;
    for (int k = 1; k < 4; ++k) s.push_back(vid(f.first->vertex((f.second + k) & 3)));
    std::sort(s.begin(), s.end());
    return s;
  };
  auto cell_ids = [&](Ch c) {
    Ids s;
    for (int k = 0; k < 4; ++k) s.push_back(vid(c->vertex(k)));
    std::sort(s.begin(), s.end());
    return s;
  };
  auto sorted = [](Ids s) {
    std::sort(s.begin(), s.end());
    return s;
  };

  const RelationGrid R = add_relations(rels, peer, 3);

  // Members' cofaces one dimension up, through CGAL's incidence queries.
  auto member_edges_at = [&](Vh v) {
    std::vector<Edge> all, out;
    tr.incident_edges(v, std::back_inserter(all));
    for (auto& e : all)
      if (!tr.is_infinite(e) && in.edge(e)) out.push_back(e);
    return out;
  };
  auto member_facets_at_edge = [&](const Edge& e) {
    std::vector<Facet> out;
    auto f = tr.incident_facets(e), done = f;
    do {
      if (!tr.is_infinite(*f) && in.facet(*f)) out.push_back(*f);
    } while (++f != done);
    return out;
  };

  std::vector<size_t> tops(4, 0);
  for (auto v : tr.finite_vertex_handles()) {
    if (!in.vertex(v)) continue;
    const Ids sigma{vid(v)};
    std::vector<Ids> verts, edges, facets, cells;
    for (auto& e : member_edges_at(v)) {
      const Ids s = edge_ids(e);
      verts.push_back({s[0] == sigma[0] ? s[1] : s[0]});
      edges.push_back(s);
    }
    std::vector<Facet> fs;
    tr.incident_facets(v, std::back_inserter(fs));
    for (auto& f : fs)
      if (!tr.is_infinite(f) && in.facet(f)) facets.push_back(facet_ids(f));
    std::vector<Ch> cs;
    tr.incident_cells(v, std::back_inserter(cs));
    for (auto c : cs)
      if (!tr.is_infinite(c) && in.cell(c)) cells.push_back(cell_ids(c));
    tops[0] += edges.empty() ? 1 : 0;
    if (with_all_faces) cx.add(sigma);
    R(0, 0).add(sigma, verts);
    R(0, 1).add(sigma, edges);
    R(0, 2).add(sigma, facets);
    R(0, 3).add(sigma, cells);
  }
  for (const Edge& e : tr.finite_edges()) {
    if (!in.edge(e)) continue;
    const Ids sigma = sorted(edge_ids(e));
    std::vector<Ids> edges, facets, cells;
    for (int end = 0; end < 2; ++end)
      for (auto& e2 : member_edges_at(end ? e.first->vertex(e.third) : e.first->vertex(e.second))) {
        Ids s = sorted(edge_ids(e2));
        if (s != sigma) edges.push_back(s);
      }
    for (auto& f : member_facets_at_edge(e)) facets.push_back(facet_ids(f));
    auto c = tr.incident_cells(e), done = c;
    do {
      if (!tr.is_infinite(c) && in.cell(c)) cells.push_back(cell_ids(c));
    } while (++c != done);
    tops[1] += facets.empty() ? 1 : 0;
    if (with_all_faces) cx.add(sigma);
    R(1, 0).add(sigma, faces_of(sigma, 0));
    R(1, 1).add(sigma, edges);
    R(1, 2).add(sigma, facets);
    R(1, 3).add(sigma, cells);
  }
  for (const Facet& f : tr.finite_facets()) {
    if (!in.facet(f)) continue;
    const Ids sigma = facet_ids(f);
    std::vector<Ids> facets, cells;
    // The facet's three edges are (c, i, j) for i, j != f.second.
    for (int a = 1; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const Edge e(f.first, (f.second + a) & 3, (f.second + b) & 3);
        for (auto& g : member_facets_at_edge(e)) {
          Ids s = facet_ids(g);
          if (s != sigma) facets.push_back(s);
        }
      }
    for (Ch c : {f.first, f.first->neighbor(f.second)})
      if (!tr.is_infinite(c) && in.cell(c)) cells.push_back(cell_ids(c));
    tops[2] += cells.empty() ? 1 : 0;
    if (with_all_faces) cx.add(sigma);
    R(2, 0).add(sigma, faces_of(sigma, 0));
    R(2, 1).add(sigma, faces_of(sigma, 1));
    R(2, 2).add(sigma, facets);
    R(2, 3).add(sigma, cells);
  }
  for (Ch c : tr.finite_cell_handles()) {
    if (!in.cell(c)) continue;
    const Ids sigma = cell_ids(c);
    std::vector<Ids> cells;
    for (int i = 0; i < 4; ++i) {
      Ch n = c->neighbor(i);
      if (!tr.is_infinite(n) && in.cell(n)) cells.push_back(cell_ids(n));
    }
    ++tops[3];
    cx.add(sigma);
    R(3, 0).add(sigma, faces_of(sigma, 0));
    R(3, 1).add(sigma, faces_of(sigma, 1));
    R(3, 2).add(sigma, faces_of(sigma, 2));
    R(3, 3).add(sigma, cells);
  }
  while (tops.size() > 1 && tops.back() == 0) tops.pop_back();
  cx.expected_tops = tops;
}

}  // namespace peers
