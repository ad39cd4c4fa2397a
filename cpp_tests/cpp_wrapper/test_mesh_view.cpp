// topoplex::MeshView (the live complex's arrays navigated inline in the header) against a
// brute-force oracle computed from the live complex's top simplices as the library lists them
// (Live::top_simplices): random non-manifold, mixed-dimensional complexes to dimension 6,
// before and after random sequences of insertions, removals, contractions, coordinate changes
// and compact().
#include "topoplex.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <map>
#include <random>
#include <set>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "../complex_of.hpp"

namespace {

using Ids = std::vector<std::uint32_t>;
using topoplex::MeshView;
using topoplex::TopRef;

Ids sorted(Ids s) {
  std::sort(s.begin(), s.end());
  return s;
}

bool subset(const Ids &small, const Ids &big) {  // both sorted
  return std::includes(big.begin(), big.end(), small.begin(), small.end());
}

// The oracle: every live top (sorted vertices) and the live vertices, from the per-call API.
struct Oracle {
  std::vector<Ids> tops;
  std::vector<bool> alive;

  explicit Oracle(const topoplex::Live &live) {
    for (std::uint32_t p = 1; p <= 15; ++p)
      for (auto s : live.top_simplices(p)) tops.push_back(sorted(s.to_vector()));
    alive.resize(live.vertex_slots());
    for (std::uint32_t v = 0; v < alive.size(); ++v) alive[v] = live.is_vertex(v);
  }
  std::vector<Ids> holding(const Ids &s) const {
    std::vector<Ids> out;
    for (const Ids &t : tops)
      if (subset(sorted(s), t)) out.push_back(t);
    std::sort(out.begin(), out.end());
    return out;
  }
};

Ids top_set(const MeshView &m, TopRef t) { return sorted(m.vertices(t).to_vector()); }

// Every MeshView answer against the oracle.
void check(const topoplex::Live &live, std::mt19937 &rng) {
  live.validate();
  const Oracle o(live);
  const MeshView m = live.mesh();
  ASSERT_EQ(m.vertex_slots(), o.alive.size());
  // The top tables: the live slots hold exactly the listed tops, in the same winding.
  std::vector<Ids> from_view;
  for (std::uint32_t p = 1; p <= 15; ++p) {
    std::vector<Ids> wound;
    for (std::uint32_t s = 0; s < m.slots(p); ++s)
      if (m.is_top(TopRef(p, s))) {
        wound.push_back(m.vertices(TopRef(p, s)).to_vector());
        from_view.push_back(sorted(wound.back()));
        EXPECT_EQ(live.top_vertices(TopRef(p, s).raw()).to_vector(), wound.back());
      }
    std::vector<Ids> listed;
    for (auto s : live.top_simplices(p)) listed.push_back(s.to_vector());
    std::sort(wound.begin(), wound.end());
    std::sort(listed.begin(), listed.end());
    EXPECT_EQ(wound, listed) << "winding of the top " << p << "-simplices";
  }
  std::sort(from_view.begin(), from_view.end());
  std::vector<Ids> all = o.tops;
  std::sort(all.begin(), all.end());
  ASSERT_EQ(from_view, all);

  Ids ring;
  topoplex::NeighbourMarks marks;
  // The batch one-ring pass: every live vertex once, ascending, its ring as the oracle's.
  std::vector<std::uint32_t> ring_of;
  std::vector<Ids> rings(m.vertex_slots());
  m.for_each_ring(marks, [&](std::uint32_t v, topoplex::SimplexView r) {
    ring_of.push_back(v);
    rings[v] = sorted(r.to_vector());
    EXPECT_EQ(rings[v].size(), r.size()) << "a neighbour named twice in the ring of " << v;
  });
  Ids live_slots;
  for (std::uint32_t v = 0; v < m.vertex_slots(); ++v)
    if (o.alive[v]) live_slots.push_back(v);
  EXPECT_EQ(ring_of, live_slots) << "for_each_ring visits every live vertex once, ascending";
  for (std::uint32_t v = 0; v < m.vertex_slots(); ++v) {
    ASSERT_EQ(m.is_vertex(v), bool(o.alive[v]));
    if (!o.alive[v]) continue;
    // Star and one-ring.
    std::vector<Ids> star;
    for (TopRef t : m.star(v)) {
      EXPECT_TRUE(m.is_top(t));
      EXPECT_TRUE(m.holds(t, v));
      star.push_back(top_set(m, t));
    }
    std::sort(star.begin(), star.end());
    EXPECT_EQ(star, o.holding({v})) << "star of " << v;
    std::set<std::uint32_t> expect;
    for (const Ids &t : o.holding({v}))
      for (std::uint32_t w : t)
        if (w != v) expect.insert(w);
    m.neighbours(v, ring);
    EXPECT_EQ(ring, Ids(expect.begin(), expect.end())) << "one-ring of " << v;
    Ids marked;  // each once, in no order
    m.for_each_neighbour(v, marks, [&](std::uint32_t w) { marked.push_back(w); });
    EXPECT_EQ(sorted(marked), ring) << "one-ring of " << v << " by marks";
    EXPECT_EQ(rings[v], ring) << "one-ring of " << v << " by for_each_ring";
    Ids by_call;
    for (auto r : live.relation({v}, 0)) by_call.push_back(r[0]);
    EXPECT_EQ(ring, by_call);
    if (m.coord_dim() > 0) {
      const std::vector<double> xyz = live.coords(v);
      EXPECT_TRUE(std::equal(xyz.begin(), xyz.end(), m.coords(v)));
    }
  }

  // Tops holding a simplex, simplex membership: faces of tops and random vertex sets.
  std::vector<std::uint32_t> live_vertices;
  for (std::uint32_t v = 0; v < o.alive.size(); ++v)
    if (o.alive[v]) live_vertices.push_back(v);
  for (int trial = 0; trial < 40 && !live_vertices.empty(); ++trial) {
    Ids s;
    if (trial % 2 == 0 && !o.tops.empty()) {
      const Ids &t = o.tops[rng() % o.tops.size()];
      for (std::uint32_t w : t)
        if (rng() % 2) s.push_back(w);
      if (s.empty()) s.push_back(t[0]);
    } else {
      std::shuffle(live_vertices.begin(), live_vertices.end(), rng);
      s.assign(live_vertices.begin(),
               live_vertices.begin() + std::min<std::size_t>(1 + rng() % 3, live_vertices.size()));
    }
    std::vector<Ids> got;
    m.for_each_top_holding(s.data(), s.size(), [&](TopRef t) { got.push_back(top_set(m, t)); });
    std::sort(got.begin(), got.end());
    const std::vector<Ids> want = o.holding(s);
    EXPECT_EQ(got, want);
    for (std::uint32_t p = 0; p <= 6; ++p) {
      std::size_t k = 0;
      for (const Ids &t : want) k += p == 0 || t.size() == p + 1;
      EXPECT_EQ(m.tops_holding(s.data(), s.size(), p), k);
    }
    EXPECT_EQ(m.is_simplex(s.data(), s.size()), s.size() == 1 || !want.empty());
    if (!want.empty()) {
      // Boundary and manifold tests inline, as the library's handle functions answer them.
      const topoplex::Simplex h = live.locate(s);
      Ids scratch_ids;
      EXPECT_EQ(m.is_boundary(s.data(), s.size(), scratch_ids), live.is_boundary(h)) << "boundary";
      EXPECT_EQ(m.is_manifold(s.data(), s.size(), scratch_ids), live.is_manifold(h)) << "manifold";
    }
  }

  // Adjacent tops: the same dimension, sharing all but one vertex; from the stars, and read
  // from the facet adjacency (each facet's entry: none, the one top across, or many).
  std::vector<TopRef> adj;
  const MeshView with = live.mesh_with_adjacency();
  ASSERT_TRUE(with.has_adjacency());
  for (std::uint32_t p = 1; p <= 15; ++p)
    for (std::uint32_t s = 0; s < m.slots(p); ++s) {
      const TopRef t(p, s);
      if (!m.is_top(t)) continue;
      const Ids me = top_set(m, t);
      for (std::uint32_t i = 0; i <= p; ++i) {
        Ids facet = m.vertices(t).to_vector();
        facet.erase(facet.begin() + i);
        std::sort(facet.begin(), facet.end());
        std::size_t across = 0;
        for (const Ids &u : o.tops)
          across += u.size() == me.size() && u != me &&
                    std::includes(u.begin(), u.end(), facet.begin(), facet.end());
        const std::uint32_t e = with.across(t, i);
        if (across == 0) EXPECT_EQ(e, TPX_ACROSS_NONE);
        else if (across > 1) EXPECT_EQ(e, TPX_ACROSS_MANY);
        else EXPECT_TRUE(e != TPX_ACROSS_NONE && e != TPX_ACROSS_MANY && m.is_top(TopRef(e)));
      }
      std::vector<TopRef> read;
      with.adjacent_tops(t, read);
      std::vector<Ids> got_read;
      for (TopRef u : read) got_read.push_back(top_set(m, u));
      std::sort(got_read.begin(), got_read.end());
      m.adjacent_tops(t, adj);
      std::vector<Ids> got;
      for (TopRef u : adj) got.push_back(top_set(m, u));
      std::sort(got.begin(), got.end());
      EXPECT_EQ(got_read, got) << "tops adjacent to a top " << p << "-simplex, read";
      std::vector<Ids> want;
      for (const Ids &u : o.tops) {
        if (u.size() != me.size() || u == me) continue;
        Ids common;
        std::set_intersection(me.begin(), me.end(), u.begin(), u.end(),
                              std::back_inserter(common));
        if (common.size() == p) want.push_back(u);
      }
      std::sort(want.begin(), want.end());
      EXPECT_EQ(got, want) << "tops adjacent to a top " << p << "-simplex";
    }

  // Whole-mesh passes: edges with their top-triangle counts; adjacent triangle pairs.
  std::vector<std::uint64_t> scratch;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> edges, want_edges;
  m.for_each_edge(2, scratch, [&](std::uint32_t a, std::uint32_t b, std::size_t k) {
    EXPECT_TRUE(edges.emplace(std::make_pair(a, b), k).second) << "edge twice";
  });
  for (const Ids &t : o.tops)
    for (std::size_t i = 0; i < t.size(); ++i)
      for (std::size_t j = i + 1; j < t.size(); ++j) {
        auto &k = want_edges[{t[i], t[j]}];
        k += t.size() == 3;
      }
  EXPECT_EQ(edges, want_edges);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> marked_edges;
  std::uint32_t last_a = 0;
  m.for_each_edge(2, marks, [&](std::uint32_t a, std::uint32_t b, std::size_t k) {
    EXPECT_LT(a, b);
    EXPECT_LE(last_a, a) << "a ascending";
    last_a = a;
    EXPECT_TRUE(marked_edges.emplace(std::make_pair(a, b), k).second) << "edge twice (marks)";
  });
  EXPECT_EQ(marked_edges, want_edges);

  // The stored rings (Live::mesh_with_rings, and with both indices): each ring as the pass
  // over the star gives it, in the same order; each edge's count of tops as the oracle's; the
  // whole-mesh passes reading them give the same calls in the same order as without them.
  const MeshView wr = live.mesh_with_rings(), both = live.mesh_with(true, true);
  ASSERT_TRUE(wr.has_rings() && !wr.has_adjacency() && both.has_rings() && both.has_adjacency());
  for (std::uint32_t v = 0; v < m.vertex_slots(); ++v) {
    Ids by_star;
    if (o.alive[v]) m.for_each_neighbour(v, marks, [&](std::uint32_t w) { by_star.push_back(w); });
    EXPECT_EQ(wr.ring(v).to_vector(), by_star) << "stored ring of " << v;
    EXPECT_EQ(both.ring(v).to_vector(), by_star) << "stored ring of " << v << " (both indices)";
    Ids by_rings;
    wr.for_each_neighbour(v, marks, [&](std::uint32_t w) { by_rings.push_back(w); });
    EXPECT_EQ(by_rings, by_star);
    const topoplex::SimplexView tops = wr.ring_tops(v);
    ASSERT_EQ(tops.size(), by_star.size());
    for (std::size_t i = 0; i < by_star.size(); ++i)
      EXPECT_EQ(tops[i], o.holding({v, by_star[i]}).size()) << "tops at edge " << v << "-" << by_star[i];
  }
  using Call = std::tuple<std::uint32_t, std::uint32_t, std::size_t>;
  std::vector<std::pair<std::uint32_t, Ids>> ring_calls, stored_ring_calls;
  m.for_each_ring(marks, [&](std::uint32_t v, topoplex::SimplexView r) { ring_calls.emplace_back(v, r.to_vector()); });
  wr.for_each_ring(marks, [&](std::uint32_t v, topoplex::SimplexView r) { stored_ring_calls.emplace_back(v, r.to_vector()); });
  EXPECT_EQ(stored_ring_calls, ring_calls);
  for (std::uint32_t p = 1; p <= 6; ++p) {
    std::vector<Call> calls, stored_calls;
    m.for_each_edge(p, marks, [&](std::uint32_t a, std::uint32_t b, std::size_t k) { calls.emplace_back(a, b, k); });
    wr.for_each_edge(p, marks, [&](std::uint32_t a, std::uint32_t b, std::size_t k) { stored_calls.emplace_back(a, b, k); });
    EXPECT_EQ(stored_calls, calls) << "for_each_edge(" << p << ") with the rings";
  }

  std::multiset<std::pair<Ids, Ids>> pairs, want_pairs;
  m.for_each_adjacent_triangle_pair(scratch, [&](TopRef t, TopRef u) {
    pairs.emplace(top_set(m, t), top_set(m, u));
  });
  for (const Ids &t : o.tops)
    for (const Ids &u : o.tops) {
      if (t.size() != 3 || u.size() != 3 || t == u) continue;
      Ids common;
      std::set_intersection(t.begin(), t.end(), u.begin(), u.end(), std::back_inserter(common));
      if (common.size() == 2) want_pairs.emplace(t, u);
    }
  EXPECT_EQ(pairs, want_pairs);
}

// A random complex on n vertices: simplices of dimension 1..max_dim drawn from a small vertex
// pool (so they meet along non-manifold faces), plus an isolated vertex.
topoplex::Complex random_complex(std::mt19937 &rng, std::uint32_t n, std::uint32_t max_dim) {
  std::vector<Ids> simplices;
  const std::size_t count = 3 + rng() % 8;
  for (std::size_t i = 0; i < count; ++i) {
    Ids pool(n - 1);
    for (std::uint32_t v = 0; v + 1 < n; ++v) pool[v] = v;
    std::shuffle(pool.begin(), pool.end(), rng);
    const std::size_t k = 2 + rng() % std::min<std::size_t>(max_dim, n - 2);
    simplices.emplace_back(pool.begin(), pool.begin() + k);
  }
  simplices.push_back({n - 1});
  std::vector<double> xyz(3 * n);
  for (double &x : xyz) x = double(rng() % 1000) / 10;
  return topoplex_tests::complex_of(n, simplices, xyz);
}

// Cyclic groups in a numbering-free form: each group its tops' sorted vertex sets in order, a
// cycle rotated to its least set, an unoriented group read in its lesser direction; groups
// sorted. Oriented groups keep their direction: both sides must list them counter-clockwise.
struct Group {
  std::vector<Ids> items;
  bool closed, oriented;
  bool operator<(const Group &o) const {
    return std::tie(items, closed, oriented) < std::tie(o.items, o.closed, o.oriented);
  }
  bool operator==(const Group &o) const {
    return items == o.items && closed == o.closed && oriented == o.oriented;
  }
};
Group canonical(std::vector<Ids> items, bool closed, bool oriented) {
  if (closed) std::rotate(items.begin(), std::min_element(items.begin(), items.end()), items.end());
  if (!oriented) {
    std::vector<Ids> back = items;
    std::reverse(back.begin() + (closed ? 1 : 0), back.end());
    items = std::min(items, back);
  }
  return {items, closed, oriented};
}
std::vector<Ids> sorted_rows(std::vector<Ids> rows) {
  std::sort(rows.begin(), rows.end());
  return rows;
}
std::vector<Group> groups_of(const MeshView &m, const topoplex::TopFans &f) {
  std::vector<Group> out;
  for (std::size_t k = 0; k < f.size(); ++k) {
    std::vector<Ids> items;
    for (TopRef t : f[k]) items.push_back(top_set(m, t));
    out.push_back(canonical(items, f.closed(k), f.oriented(k)));
  }
  std::sort(out.begin(), out.end());
  return out;
}
std::vector<Group> groups_of(const topoplex::Live &live, const topoplex::HandleFans &f) {
  std::vector<Group> out;
  for (std::size_t k = 0; k < f.size(); ++k) {
    std::vector<Ids> items;
    for (std::size_t i = 0; i < f[k].size(); ++i) items.push_back(live.vertices(f[k][i]));
    out.push_back(canonical(items, f.closed(k), f.oriented(k)));
  }
  std::sort(out.begin(), out.end());
  return out;
}

// MeshView's inline fans and radial groups equal the library's (Live::fans_around,
// Live::around_edge, tpx_cyclic) on random non-manifold 2- and 3-complexes, with random
// windings, before and after contractions and removals; the fans of a closed disc are one
// oriented cycle.
TEST(MeshView, FansAndRadialGroupsEqualTheLibrarysOnRandomComplexes) {
  std::mt19937 rng(20261203);
  std::size_t fans = 0, oriented = 0, radial = 0;
  for (int round = 0; round < 80; ++round) {
    const std::uint32_t n = 6 + rng() % 7, dim = 2 + round % 2;
    topoplex::Live live(random_complex(rng, n, dim));
    topoplex::TopFans mine;
    topoplex::HandleFans theirs;
    for (int edit = 0; edit < 6; ++edit) {
      const MeshView m = live.mesh();
      const Oracle o(live);
      for (std::uint32_t v = 0; v < o.alive.size(); ++v) {
        if (!o.alive[v]) continue;
        if (live.dimension() <= 2) {
          m.fans_around(v, mine);
          live.fans_around(live.locate({v}), theirs);
          ASSERT_EQ(groups_of(m, mine), groups_of(live, theirs)) << "fans at " << v;
          fans += mine.size();
          for (std::size_t k = 0; k < mine.size(); ++k) oriented += mine.oriented(k) && mine[k].size() > 1;
          for (std::uint32_t w = v + 1; w < o.alive.size() && live.dimension() == 2; ++w) {
            if (!o.alive[w] || o.holding({v, w}).empty()) continue;
            m.around_edge(v, w, 2, mine);  // the triangles at an edge: one group, no order
            live.around_edge(live.locate({v, w}), 2, theirs);
            ASSERT_EQ(mine.size(), 1u) << "triangles around " << v << "," << w;
            ASSERT_EQ(theirs.size(), 1u);
            EXPECT_EQ(mine.closed(0), theirs.closed(0));
            std::vector<Ids> a, b;
            for (TopRef t : mine[0]) a.push_back(top_set(m, t));
            for (std::size_t i = 0; i < theirs[0].size(); ++i) b.push_back(live.vertices(theirs[0][i]));
            EXPECT_EQ(sorted_rows(a), sorted_rows(b)) << "triangles around " << v << "," << w;
          }
        }
        if (live.dimension() == 3)
          for (std::uint32_t w = v + 1; w < o.alive.size(); ++w) {
            if (!o.alive[w] || o.holding({v, w}).empty()) continue;
            m.around_edge(v, w, 3, mine);
            live.around_edge(live.locate({v, w}), 3, theirs);
            ASSERT_EQ(groups_of(m, mine), groups_of(live, theirs)) << "around " << v << "," << w;
            radial += mine.size();
          }
      }
      if (o.tops.empty()) break;
      const Ids &t = o.tops[rng() % o.tops.size()];
      try {
        if (rng() % 3 == 0) live.remove_top(t);
        else live.contract(t[0], t[1], topoplex::ContractMode::Free);
      } catch (const topoplex::Error &) {
      }
    }
  }
  EXPECT_GT(fans, 500u);
  EXPECT_GT(oriented, 20u);
  EXPECT_GT(radial, 500u);
}

// Vertex 0 in the middle of six triangles wound counter-clockwise.
topoplex::Live disc() {
  std::vector<std::uint32_t> ids;
  std::vector<std::size_t> offsets{0};
  for (std::uint32_t i = 1; i <= 6; ++i) {
    ids.insert(ids.end(), {0, i, i % 6 + 1});
    offsets.push_back(ids.size());
  }
  return topoplex::Live(topoplex::Complex::from_arrays(7, ids, offsets, {}, 0));
}

TEST(MeshView, ClosedDiscIsOneOrientedCycle) {
  topoplex::Live live = disc();
  const MeshView m = live.mesh();
  topoplex::TopFans f;
  m.fans_around(0, f);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_TRUE(f.closed(0));
  EXPECT_TRUE(f.oriented(0));
  ASSERT_EQ(f[0].size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) {  // each triangle's last vertex is the next one's second
    const auto a = m.vertices(f[0][i]), b = m.vertices(f[0][(i + 1) % 6]);
    EXPECT_EQ(a[2], b[1]);
  }
  m.fans_around(1, f);  // a boundary vertex: one open fan of two triangles
  ASSERT_EQ(f.size(), 1u);
  EXPECT_FALSE(f.closed(0));
  EXPECT_EQ(f[0].size(), 2u);
}

// A pure triangle mesh, so the rings' counts are triangle counts and for_each_edge(2) reads
// them: the disc's six spokes are held by two triangles each, its rim edges by one.
TEST(MeshView, DiscRingsHoldTwoTrianglesAtSpokesAndOneAtTheRim) {
  topoplex::Live live = disc();
  const MeshView m = live.mesh_with_rings();
  EXPECT_EQ(sorted(m.ring(0).to_vector()), (Ids{1, 2, 3, 4, 5, 6}));
  for (std::uint32_t k : m.ring_tops(0)) EXPECT_EQ(k, 2u);
  EXPECT_EQ(sorted(m.ring(1).to_vector()), (Ids{0, 2, 6}));
  std::size_t spokes = 0, rim = 0;
  topoplex::NeighbourMarks marks;
  m.for_each_edge(2, marks, [&](std::uint32_t a, std::uint32_t, std::size_t k) {
    (a == 0 ? spokes : rim) += 1;
    EXPECT_EQ(k, a == 0 ? 2u : 1u);
  });
  EXPECT_EQ(spokes, 6u);
  EXPECT_EQ(rim, 6u);
  std::mt19937 rng(7);
  ASSERT_NO_FATAL_FAILURE(check(live, rng));
}

TEST(MeshView, RandomNonManifoldComplexesBeforeAndAfterEdits) {
  std::mt19937 rng(20261202);
  for (int round = 0; round < 60; ++round) {
    const std::uint32_t n = 6 + rng() % 8;
    topoplex::Live live(random_complex(rng, n, 2 + round % 5));  // dimensions 2..6
    if (round % 2) live.keep_adjacency();  // check() then reads the repaired facet adjacency
    ASSERT_NO_FATAL_FAILURE(check(live, rng));
    for (int edit = 0; edit < 12; ++edit) {
      const Oracle o(live);
      std::vector<std::uint32_t> vs;
      for (std::uint32_t v = 0; v < o.alive.size(); ++v)
        if (o.alive[v]) vs.push_back(v);
      try {
        switch (rng() % 5) {
          case 0: {  // insert a random simplex (refused when present or absorbed by a top)
            std::shuffle(vs.begin(), vs.end(), rng);
            vs.resize(std::min<std::size_t>(vs.size(), 2 + rng() % 3));
            live.insert_top(vs);
            break;
          }
          case 1:
            if (!o.tops.empty()) live.remove_top(o.tops[rng() % o.tops.size()]);
            break;
          case 2:
          case 3: {  // contract an edge of a top, link-checked or free
            if (o.tops.empty()) break;
            const Ids &t = o.tops[rng() % o.tops.size()];
            live.contract(t[0], t[1], rng() % 2 ? topoplex::ContractMode::Free
                                                : topoplex::ContractMode::PreserveTopology);
            break;
          }
          default:  // move a vertex: the MeshView of before stays valid
            if (!vs.empty()) live.set_coords(vs[rng() % vs.size()], {1.5, -2.0, 0.25});
        }
      } catch (const topoplex::Error &) {
        // A refused edit leaves the complex unchanged; the check below still holds.
      }
      ASSERT_NO_FATAL_FAILURE(check(live, rng)) << "round " << round << " edit " << edit;
    }
    live.compact();
    ASSERT_NO_FATAL_FAILURE(check(live, rng)) << "round " << round << " after compact";
  }
}

// Live::from_file gives the live complex Live(Complex::from_file) gives: the same slots,
// windings and coordinates, whether the file is read straight into it (a plain listing) or
// normalised first (a repeated triangle, which the complex absorbs); a bad file is the same error.
TEST(MeshView, FromFileEqualsLiveOfTheComplex) {
  const std::string data = TPX_TEST_DATA_DIR;
  const std::string repeated = testing::TempDir() + "tpx_repeated_triangle.off";
  {
    std::ofstream f(repeated);
    f << "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n1 1 1\n3 0 1 2\n3 2 1 3\n3 0 1 2\n";
  }
  for (const std::string &path :
       {data + "/../../cpp_wrapper/data/grid_fin.off", data + "/tet_triangle_wire.simplices",
        repeated}) {
    const topoplex::Live direct = topoplex::Live::from_file(path);
    const topoplex::Live via(topoplex::Complex::from_file(path));
    direct.validate();
    ASSERT_EQ(direct.vertex_slots(), via.vertex_slots()) << path;
    const MeshView a = direct.mesh(), b = via.mesh();
    for (std::uint32_t p = 1; p <= 15; ++p) {
      ASSERT_EQ(a.slots(p), b.slots(p)) << path << " dimension " << p;
      for (std::uint32_t s = 0; s < a.slots(p); ++s)
        EXPECT_EQ(a.vertices(TopRef(p, s)).to_vector(), b.vertices(TopRef(p, s)).to_vector());
    }
    ASSERT_EQ(direct.coord_dim(), via.coord_dim());
    const auto xa = direct.all_coords(), xb = via.all_coords();
    EXPECT_TRUE(std::equal(xa.begin(), xa.end(), xb.begin(), xb.end())) << path;
    for (std::uint32_t v = 0; v < a.vertex_slots(); ++v) {
      std::vector<TopRef> sa(a.star(v).begin(), a.star(v).end()),
          sb(b.star(v).begin(), b.star(v).end());
      std::sort(sa.begin(), sa.end());
      std::sort(sb.begin(), sb.end());
      EXPECT_EQ(sa, sb) << path << " star of " << v;
    }
  }
  std::remove(repeated.c_str());
  for (const char *bad : {"/garbage.off", "/repeated_vertex.simplices", "/missing.off"}) {
    TpxStatus direct = TPX_STATUS_OK, via = TPX_STATUS_OK;
    std::string what_direct, what_via;
    try {
      topoplex::Live::from_file(data + bad);
    } catch (const topoplex::Error &e) {
      direct = e.status();
      what_direct = e.what();
    }
    try {
      topoplex::Complex::from_file(data + bad);
    } catch (const topoplex::Error &e) {
      via = e.status();
      what_via = e.what();
    }
    EXPECT_NE(direct, TPX_STATUS_OK) << bad;
    EXPECT_EQ(direct, via) << bad;
    EXPECT_EQ(what_direct, what_via) << bad;
  }
}

// Reads from several threads at once: one MeshView, const pointers only.
TEST(MeshView, OneViewReadFromFourThreads) {
  std::mt19937 rng(7);
  topoplex::Live live(random_complex(rng, 12, 4));
  const MeshView m = live.mesh();
  std::vector<std::size_t> sums(4);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < sums.size(); ++i)
    threads.emplace_back([&, i] {
      Ids ring;
      for (std::uint32_t v = 0; v < m.vertex_slots(); ++v)
        if (m.is_vertex(v)) {
          m.neighbours(v, ring);
          sums[i] += ring.size();
        }
    });
  for (auto &t : threads) t.join();
  std::size_t want = 0;
  for (std::uint32_t v = 0; v < live.vertex_slots(); ++v)
    if (live.is_vertex(v)) want += live.relation({v}, 0).size();
  for (std::size_t s : sums) EXPECT_EQ(s, want);
}

}  // namespace
