#include "bench_common.hpp"

#include "topoplex.hpp"

#include <malloc.h>

#include <atomic>
#include <chrono>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <tuple>

#if defined(__SANITIZE_ADDRESS__)
#define TPXBENCH_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TPXBENCH_SANITIZED 1
#endif
#endif

// ---------------------------------------------------------------------------------------------
// Peak heap: glibc keeps no high-water mark of live bytes, so the executable interposes the
// malloc family (its definitions come first in the dynamic lookup, for libtopoplex.so and the
// C++ runtime too) and forwards to glibc's own entry points. Inside a window opened by
// heap_window_begin it adds the chunk size of every block allocated and subtracts it for every
// block freed, keeping the maximum. The chunk size (malloc_usable_size + glibc's one size_t
// header) is what mallinfo2 counts, so the peak and heap_bytes are in the same units: with many
// small blocks (GUDHI's tree nodes) the headers are a good part of the heap; outside a window the cost is one relaxed load and a
// branch per call, so the timed runs are unaffected. Under AddressSanitizer (which interposes
// malloc itself) there is no peak: peak_heap_bytes is then -1.
#ifndef TPXBENCH_SANITIZED
extern "C" {
void* __libc_malloc(size_t);
void __libc_free(void*);
void* __libc_calloc(size_t, size_t);
void* __libc_realloc(void*, size_t);
void* __libc_memalign(size_t, size_t);
void* __libc_valloc(size_t);
void* __libc_pvalloc(size_t);
}

namespace {
std::atomic<bool> g_tracking{false};
std::atomic<int64_t> g_live{0};
std::atomic<int64_t> g_peak{0};

inline int64_t chunk_size(void* p) { return int64_t(malloc_usable_size(p) + sizeof(size_t)); }
inline void account_alloc(void* p) {
  if (p == nullptr) return;
  const int64_t size = chunk_size(p);
  const int64_t now = g_live.fetch_add(size, std::memory_order_relaxed) + size;
  int64_t peak = g_peak.load(std::memory_order_relaxed);
  while (now > peak && !g_peak.compare_exchange_weak(peak, now, std::memory_order_relaxed)) {
  }
}
inline void account_free(void* p) {
  if (p != nullptr) g_live.fetch_sub(chunk_size(p), std::memory_order_relaxed);
}
inline bool tracking() { return g_tracking.load(std::memory_order_relaxed); }
}  // namespace

extern "C" {
void* malloc(size_t n) {
  void* p = __libc_malloc(n);
  if (tracking()) account_alloc(p);
  return p;
}
void free(void* p) {
  if (tracking()) account_free(p);
  __libc_free(p);
}
void* calloc(size_t n, size_t size) {
  void* p = __libc_calloc(n, size);
  if (tracking()) account_alloc(p);
  return p;
}
void* realloc(void* old, size_t n) {
  if (!tracking()) return __libc_realloc(old, n);
  const int64_t before = old ? chunk_size(old) : 0;
  void* p = __libc_realloc(old, n);
  if (p != nullptr || n == 0) {
    // The old block is gone (moved, resized or freed by a zero-size realloc).
    g_live.fetch_sub(before, std::memory_order_relaxed);
    account_alloc(p);
  }
  return p;
}
void* memalign(size_t align, size_t n) {
  void* p = __libc_memalign(align, n);
  if (tracking()) account_alloc(p);
  return p;
}
void* aligned_alloc(size_t align, size_t n) { return memalign(align, n); }
int posix_memalign(void** out, size_t align, size_t n) {
  if (align < sizeof(void*) || (align & (align - 1)) != 0) return EINVAL;
  void* p = memalign(align, n);
  if (p == nullptr && n != 0) return ENOMEM;
  *out = p;
  return 0;
}
void* valloc(size_t n) {
  void* p = __libc_valloc(n);
  if (tracking()) account_alloc(p);
  return p;
}
void* pvalloc(size_t n) {
  void* p = __libc_pvalloc(n);
  if (tracking()) account_alloc(p);
  return p;
}
}
#endif

namespace tpxbench {

namespace {
int64_t heap_in_use() {
  const struct mallinfo2 mi = mallinfo2();
  return int64_t(mi.uordblks) + int64_t(mi.hblkhd);
}
int64_t g_window_start = 0;
int g_failures = 0;
std::string g_running;  // `<op>/<lib>` of the running benchmark (State::name is libbenchmark 1.8+)
}  // namespace

void heap_window_begin() {
  g_window_start = heap_in_use();
#ifndef TPXBENCH_SANITIZED
  g_live.store(0, std::memory_order_relaxed);
  g_peak.store(0, std::memory_order_relaxed);
  g_tracking.store(true, std::memory_order_seq_cst);
#endif
}

HeapUse heap_window_end() {
  HeapUse use;
#ifndef TPXBENCH_SANITIZED
  g_tracking.store(false, std::memory_order_seq_cst);
  use.peak = g_peak.load(std::memory_order_relaxed);
#endif
  use.retained = heap_in_use() - g_window_start;
  return use;
}

void set_heap_counters(benchmark::State& state, const HeapUse& use) {
  state.counters["heap_bytes"] = double(use.retained);
  state.counters["peak_heap_bytes"] = double(use.peak);
}

void fail(benchmark::State& state, const std::string& why) {
  ++g_failures;
  std::fprintf(stderr, "FAILED %s: %s\n", g_running.c_str(), why.c_str());
  state.SkipWithError(why.c_str());
}

void check_count(benchmark::State& state, const std::string& op, const std::string& lib, uint64_t count) {
  static std::map<std::string, std::pair<std::string, uint64_t>> first;
  auto [it, inserted] = first.emplace(op, std::make_pair(lib, count));
  if (!inserted && it->second.second != count) {
    std::ostringstream why;
    why << op << ": " << lib << " retrieved " << count << " elements, " << it->second.first << " retrieved "
        << it->second.second;
    fail(state, why.str());
  }
}

void set_elements(benchmark::State& state, uint64_t per_iteration) {
  state.SetItemsProcessed(int64_t(per_iteration) * int64_t(state.iterations()));
  state.counters["elements"] = double(per_iteration);
}

void note(const std::string& what) { std::fprintf(stderr, "note: %s\n", what.c_str()); }

std::vector<Kind> kinds_from_env() {
  // Names both ways through the library (tpx_kind_name, tpx_kind_from_name): no map here.
  std::vector<Kind> all;
  for (uint32_t k = 0; k <= TPX_KIND_DE; ++k) {
    const char* name = nullptr;
    tpx_check(tpx_kind_name(k, &name), "tpx_kind_name");
    all.push_back({k, name});
  }
  const char* env = std::getenv("TOPOPLEX_BENCH_KINDS");
  if (env == nullptr || *env == '\0') return all;
  std::vector<Kind> out;
  std::stringstream ss(env);
  std::string name;
  while (std::getline(ss, name, ',')) {
    uint32_t k = 0;
    if (name.empty()) continue;
    if (tpx_kind_from_name(name.c_str(), &k) != TPX_STATUS_OK) {
      std::fprintf(stderr, "TOPOPLEX_BENCH_KINDS: %s\n", tpx_last_error_message());
      std::exit(2);
    }
    if (k <= TPX_KIND_DE) out.push_back(all[k]);  // iastar: see live_from_env
  }
  return out;
}

bool live_from_env() {
  const char* env = std::getenv("TOPOPLEX_BENCH_KINDS");
  if (env == nullptr || *env == '\0') return true;
  std::stringstream ss(env);
  std::string name;
  uint32_t k = 0;
  while (std::getline(ss, name, ','))
    if (tpx_kind_from_name(name.c_str(), &k) == TPX_STATUS_OK && k == TPX_KIND_IASTAR) return true;
  return false;
}

uint32_t cofaces_stride() {
  const char* env = std::getenv("TOPOPLEX_BENCH_COFACES_STRIDE");
  if (env == nullptr || *env == '\0') return 1;
  const long k = std::strtol(env, nullptr, 10);
  if (k < 1) {
    std::fprintf(stderr, "TOPOPLEX_BENCH_COFACES_STRIDE: '%s' is not a positive integer\n", env);
    std::exit(2);
  }
  return uint32_t(k);
}

std::string tpx_message() { return tpx_last_error_message(); }

void tpx_check(TpxStatus st, const char* what) {
  if (st != TPX_STATUS_OK) {
    std::fprintf(stderr, "%s failed (status %u): %s\n", what, unsigned(st), tpx_last_error_message());
    std::exit(1);
  }
}

ComplexPtr load_complex(const std::string& path) {
  TpxComplex* c = nullptr;
  tpx_check(tpx_complex_from_file(path.c_str(), &c), ("reading " + path).c_str());
  return ComplexPtr(c);
}

namespace {
// The `count(h, p)` p-simplices that `list` writes, as rows of p+1 ids (both calls checked).
template <class H, class Count, class List>
std::vector<uint32_t> rows_of(const H* h, uint32_t p, Count count, const char* count_name, List list,
                              const char* list_name) {
  size_t n = 0;
  tpx_check(count(h, p, &n), count_name);
  std::vector<uint32_t> rows(n * (p + 1));
  size_t len = 0;
  tpx_check(list(h, p, rows.data(), rows.size(), &len), list_name);
  rows.resize(len);
  return rows;
}
}  // namespace

std::vector<uint32_t> top_simplices(const TpxComplex* c, uint32_t p) {
  return rows_of(c, p, tpx_complex_top_count, "tpx_complex_top_count", tpx_complex_top_simplices,
                 "tpx_complex_top_simplices");
}

Soup soup_of(const TpxComplex* c) {
  Soup soup;
  uint32_t d = 0;
  tpx_check(tpx_complex_vertex_count(c, &soup.n_vertices), "tpx_complex_vertex_count");
  tpx_check(tpx_complex_dimension(c, &d), "tpx_complex_dimension");
  for (uint32_t p = 0; p <= d; ++p) {
    const auto rows = top_simplices(c, p);
    for (size_t i = 0; i < rows.size(); i += p + 1) soup.add(&rows[i], p + 1);
  }
  tpx_check(tpx_complex_coord_dim(c, &soup.coord_dim), "tpx_complex_coord_dim");
  size_t len = 0;
  soup.coords.resize(soup.coord_dim * soup.n_vertices);
  tpx_check(tpx_complex_coords(c, soup.coords.data(), soup.coords.size(), &len), "tpx_complex_coords");
  return soup;
}

StructurePtr build_from_soup(const Soup& soup, uint32_t kind, TpxStatus* st) {
  TpxComplex* c = nullptr;
  *st = tpx_complex_from_arrays(soup.n_vertices, soup.ids.data(), soup.offsets.data(), soup.size(), nullptr, 0, &c);
  if (*st != TPX_STATUS_OK) return nullptr;
  ComplexPtr owned(c);
  TpxStructure* s = nullptr;
  *st = tpx_structure_build(c, kind, &s);
  return StructurePtr(s);
}

StructurePtr build_or_abort(const Soup& soup, uint32_t kind, const char* what) {
  TpxStatus st = TPX_STATUS_OK;
  StructurePtr s = build_from_soup(soup, kind, &st);
  tpx_check(st, what);
  return s;
}

uint64_t soup_simplex_count(const Soup& soup) {
  return simplex_count(build_or_abort(soup, TPX_KIND_IG, "building the IG").get());
}

LivePtr live_from_soup(const Soup& soup, TpxStatus* st) {
  TpxComplex* c = nullptr;
  *st = tpx_complex_from_arrays(soup.n_vertices, soup.ids.data(), soup.offsets.data(), soup.size(), nullptr, 0, &c);
  if (*st != TPX_STATUS_OK) return nullptr;
  ComplexPtr owned(c);
  TpxLive* l = nullptr;
  *st = tpx_live_from_complex(c, &l);
  return LivePtr(l);
}

std::unique_ptr<MeshBuilt> mesh_or_abort(const Soup& soup) {
  auto b = std::make_unique<MeshBuilt>();
  TpxStatus st = TPX_STATUS_OK;
  b->live = live_from_soup(soup, &st);
  if (!b->live || tpx_live_arrays(b->live.get(), &b->arrays) != TPX_STATUS_OK) {
    std::fprintf(stderr, "tpx_mesh: the live complex refused the soup: %s\n", tpx_message().c_str());
    std::exit(1);
  }
  return b;
}

StructurePtr load_structure(const std::string& path, uint32_t kind, TpxStatus* st) {
  TpxComplex* c = nullptr;
  *st = tpx_complex_from_file(path.c_str(), &c);
  if (*st != TPX_STATUS_OK) return nullptr;
  ComplexPtr owned(c);
  TpxStructure* s = nullptr;
  *st = tpx_structure_build(c, kind, &s);
  return StructurePtr(s);
}

uint64_t simplex_count(const TpxStructure* s) {
  uint32_t d = 0;
  tpx_check(tpx_structure_dimension(s, &d), "tpx_structure_dimension");
  uint64_t total = 0;
  for (uint32_t p = 0; p <= d; ++p) {
    size_t n = 0;
    tpx_check(tpx_structure_count(s, p, &n), "tpx_structure_count");
    total += n;
  }
  return total;
}

uint64_t walk(benchmark::State& state, const TpxStructure* s, const std::vector<uint32_t>& simplices, uint32_t p,
              const std::vector<uint32_t>& qs, Walker& w, uint32_t stride) {
  uint64_t count = 0;
  bool ok = true;
  const size_t arity = p + 1;
  uint32_t stamp = 0;
  tpx_check(tpx_structure_stamp(s, &stamp), "tpx_structure_stamp");
  const uint32_t n = uint32_t(simplices.size() / arity);
  for (uint32_t i = 0; i < n; i += stride) {
    const TpxSimplex h{i, p, stamp};
    for (uint32_t q : qs) count += w.related(s, h, q, &ok);
  }
  if (!ok) fail(state, "tpx_related failed: " + tpx_message());
  return count;
}

uint64_t walk_handles(benchmark::State& state, const TpxStructure* s, const std::vector<TpxSimplex>& handles,
                      const std::vector<uint32_t>& qs, Walker& w) {
  uint64_t count = 0;
  bool ok = true;
  for (const TpxSimplex& h : handles)
    for (uint32_t q : qs) count += w.related_handles(s, h, q, &ok);
  if (!ok) fail(state, "tpx_related_handles failed: " + tpx_message());
  return count;
}

namespace {
// The lent view of R_{p,q} of `s` and how long its first call took (per structure stamp: a
// Google Benchmark function runs several times, only the first call builds).
struct TakenView {
  TpxRelationView raw{};
  double first_ms = 0;
};
TakenView take_view(const TpxStructure* s, uint32_t p, uint32_t q) {
  static std::map<std::tuple<uint32_t, uint32_t, uint32_t>, double> first;
  uint32_t stamp = 0;
  tpx_check(tpx_structure_stamp(s, &stamp), "tpx_structure_stamp");
  TakenView t;
  const auto t0 = std::chrono::steady_clock::now();
  tpx_check(tpx_relation_view(s, p, q, &t.raw), "tpx_relation_view");
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  t.first_ms = first.emplace(std::make_tuple(stamp, p, q), ms).first->second;
  return t;
}
}  // namespace

void add_view_walk(const std::string& op, const std::string& lib, std::function<const TpxStructure*()> get,
                   uint32_t p, uint32_t q) {
  const std::string name = op + "_view";
  add(name, lib, Unit::Walk, [=](benchmark::State& state) {
    const TakenView t = take_view(get(), p, q);
    const topoplex::RelationView view(t.raw, q, 0);
    const uint32_t n = uint32_t(view.size());
    uint64_t count = 0, sum = 0;
    for (auto _ : state) {
      count = 0;
      for (uint32_t i = 0; i < n; ++i)
        for (auto x : view[i]) {
          sum += x.index();
          ++count;
        }
      benchmark::DoNotOptimize(sum);
    }
    check_count(state, op, lib, count);  // the same count as the peers' walk of `op`
    set_elements(state, count);
    state.counters["view_first_ms"] = t.first_ms;
    state.counters["index_bytes"] = t.raw.built ? double(t.raw.bytes) : 0.0;
  });
}

std::vector<uint32_t> simplices_of(const TpxStructure* s, uint32_t p) {
  return rows_of(s, p, tpx_structure_count, "tpx_structure_count", tpx_structure_simplices,
                 "tpx_structure_simplices");
}

std::vector<uint32_t> vertex_rows(uint32_t n) {
  std::vector<uint32_t> v(n);
  for (uint32_t i = 0; i < n; ++i) v[i] = i;
  return v;
}

Slot& slot() {
  static Slot s;
  return s;
}

void add(const std::string& op, const std::string& lib, Unit unit, std::function<void(benchmark::State&)> fn) {
  const std::string name = op + "/" + lib;
  auto* b = benchmark::RegisterBenchmark(name.c_str(), [fn, name](benchmark::State& st) {
    g_running = name;
    fn(st);
  });
  b->Unit(unit == Unit::Build ? benchmark::kMillisecond : benchmark::kMicrosecond);
}

namespace {
// The shared body of `load` and `build`: time `make` (destruction untimed), then measure one
// more build's heap.
template <class Make>
void time_build(benchmark::State& state, uint64_t simplices, Make make) {
  slot().clear();  // nothing else of ours on the heap while building
  for (auto _ : state) {
    TpxStatus st = TPX_STATUS_OK;
    auto s = make(&st);
    if (!s) {
      fail(state, tpx_message());
      return;
    }
    state.PauseTiming();
    s.reset();
    state.ResumeTiming();
  }
  HeapUse use;
  TpxStatus st = TPX_STATUS_OK;
  auto s = measure_heap([&] { return make(&st); }, &use);
  set_heap_counters(state, use);
  set_elements(state, simplices);
}
}  // namespace

void add_tpx_load(const std::string& path, const Kind& k, uint64_t simplices) {
  add("load", "tpx_" + k.name, Unit::Build, [path, k, simplices](benchmark::State& state) {
    time_build(state, simplices, [&](TpxStatus* st) { return load_structure(path, k.id, st); });
  });
}

std::vector<Kind> kinds_that_build(const Soup& soup) {
  std::vector<Kind> kinds;
  for (const auto& k : kinds_from_env()) {
    TpxStatus st = TPX_STATUS_OK;
    if (build_from_soup(soup, k.id, &st))
      kinds.push_back(k);
    else
      note("tpx_" + k.name + " skipped: " + tpx_message());
  }
  return kinds;
}

void add_tpx_build(const Soup& soup, const Kind& k, uint64_t simplices) {
  add("build", "tpx_" + k.name, Unit::Build, [&soup, k, simplices](benchmark::State& state) {
    time_build(state, simplices, [&](TpxStatus* st) { return build_from_soup(soup, k.id, st); });
  });
}

void add_tpx_live_build(const Soup& soup, uint64_t simplices) {
  add("build", "tpx_iastar", Unit::Build, [&soup, simplices](benchmark::State& state) {
    time_build(state, simplices, [&](TpxStatus* st) { return live_from_soup(soup, st); });
  });
}

std::string init(int* argc, char** argv, const char* usage) {
  benchmark::Initialize(argc, argv);
  if (*argc != 2 || argv[1][0] == '-') {
    std::fprintf(stderr, "usage: %s [--benchmark_* flags] %s\n", argv[0], usage);
    std::exit(2);
  }
  return argv[1];
}

int run() {
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  slot().clear();
  if (g_failures > 0) {
    std::fprintf(stderr, "%d benchmark(s) FAILED (see above): Topoplex and a peer disagree or a call failed\n",
                 g_failures);
    return 1;
  }
  return 0;
}

}  // namespace tpxbench
