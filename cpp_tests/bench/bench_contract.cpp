// topoplex_bench_contract K: link-checked edge contractions per second on the K×K triangle
// grid (K = 300: 180,000 triangles, 90,601 vertices, the `tri-180k` mesh of benches/live.rs),
// Topoplex's live complex next to OpenMesh's half-edge collapse with its own check.
//
// The mesh: K×K unit squares, each cut along its diagonal into two triangles, oriented
// consistently (OpenMesh needs that; Topoplex does not care). The calls: the grid's edges as
// (lower id, higher id) pairs in ascending order, every ⌈E / 20,000⌉-th one, 20,000 in all —
// the sample benches/live.rs takes. Each op runs the calls in that order on a fresh copy of
// the mesh (the copy untimed) and counts calls, done or not:
//   contract/openmesh      a dead vertex is skipped; otherwise the halfedge b→a is looked up
//                          (none: refused), is_collapse_ok (the link condition of a
//                          2-manifold: the two vertices share exactly the opposite vertices of
//                          the edge's faces, plus its boundary rules), then collapse (b removed,
//                          a kept). Deleted elements are left to garbage collection (untimed).
//   contract/tpx           tpx_live_contract(b into a, TPX_CONTRACT_PRESERVE_TOPOLOGY): not an
//                          edge, or the link condition Lk(a) ∩ Lk(b) = Lk(ab) failing in any
//                          dimension, is refused; a dead vertex is refused.
//   contract/tpx_manifold  the same with TPX_CONTRACT_PRESERVE_MANIFOLD (the link condition
//                          with the boundary's cone, as OpenMesh's boundary rules).
//   check/openmesh         the check alone on the fresh mesh (nothing collapsed, so every call
//                          sees the same mesh): a dead vertex skipped, find_halfedge(b, a),
//                          is_collapse_ok.
//   check/tpx, check/tpx_manifold  the check alone: tpx_live_link_condition and
//                          tpx_live_link_condition_with_boundary (a refusal also writes its
//                          message, as in contract/*).
// Counters: `elements` = calls per iteration (items per second = calls per second),
// `contracted` = calls that contracted (they differ by library: each refuses by its own rule),
// `passed` = calls whose check passed (check/*).
// Tetrahedral meshes have no peer here: neither OpenMesh nor CGAL's Triangulation_3 collapses
// edges of a tetrahedral mesh with a link check.
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "bench_common.hpp"

namespace {

using namespace tpxbench;

using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;

constexpr size_t kSample = 20000;

struct Grid {
  uint32_t n_vertices = 0;
  std::vector<uint32_t> tris;  // 3 ids per triangle, counter-clockwise
};

Grid triangle_grid(uint32_t k) {
  Grid g;
  g.n_vertices = (k + 1) * (k + 1);
  auto id = [k](uint32_t i, uint32_t j) { return i * (k + 1) + j; };
  for (uint32_t i = 0; i < k; ++i) {
    for (uint32_t j = 0; j < k; ++j) {
      g.tris.insert(g.tris.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      g.tris.insert(g.tris.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return g;
}

// The edge sample of benches/live.rs: sorted (lower, higher) pairs, every step-th, 20,000.
// The grid as a Topoplex complex (tpx_complex_from_arrays, no coordinates).
ComplexPtr grid_complex(const Grid& g) {
  std::vector<size_t> offsets(g.tris.size() / 3 + 1);
  for (size_t i = 0; i < offsets.size(); ++i) offsets[i] = 3 * i;
  TpxComplex* c = nullptr;
  tpx_check(tpx_complex_from_arrays(g.n_vertices, g.tris.data(), offsets.data(), offsets.size() - 1, nullptr, 0, &c),
            "tpx_complex_from_arrays");
  return ComplexPtr(c);
}

std::vector<std::pair<uint32_t, uint32_t>> edge_sample(const Grid& g) {
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  for (size_t t = 0; t < g.tris.size(); t += 3) {
    for (int i = 0; i < 3; ++i) {
      const uint32_t u = g.tris[t + i], v = g.tris[t + (i + 1) % 3];
      edges.emplace_back(std::min(u, v), std::max(u, v));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const size_t step = std::max<size_t>(edges.size() / kSample, 1);
  std::vector<std::pair<uint32_t, uint32_t>> out;
  for (size_t i = 0; i < edges.size() && out.size() < kSample; i += step) out.push_back(edges[i]);
  return out;
}

OMesh openmesh_grid(const Grid& g, uint32_t k) {
  OMesh m;
  for (uint32_t v = 0; v < g.n_vertices; ++v) m.add_vertex(OMesh::Point(float(v / (k + 1)), float(v % (k + 1)), 0));
  for (size_t t = 0; t < g.tris.size(); t += 3) {
    m.add_face(OMesh::VertexHandle(int(g.tris[t])), OMesh::VertexHandle(int(g.tris[t + 1])),
               OMesh::VertexHandle(int(g.tris[t + 2])));
  }
  m.request_vertex_status();
  m.request_edge_status();
  m.request_halfedge_status();
  m.request_face_status();
  return m;
}

// The halfedge b -> a whose collapse keeps a; invalid when either vertex is gone or no edge
// joins them.
OMesh::HalfedgeHandle collapse_halfedge(const OMesh& m, uint32_t a, uint32_t b) {
  const OMesh::VertexHandle va{int(a)}, vb{int(b)};
  if (m.status(va).deleted() || m.status(vb).deleted()) return OMesh::HalfedgeHandle();
  return m.find_halfedge(vb, va);
}

// One pass of the calls on `m`; returns how many contracted.
size_t openmesh_pass(OMesh& m, const std::vector<std::pair<uint32_t, uint32_t>>& calls) {
  size_t done = 0;
  for (const auto& [a, b] : calls) {
    const OMesh::HalfedgeHandle h = collapse_halfedge(m, a, b);
    if (!h.is_valid() || !m.is_collapse_ok(h)) continue;
    m.collapse(h);
    ++done;
  }
  return done;
}

// The checks alone, on the unchanged mesh; returns how many passed.
size_t openmesh_checks(OMesh& m, const std::vector<std::pair<uint32_t, uint32_t>>& calls) {
  size_t ok = 0;
  for (const auto& [a, b] : calls) {
    const OMesh::HalfedgeHandle h = collapse_halfedge(m, a, b);
    ok += h.is_valid() && m.is_collapse_ok(h);
  }
  return ok;
}

size_t tpx_checks(const TpxLive* l, const std::vector<std::pair<uint32_t, uint32_t>>& calls, bool manifold) {
  size_t ok = 0;
  for (const auto& [a, b] : calls) {
    const TpxStatus st =
        manifold ? tpx_live_link_condition_with_boundary(l, a, b) : tpx_live_link_condition(l, a, b);
    ok += st == TPX_STATUS_OK;
  }
  return ok;
}

size_t tpx_pass(TpxLive* l, const std::vector<std::pair<uint32_t, uint32_t>>& calls, uint32_t mode) {
  size_t done = 0;
  for (const auto& [a, b] : calls) done += tpx_live_contract(l, a, b, mode, nullptr, 0, nullptr) == TPX_STATUS_OK;
  return done;
}

void set_counters(benchmark::State& st, size_t calls, size_t done, const char* what = "contracted") {
  set_elements(st, calls);
  st.counters[what] = double(done);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string arg = init(&argc, argv, "K (grid of K×K squares, 300 for tri-180k)");
  const uint32_t k = uint32_t(std::strtoul(arg.c_str(), nullptr, 10));
  if (k < 2 || k > 4000) {
    std::fprintf(stderr, "K must be in 2..4000, got %s\n", arg.c_str());
    return 2;
  }
  const Grid grid = triangle_grid(k);
  const auto calls = edge_sample(grid);
  std::fprintf(stderr, "grid %u: %zu triangles, %u vertices, %zu calls\n", k, grid.tris.size() / 3, grid.n_vertices,
               calls.size());

  add("contract", "openmesh", Unit::Walk, [&](benchmark::State& st) {
    const OMesh fresh = openmesh_grid(grid, k);
    size_t done = 0;
    for (auto _ : st) {
      st.PauseTiming();
      OMesh m = fresh;
      st.ResumeTiming();
      done = openmesh_pass(m, calls);
      st.PauseTiming();
      m = OMesh();
      st.ResumeTiming();
    }
    set_counters(st, calls.size(), done);
  });
  for (uint32_t mode : {uint32_t(TPX_CONTRACT_PRESERVE_TOPOLOGY), uint32_t(TPX_CONTRACT_PRESERVE_MANIFOLD)}) {
    const char* lib = mode == TPX_CONTRACT_PRESERVE_TOPOLOGY ? "tpx" : "tpx_manifold";
    add("contract", lib, Unit::Walk, [&, mode](benchmark::State& st) {
      const ComplexPtr c = grid_complex(grid);
      size_t done = 0;
      for (auto _ : st) {
        st.PauseTiming();
        TpxLive* l = nullptr;
        tpx_check(tpx_live_from_complex(c.get(), &l), "tpx_live_from_complex");
        st.ResumeTiming();
        done = tpx_pass(l, calls, mode);
        st.PauseTiming();
        tpx_live_free(l);
        st.ResumeTiming();
      }
      set_counters(st, calls.size(), done);
    });
  }
  add("check", "openmesh", Unit::Walk, [&](benchmark::State& st) {
    // is_collapse_ok is a member of the (non-const) mesh; it does not change it.
    OMesh m = openmesh_grid(grid, k);
    size_t ok = 0;
    for (auto _ : st) {
      ok = openmesh_checks(m, calls);
      benchmark::DoNotOptimize(ok);
    }
    set_counters(st, calls.size(), ok, "passed");
  });
  for (const bool manifold : {false, true}) {
    add("check", manifold ? "tpx_manifold" : "tpx", Unit::Walk, [&, manifold](benchmark::State& st) {
      const ComplexPtr c = grid_complex(grid);
      TpxLive* l = nullptr;
      tpx_check(tpx_live_from_complex(c.get(), &l), "tpx_live_from_complex");
      size_t ok = 0;
      for (auto _ : st) {
        ok = tpx_checks(l, calls, manifold);
        benchmark::DoNotOptimize(ok);
      }
      tpx_live_free(l);
      set_counters(st, calls.size(), ok, "passed");
    });
  }
  return run();
}
