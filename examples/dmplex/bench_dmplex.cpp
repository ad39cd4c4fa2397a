// Issue 29's benchmarks of the DMPlex bridge (a benchmark, not a test: scripts/bench_dmplex.sh
// runs it and assembles the tables; docs/dmplex.md "Benchmarks").
//
//   mpiexec -n 2 ./bench_dmplex -simplices 1e7 [-per_rank] [-self_dm 0] [-interpolate_late 0]
//       [-label TEXT] [-malloc_view -malloc_view_threshold 1e15]
//
// The grid: a box of nx x ny x nz cubes, each cut into 6 tetrahedra around its main diagonal
// (Freudenthal / Kuhn), sized so that it holds about `-simplices` simplices counting every
// dimension (vertices + edges + triangles + tetrahedra); with -per_rank, that many per rank
// (nz grows with the ranks: weak scaling). Each rank generates the cells of its own z-slab and
// PETSc builds the DM in parallel (DMPlexCreateFromCellListParallelPetsc, interpolated), so no
// rank ever holds the whole mesh; then DMPlexDistribute partitions it with the "simple"
// partitioner (contiguous cell ranges; -petscpartitioner_type ptscotch for another) and grows
// overlap 1.
//
// Per rank it measures:
//  (a) DMPlex topology memory: the rank's cells (its distributed DM's cells, overlap included)
//      rebuilt as an interpolated DMPlex on PETSC_COMM_SELF (cones, cone orientations, supports,
//      their sections, the depth and celltype labels: no coordinates, no SF), measured as the
//      growth of PetscMallocGetCurrentUsage (needs PETSc's counting allocator: -malloc_view
//      -malloc_view_threshold 1e15 turns it on without logging; -malloc_debug also does but
//      checks the heap on every call, far too slow here) and of glibc's heap in use (mallinfo2) across the build, the scratch
//      cell-vertex DM destroyed; and the distributed DM as held at the end (what its DMDestroy
//      frees: topology, point SF, labels, vertex numbering, coordinate section) minus its
//      coordinate values (8 B x 3 per local vertex in the local vector and per owned vertex in
//      the global one). Against it, every byte Topoplex keeps but coordinates (which DMPlex's
//      topology leaves out too): the IA as held (the heap its build grows: its arrays and its
//      handle bookkeeping; its own arrays, tpx_structure_storage, shown apart), the bridge's
//      RankMesh maps (RankMesh::bytes()), and the edge and triangle tables the first query
//      naming an edge or triangle by dense id builds (timed and sized before part (c)); the
//      complex's heap less its coordinates is shown but not kept: the IA holds the tops, so the
//      complex is moved out of the RankMesh (take_complex) and dropped once the IA is built.
//  (b) conversion: RankMesh::from_dm (interpolated DM -> complex and maps) and the IA's build,
//      in tetrahedra per second on the rank (wall time; oversubscribed ranks share cores), and
//      the core's share: Complex::from_arrays alone on the same tops (timed apart).
//  (c) every owned vertex's star: DMPlexGetTransitiveClosure(useCone = PETSC_FALSE) over the
//      owned vertices' points against Topoplex on the rank's IA: R_{0,3} (tpx_related), the full
//      star as R_{0,1} + R_{0,2} + R_{0,3} (three tpx_related), tpx_star, and the three relations
//      read inline from Structure::view (their indices built once, timed and sized apart); the counts are
//      checked vertex by vertex (closure size = star + the vertex itself; cells in the closure =
//      |R_{0,3}|) and a mismatch fails the run.
//  (d), (e) the phases' times and each rank's peak resident set (VmHWM).
// Rank 0 prints one line per rank and part, "@a|...", "@b|...", ..., which the script gathers into
// markdown tables.
#include "topoplex_dmplex.hpp"

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

namespace dx = topoplex::dmplex;
namespace tp = topoplex;

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Heap bytes in use (glibc): the arenas' allocated chunks plus mmapped blocks.
double heap_bytes() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks) + static_cast<double>(m.hblkhd);
}

double petsc_bytes() {
  PetscLogDouble b = 0;
  PetscMallocGetCurrentUsage(&b);
  return b;
}

// A field of /proc/self/status in bytes (VmHWM, VmRSS).
double status_bytes(const char *field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::size_t n = std::strlen(field);
  while (std::getline(in, line)) {
    if (line.compare(0, n, field) == 0 && line.size() > n && line[n] == ':') {
      return 1024.0 * std::atof(line.c_str() + n + 1);
    }
  }
  return 0;
}

double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double load_average() {
  std::ifstream in("/proc/loadavg");
  double l = 0;
  in >> l;
  return l;
}

struct Box {
  PetscInt nx, ny, nz;
  double vertices() const { return double(nx + 1) * double(ny + 1) * double(nz + 1); }
  double tets() const { return 6.0 * double(nx) * double(ny) * double(nz); }
  // Every simplex: V + E + F + T with F = (4T + boundary faces) / 2 and V - E + F - T = 1.
  double simplices() const {
    const double bf = 4.0 * (double(nx) * double(ny) + double(ny) * double(nz) + double(nx) * double(nz));
    const double f = (4.0 * tets() + bf) / 2.0;
    return 2.0 * vertices() + 2.0 * f - 1.0;
  }
};

// The cube n x n x n whose simplex count is nearest to `target`.
PetscInt cube_side(double target) {
  PetscInt n = 1;
  while (Box{n + 1, n + 1, n + 1}.simplices() <= target) ++n;
  const double lo = Box{n, n, n}.simplices(), hi = Box{n + 1, n + 1, n + 1}.simplices();
  return target - lo <= hi - target ? n : n + 1;
}

// Rank r's z-slab [z0, z1) of nz layers of cubes.
void slab(PetscInt nz, int rank, int size, PetscInt &z0, PetscInt &z1) {
  z0 = nz * rank / size;
  z1 = nz * (rank + 1) / size;
}

// The rank's cells (PETSc's winding: a positive tetrahedron with vertices 0 and 1 swapped) and
// the coordinates of the vertex planes it owns ([z0, z1), and plane nz on the last rank).
void slab_cells(const Box &b, int rank, int size, std::vector<PetscInt> &cells, std::vector<PetscReal> &xyz,
                PetscInt &owned_vertices) {
  PetscInt z0, z1;
  slab(b.nz, rank, size, z0, z1);
  const PetscInt mx = b.nx + 1, my = b.ny + 1;
  auto id = [&](PetscInt i, PetscInt j, PetscInt k) { return (k * my + j) * mx + i; };
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  cells.clear();
  cells.reserve(static_cast<std::size_t>(24 * b.nx * b.ny * (z1 - z0)));
  for (PetscInt k = z0; k < z1; ++k)
    for (PetscInt j = 0; j < b.ny; ++j)
      for (PetscInt i = 0; i < b.nx; ++i)
        for (const auto &p : perms) {
          PetscInt c[3] = {i, j, k}, t[4], x[4][3];
          for (int s = 0; s < 4; ++s) {
            if (s > 0) ++c[p[s - 1]];
            t[s] = id(c[0], c[1], c[2]);
            for (int a = 0; a < 3; ++a) x[s][a] = c[a];
          }
          // The volume's sign: the permutation's parity; make it positive (Topoplex's winding).
          PetscInt e[3][3];
          for (int r = 0; r < 3; ++r)
            for (int a = 0; a < 3; ++a) e[r][a] = x[r + 1][a] - x[0][a];
          const PetscInt det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                               e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                               e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
          if (det < 0) std::swap(t[2], t[3]);
          std::swap(t[0], t[1]);  // PETSc's tetrahedron order
          cells.insert(cells.end(), t, t + 4);
        }
  const PetscInt k_end = rank == size - 1 ? b.nz + 1 : z1;
  owned_vertices = (k_end - z0) * mx * my;
  xyz.clear();
  xyz.reserve(static_cast<std::size_t>(3 * owned_vertices));
  for (PetscInt k = z0; k < k_end; ++k)
    for (PetscInt j = 0; j < my; ++j)
      for (PetscInt i = 0; i < mx; ++i) xyz.insert(xyz.end(), {PetscReal(i), PetscReal(j), PetscReal(k)});
}

// An interpolated DMPlex on PETSC_COMM_SELF from cell-vertex lists (no coordinates): the cells
// first, vertices after, as DMPlexCreateFromCellListPetsc numbers them.
DM topology_dm(const std::vector<PetscInt> &cells, PetscInt ncells, PetscInt nverts) {
  DM dm, idm;
  PetscCallAbort(PETSC_COMM_SELF, DMCreate(PETSC_COMM_SELF, &dm));
  PetscCallAbort(PETSC_COMM_SELF, DMSetType(dm, DMPLEX));
  PetscCallAbort(PETSC_COMM_SELF, DMSetDimension(dm, 3));
  PetscCallAbort(PETSC_COMM_SELF, DMPlexSetChart(dm, 0, ncells + nverts));
  for (PetscInt c = 0; c < ncells; ++c) PetscCallAbort(PETSC_COMM_SELF, DMPlexSetConeSize(dm, c, 4));
  PetscCallAbort(PETSC_COMM_SELF, DMSetUp(dm));
  for (PetscInt c = 0; c < ncells; ++c) PetscCallAbort(PETSC_COMM_SELF, DMPlexSetCone(dm, c, &cells[static_cast<std::size_t>(4 * c)]));
  PetscCallAbort(PETSC_COMM_SELF, DMPlexSymmetrize(dm));
  PetscCallAbort(PETSC_COMM_SELF, DMPlexStratify(dm));
  PetscCallAbort(PETSC_COMM_SELF, DMPlexInterpolate(dm, &idm));
  PetscCallAbort(PETSC_COMM_SELF, DMDestroy(&dm));
  return idm;
}

[[noreturn]] void fail(int rank, const char *what) {
  std::fprintf(stderr, "rank %d: %s: %s\n", rank, what, tpx_last_error_message());
  MPI_Abort(PETSC_COMM_WORLD, 1);
  std::abort();
}

// One query of the handle API into `buf` (`query(data, capacity, &len)`), `buf` grown to the
// length asked for and the query made again when it was too small; aborts naming `what` on any
// other failure. Returns the answer's length.
template <class T, class Query>
std::size_t query_grown(int rank, const char *what, std::vector<T> &buf, Query query) {
  std::size_t len = 0;
  TpxStatus s = query(buf.data(), buf.size(), &len);
  if (s == TPX_STATUS_BUFFER_TOO_SMALL) {
    buf.resize(len);
    s = query(buf.data(), buf.size(), &len);
  }
  if (s != TPX_STATUS_OK) fail(rank, what);
  return len;
}

// Per-rank results, gathered on rank 0.
enum Field {
  Tets, Points, Vertices, OwnedVertices, DmTopoPetsc, DmTopoHeap, DmTopoPoints, DmHeld, CoordBytes,
  FromDm, FromArrays, IaBuild, IaBytes, ComplexHeap, MapsBytes, FromDmHeap, IaHeap,
  DmLoop, R03Loop, StarLoop, RelLoop, StarSum, CellSum, Mismatch, Create, Distribute, HwmBytes,
  FromDmCpu, DmLoopCpu, R03LoopCpu, ViewBuild, ViewLoop, ViewBytes, Checksum, HwmCreate, HwmDistribute, HwmSelf, HwmConvert,
  TablesBuild, TablesHeap, RelLoopCpu, StarLoopCpu, NFields
};

}  // namespace

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  PetscReal target = 1e6;
  PetscBool per_rank = PETSC_FALSE, self_dm = PETSC_TRUE, late = PETSC_TRUE, interpolate = PETSC_TRUE;
  char label[64] = "";
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-simplices", &target, nullptr));
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-per_rank", &per_rank, nullptr));
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-self_dm", &self_dm, nullptr));
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-interpolate_late", &late, nullptr));
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-interpolate", &interpolate, nullptr));
  if (!interpolate) late = PETSC_TRUE;  // cell-vertex throughout
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-label", label, sizeof label, nullptr));
  const double load = load_average();

  const PetscInt n = cube_side(target);
  const Box box{n, n, per_rank ? n * size : n};
  double f[NFields] = {};

  // Build the DM in parallel, each rank its slab.
  double t = now();
  DM dm = nullptr;
  {
    std::vector<PetscInt> cells;
    std::vector<PetscReal> xyz;
    PetscInt nowned = 0;
    slab_cells(box, rank, size, cells, xyz, nowned);
    const PetscInt nvglobal = static_cast<PetscInt>(box.vertices());
    PetscCall(DMPlexCreateFromCellListParallelPetsc(PETSC_COMM_WORLD, 3, static_cast<PetscInt>(cells.size() / 4), nowned,
                                                    nvglobal, 4, late ? PETSC_FALSE : PETSC_TRUE, cells.data(), 3, xyz.data(), nullptr,
                                                    nullptr, &dm));
  }
  f[Create] = now() - t;
  f[HwmCreate] = status_bytes("VmHWM");
  t = now();
  {
    PetscPartitioner part;
    PetscCall(DMPlexGetPartitioner(dm, &part));
    PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERSIMPLE));
    PetscCall(PetscPartitionerSetFromOptions(part));
    DM dist = nullptr;
    PetscCall(DMPlexDistribute(dm, 1, nullptr, &dist));
    if (dist) {
      PetscCall(DMDestroy(&dm));
      dm = dist;
    }
    if (late && interpolate) {
      DM idm = nullptr;
      PetscCall(DMPlexInterpolate(dm, &idm));
      PetscCall(DMPlexCopyCoordinates(dm, idm));
      PetscCall(DMDestroy(&dm));
      dm = idm;
    }
  }
  f[Distribute] = now() - t;
  f[HwmDistribute] = status_bytes("VmHWM");

  PetscInt pStart, pEnd, cStart, cEnd, vStart, vEnd;
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  f[Tets] = double(cEnd - cStart);
  f[Points] = double(pEnd - pStart);
  f[Vertices] = double(vEnd - vStart);

  // (a) the rank's DMPlex topology, rebuilt alone on PETSC_COMM_SELF.
  if (self_dm) {
    std::vector<PetscInt> cells;
    cells.reserve(static_cast<std::size_t>(4 * (cEnd - cStart)));
    for (PetscInt c = cStart; c < cEnd; ++c) {
      PetscInt nc = 0, *cl = nullptr;
      PetscCall(DMPlexGetTransitiveClosure(dm, c, PETSC_TRUE, &nc, &cl));
      for (PetscInt k = 0; k < nc; ++k) {
        const PetscInt q = cl[2 * k];
        if (q >= vStart && q < vEnd) cells.push_back(cEnd - cStart + q - vStart);
      }
      PetscCall(DMPlexRestoreTransitiveClosure(dm, c, PETSC_TRUE, &nc, &cl));
    }
    const double p0 = petsc_bytes(), h0 = heap_bytes();
    DM topo = topology_dm(cells, cEnd - cStart, vEnd - vStart);
    f[DmTopoPetsc] = petsc_bytes() - p0;
    f[DmTopoHeap] = heap_bytes() - h0;
    PetscInt a, b;
    PetscCall(DMPlexGetChart(topo, &a, &b));
    f[DmTopoPoints] = double(b - a);
    PetscCall(DMDestroy(&topo));
  }
  f[HwmSelf] = status_bytes("VmHWM");

  // (b) conversion and the IA.
  std::vector<std::uint32_t> owned;
  std::vector<PetscInt> owned_points;
  try {
    // from_dm is collective (the vertex numbering): start the ranks together, so that no rank's
    // conversion time holds its wait for a slower rank's part (a).
    MPI_Barrier(PETSC_COMM_WORLD);
    double h0 = heap_bytes();
    t = now();
    double c0 = cpu_now();
    dx::RankMesh rm = dx::RankMesh::from_dm(dm);
    f[FromDm] = now() - t;
    f[FromDmCpu] = cpu_now() - c0;
    f[FromDmHeap] = heap_bytes() - h0;
    f[MapsBytes] = double(rm.bytes());
    f[CoordBytes] = 24.0 * f[Vertices];
    f[ComplexHeap] = f[FromDmHeap] - f[MapsBytes] - f[CoordBytes];
    // The core's share of the conversion: Complex::from_arrays alone on the same tops.
    {
      const tp::Complex &c = rm.complex();
      std::vector<std::uint32_t> tids;
      std::vector<std::size_t> toffs{0};
      tids.reserve(4 * static_cast<std::size_t>(f[Tets]));
      for (std::uint32_t d = 0; d <= c.dimension(); ++d) {
        for (std::uint32_t i = 0; i < c.top_count(d); ++i) {
          const tp::SimplexView sv = c.top_oriented(d, i);
          tids.insert(tids.end(), sv.begin(), sv.end());
          toffs.push_back(tids.size());
        }
      }
      const std::vector<double> xyz = c.coords();
      t = now();
      const tp::Complex again = tp::Complex::from_arrays(c.vertex_count(), tids, toffs, xyz, c.coord_dim());
      f[FromArrays] = now() - t;
    }
    h0 = heap_bytes();
    t = now();
    const tp::Structure ia(rm.complex(), tp::Kind::IA);
    f[IaBuild] = now() - t;
    f[IaHeap] = heap_bytes() - h0;  // the IA as held: its arrays and its handle bookkeeping
    f[IaBytes] = double(ia.storage().bytes);
    // The IA holds the tops' vertices and adjacency: the complex is moved out and dropped (the
    // maps answer without it), so what Topoplex keeps is the IA as held and the maps.
    { const tp::Complex dropped = rm.take_complex(); }
    f[HwmConvert] = status_bytes("VmHWM");

    for (std::uint32_t v = 0; v < rm.vertex_count(); ++v) {
      if (rm.vertex_owned(v)) {
        owned.push_back(v);
        owned_points.push_back(rm.point_of_vertex(v));
      }
    }
    f[OwnedVertices] = double(owned.size());
    const std::size_t no = owned.size();

    // (c) DMPlex: the star of each owned vertex as a transitive closure with useCone = false.
    std::vector<std::uint32_t> dm_size(no), dm_cells(no), tp_cells(no), tp_star(no);
    t = now();
    c0 = cpu_now();
    for (std::size_t i = 0; i < no; ++i) {
      PetscInt ns = 0, *st = nullptr;
      PetscCall(DMPlexGetTransitiveClosure(dm, owned_points[i], PETSC_FALSE, &ns, &st));
      std::uint32_t nc = 0;
      for (PetscInt k = 0; k < ns; ++k) nc += st[2 * k] >= cStart && st[2 * k] < cEnd;
      dm_size[i] = static_cast<std::uint32_t>(ns);  // interpolated: the star; else the vertex and its cells
      PetscCall(DMPlexRestoreTransitiveClosure(dm, owned_points[i], PETSC_FALSE, &ns, &st));
      dm_cells[i] = nc;
    }
    f[DmLoop] = now() - t;
    f[DmLoopCpu] = cpu_now() - c0;

    // The lexicographic edge and triangle tables that dense ids of edges and triangles need (the
    // IA stores neither): built by the first query naming one, here timed and sized apart.
    std::vector<std::uint32_t> ids(64);
    h0 = heap_bytes();
    t = now();
    if (no > 0) {
      const TpxSimplex h{owned[0], 0, ia.stamp()};
      std::size_t len = 0;
      for (std::uint32_t q = 1; q <= 2; ++q) {
        ids.resize(4096);
        if (tpx_related(ia.get(), &h, q, TPX_ORDER_NATURAL, ids.data(), ids.size(), &len) != TPX_STATUS_OK) fail(rank, "tpx_related");
      }
    }
    f[TablesBuild] = now() - t;
    f[TablesHeap] = heap_bytes() - h0;

    // Topoplex: R_{0,3} into a reused buffer.
    t = now();
    c0 = cpu_now();
    for (std::size_t i = 0; i < no; ++i) {
      const TpxSimplex h{owned[i], 0, ia.stamp()};
      const std::size_t len =
          query_grown(rank, "tpx_related", ids, [&](std::uint32_t *buf, std::size_t cap, std::size_t *n) {
            return tpx_related(ia.get(), &h, 3, TPX_ORDER_NATURAL, buf, cap, n);
          });
      tp_cells[i] = static_cast<std::uint32_t>(len);
    }
    f[R03Loop] = now() - t;
    f[R03LoopCpu] = cpu_now() - c0;

    // Topoplex: the full star (every simplex containing the vertex, the vertex left out).
    std::vector<TpxSimplex> star(256);
    t = now();
    c0 = cpu_now();
    for (std::size_t i = 0; i < no; ++i) {
      const TpxSimplex h{owned[i], 0, ia.stamp()};
      const std::size_t len =
          query_grown(rank, "tpx_star", star, [&](TpxSimplex *buf, std::size_t cap, std::size_t *n) {
            return tpx_star(ia.get(), &h, 0, TPX_ORDER_NATURAL, buf, cap, n);
          });
      tp_star[i] = static_cast<std::uint32_t>(len);
    }
    f[StarLoop] = now() - t;
    f[StarLoopCpu] = cpu_now() - c0;

    // Topoplex: the star as its three co-boundary relations R_{0,1}, R_{0,2}, R_{0,3}.
    std::vector<std::uint32_t> tp_rel(no);
    t = now();
    c0 = cpu_now();
    for (std::size_t i = 0; i < no; ++i) {
      const TpxSimplex h{owned[i], 0, ia.stamp()};
      std::size_t total = 0;
      for (std::uint32_t q = 1; q <= 3; ++q) {
        total +=
            query_grown(rank, "tpx_related", ids, [&](std::uint32_t *buf, std::size_t cap, std::size_t *n) {
              return tpx_related(ia.get(), &h, q, TPX_ORDER_NATURAL, buf, cap, n);
            });
      }
      tp_rel[i] = static_cast<std::uint32_t>(total);
    }
    f[RelLoop] = now() - t;
    f[RelLoopCpu] = cpu_now() - c0;

    // Topoplex: the star through lent CSR views of R_{0,1}, R_{0,2}, R_{0,3} (Structure::view:
    // the IA stores none of them, so the first view of each builds an index once, timed and
    // counted apart), then every owned vertex's star read inline.
    std::vector<std::uint32_t> tp_view(no);
    t = now();
    const tp::RelationView v1 = ia.view(0, 1), v2 = ia.view(0, 2), v3 = ia.view(0, 3);
    f[ViewBuild] = now() - t;
    f[ViewBytes] = double(v1.bytes() + v2.bytes() + v3.bytes());
    std::uint64_t checksum = 0;
    t = now();
    for (std::size_t i = 0; i < no; ++i) {
      std::uint32_t n = 0;
      for (const tp::RelationView *v : {&v1, &v2, &v3}) {
        for (tp::Simplex x : (*v)[owned[i]]) {
          checksum += x.index();
          ++n;
        }
      }
      tp_view[i] = n;
    }
    f[ViewLoop] = now() - t;
    f[Checksum] = double(checksum % 1000);

    for (std::size_t i = 0; i < no; ++i) {
      f[StarSum] += dm_size[i];
      f[CellSum] += dm_cells[i];
      const bool equal = tp_view[i] == tp_rel[i] &&
                         (interpolate ? dm_cells[i] == tp_cells[i] && dm_size[i] == tp_star[i] + 1 && dm_size[i] == tp_rel[i] + 1
                                      : dm_cells[i] == tp_cells[i] && dm_size[i] == dm_cells[i] + 1 && tp_star[i] == tp_rel[i]);
      if (!equal) {
        if (f[Mismatch] == 0) {
          std::fprintf(stderr, "rank %d: vertex %u (point %d): DMPlex star %u points, %u cells; Topoplex star %u + 1, R01+R02+R03 %u + 1, R03 %u\n",
                       rank, owned[i], static_cast<int>(owned_points[i]), dm_size[i], dm_cells[i], tp_star[i], tp_rel[i], tp_cells[i]);
        }
        ++f[Mismatch];
      }
    }
  } catch (const std::exception &e) {
    std::fprintf(stderr, "rank %d: %s\n", rank, e.what());
    MPI_Abort(PETSC_COMM_WORLD, 1);
  }

  // What the distributed DM holds: the heap its destruction frees, less coordinate values.
  {
    Vec g = nullptr;
    PetscCall(DMGetCoordinates(dm, &g));
    PetscInt ng = 0;
    if (g) PetscCall(VecGetLocalSize(g, &ng));
    const double h0 = heap_bytes();
    PetscCall(DMDestroy(&dm));
    f[DmHeld] = h0 - heap_bytes() - f[CoordBytes] - 8.0 * double(ng);
  }
  f[HwmBytes] = status_bytes("VmHWM");

  std::vector<double> all(static_cast<std::size_t>(NFields) * static_cast<std::size_t>(size));
  MPI_Gather(f, NFields, MPI_DOUBLE, all.data(), NFields, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  double mismatches = 0;
  if (rank == 0) {
    const std::string run = std::string(label[0] ? label : "run");
    const bool over = size > static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN));
    double hwm_max = 0;
    auto mb = [](double b) { return b / 1048576.0; };
    std::printf("# %s: grid %dx%dx%d cubes: %.4g simplices (%.4g tetrahedra), %d ranks%s, %s DM, load %.2f\n", run.c_str(),
                static_cast<int>(box.nx), static_cast<int>(box.ny), static_cast<int>(box.nz), box.simplices(), box.tets(),
                size, over ? " (oversubscribed)" : "", interpolate ? "interpolated" : "cell-vertex", load);
    for (int r = 0; r < size; ++r) {
      const double *a = &all[static_cast<std::size_t>(r) * NFields];
      mismatches += a[Mismatch];
      hwm_max = std::max(hwm_max, a[HwmBytes]);
      const double topo = a[DmTopoPetsc] > 0 ? a[DmTopoPetsc] : a[DmTopoHeap];
      // (a) memory ("n/a": the topology was not rebuilt, -self_dm 0)
      char ratios[160] = "n/a | n/a | n/a | n/a";
      if (topo > 0) {
        std::snprintf(ratios, sizeof ratios, "%.3f | %.3f | %.3f | %.3f", a[IaBytes] / topo, (a[IaHeap] + a[MapsBytes]) / topo,
                      (a[IaHeap] + a[MapsBytes] + a[TablesHeap]) / topo, (a[IaHeap] + a[ComplexHeap] + a[MapsBytes]) / topo);
      }
      std::printf("@a| %s | %d | %d | %.0f | %.0f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f | %.1f | %s |\n", run.c_str(), size, r,
                  a[Tets], a[Points], mb(a[DmTopoPetsc]), mb(a[DmTopoHeap]), a[Tets] > 0 ? topo / a[Tets] : 0.0, mb(a[DmHeld]),
                  mb(a[IaBytes]), mb(a[IaHeap]), mb(a[ComplexHeap]), mb(a[MapsBytes]), mb(a[TablesHeap]), ratios);
      // (b) conversion
      std::printf("@b| %s | %d | %d | %.0f | %.3f | %.3f | %.3f | %.3f | %.2f | %.2f | %.2f |\n", run.c_str(), size, r, a[Tets],
                  a[FromDm], a[FromDmCpu], a[FromArrays], a[IaBuild], a[Tets] / a[FromDm] / 1e6, a[Tets] / a[FromDmCpu] / 1e6,
                  a[Tets] / (a[FromDm] + a[IaBuild]) / 1e6);
      // (c) stars
      std::printf("@c| %s | %d | %d | %.0f | %.4f | %.4f | %.4f | %.4f | %.4f | %.3f | %.4f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.0f | %.0f | %s |\n",
                  run.c_str(), size, r, a[OwnedVertices], a[DmLoop], a[R03Loop], a[RelLoop], a[StarLoop], a[TablesBuild], a[ViewBuild],
                  a[ViewLoop], mb(a[ViewBytes]), a[DmLoop] / a[R03Loop], a[DmLoopCpu] / a[R03LoopCpu], a[DmLoop] / a[RelLoop],
                  a[DmLoopCpu] / a[RelLoopCpu], a[DmLoop] / a[StarLoop], a[DmLoopCpu] / a[StarLoopCpu], a[DmLoop] / a[ViewLoop],
                  a[StarSum], a[CellSum], a[Mismatch] == 0 ? "yes" : "NO");
      // (d)/(e) phases and peak
      std::printf("@d| %s | %d%s | %d | %.0f | %.0f | %.2f | %.2f | %.2f | %.2f | %.3f | %.3f | %.0f |\n", run.c_str(), size,
                  over ? " (over)" : "", r, a[Points], a[Tets], a[Create], a[Distribute], a[FromDm], a[IaBuild], a[DmLoop],
                  a[R03Loop], mb(a[HwmBytes]));
      std::printf("@e| %s | %d | %d | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f |\n", run.c_str(), size, r, a[Tets],
                  mb(a[HwmCreate]), mb(a[HwmDistribute]), mb(a[HwmSelf]), mb(a[HwmConvert]), mb(a[HwmBytes]));
    }
    std::printf("@s| %s | %d | %.4g | %.0f | %.0f | %.2f |\n", run.c_str(), size, box.simplices(), box.tets(), mb(hwm_max), load);
  }
  MPI_Bcast(&mismatches, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  PetscCall(PetscFinalize());
  return mismatches == 0 ? 0 : 2;
}
