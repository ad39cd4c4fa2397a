// Shared parts of the Google Benchmark programs that compare Topoplex (through its C ABI) with
// OpenMesh, CGAL and GUDHI on the same complexes:
//   topoplex_bench_surface FILE.off    (bench_surface.cpp)
//   topoplex_bench_tets FILE.mesh      (bench_tets.cpp)
//   topoplex_bench_gudhi FILE          (bench_gudhi.cpp)
//
// Conventions every program follows (agreed with scripts/bench.sh):
// - Benchmark names are `<op>/<lib>`: lib is a peer (`openmesh`, `cgal_sm`, `cgal_t3`, `gudhi`)
//   or `tpx_<kind>` for each Topoplex kind that encodes the complex (TOPOPLEX_BENCH_KINDS=ia,ts
//   restricts them; kinds that refuse the complex are reported on stderr and left out). The
//   live complex (`tpx_iastar`: tpx_live_from_complex, navigated through tpx_live_structure) is
//   a contender of topoplex_bench_gudhi only; TOPOPLEX_BENCH_KINDS names it `iastar`, the other
//   programs accept the name and leave it out.
// - Every benchmark sets SetItemsProcessed(elements retrieved) and the counter `elements`
//   (per iteration). For a walk that is the number of rows (simplices) the relation returned
//   over all elements; for `load`/`build` it is the number of simplices of the complex (all
//   dimensions), so time / elements is the build time per simplex.
// - `load`/`build` also set `heap_bytes` (what the built object keeps on the heap: glibc
//   mallinfo2 uordblks + hblkhd after the build minus before it, mmapped blocks included) and
//   `peak_heap_bytes` (the highest live heap during the build, above the level at its start;
//   see heap_window_begin). Both are measured on one extra, untimed build after the timed ones.
// - Every walk counts what it retrieves; the count of each `<op>/<lib>` must equal the count of
//   the first benchmark of the same op that ran (peers are registered first), otherwise the
//   benchmark stops with an error, the mismatch is printed, and the program exits 1. So a run
//   is also a correctness check of Topoplex against the peers.
#pragma once

#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "../c_ptr.hpp"
#include "topoplex.h"

namespace tpxbench {

// ---------------------------------------------------------------------------------------------
// Heap measurement.

// What one build left on the heap and the most it held on the way.
struct HeapUse {
  int64_t retained = 0;  // mallinfo2 delta (uordblks + hblkhd)
  int64_t peak = -1;     // peak live bytes above the start, -1 when not measurable
};

// Opens/closes a window in which every malloc/free of the process (C++ peers and the Rust
// library alike, since the executable interposes glibc's malloc) is accounted.
void heap_window_begin();
HeapUse heap_window_end();

// Runs `make` inside a heap window and returns its result; `use` receives the measurement.
template <class F>
auto measure_heap(F&& make, HeapUse* use) -> decltype(make()) {
  heap_window_begin();
  auto out = make();
  *use = heap_window_end();
  return out;
}

// Sets the `heap_bytes` / `peak_heap_bytes` counters.
void set_heap_counters(benchmark::State& state, const HeapUse& use);

// ---------------------------------------------------------------------------------------------
// Failures and cross-checks.

// Stops the benchmark with `why` and makes the program exit 1.
void fail(benchmark::State& state, const std::string& why);
// Records `count` for `op`, or compares it with the count the first benchmark of `op` recorded.
void check_count(benchmark::State& state, const std::string& op, const std::string& lib, uint64_t count);
// Sets items processed and the `elements` counter from a per-iteration count.
void set_elements(benchmark::State& state, uint64_t per_iteration);
// Prints a note on stderr (skipped kinds and peers).
void note(const std::string& what);

// ---------------------------------------------------------------------------------------------
// Topoplex through the C ABI.

struct Kind {
  uint32_t id;
  std::string name;  // "ia", used as `tpx_ia`
};
// All kinds, or those TOPOPLEX_BENCH_KINDS lists (comma-separated names; unknown names abort;
// `iastar` is accepted and left out: see live_from_env).
std::vector<Kind> kinds_from_env();
// Whether the live complex is a contender: TOPOPLEX_BENCH_KINDS unset or empty, or naming `iastar`.
bool live_from_env();
std::string tpx_message();
// Aborts the program with the library's message if `st` is not OK (setup code only).
void tpx_check(TpxStatus st, const char* what);

using ComplexPtr = topoplex_tests::CPtr<TpxComplex, tpx_complex_free>;
using StructurePtr = topoplex_tests::CPtr<TpxStructure, tpx_structure_free>;
using LivePtr = topoplex_tests::CPtr<TpxLive, tpx_live_free>;

ComplexPtr load_complex(const std::string& path);

// A complex as flat arrays: simplex i is ids[offsets[i] .. offsets[i+1]], coordinates
// vertex-major (coord_dim per vertex, possibly none).
struct Soup {
  uint32_t n_vertices = 0;
  std::vector<uint32_t> ids;
  std::vector<size_t> offsets{0};
  std::vector<double> coords;
  size_t coord_dim = 0;
  size_t size() const { return offsets.size() - 1; }
  void add(const uint32_t* s, size_t n) {
    ids.insert(ids.end(), s, s + n);
    offsets.push_back(ids.size());
  }
};

// The complex's top simplices of every dimension and its coordinates (tpx_complex_top_simplices,
// tpx_complex_coords).
Soup soup_of(const TpxComplex* c);
// The top p-simplices only, as rows of p+1 ids.
std::vector<uint32_t> top_simplices(const TpxComplex* c, uint32_t p);

// Topoplex's `build`: the same in-memory arrays the peers build from go through
// tpx_complex_from_arrays (normalisation) and tpx_structure_build; the intermediate complex is
// freed, so what stays is the structure alone. Coordinates are not passed: no structure keeps
// geometry. Returns null (status in *st) if the kind refuses the complex.
StructurePtr build_from_soup(const Soup& soup, uint32_t kind, TpxStatus* st);
// build_from_soup for set-up code (the kinds of kinds_that_build): aborts the program with the
// library's message, naming `what`, if the kind refuses the complex.
StructurePtr build_or_abort(const Soup& soup, uint32_t kind, const char* what = "tpx_structure_build");
// The number of simplices of all dimensions of `soup` (the `elements` of load/build), from its IG.
uint64_t soup_simplex_count(const Soup& soup);
// The live complex's `build`: tpx_complex_from_arrays + tpx_live_from_complex, complex freed, as
// build_from_soup. Returns null (status in *st) on a refusal.
LivePtr live_from_soup(const Soup& soup, TpxStatus* st);
// The mesh of `soup` (live_from_soup) with its lent arrays (tpx_live_arrays), for the `tpx_mesh`
// walks; aborts the program with the library's message on a refusal.
struct MeshBuilt {
  LivePtr live;
  TpxLiveArrays arrays{};
};
std::unique_ptr<MeshBuilt> mesh_or_abort(const Soup& soup);
// The kinds of kinds_from_env() that encode `soup`; each refusal is noted on stderr.
std::vector<Kind> kinds_that_build(const Soup& soup);
// Topoplex's `load`: tpx_complex_from_file + tpx_structure_build, complex freed.
StructurePtr load_structure(const std::string& path, uint32_t kind, TpxStatus* st);

// Number of simplices of all dimensions.
uint64_t simplex_count(const TpxStructure* s);

// The like-for-like walk: one tpx_relation call per query simplex into a buffer reused across
// calls (grown on BUFFER_TOO_SMALL), as a C or C++ caller walking a mesh would do. The
// relation-table call (tpx_relation_table) would amortise the per-call cost but materialises
// every answer at once, which the peers' circulators do not.
class Walker {
 public:
  Walker() : buf_(4096) {}
  // Number of rows of R_{p,q}(sigma), p = len - 1; 0 with `ok` false on an error.
  uint64_t rows(const TpxStructure* s, const uint32_t* sigma, size_t len, uint32_t q, bool* ok) {
    return call(buf_, ok, [&](uint32_t* b, size_t n, size_t* out) {
             return tpx_relation(s, sigma, len, q, b, n, out);
           }) /
           (q + 1);
  }
  // Number of simplices of R_{p,q}(h) through the handle API (dense indices into the reused
  // buffer); 0 with `ok` false on an error.
  uint64_t related(const TpxStructure* s, const TpxSimplex& h, uint32_t q, bool* ok) {
    return call(buf_, ok, [&](uint32_t* b, size_t n, size_t* out) {
      return tpx_related(s, &h, q, TPX_ORDER_NATURAL, b, n, out);
    });
  }
  // Number of simplices of R_{p,q}(h) as handles (tpx_related_handles into a reused buffer: the
  // call for structures without dense indices, the live complex); 0 with `ok` false on an error.
  uint64_t related_handles(const TpxStructure* s, const TpxSimplex& h, uint32_t q, bool* ok) {
    return call(hbuf_, ok, [&](TpxSimplex* b, size_t n, size_t* out) {
      return tpx_related_handles(s, &h, q, TPX_ORDER_NATURAL, b, n, out);
    });
  }
  const uint32_t* data() const { return buf_.data(); }

 private:
  // fn(buf.data(), buf.size(), &len), once more after growing `buf` to twice the length asked
  // for on BUFFER_TOO_SMALL; the length written, or 0 with `ok` false on an error.
  template <class V, class F>
  static uint64_t call(V& buf, bool* ok, F fn) {
    size_t out = 0;
    TpxStatus st = fn(buf.data(), buf.size(), &out);
    if (st == TPX_STATUS_BUFFER_TOO_SMALL) {
      buf.resize(2 * out);
      st = fn(buf.data(), buf.size(), &out);
    }
    if (st != TPX_STATUS_OK) {
      *ok = false;
      return 0;
    }
    return out;
  }

  std::vector<uint32_t> buf_;
  std::vector<TpxSimplex> hbuf_ = std::vector<TpxSimplex>(1024);
};

// Walks R_{p,q} over every handle of `handles` (located before timing) for each q in `qs`, one
// tpx_related_handles call per handle and q, counting the answers; fails the benchmark on a
// Topoplex error.
uint64_t walk_handles(benchmark::State& state, const TpxStructure* s, const std::vector<TpxSimplex>& handles,
                      const std::vector<uint32_t>& qs, Walker& w);

// Walks R_{p,q} over every simplex of `simplices` (rows of p+1 ids, ascending lexicographic, so
// row i is the simplex of dense index i) for each q in `qs`, through the handle API (one
// tpx_related per simplex and q, from the handle {i, p, stamp}: no locating), counting the
// answers; fails the benchmark on a Topoplex error.
// With `stride` > 1 only the simplices of dense index 0, stride, 2·stride, ... are walked.
uint64_t walk(benchmark::State& state, const TpxStructure* s, const std::vector<uint32_t>& simplices, uint32_t p,
              const std::vector<uint32_t>& qs, Walker& w, uint32_t stride = 1);

// TOPOPLEX_BENCH_COFACES_STRIDE (default 1): topoplex_bench_gudhi's cofaces walks query every
// stride-th vertex and edge (ascending lexicographic order, the same simplices for every library),
// so that GUDHI 3.7's cofaces_simplex_range, which walks the tree below the simplex's vertices
// for every query (quadratic over all vertices), can be timed on large complexes too.
uint32_t cofaces_stride();

// The walk of R_{p,q} over every p-simplex reading each answer inline from a lent relation
// view (tpx_relation_view, iterated by topoplex::RelationView of topoplex.hpp: no library call
// per query), registered as `<op>_view/<lib>`. `get` returns the library's structure (built
// once, shared with its other walks). The view is taken outside the timed loop; for a
// relation the structure does not store, the first call of a structure builds its index: that
// call's time and the index's bytes are the counters `view_first_ms` and `index_bytes` (the
// `<op>_batch` op is the same index built again, as a whole-mesh pass would pay it). Every id
// is read (summed), as the peers' circulators read theirs.
void add_view_walk(const std::string& op, const std::string& lib, std::function<const TpxStructure*()> get,
                   uint32_t p, uint32_t q);

// All p-simplices of a structure (rows of p+1 ids, ascending).
std::vector<uint32_t> simplices_of(const TpxStructure* s, uint32_t p);
// 0 .. n-1 as vertex rows.
std::vector<uint32_t> vertex_rows(uint32_t n);

// A built structure and the vertex rows its walks from every vertex go through; a program's
// own `Built` derives from it to keep more rows beside them.
struct BuiltWalk {
  StructurePtr s;
  std::vector<uint32_t> vertices;
};
// Kind `kind` of `soup` (build_or_abort) with the rows of its vertices, as a `B`.
template <class B>
std::unique_ptr<B> build_walk(const Soup& soup, uint32_t kind) {
  auto b = std::make_unique<B>();
  b->s = build_or_abort(soup, kind);
  b->vertices = vertex_rows(soup.n_vertices);
  return b;
}

// ---------------------------------------------------------------------------------------------
// One heavy object alive at a time: the walks of a library share the object its first walk
// built, and switching library frees it first, so memory stays bounded on big inputs whatever
// the benchmark filter.
class Slot {
 public:
  template <class T>
  T& get(const std::string& key, const std::function<std::unique_ptr<T>()>& make) {
    if (key != key_ || !obj_) {
      obj_.reset();
      key_.clear();
      std::unique_ptr<T> made = make();
      obj_ = std::shared_ptr<void>(made.release(), [](void* p) { delete static_cast<T*>(p); });
      key_ = key;
    }
    return *static_cast<T*>(obj_.get());
  }
  void clear() {
    obj_.reset();
    key_.clear();
  }

 private:
  std::string key_;
  std::shared_ptr<void> obj_;
};
Slot& slot();

// ---------------------------------------------------------------------------------------------
// Registration and main.

enum class Unit { Build, Walk };
// Registers `fn` as `<op>/<lib>` with the unit the programs use (ms for load/build, us for walks).
void add(const std::string& op, const std::string& lib, Unit unit, std::function<void(benchmark::State&)> fn);

// Registers the walk `<op>/<lib>`: walk_fn(object) timed, the object made once per slot by
// `make`; walk_fn returns the elements it visited (checked across libraries, and the rate's unit).
template <class T, class Walk>
void add_walk(const std::string& op, const std::string& lib, const std::function<std::unique_ptr<T>()>& make,
              Walk walk_fn) {
  add(op, lib, Unit::Walk, [=](benchmark::State& state) {
    const T& m = slot().get<T>(lib, make);
    uint64_t n = 0;
    for (auto _ : state) {
      n = walk_fn(m);
      benchmark::DoNotOptimize(n);
    }
    check_count(state, op, lib, n);
    set_elements(state, n);
  });
}

// Topoplex's `load` and `build` benchmarks for one kind (same in every program).
void add_tpx_load(const std::string& path, const Kind& k, uint64_t simplices);
void add_tpx_build(const Soup& soup, const Kind& k, uint64_t simplices);
// The live complex's `build` (`build/tpx_iastar`), timed and measured as add_tpx_build.
void add_tpx_live_build(const Soup& soup, uint64_t simplices);

// A peer's `load` / `build`: times `make` (destruction untimed), then measures one more build's
// heap. `what` names the peer's object in the failure message; `geometry_bytes` (the peer's
// coordinate storage) is set as a counter when not negative.
template <class T>
void time_peer_build(benchmark::State& state, uint64_t simplices, const std::function<std::unique_ptr<T>()>& make,
                     const char* what, double geometry_bytes = -1) {
  slot().clear();
  for (auto _ : state) {
    auto m = make();
    if (!m) {
      fail(state, std::string("the peer failed to build the ") + what);
      return;
    }
    state.PauseTiming();
    m.reset();
    state.ResumeTiming();
  }
  HeapUse use;
  auto m = measure_heap(make, &use);
  set_heap_counters(state, use);
  set_elements(state, simplices);
  if (geometry_bytes >= 0) state.counters["geometry_bytes"] = geometry_bytes;
}

// Parses the benchmark flags and the one FILE argument; exits with usage otherwise.
std::string init(int* argc, char** argv, const char* usage);
// Runs the registered benchmarks; returns the exit code (1 after any failure).
int run();

}  // namespace tpxbench
