// GUDHI's Simplex_tree as the peer in any dimension: boundaries by repeated
// boundary_simplex_range, cofaces by cofaces_simplex_range(sh, q - p), adjacencies through the
// cofaces of the boundary.
#pragma once

#include <gudhi/Simplex_tree.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "peer_check.hpp"

namespace peers {

using Stree = Gudhi::Simplex_tree<>;

inline Ids vertices_of(Stree& st, Stree::Simplex_handle sh) {
  Ids s;
  for (auto v : st.simplex_vertex_range(sh)) s.push_back(uint32_t(v));
  std::sort(s.begin(), s.end());
  return s;
}

// Appends the GUDHI answers to every R_{p,q}, p, q <= dimension, and returns, per dimension,
// how many simplices have no coface one dimension up (the tops as the tree sees them).
inline std::vector<size_t> gudhi_relations(Stree& st, std::vector<Relation>& rels) {
  const int d = st.dimension();
  const RelationGrid R = add_relations(rels, "GUDHI Simplex_tree", uint32_t(d));

  // Cofaces one dimension up are asked once per simplex: adjacency needs them for every facet.
  std::map<Ids, std::vector<Ids>> up;
  for (auto sh : st.complex_simplex_range()) {
    auto& rows = up[vertices_of(st, sh)];
    for (auto c : st.cofaces_simplex_range(sh, 1)) rows.push_back(vertices_of(st, c));
  }

  std::vector<size_t> tops(size_t(d + 1), 0);
  for (auto sh : st.complex_simplex_range()) {
    const int p = st.dimension(sh);
    const Ids sigma = vertices_of(st, sh);
    if (up.at(sigma).empty()) ++tops[size_t(p)];

    // Boundary, one codimension at a time through the tree's own boundary ranges.
    std::vector<Stree::Simplex_handle> level{sh};
    for (int q = p - 1; q >= 0; --q) {
      std::map<Ids, Stree::Simplex_handle> next;
      for (auto h : level)
        for (auto b : st.boundary_simplex_range(h)) next.emplace(vertices_of(st, b), b);
      std::vector<Ids> rows;
      level.clear();
      for (auto& [ids, h] : next) {
        rows.push_back(ids);
        level.push_back(h);
      }
      R(p, q).add(sigma, rows);
    }
    // Cofaces.
    for (int q = p + 1; q <= d; ++q) {
      std::vector<Ids> rows;
      for (auto c : st.cofaces_simplex_range(sh, q - p)) rows.push_back(vertices_of(st, c));
      R(p, q).add(sigma, rows);
    }
    // Adjacency: vertices through their edges; p-simplices through their (p-1)-faces.
    std::vector<Ids> adj;
    if (p == 0) {
      for (auto& e : up.at(sigma)) adj.push_back({e[0] == sigma[0] ? e[1] : e[0]});
    } else {
      std::set<Ids> seen;
      for (auto b : st.boundary_simplex_range(sh))
        for (auto& c : up.at(vertices_of(st, b)))
          if (c != sigma && seen.insert(c).second) adj.push_back(c);
    }
    R(p, p).add(sigma, adj);
  }
  return tops;
}

// Hands the tree's top simplices to Topoplex.
inline void add_tops(Stree& st, peers::PeerComplex& cx) {
  for (auto sh : st.complex_simplex_range())
    if (st.cofaces_simplex_range(sh, 1).empty()) cx.add(vertices_of(st, sh));
}

}  // namespace peers
