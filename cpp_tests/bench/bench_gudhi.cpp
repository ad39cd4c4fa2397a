// topoplex_bench_gudhi FILE: any complex Topoplex reads (.off .obj .mesh .simplices), Topoplex
// next to GUDHI's Simplex_tree (see bench_common.hpp for names, counters and the cross-check).
//
// Ops:
//   build      from the complex's top simplices in memory: Simplex_tree::insert_simplex_and_subfaces
//              of each; tpx_complex_from_arrays + tpx_structure_build for Topoplex
//              (tpx_live_from_complex for the live complex, `tpx_iastar`)
//   cofaces_v  the whole star of every vertex: GUDHI cofaces_simplex_range(v, 0); Topoplex
//              R_{0,q} for q = 1..d (one tpx_relation call per q)
//   cofaces_e  the whole star of every edge: cofaces_simplex_range(e, 0); R_{1,q}, q = 2..d
// TOPOPLEX_BENCH_COFACES_STRIDE=k walks every k-th vertex and edge only (bench_common.hpp).
// GUDHI's star includes the simplex itself, which the count leaves out. The tree uses the
// lightest options GUDHI 3.7 offers (no filtration value, no key stored), so its heap is the
// tree alone; simplex handles of the vertices and edges are looked up before timing, as
// Topoplex's edge list is. The live complex (`tpx_iastar`, TOPOPLEX_BENCH_KINDS name `iastar`)
// numbers only its vertices densely: its walks take handles located before timing (tpx_locate)
// and call tpx_related_handles, one call per simplex and q as the other kinds' tpx_related.
#include <gudhi/Simplex_tree.h>

#include <algorithm>
#include <cstdio>
#include <utility>

#include "bench_common.hpp"

namespace {

using namespace tpxbench;

struct LightOptions {
  typedef Gudhi::linear_indexing_tag Indexing_tag;
  typedef int Vertex_handle;
  typedef float Filtration_value;
  typedef std::uint32_t Simplex_key;
  static const bool store_key = false;
  static const bool store_filtration = false;
  static const bool contiguous_vertices = false;
};
using Stree = Gudhi::Simplex_tree<LightOptions>;
using Sh = Stree::Simplex_handle;

Soup g_soup;

std::unique_ptr<Stree> gudhi_build(const Soup& soup) {
  auto st = std::make_unique<Stree>();
  std::vector<int> s;
  for (size_t i = 0; i < soup.size(); ++i) {
    s.assign(soup.ids.begin() + long(soup.offsets[i]), soup.ids.begin() + long(soup.offsets[i + 1]));
    st->insert_simplex_and_subfaces(s);
  }
  return st;
}

struct GudhiWalk {
  std::unique_ptr<Stree> st;
  std::vector<Sh> vertices, edges;
};

uint64_t star_count(Stree& st, const std::vector<Sh>& handles) {
  uint64_t n = 0;
  for (Sh sh : handles) {
    const auto star = st.cofaces_simplex_range(sh, 0);
    n += star.empty() ? 0 : star.size() - 1;
  }
  return n;
}

struct Built {
  StructurePtr s;
  std::vector<uint32_t> vertices, edges;
  uint32_t d = 0;
};

// The live complex and the handles of its vertices and edges (located before timing).
struct BuiltLive {
  LivePtr live;
  const TpxStructure* view = nullptr;  // borrowed from `live`
  std::vector<TpxSimplex> vertices, edges;
  uint32_t d = 0;
};

std::unique_ptr<BuiltLive> make_live() {
  auto b = std::make_unique<BuiltLive>();
  TpxStatus st = TPX_STATUS_OK;
  b->live = live_from_soup(g_soup, &st);
  tpx_check(st, "tpx_live_from_complex");
  tpx_check(tpx_live_structure(b->live.get(), &b->view), "tpx_live_structure");
  tpx_check(tpx_structure_dimension(b->view, &b->d), "tpx_structure_dimension");
  const auto locate = [&](const uint32_t* s, size_t len) {
    TpxSimplex h{};
    tpx_check(tpx_locate(b->view, s, len, &h), "tpx_locate");
    return h;
  };
  const size_t stride = cofaces_stride();
  for (uint32_t v = 0; v < g_soup.n_vertices; v += uint32_t(stride)) b->vertices.push_back(locate(&v, 1));
  if (b->d >= 1) {
    const auto edges = simplices_of(b->view, 1);
    for (size_t i = 0; i < edges.size(); i += 2 * stride) b->edges.push_back(locate(&edges[i], 2));
  }
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = init(&argc, argv, "FILE (.off .obj .mesh .simplices)");
  const auto cx = load_complex(path);
  g_soup = soup_of(cx.get());
  uint32_t d = 0;
  tpx_check(tpx_complex_dimension(cx.get(), &d), "tpx_complex_dimension");

  const uint64_t simplices = soup_simplex_count(g_soup);
  {
    const auto st = gudhi_build(g_soup);
    if (st->num_simplices() != simplices) {
      std::fprintf(stderr, "GUDHI holds %zu simplices, Topoplex %llu\n", size_t(st->num_simplices()),
                   static_cast<unsigned long long>(simplices));
      return 1;
    }
  }

  const std::vector<Kind> kinds = kinds_that_build(g_soup);
  bool live = live_from_env();
  if (live) {
    TpxStatus st = TPX_STATUS_OK;
    if (!live_from_soup(g_soup, &st)) {
      note("tpx_iastar skipped: " + tpx_message());
      live = false;
    }
  }

  add("build", "gudhi", Unit::Build, [simplices](benchmark::State& state) {
    time_peer_build<Stree>(state, simplices, [] { return gudhi_build(g_soup); }, "simplex tree");
  });
  for (const auto& k : kinds) add_tpx_build(g_soup, k, simplices);
  if (live) add_tpx_live_build(g_soup, simplices);

  const std::function<std::unique_ptr<GudhiWalk>()> gmake = [] {
    auto w = std::make_unique<GudhiWalk>();
    w->st = gudhi_build(g_soup);
    const uint32_t stride = cofaces_stride();
    for (uint32_t v = 0; v < g_soup.n_vertices; v += stride)
      w->vertices.push_back(w->st->find(std::vector<int>{int(v)}));
    // Edges in ascending lexicographic order, as Topoplex lists them, so a stride picks the same.
    std::vector<std::pair<std::pair<int, int>, Sh>> edges;
    for (Sh sh : w->st->skeleton_simplex_range(1))
      if (w->st->dimension(sh) == 1) {
        const auto vs = w->st->simplex_vertex_range(sh);  // decreasing
        auto it = vs.begin();
        const int hi = *it;
        const int lo = *++it;
        edges.push_back({{lo, hi}, sh});
      }
    std::sort(edges.begin(), edges.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (size_t i = 0; i < edges.size(); i += stride) w->edges.push_back(edges[i].second);
    return w;
  };
  for (const char* op : {"cofaces_v", "cofaces_e"}) {
    const bool vertices = op[8] == 'v';
    add_walk(op, "gudhi", gmake, [vertices](const GudhiWalk& w) {
      return star_count(*w.st, vertices ? w.vertices : w.edges);
    });
  }

  for (const auto& k : kinds) {
    const std::string lib = "tpx_" + k.name;
    const std::function<std::unique_ptr<Built>()> make = [k] {
      auto b = std::make_unique<Built>();
      b->s = build_or_abort(g_soup, k.id);
      tpx_check(tpx_structure_dimension(b->s.get(), &b->d), "tpx_structure_dimension");
      b->vertices = vertex_rows(g_soup.n_vertices);
      if (b->d >= 1) b->edges = simplices_of(b->s.get(), 1);
      return b;
    };
    for (const char* op : {"cofaces_v", "cofaces_e"}) {
      const uint32_t p = op[8] == 'v' ? 0 : 1;
      add(op, lib, Unit::Walk, [=](benchmark::State& state) {
        const Built& b = slot().get<Built>(lib, make);
        std::vector<uint32_t> qs;
        for (uint32_t q = p + 1; q <= b.d; ++q) qs.push_back(q);
        Walker w;
        uint64_t count = 0;
        for (auto _ : state) {
          count = walk(state, b.s.get(), p == 0 ? b.vertices : b.edges, p, qs, w, cofaces_stride());
          benchmark::DoNotOptimize(count);
        }
        check_count(state, op, lib, count);
        set_elements(state, count);
      });
    }
  }
  if (live) {
    const std::function<std::unique_ptr<BuiltLive>()> make = make_live;
    for (const char* op : {"cofaces_v", "cofaces_e"}) {
      const uint32_t p = op[8] == 'v' ? 0 : 1;
      add(op, "tpx_iastar", Unit::Walk, [=](benchmark::State& state) {
        const BuiltLive& b = slot().get<BuiltLive>("tpx_iastar", make);
        std::vector<uint32_t> qs;
        for (uint32_t q = p + 1; q <= b.d; ++q) qs.push_back(q);
        Walker w;
        uint64_t count = 0;
        for (auto _ : state) {
          count = walk_handles(state, b.view, p == 0 ? b.vertices : b.edges, qs, w);
          benchmark::DoNotOptimize(count);
        }
        check_count(state, op, "tpx_iastar", count);
        set_elements(state, count);
      });
    }
  }
  return run();
}
