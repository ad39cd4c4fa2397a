// topoplex_bench_surface FILE.off: triangle meshes, Topoplex next to OpenMesh's TriMesh and
// CGAL's Surface_mesh (see bench_common.hpp for names, counters and the cross-check).
//
// Ops, each over all elements of the mesh:
//   load   read the file into the library's structure (Topoplex: tpx_complex_from_file +
//          tpx_structure_build; OpenMesh: IO::read_mesh; CGAL: IO::read_OFF)
//   build  the structure from the same in-memory triangle soup (the file's faces, oriented):
//          add_vertex/add_face after reserve() for the peers, tpx_complex_from_arrays +
//          tpx_structure_build for Topoplex
//   VF     R_{0,2} of every vertex (OpenMesh vf_range, CGAL faces_around_target)
//   VV     R_{0,0} of every vertex (vv_range, vertices_around_target)
//   FF     R_{2,2} of every triangle, the triangles sharing an edge (ff_range, faces_around_face)
//   stats  whole-mesh pass (issue 13): valence histogram + boundary and non-manifold edge lists
//          (OpenMesh valence/is_boundary; Topoplex tpx_degree per handle, or `stats_batch`: two
//          tpx_degree_batch calls, counts only)
//   FF_index  whole-mesh pass: every face's neighbour faces as indices (ff_range + idx();
//          tpx_related per face handle; `FF_index_batch`: one tpx_related_batch, then the pass
//          over its CSR; `FF_index_view`: the lent view, see below)
//   <op>_batch  VF/VV/FF as one tpx_related_batch over every simplex
//   <op>_view   VF/VV/FF/FF_index read inline from a lent relation view (bench_common.hpp)
//   tpx_mesh     VF/VV/FF on the mesh (the live complex) read inline through MeshView, per
//          element, nothing prebuilt; `tpx_mesh_adj`: FF read from the mesh's facet adjacency
//          (tpx_live_adjacency, built before the timing; its bytes in `index_bytes`);
//          `tpx_mesh_rings`: VV read from the mesh's stored one-rings (tpx_live_rings, likewise)
// The peers' heap includes their vertex coordinates (OpenMesh 3 floats, CGAL 3 doubles per
// vertex; counter `geometry_bytes`), Topoplex's structures hold none.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "bench_halfedge.hpp"
#include "topoplex.hpp"

namespace {

using namespace tpxbench;

// The file's triangles as it orders them (orientation kept, which add_face needs; Topoplex's
// own top simplices are sorted) and its vertex coordinates. Returns an error text or "".
std::string read_off_soup(const std::string& path, Soup* soup) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot open " + path;
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  std::vector<std::string> lines;
  {
    std::istringstream ls(text);
    std::string line;
    while (std::getline(ls, line)) {
      const size_t hash = line.find('#');
      if (hash != std::string::npos) line.resize(hash);
      if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
    }
  }
  size_t li = 0;
  if (lines.empty() || lines[0].compare(0, 3, "OFF") != 0) return path + ": not an OFF file";
  std::istringstream head(lines[0].substr(3));
  size_t nv = 0, nf = 0;
  if (!(head >> nv >> nf)) {
    if (lines.size() < 2) return path + ": no counts";
    std::istringstream counts(lines[1]);
    if (!(counts >> nv >> nf)) return path + ": bad counts";
    li = 2;
  } else {
    li = 1;
  }
  if (lines.size() < li + nv + nf) return path + ": truncated";
  soup->n_vertices = uint32_t(nv);
  soup->coord_dim = 3;
  soup->coords.reserve(3 * nv);
  for (size_t i = 0; i < nv; ++i) {
    const char* p = lines[li + i].c_str();
    char* end = nullptr;
    for (int k = 0; k < 3; ++k) {
      soup->coords.push_back(std::strtod(p, &end));
      if (end == p) return path + ": bad vertex line " + std::to_string(i);
      p = end;
    }
  }
  soup->ids.reserve(3 * nf);
  for (size_t i = 0; i < nf; ++i) {
    const char* p = lines[li + nv + i].c_str();
    char* end = nullptr;
    const unsigned long n = std::strtoul(p, &end, 10);
    if (n != 3) return path + ": face " + std::to_string(i) + " is not a triangle";
    uint32_t t[3];
    for (int k = 0; k < 3; ++k) {
      p = end;
      t[k] = uint32_t(std::strtoul(p, &end, 10));
      if (end == p || t[k] >= nv) return path + ": bad face line " + std::to_string(i);
    }
    soup->add(t, 3);
  }
  return "";
}

std::unique_ptr<OMesh> openmesh_load(const std::string& path) {
  auto m = std::make_unique<OMesh>();
  if (!OpenMesh::IO::read_mesh(*m, path)) return nullptr;
  return m;
}

std::unique_ptr<SMesh> cgal_load(const std::string& path) {
  auto m = std::make_unique<SMesh>();
  if (!CGAL::IO::read_OFF(path, *m)) return nullptr;
  return m;
}

// The peers' walks. Each counts the elements its circulator yields.
// What the circulator `around(x)` yields over every x of `elements`.
template <class Elements, class Around>
uint64_t count_around(Elements elements, Around around) {
  uint64_t n = 0;
  for (auto x : elements)
    for (auto y : around(x)) {
      (void)y;
      ++n;
    }
  return n;
}
uint64_t om_vf(const OMesh& m) {
  return count_around(m.vertices(), [&](auto v) { return m.vf_range(v); });
}
uint64_t om_vv(const OMesh& m) {
  return count_around(m.vertices(), [&](auto v) { return m.vv_range(v); });
}
uint64_t om_ff(const OMesh& m) {
  return count_around(m.faces(), [&](auto f) { return m.ff_range(f); });
}
uint64_t sm_vf(const SMesh& m) {
  uint64_t n = 0;
  for (auto v : m.vertices()) {
    const auto h = m.halfedge(v);
    if (h == SMesh::null_halfedge()) continue;
    for (auto f : CGAL::faces_around_target(h, m)) n += f != SMesh::null_face() ? 1 : 0;
  }
  return n;
}
uint64_t sm_vv(const SMesh& m) {
  uint64_t n = 0;
  for (auto v : m.vertices()) {
    const auto h = m.halfedge(v);
    if (h == SMesh::null_halfedge()) continue;
    for (auto u : CGAL::vertices_around_target(h, m)) {
      (void)u;
      ++n;
    }
  }
  return n;
}
uint64_t sm_ff(const SMesh& m) {
  uint64_t n = 0;
  for (auto f : m.faces())
    for (auto g : CGAL::faces_around_face(m.halfedge(f), m)) n += g != SMesh::null_face() ? 1 : 0;
  return n;
}

// Whole-mesh passes of issue 13, as an application writes them. `stats`: the valence histogram,
// the boundary edges (one triangle) and the non-manifold edges (three or more) as index lists;
// `FF_index`: every face's neighbour faces as indices, summed. Each returns a checksum of what
// every library must agree on (counts, not indices: the libraries number faces differently).
struct Stats {
  std::vector<uint32_t> hist = std::vector<uint32_t>(64, 0), boundary, nonmanifold;

  // Empties the results, keeping their memory for the next pass.
  void clear() {
    std::fill(hist.begin(), hist.end(), 0);
    boundary.clear();
    nonmanifold.clear();
  }
  // A vertex of valence `k` into the histogram.
  void valence(size_t k) {
    if (k >= hist.size()) hist.resize(k + 1, 0);
    ++hist[k];
  }
  // Edge `e`, in `n` triangles: boundary with one, non-manifold with three or more.
  void edge(uint32_t e, size_t n) {
    if (n == 1) boundary.push_back(e);
    if (n > 2) nonmanifold.push_back(e);
  }
  uint64_t checksum() const {
    uint64_t c = 1000003ull * boundary.size() + 7919ull * nonmanifold.size();
    for (size_t k = 0; k < hist.size(); ++k) c += uint64_t(hist[k]) * (k + 1) * (k + 7);
    return c;
  }
};
// Times `pass(st)`, one whole stats pass into a cleared `st`, and checks its checksum for `lib`.
template <class Pass>
void time_stats(benchmark::State& state, const std::string& lib, uint64_t elements, Pass pass) {
  Stats st;
  uint64_t sum = 0;
  for (auto _ : state) {
    st.clear();
    pass(st);
    sum = st.checksum();
    benchmark::DoNotOptimize(sum);
  }
  check_count(state, "stats", lib, sum);
  set_elements(state, elements);
}
// Times every vertex's one-ring through `m`'s for_each_neighbour (from the stars, or the stored
// rings when `m` has them) and checks the neighbour count for `lib`.
void time_neighbours(benchmark::State& state, const topoplex::MeshView& m, const std::string& lib) {
  topoplex::NeighbourMarks marks;
  uint64_t count = 0, sum = 0;
  for (auto _ : state) {
    count = 0;
    for (uint32_t v = 0; v < m.vertex_slots(); ++v)
      m.for_each_neighbour(v, marks, [&](uint32_t w) {
        sum += w;
        ++count;
      });
    benchmark::DoNotOptimize(sum);
  }
  check_count(state, "VV", lib, count);
  set_elements(state, count);
}
uint64_t om_stats(const OMesh& m) {
  Stats st;  // OpenMesh holds no non-manifold edge
  for (auto v : m.vertices()) st.valence(m.valence(v));
  for (auto e : m.edges())
    if (m.is_boundary(e)) st.boundary.push_back(uint32_t(e.idx()));
  benchmark::DoNotOptimize(st.boundary.data());
  return st.checksum();
}
uint64_t om_ff_index(const OMesh& m) {
  uint64_t n = 0, sum = 0;
  for (auto f : m.faces())
    for (auto g : m.ff_range(f)) {
      sum += uint32_t(g.idx());
      ++n;
    }
  benchmark::DoNotOptimize(sum);
  return n;
}

struct Built : BuiltWalk {
  std::vector<uint32_t> triangles;
};

}  // namespace

int main(int argc, char** argv) {
  const std::string path = init(&argc, argv, "FILE.off");
  const auto cx = load_complex(path);
  uint32_t d = 0, n = 0;
  tpx_check(tpx_complex_dimension(cx.get(), &d), "tpx_complex_dimension");
  tpx_check(tpx_complex_vertex_count(cx.get(), &n), "tpx_complex_vertex_count");
  size_t tris = 0;
  tpx_check(tpx_complex_top_count(cx.get(), 2, &tris), "tpx_complex_top_count");
  if (d != 2) {
    std::fprintf(stderr, "%s: a triangle mesh has dimension 2, this complex has %u\n", path.c_str(), d);
    return 2;
  }

  static Soup soup;
  const std::string bad = read_off_soup(path, &soup);
  if (!bad.empty()) {
    std::fprintf(stderr, "%s\n", bad.c_str());
    return 2;
  }
  if (soup.size() != tris || soup.n_vertices != n) {
    std::fprintf(stderr, "%s: Topoplex reads %u vertices and %zu triangles, the file lists %u and %zu "
                 "(repeated triangles?): the libraries would not see the same complex\n",
                 path.c_str(), n, tris, soup.n_vertices, soup.size());
    return 2;
  }

  // The number of simplices of all dimensions (the `elements` of load/build), from the IG.
  const uint64_t simplices = soup_simplex_count(soup);
  const double om_geometry = double(n) * sizeof(OMesh::Point);
  const double sm_geometry = double(n) * sizeof(K::Point_3);

  // Which peers hold this mesh as the file gives it (manifold, consistently oriented).
  std::string why;
  const bool have_om = openmesh_from_soup(soup, &why) != nullptr;
  if (!have_om) note("openmesh skipped: " + why);
  const bool have_sm = cgal_from_soup(soup, &why) != nullptr;
  if (!have_sm) note("cgal_sm skipped: " + why);

  const std::vector<Kind> kinds = kinds_that_build(soup);

  using OMake = std::function<std::unique_ptr<OMesh>()>;
  using SMake = std::function<std::unique_ptr<SMesh>()>;
  const OMake om_build = [] {
    std::string w;
    return openmesh_from_soup(soup, &w);
  };
  const SMake sm_build = [] {
    std::string w;
    return cgal_from_soup(soup, &w);
  };
  const OMake om_load = [path] { return openmesh_load(path); };
  const SMake sm_load = [path] { return cgal_load(path); };

  // `op` (load or build) for the peers present, each making its mesh with its own maker.
  const auto add_peer_builds = [&](const char* op, const OMake& om_make, const SMake& sm_make) {
    if (have_om)
      add(op, "openmesh", Unit::Build,
          [=](benchmark::State& s) { time_peer_build<OMesh>(s, simplices, om_make, "mesh", om_geometry); });
    if (have_sm)
      add(op, "cgal_sm", Unit::Build,
          [=](benchmark::State& s) { time_peer_build<SMesh>(s, simplices, sm_make, "mesh", sm_geometry); });
  };
  add_peer_builds("load", om_load, sm_load);
  for (const auto& k : kinds) add_tpx_load(path, k, simplices);
  add_peer_builds("build", om_build, sm_build);
  for (const auto& k : kinds) add_tpx_build(soup, k, simplices);

  // Walks, library by library so that each builds its structure once (Slot).
  if (have_om) {
    add_walk<OMesh>("VF", "openmesh", om_build, om_vf);
    add_walk<OMesh>("VV", "openmesh", om_build, om_vv);
    add_walk<OMesh>("FF", "openmesh", om_build, om_ff);
  }
  if (have_om) {
    // Elements: vertices + edges visited (the checksum is not a count).
    add("stats", "openmesh", Unit::Walk, [=](benchmark::State& state) {
      const OMesh& m = slot().get<OMesh>("openmesh", om_build);
      uint64_t sum = 0;
      for (auto _ : state) {
        sum = om_stats(m);
        benchmark::DoNotOptimize(sum);
      }
      check_count(state, "stats", "openmesh", sum);
      set_elements(state, m.n_vertices() + m.n_edges());
    });
    add_walk<OMesh>("FF_index", "openmesh", om_build, om_ff_index);
  }
  if (have_sm) {
    add_walk<SMesh>("VF", "cgal_sm", sm_build, sm_vf);
    add_walk<SMesh>("VV", "cgal_sm", sm_build, sm_vv);
    add_walk<SMesh>("FF", "cgal_sm", sm_build, sm_ff);
  }
  for (const auto& k : kinds) {
    const std::string lib = "tpx_" + k.name;
    const std::function<std::unique_ptr<Built>()> make = [k] {
      auto b = build_walk<Built>(soup, k.id);
      b->triangles = simplices_of(b->s.get(), 2);
      return b;
    };
    struct Op {
      const char* name;
      uint32_t p, q;
    };
    for (const Op& op : {Op{"VF", 0, 2}, Op{"VV", 0, 0}, Op{"FF", 2, 2}}) {
      add(op.name, lib, Unit::Walk, [=](benchmark::State& state) {
        const Built& b = slot().get<Built>(lib, make);
        const auto& rows = op.p == 0 ? b.vertices : b.triangles;
        Walker w;
        uint64_t count = 0;
        for (auto _ : state) {
          count = walk(state, b.s.get(), rows, op.p, {op.q}, w);
          benchmark::DoNotOptimize(count);
        }
        check_count(state, op.name, lib, count);
        set_elements(state, count);
      });
      // The same walk as one batch call (tpx_related_batch: CSR over every simplex), buffers
      // reused across iterations: what a whole-mesh pass costs without per-call overhead.
      const std::string batch = std::string(op.name) + "_batch";
      add(batch, lib, Unit::Walk, [=](benchmark::State& state) {
        const Built& b = slot().get<Built>(lib, make);
        const uint32_t n = uint32_t((op.p == 0 ? b.vertices.size() : b.triangles.size()) / (op.p + 1));
        std::vector<uint32_t> idx(n), offsets(n + 1), ids(16 * size_t(n) + 16);
        for (uint32_t i = 0; i < n; ++i) idx[i] = i;
        uint64_t count = 0;
        for (auto _ : state) {
          size_t len = 0;
          const TpxStatus st = tpx_related_batch(b.s.get(), op.p, idx.data(), n, op.q, TPX_ORDER_NATURAL,
                                                 offsets.data(), ids.data(), ids.size(), &len);
          if (st != TPX_STATUS_OK) fail(state, "tpx_related_batch failed: " + tpx_message());
          count = len;
          benchmark::DoNotOptimize(ids.data());
        }
        check_count(state, batch, lib, count);
        set_elements(state, count);
      });
      add_view_walk(op.name, lib, [lib, make] { return slot().get<Built>(lib, make).s.get(); }, op.p, op.q);
    }
  }
  // The mesh (the live complex) walked per element inline through its lent arrays
  // (topoplex::MeshView): no library call per query and no prebuilt view, what an application
  // on the mesh does. VF: the triangles of each vertex's star; VV: its one-ring; FF: the tops
  // across each triangle's edges.
  {
    const std::string lib = "tpx_mesh";
    const std::function<std::unique_ptr<MeshBuilt>()> make = [] { return mesh_or_abort(soup); };
    add("VF", lib, Unit::Walk, [=](benchmark::State& state) {
      const topoplex::MeshView m(slot().get<MeshBuilt>(lib, make).arrays);
      uint64_t count = 0, sum = 0;
      for (auto _ : state) {
        count = 0;
        for (uint32_t v = 0; v < m.vertex_slots(); ++v)
          for (topoplex::TopRef t : m.star(v))
            if (t.dim() == 2) {
              sum += t.slot();
              ++count;
            }
        benchmark::DoNotOptimize(sum);
      }
      check_count(state, "VF", lib, count);
      set_elements(state, count);
    });
    add("VV", lib, Unit::Walk, [=](benchmark::State& state) {
      const topoplex::MeshView m(slot().get<MeshBuilt>(lib, make).arrays);
      time_neighbours(state, m, lib);
    });
    // VV read from the mesh's stored one-rings (tpx_live_rings, built before the timing, its
    // bytes in `index_bytes`): an index, so not what the per-call aims compare.
    add("VV", "tpx_mesh_rings", Unit::Walk, [=](benchmark::State& state) {
      const MeshBuilt& b = slot().get<MeshBuilt>(lib, make);
      TpxLiveRings rings{};
      if (tpx_live_rings(b.live.get(), &rings) != TPX_STATUS_OK) {
        state.SkipWithError("tpx_live_rings failed");
        return;
      }
      const topoplex::MeshView m(b.arrays, nullptr, &rings);
      time_neighbours(state, m, "tpx_mesh_rings");
      state.counters["index_bytes"] = double(rings.bytes);
    });
    for (const bool with_adj : {false, true}) {
      const std::string name = with_adj ? "tpx_mesh_adj" : lib;
      add("FF", name, Unit::Walk, [=](benchmark::State& state) {
        const MeshBuilt& b = slot().get<MeshBuilt>(lib, make);
        TpxLiveAdjacency adj{};
        if (with_adj && tpx_live_adjacency(b.live.get(), &adj) != TPX_STATUS_OK) {
          state.SkipWithError("tpx_live_adjacency failed");
          return;
        }
        const topoplex::MeshView m = with_adj ? topoplex::MeshView(b.arrays, adj) : topoplex::MeshView(b.arrays);
        uint64_t count = 0, sum = 0;
        for (auto _ : state) {
          count = 0;
          for (uint32_t f = 0; f < m.slots(2); ++f)
            m.for_each_adjacent_top(topoplex::TopRef(2, f), [&](topoplex::TopRef u) {
              sum += u.slot();
              ++count;
            });
          benchmark::DoNotOptimize(sum);
        }
        check_count(state, "FF", name, count);
        set_elements(state, count);
        if (with_adj) state.counters["index_bytes"] = double(adj.bytes);
      });
    }
  }
  // The whole-mesh passes through the handle API: one tpx_degree / tpx_related per handle
  // (`stats`, `FF_index`), and the same with one tpx_related_batch per relation (`_batch`).
  for (const auto& k : kinds) {
    const std::string lib = "tpx_" + k.name;
    const std::function<std::unique_ptr<Built>()> make = [k] {
      auto b = std::make_unique<Built>();
      b->s = build_or_abort(soup, k.id);
      return b;
    };
    add("stats", lib, Unit::Walk, [=](benchmark::State& state) {
      const Built& b = slot().get<Built>(lib + "_whole", make);
      size_t nv = 0, ne = 0;
      tpx_check(tpx_structure_count(b.s.get(), 0, &nv), "tpx_structure_count");
      tpx_check(tpx_structure_count(b.s.get(), 1, &ne), "tpx_structure_count");
      time_stats(state, lib, nv + ne, [&](Stats& st) {
        TpxSimplex h;
        size_t deg = 0;
        for (uint32_t i = 0; i < nv; ++i) {
          if (tpx_handle(b.s.get(), 0, i, &h) != TPX_STATUS_OK || tpx_degree(b.s.get(), &h, 0, &deg) != TPX_STATUS_OK)
            fail(state, "tpx_degree failed: " + tpx_message());
          st.valence(deg);
        }
        for (uint32_t i = 0; i < ne; ++i) {
          if (tpx_handle(b.s.get(), 1, i, &h) != TPX_STATUS_OK || tpx_degree(b.s.get(), &h, 2, &deg) != TPX_STATUS_OK)
            fail(state, "tpx_degree failed: " + tpx_message());
          st.edge(i, deg);
        }
      });
    });
    add("stats_batch", lib, Unit::Walk, [=](benchmark::State& state) {
      const Built& b = slot().get<Built>(lib + "_whole", make);
      size_t nv = 0, ne = 0;
      tpx_check(tpx_structure_count(b.s.get(), 0, &nv), "tpx_structure_count");
      tpx_check(tpx_structure_count(b.s.get(), 1, &ne), "tpx_structure_count");
      std::vector<uint32_t> vi(nv), ei(ne), deg(std::max(nv, ne));
      for (uint32_t i = 0; i < nv; ++i) vi[i] = i;
      for (uint32_t i = 0; i < ne; ++i) ei[i] = i;
      time_stats(state, lib, nv + ne, [&](Stats& st) {
        // Counts only (tpx_degree_batch): valences R_{0,0}, then triangles per edge R_{1,2}.
        if (tpx_degree_batch(b.s.get(), 0, vi.data(), nv, 0, deg.data()) != TPX_STATUS_OK)
          fail(state, "tpx_degree_batch failed: " + tpx_message());
        for (size_t i = 0; i < nv; ++i) st.valence(deg[i]);
        if (tpx_degree_batch(b.s.get(), 1, ei.data(), ne, 2, deg.data()) != TPX_STATUS_OK)
          fail(state, "tpx_degree_batch failed: " + tpx_message());
        for (uint32_t i = 0; i < ne; ++i) st.edge(i, deg[i]);
      });
    });
    // FF_index as one tpx_related_batch into the caller's CSR, then the same pass over it: the
    // index is built inside the timed loop (what a whole-mesh pass pays for it).
    add("FF_index_batch", lib, Unit::Walk, [=](benchmark::State& state) {
      const Built& b = slot().get<Built>(lib + "_whole", make);
      size_t nf = 0;
      tpx_check(tpx_structure_count(b.s.get(), 2, &nf), "tpx_structure_count");
      std::vector<uint32_t> fi(nf), off(nf + 1), ids(4 * nf + 16);
      for (uint32_t i = 0; i < nf; ++i) fi[i] = i;
      uint64_t n = 0, sum = 0;
      for (auto _ : state) {
        size_t len = 0;
        if (tpx_related_batch(b.s.get(), 2, fi.data(), nf, 2, TPX_ORDER_NATURAL, off.data(), ids.data(), ids.size(),
                              &len) != TPX_STATUS_OK)
          fail(state, "tpx_related_batch failed: " + tpx_message());
        n = 0;
        for (size_t f = 0; f < nf; ++f)
          for (uint32_t k = off[f]; k < off[f + 1]; ++k) {
            sum += ids[k];
            ++n;
          }
        benchmark::DoNotOptimize(sum);
      }
      check_count(state, "FF_index", lib, n);
      set_elements(state, n);
    });
    add_view_walk("FF_index", lib, [lib, make] { return slot().get<Built>(lib + "_whole", make).s.get(); }, 2, 2);
    add("FF_index", lib, Unit::Walk, [=](benchmark::State& state) {
      const Built& b = slot().get<Built>(lib + "_whole", make);
      size_t nf = 0;
      tpx_check(tpx_structure_count(b.s.get(), 2, &nf), "tpx_structure_count");
      std::vector<uint32_t> buf(256);
      uint64_t n = 0, sum = 0;
      for (auto _ : state) {
        n = 0;
        TpxSimplex h;
        size_t len = 0;
        for (uint32_t i = 0; i < nf; ++i) {
          if (tpx_handle(b.s.get(), 2, i, &h) != TPX_STATUS_OK ||
              tpx_related(b.s.get(), &h, 2, TPX_ORDER_NATURAL, buf.data(), buf.size(), &len) != TPX_STATUS_OK)
            fail(state, "tpx_related failed: " + tpx_message());
          for (size_t j = 0; j < len; ++j) sum += buf[j];
          n += len;
        }
        benchmark::DoNotOptimize(sum);
      }
      check_count(state, "FF_index", lib, n);
      set_elements(state, n);
    });
  }
  return run();
}
