// topoplex_bench_app LIB INPUT [OUTPUT]: the small mesh application of issue 25, written once
// on OpenMesh and once on Topoplex's live mesh as each library's guide recommends, so that a
// driver (scripts/bench_app.py) can time the two side by side, phase by phase, each in its own
// process (so that each process's peak RSS is that application's alone).
//
// LIB: `openmesh` (TriMesh with double coordinates, faces and vertices in file order),
//      `topoplex` (topoplex::Live and its inline MeshView; no survey structure built) or
//      `topoplex-kept` (the indexed mesh: the same with its two indices built in `load`, as
//      OpenMesh builds its halfedges while loading: the facet adjacency, kept from then on and
//      read by `ff`, and every vertex's one-ring, read by the smoothing and the stats).
// Phases (each timed once, wall clock):
//   load     read the file into the application's mesh (Topoplex: Live::from_file, which reads
//            a plain mesh file straight into the live complex)
//   smooth   10 rounds of Laplacian smoothing: every vertex to the mean of its one-ring, the new
//            positions written back into the mesh after each round (Topoplex: the one-rings
//            by MeshView::for_each_ring, the pass over every vertex's ring)
//   stats    valence histogram, boundary and non-manifold edge counts
//   ff       every face's neighbour faces, summed into per-face data (one pass over all faces:
//            OpenMesh's ff_range per face; Topoplex: the facet adjacency built on request,
//            Live::mesh_with_adjacency, then MeshView::for_each_adjacent_top per face)
//   ff_each  the same pass again (the index kept), for the per-call cost
//   write    write the mesh back (OFF; Topoplex: Live::write, straight from its tables)
// Output: one line of `key=value` pairs: the phase times in ms, the process's peak RSS in KiB
// (VmHWM) and checksums that do not depend on either library's numbering (the driver compares
// them between the two).
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <topoplex.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace {

struct DoubleTraits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
};
using OMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// VmHWM (the process's peak RSS so far) or VmRSS (now), in KiB.
long status_kib(const char *field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(field, 0) == 0) return std::stol(line.substr(std::strlen(field)));
  return -1;
}
long peak_rss_kib() { return status_kib("VmHWM:"); }

// A face's key independent of numbering: its sorted vertex ids mixed.
std::uint64_t face_key(std::array<std::uint32_t, 3> v) {
  std::sort(v.begin(), v.end());
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint32_t x : v) h = (h ^ x) * 1099511628211ull;
  return h;
}

struct Result {
  std::map<std::string, double> ms;
  double coord_sum = 0;
  std::uint64_t ff_sum = 0, ff_each_sum = 0;
  std::size_t boundary = 0, nonmanifold = 0, valence_hash = 0, faces = 0;
  long load_peak_kib = 0, kept_kib = 0;  // peak RSS of the load; RSS held after it
};

Result run_openmesh(const char *in, const char *out) {
  Result r;
  auto t0 = Clock::now();
  OMesh mesh;
  if (!OpenMesh::IO::read_mesh(mesh, in)) throw std::runtime_error("OpenMesh cannot read it");
  // OpenMesh 9.0's OFF reader reads no face after a comment line and still reports success
  // (scripts/bench_app.py hands both libraries a copy without comments).
  if (mesh.n_faces() == 0) throw std::runtime_error("OpenMesh read no face (a comment line in the OFF?)");
  r.ms["load"] = ms_since(t0);
  r.load_peak_kib = peak_rss_kib();
  r.kept_kib = status_kib("VmRSS:");

  t0 = Clock::now();
  std::vector<OMesh::Point> next(mesh.n_vertices());
  for (int round = 0; round < 10; ++round) {
    for (auto v : mesh.vertices()) {
      OMesh::Point sum(0, 0, 0);
      std::size_t k = 0;
      for (auto w : mesh.vv_range(v)) {
        sum += mesh.point(w);
        ++k;
      }
      next[v.idx()] = k ? sum / double(k) : mesh.point(v);
    }
    for (auto v : mesh.vertices()) mesh.set_point(v, next[v.idx()]);
  }
  r.ms["smooth"] = ms_since(t0);

  t0 = Clock::now();
  std::map<std::size_t, std::size_t> valence;
  for (auto v : mesh.vertices()) ++valence[mesh.valence(v)];
  for (auto e : mesh.edges()) r.boundary += mesh.is_boundary(e);
  // A half-edge mesh holds no non-manifold edge (OpenMesh refuses those faces when reading).
  r.ms["stats"] = ms_since(t0);
  for (auto &kv : valence) r.valence_hash = r.valence_hash * 31 + kv.first * 1000003 + kv.second;

  std::vector<std::uint64_t> key(mesh.n_faces());
  for (auto f : mesh.faces()) {
    std::array<std::uint32_t, 3> v{};
    int i = 0;
    for (auto w : mesh.fv_range(f)) v[i++] = static_cast<std::uint32_t>(w.idx());
    key[f.idx()] = face_key(v);
  }
  t0 = Clock::now();
  std::vector<std::uint64_t> sum(mesh.n_faces());
  for (auto f : mesh.faces())
    for (auto g : mesh.ff_range(f)) sum[f.idx()] += key[g.idx()];
  r.ms["ff"] = ms_since(t0);
  for (auto f : mesh.faces()) r.ff_sum += sum[f.idx()] * key[f.idx()];
  t0 = Clock::now();
  std::fill(sum.begin(), sum.end(), 0);
  for (auto f : mesh.faces())
    for (auto g : mesh.ff_range(f)) sum[f.idx()] += key[g.idx()];
  r.ms["ff_each"] = ms_since(t0);
  for (auto f : mesh.faces()) r.ff_each_sum += sum[f.idx()] * key[f.idx()];
  r.faces = mesh.n_faces();

  for (auto v : mesh.vertices())
    for (int k = 0; k < 3; ++k) r.coord_sum += mesh.point(v)[k];
  if (out) {
    t0 = Clock::now();
    OpenMesh::IO::Options opt;
    if (!OpenMesh::IO::write_mesh(mesh, out, opt, 17))
      throw std::runtime_error("OpenMesh cannot write it");
    r.ms["write"] = ms_since(t0);
  }
  return r;
}

// One round of Laplacian smoothing into `next`: every live vertex to the mean of its one-ring
// (MeshView::for_each_ring, the whole-mesh pass over one-rings). D coordinates a vertex, known
// when compiling (D = 0: m.coord_dim() at run time).
template <std::size_t D>
void smooth_round(const topoplex::MeshView &m, topoplex::NeighbourMarks &marks, std::vector<double> &next) {
  const std::size_t dim = D ? D : m.coord_dim();
  // The ring's sum: in registers when D is known, else in a buffer as long as a point.
  std::array<double, D ? D : 1> fixed{};
  std::vector<double> dynamic(D ? 0 : dim);
  double *sum = D ? fixed.data() : dynamic.data();
  m.for_each_ring(marks, [&](std::uint32_t v, topoplex::SimplexView ring) {
    for (std::size_t k = 0; k < dim; ++k) sum[k] = 0.0;
    for (std::uint32_t w : ring) {
      const double *c = m.coords(w);
      for (std::size_t k = 0; k < dim; ++k) sum[k] += c[k];
    }
    const double *own = m.coords(v);
    const std::size_t n = ring.size();
    for (std::size_t k = 0; k < dim; ++k) next[v * dim + k] = n == 0 ? own[k] : sum[k] / double(n);
  });
}

// `kept`: the mesh builds its two indices while loading, as OpenMesh builds its halfedges, so
// their builds count in `load`: the facet adjacency, kept from then on (Live::keep_adjacency),
// which `ff` only reads, and the one-rings (Live::mesh_with_rings: kept while only coordinates
// change), which the smoothing and the stats read.
Result run_topoplex(const char *in, const char *out, bool kept) {
  Result r;
  auto t0 = Clock::now();
  topoplex::Live live = topoplex::Live::from_file(in);
  if (kept) {
    live.keep_adjacency();
    live.mesh_with_rings();
  }
  r.ms["load"] = ms_since(t0);
  r.load_peak_kib = peak_rss_kib();
  r.kept_kib = status_kib("VmRSS:");

  t0 = Clock::now();
  const std::size_t dim = live.coord_dim(), slots = live.vertex_slots();
  std::vector<double> next(slots * dim);
  topoplex::NeighbourMarks marks;
  for (int round = 0; round < 10; ++round) {
    // Coordinates read from the mesh itself.
    const topoplex::MeshView m = kept ? live.mesh_with_rings() : live.mesh();
    if (dim == 3)
      smooth_round<3>(m, marks, next);  // points of three numbers, as OpenMesh's Vec3d
    else
      smooth_round<0>(m, marks, next);
    live.set_all_coords(next.data(), next.size());  // in place: m stays valid
  }
  r.ms["smooth"] = ms_since(t0);

  t0 = Clock::now();
  const topoplex::MeshView m = kept ? live.mesh_with_rings() : live.mesh();
  std::vector<std::uint32_t> degree(slots);
  m.for_each_edge(2, marks, [&](std::uint32_t a, std::uint32_t b, std::size_t k) {
    ++degree[a];
    ++degree[b];
    r.boundary += k == 1;
    r.nonmanifold += k > 2;
  });
  std::map<std::size_t, std::size_t> valence;
  for (std::uint32_t v = 0; v < slots; ++v)
    if (m.is_vertex(v)) ++valence[degree[v]];
  r.ms["stats"] = ms_since(t0);
  for (auto &kv : valence) r.valence_hash = r.valence_hash * 31 + kv.first * 1000003 + kv.second;

  const std::uint32_t faces = m.slots(2);
  std::vector<std::uint64_t> key(faces);
  for (std::uint32_t f = 0; f < faces; ++f) {
    const topoplex::SimplexView v = m.vertices(topoplex::TopRef(2, f));
    key[f] = face_key({v[0], v[1], v[2]});
  }
  // Face neighbours from the facet adjacency, which the mesh builds on request (its time is in
  // this phase, its 12 bytes a triangle in the peak).
  t0 = Clock::now();
  const topoplex::MeshView ma = live.mesh_with_adjacency();
  std::vector<std::uint64_t> sum(faces);
  for (std::uint32_t f = 0; f < faces; ++f)
    ma.for_each_adjacent_top(topoplex::TopRef(2, f),
                             [&](topoplex::TopRef u) { sum[f] += key[u.slot()]; });
  r.ms["ff"] = ms_since(t0);
  for (std::uint32_t f = 0; f < faces; ++f) r.ff_sum += sum[f] * key[f];
  t0 = Clock::now();
  std::fill(sum.begin(), sum.end(), 0);
  for (std::uint32_t f = 0; f < faces; ++f)
    ma.for_each_adjacent_top(topoplex::TopRef(2, f),
                             [&](topoplex::TopRef u) { sum[f] += key[u.slot()]; });
  r.ms["ff_each"] = ms_since(t0);
  for (std::uint32_t f = 0; f < faces; ++f) r.ff_each_sum += sum[f] * key[f];
  r.faces = faces;

  for (double x : live.all_coords()) r.coord_sum += x;
  if (out) {
    t0 = Clock::now();
    live.write(out);
    r.ms["write"] = ms_since(t0);
  }
  return r;
}

}  // namespace

int main(int argc, char **argv) {
  const bool known = argc >= 3 && (std::strcmp(argv[1], "openmesh") == 0 || std::strcmp(argv[1], "topoplex") == 0 ||
                                   std::strcmp(argv[1], "topoplex-kept") == 0);
  if (!known) {
    std::fprintf(stderr, "usage: topoplex_bench_app openmesh|topoplex|topoplex-kept INPUT.off [OUTPUT.off]\n");
    return 2;
  }
  try {
    const char *out = argc > 3 ? argv[3] : nullptr;
    const auto t0 = Clock::now();
    Result r = std::strcmp(argv[1], "openmesh") == 0 ? run_openmesh(argv[2], out)
                                                      : run_topoplex(argv[2], out, std::strcmp(argv[1], "topoplex-kept") == 0);
    r.ms["total"] = ms_since(t0);
    std::printf("lib=%s faces=%zu", argv[1], r.faces);
    for (const auto &kv : r.ms) std::printf(" %s_ms=%.3f", kv.first.c_str(), kv.second);
    std::printf(" load_peak_kib=%ld kept_kib=%ld", r.load_peak_kib, r.kept_kib);
    std::printf(" peak_rss_kib=%ld coord_sum=%.9g ff_sum=%llu ff_each_sum=%llu boundary=%zu "
                "nonmanifold=%zu valence_hash=%zu\n",
                peak_rss_kib(), r.coord_sum, static_cast<unsigned long long>(r.ff_sum),
                static_cast<unsigned long long>(r.ff_each_sum), r.boundary, r.nonmanifold,
                r.valence_hash);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "topoplex_bench_app: %s: %s\n", argv[2], e.what());
    return 1;
  }
  return 0;
}
