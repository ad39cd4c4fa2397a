// The PETSc DMPlex bridge (Topoplex::dmplex) on 1, 2 and 4 MPI ranks (ctest runs this binary under
// mpiexec -n 1, 2 and 4). Every distributed answer is checked against the serial complex the DM
// came from, through the migration SF's serial point numbers (vertex ids of the serial DM are the
// complex's; coordinates are compared too, so a wrong map cannot pass).
//
// Each test is collective: an unexpected failure on a rank prints it and aborts the whole job
// (MPI_Abort), since the other ranks may be waiting in a collective call.
#include "topoplex_dmplex.hpp"

#include <petscdmplex.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace tp = topoplex;
namespace dx = topoplex::dmplex;

namespace {

int g_rank = 0, g_size = 1;

struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

#define CHECK(cond)                                                                           \
  do {                                                                                        \
    if (!(cond)) {                                                                            \
      std::ostringstream _m;                                                                  \
      _m << __FILE__ << ":" << __LINE__ << ": rank " << g_rank << ": CHECK(" #cond ") failed"; \
      throw Failure(_m.str());                                                                \
    }                                                                                         \
  } while (0)

#define CHECK_MSG(cond, msg)                                                                          \
  do {                                                                                                \
    if (!(cond)) {                                                                                    \
      std::ostringstream _m;                                                                          \
      _m << __FILE__ << ":" << __LINE__ << ": rank " << g_rank << ": CHECK(" #cond ") failed: " << msg; \
      throw Failure(_m.str());                                                                        \
    }                                                                                                 \
  } while (0)

template <class F>
dx::Code code_of(F &&f) {
  try {
    f();
  } catch (const dx::Error &e) {
    return e.code();
  }
  throw Failure("rank " + std::to_string(g_rank) + ": expected a dmplex::Error, got none");
}

using Simplex = std::vector<std::uint32_t>;
using Answer = std::vector<Simplex>;  // rows, each sorted, rows sorted

Answer canonical(const tp::Rows &rows, const std::function<std::uint32_t(std::uint32_t)> &map) {
  Answer out;
  for (auto r : rows) {
    Simplex s;
    for (std::uint32_t v : r) s.push_back(map(v));
    std::sort(s.begin(), s.end());
    out.push_back(std::move(s));
  }
  std::sort(out.begin(), out.end());
  return out;
}

double signed_volume(const std::vector<double> &xyz, const Simplex &t) {
  auto p = [&](std::size_t i, int k) { return xyz[3 * t[i] + static_cast<std::size_t>(k)]; };
  double a[3], b[3], c[3];
  for (int k = 0; k < 3; ++k) {
    a[k] = p(1, k) - p(0, k);
    b[k] = p(2, k) - p(0, k);
    c[k] = p(3, k) - p(0, k);
  }
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

// ---------------------------------------------------------------------------------------------
// Fixtures, built here (no files needed).

// n^3 cubes, 6 tetrahedra each around the main diagonal (Freudenthal / Kuhn), each wound with a
// positive volume; listing attribute gmsh:physical = cube's x-slab + 1; vertex attribute
// medit:ref = 1 on the plane x = 0.
tp::Complex freudenthal(std::uint32_t n) {
  const std::uint32_t m = n + 1;
  auto id = [m](std::uint32_t i, std::uint32_t j, std::uint32_t k) { return (k * m + j) * m + i; };
  std::vector<double> xyz;
  for (std::uint32_t k = 0; k < m; ++k)
    for (std::uint32_t j = 0; j < m; ++j)
      for (std::uint32_t i = 0; i < m; ++i) xyz.insert(xyz.end(), {double(i), double(j), double(k)});
  std::vector<std::vector<std::uint32_t>> tets;
  std::vector<std::int32_t> physical;
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (std::uint32_t k = 0; k < n; ++k)
    for (std::uint32_t j = 0; j < n; ++j)
      for (std::uint32_t i = 0; i < n; ++i)
        for (const auto &p : perms) {
          std::uint32_t c[3] = {i, j, k};
          Simplex t{id(c[0], c[1], c[2])};
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t.push_back(id(c[0], c[1], c[2]));
          }
          if (signed_volume(xyz, t) < 0) std::swap(t[2], t[3]);
          tets.push_back(t);
          physical.push_back(static_cast<std::int32_t>(i + 1));
        }
  tp::Complex c = tp::Complex::from_simplices(m * m * m, tets);
  c.set_coords(xyz, 3);
  c.set_attribute("gmsh:physical", tp::Location::Listed, 1, physical);
  std::vector<std::int32_t> ref(m * m * m, -1);
  for (std::uint32_t v = 0; v < m * m * m; ++v)
    if (v % m == 0) ref[v] = 1;
  c.set_attribute("medit:ref", tp::Location::Vertices, 1, ref);
  return c;
}

// An n x n square of 2n^2 triangles (counter-clockwise), coordinates in 2D.
tp::Complex triangles(std::uint32_t n) {
  const std::uint32_t m = n + 1;
  std::vector<double> xy;
  for (std::uint32_t j = 0; j < m; ++j)
    for (std::uint32_t i = 0; i < m; ++i) xy.insert(xy.end(), {double(i), double(j)});
  std::vector<std::vector<std::uint32_t>> tris;
  std::vector<std::int32_t> physical;
  for (std::uint32_t j = 0; j < n; ++j)
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t a = j * m + i, b = a + 1, c = a + m + 1, d = a + m;
      tris.push_back({a, b, c});
      tris.push_back({a, c, d});
      physical.push_back(static_cast<std::int32_t>(j + 7));
      physical.push_back(static_cast<std::int32_t>(j + 7));
    }
  tp::Complex c = tp::Complex::from_simplices(m * m, tris);
  c.set_coords(xy, 2);
  c.set_attribute("gmsh:physical", tp::Location::Listed, 1, physical);
  return c;
}

// Mixed dimensions and non-manifold: two tetrahedra pinched at vertex 3, a dangling triangle on
// vertex 6, a wire edge, three triangles on one edge (10,11), a wire path linking the parts.
tp::Complex mixed(bool isolated_vertex) {
  std::vector<std::vector<std::uint32_t>> s = {{0, 1, 2, 3}, {3, 4, 5, 6}, {6, 7, 8},   {8, 9},
                                               {9, 10},      {10, 11, 12}, {10, 11, 13}, {10, 11, 14},
                                               {14, 0}};
  const std::uint32_t nv = isolated_vertex ? 16 : 15;
  std::vector<double> xyz;
  for (std::uint32_t v = 0; v < nv; ++v) xyz.insert(xyz.end(), {double(v), double(v * v % 7), double(v % 3)});
  for (auto &t : s)
    if (t.size() == 4 && signed_volume(xyz, t) < 0) std::swap(t[2], t[3]);
  if (isolated_vertex) s.push_back({15});
  tp::Complex c = tp::Complex::from_simplices(nv, s);
  c.set_coords(xyz, 3);
  std::vector<std::int32_t> physical;
  for (std::size_t i = 0; i < s.size(); ++i) physical.push_back(static_cast<std::int32_t>(s[i].size() * 10 + i));
  c.set_attribute("gmsh:physical", tp::Location::Listed, 1, physical);
  return c;
}

// Pure but non-manifold: triangles(4) plus two triangles on grid edge {0, 1} (three triangles
// on one edge) and a triangle pinched at the far corner vertex 24.
tp::Complex nonmanifold_triangles() {
  tp::Complex g = triangles(4);
  std::vector<std::vector<std::uint32_t>> tris;
  for (auto r : g.top_simplices(2)) tris.push_back({r[0], r[1], r[2]});
  tris.push_back({0, 1, 25});
  tris.push_back({1, 0, 26});
  tris.push_back({24, 27, 28});
  std::vector<double> xy = g.coords();
  xy.insert(xy.end(), {0.5, -1.0, 0.5, -2.0, 5.0, 5.0, 4.0, 6.0});
  tp::Complex c = tp::Complex::from_simplices(29, tris);
  c.set_coords(xy, 2);
  return c;
}

// Tops of a complex with winding: listing order is not kept by every path, so a sorted list of
// (winding as given, rotated to start at its smallest vertex for segments and triangles is NOT
// applied: windings must match exactly).
std::vector<Simplex> tops_wound(const tp::Complex &c) {
  std::vector<Simplex> out;
  const TpxInputStats st = c.input_stats();
  for (std::size_t i = 0; i < st.input_simplices; ++i) {
    std::uint32_t top = 0;
    Simplex s = c.input_simplex(i, top);
    if (top != UINT32_MAX) out.push_back(s);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Label values as simplex (sorted vertices) -> value, over listings and vertices. A DM point
// cannot tell a listed isolated vertex from a vertex, so the import gives such a vertex's value
// at both locations: vertex values of isolated vertices are left out here.
std::map<std::pair<std::string, Simplex>, std::int64_t> label_values(const tp::Complex &c, const std::string &name) {
  std::map<std::pair<std::string, Simplex>, std::int64_t> out;
  std::set<std::uint32_t> isolated;
  if (c.top_count(0) > 0)
    for (auto r : c.top_simplices(0)) isolated.insert(r[0]);
  for (const auto &a : c.attributes()) {
    if (a.name != name) continue;
    const auto values = c.attribute<std::int32_t>(a.name, a.location);
    if (a.location == tp::Location::Vertices) {
      for (std::uint32_t v = 0; v < c.vertex_count(); ++v)
        if (values[v] != -1 && !isolated.count(v)) out[{"v", {v}}] = values[v];
    } else {
      const TpxInputStats st = c.input_stats();
      for (std::size_t i = 0; i < st.input_simplices; ++i) {
        std::uint32_t top = 0;
        Simplex s = c.input_simplex(i, top);
        std::sort(s.begin(), s.end());
        if (values[i] != -1) out[{"s", s}] = values[i];
      }
    }
  }
  return out;
}

// The cells of a complex (tops of dimension >= 1) over the vertices they use, renumbered in
// order, with coordinates: what DMPlexDistribute keeps of a mesh (a vertex in no cell is lost).
tp::Complex cells_only(const tp::Complex &c) {
  std::vector<std::vector<std::uint32_t>> cells;
  std::vector<std::uint32_t> renum(c.vertex_count(), UINT32_MAX);
  std::uint32_t n = 0;
  const TpxInputStats st = c.input_stats();
  for (std::size_t i = 0; i < st.input_simplices; ++i) {
    std::uint32_t top = 0;
    Simplex s = c.input_simplex(i, top);
    if (top == UINT32_MAX || s.size() < 2) continue;
    cells.push_back(s);
  }
  std::vector<bool> used(c.vertex_count(), false);
  for (const auto &s : cells)
    for (auto v : s) used[v] = true;
  for (std::uint32_t v = 0; v < c.vertex_count(); ++v)
    if (used[v]) renum[v] = n++;
  for (auto &s : cells)
    for (auto &v : s) v = renum[v];
  const std::vector<double> xyz = c.coords();
  const std::size_t cd = c.coord_dim();
  std::vector<double> kept;
  for (std::uint32_t v = 0; v < c.vertex_count(); ++v)
    if (renum[v] != UINT32_MAX) kept.insert(kept.end(), xyz.begin() + v * cd, xyz.begin() + (v + 1) * cd);
  tp::Complex out = tp::Complex::from_simplices(n, cells);
  if (cd > 0) out.set_coords(kept, cd);
  return out;
}

// ---------------------------------------------------------------------------------------------
// Distributed check: the serial complex `c` on rank 0 -> DM -> distribute(overlap) -> per rank
// RankMesh; every owned simplex's relations equal the serial ones; every serial simplex is owned
// by exactly one rank. Returns whether some owned vertex's local star differed from the serial
// one (only possible with overlap 0).
struct DistributedReport {
  std::size_t owned_checked = 0;
  std::size_t ghosts = 0;
  bool cut_star_seen = false;
};

DistributedReport check_distributed(const tp::Complex &c, bool interpolate, PetscInt overlap, bool expect_exact,
                                    bool vertices_only = false) {
  DM serial = dx::to_dm(PETSC_COMM_WORLD, g_rank == 0 ? &c : nullptr, dx::ExportOptions{interpolate, true});
  PetscInt serial_vstart = 0, vend = 0;
  PetscCallAbort(PETSC_COMM_WORLD, DMPlexGetDepthStratum(serial, 0, &serial_vstart, &vend));
  MPI_Bcast(&serial_vstart, 1, MPIU_INT, 0, PETSC_COMM_WORLD);
  PetscSF migration = nullptr;
  DM local = dx::distribute(serial, overlap, &migration);
  const std::vector<PetscInt> serial_point = dx::serial_points(local, migration);
  dx::RankMesh rm = dx::RankMesh::from_dm(local);

  tp::Structure global(c, tp::Kind::IG);  // the serial answer, on every rank
  const std::uint32_t D = c.dimension();
  const std::vector<double> gxyz = c.coords();
  const std::size_t cd = c.coord_dim();
  const std::vector<double> lxyz = rm.complex().coords();
  CHECK(rm.complex().coord_dim() == cd);

  PetscInt pStart, pEnd;
  PetscCallAbort(PETSC_COMM_WORLD, DMPlexGetChart(local, &pStart, &pEnd));
  std::vector<std::uint32_t> to_global(rm.vertex_count());
  for (std::uint32_t v = 0; v < rm.vertex_count(); ++v) {
    const PetscInt sp = serial_point[static_cast<std::size_t>(rm.point_of_vertex(v) - pStart)];
    CHECK(sp >= serial_vstart);
    to_global[v] = static_cast<std::uint32_t>(sp - serial_vstart);
    CHECK(to_global[v] < c.vertex_count());
    for (std::size_t k = 0; k < cd; ++k) CHECK(lxyz[v * cd + k] == gxyz[to_global[v] * cd + k]);
    CHECK(rm.vertex_of_point(rm.point_of_vertex(v)) == v);
  }
  // Global vertex numbers (from_dm makes them from the point SF's vertex leaves) are PETSc's own.
  {
    IS numbering = nullptr;
    const PetscInt *gn = nullptr;
    PetscCallAbort(PETSC_COMM_WORLD, DMPlexGetVertexNumbering(local, &numbering));
    PetscCallAbort(PETSC_COMM_WORLD, ISGetIndices(numbering, &gn));
    for (std::uint32_t v = 0; v < rm.vertex_count(); ++v) CHECK(rm.global_vertex(v) == (gn[v] < 0 ? -(gn[v] + 1) : gn[v]));
    PetscCallAbort(PETSC_COMM_WORLD, ISRestoreIndices(numbering, &gn));
  }
  auto g = [&](std::uint32_t v) { return to_global[v]; };

  DistributedReport rep;
  tp::Structure s(rm.complex(), tp::Kind::IG);
  const tp::Live live(rm.complex());  // the live mesh on a rank answers like the structure
  std::vector<std::map<Simplex, std::size_t>> serial_index(D + 1);
  std::size_t total = 0;
  std::vector<std::size_t> base(D + 2, 0);
  for (std::uint32_t p = 0; p <= D; ++p) {
    std::size_t i = 0;
    for (auto r : global.simplices(p)) serial_index[p][Simplex(r.begin(), r.end())] = i++;
    base[p] = total;
    total += i;
  }
  std::vector<int> owned_count(total, 0);
  for (std::uint32_t p = 0; p <= s.dimension(); ++p) {
    for (auto r : s.simplices(p)) {
      const Simplex ls(r.begin(), r.end());
      Simplex gs;
      for (std::uint32_t v : ls) gs.push_back(g(v));
      std::sort(gs.begin(), gs.end());
      const auto it = serial_index[p].find(gs);
      CHECK_MSG(it != serial_index[p].end(), "a local simplex that is not in the serial complex");
      if (!rm.owned(s, ls)) {
        ++rep.ghosts;
        if (g_size > 1) CHECK(code_of([&] { rm.owned_relation(s, ls, p); }) == dx::Code::Ghost ||
                              overlap < dx::overlap_needed(p, p));
        continue;
      }
      owned_count[base[p] + it->second] += 1;
      if (vertices_only && p > 0) continue;
      for (std::uint32_t q = 0; q <= D; ++q) {
        const Answer want = canonical(global.relation(gs, q), [](std::uint32_t v) { return v; });
        const Answer here = q > s.dimension() ? Answer{} : canonical(s.relation(ls, q), g);
        if (expect_exact) {
          CHECK_MSG(here == want, "R(" << p << "," << q << ") of an owned simplex differs from the serial answer");
          const Answer guarded = canonical(rm.owned_relation(s, ls, q), g);
          CHECK(guarded == want);
          if (p == 0 && q <= s.dimension()) CHECK(canonical(live.relation(ls, q), g) == want);
        } else if (p == 0 && q == D && here != want) {
          rep.cut_star_seen = true;
        }
        if (g_size > 1 && overlap < dx::overlap_needed(p, q)) {
          CHECK(code_of([&] { rm.owned_relation(s, ls, q); }) == dx::Code::OverlapTooSmall);
        }
      }
      ++rep.owned_checked;
    }
  }
  // Ownership is a partition: each serial simplex owned exactly once over all ranks.
  MPI_Allreduce(MPI_IN_PLACE, owned_count.data(), static_cast<int>(total), MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
  for (std::size_t i = 0; i < total; ++i) CHECK_MSG(owned_count[i] == 1, "serial simplex " << i << " owned " << owned_count[i] << " times");

  PetscCallAbort(PETSC_COMM_WORLD, PetscSFDestroy(&migration));
  PetscCallAbort(PETSC_COMM_WORLD, DMDestroy(&local));
  PetscCallAbort(PETSC_COMM_WORLD, DMDestroy(&serial));
  return rep;
}

// ---------------------------------------------------------------------------------------------
// The tests.

// A named complex exported to a DMPlex with or without its intermediate faces (the round trip's
// and the distributed relations' cases).
struct InterpolationCase {
  const char *name;
  tp::Complex c;
  bool interpolate;
};

void tetrahedra_exported_have_positive_petsc_jacobians() {
  for (bool interpolate : {false, true}) {
    const tp::Complex c = freudenthal(2);
    DM dm = dx::to_dm(PETSC_COMM_WORLD, g_rank == 0 ? &c : nullptr, dx::ExportOptions{interpolate, false});
    PetscInt cStart, cEnd;
    PetscCallAbort(PETSC_COMM_WORLD, DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
    CHECK(cEnd - cStart == (g_rank == 0 ? 48 : 0));
    for (PetscInt cell = cStart; cell < cEnd; ++cell) {
      PetscReal v0[3], J[9], invJ[9], detJ;
      PetscCallAbort(PETSC_COMM_WORLD, DMPlexComputeCellGeometryFEM(dm, cell, nullptr, v0, J, invJ, &detJ));
      CHECK_MSG(detJ > 0, "PETSc sees cell " << cell << " inverted (detJ " << detJ << ")");
    }
    PetscCallAbort(PETSC_COMM_WORLD, DMDestroy(&dm));
  }
}

void serial_round_trip_keeps_simplices_winding_and_labels() {
  std::vector<InterpolationCase> cases;
  cases.push_back({"tets non-interpolated", freudenthal(2), false});
  cases.push_back({"tets interpolated", freudenthal(2), true});
  cases.push_back({"triangles non-interpolated", triangles(3), false});
  cases.push_back({"triangles interpolated", triangles(3), true});
  cases.push_back({"mixed non-manifold", mixed(true), false});
  {  // interpolated, with labelled boundary faces (listed non-top simplices) and edges
    tp::Complex c = freudenthal(1);
    std::vector<std::vector<std::uint32_t>> listing;
    const TpxInputStats st = c.input_stats();
    for (std::size_t i = 0; i < st.input_simplices; ++i) {
      std::uint32_t top = 0;
      listing.push_back(c.input_simplex(i, top));
    }
    listing.push_back({0, 2, 6});  // a face on x = 0 (of tetrahedron {0, 2, 6, 7})
    listing.push_back({0, 2});     // an edge
    std::vector<std::int32_t> physical;
    for (std::size_t i = 0; i < listing.size(); ++i) physical.push_back(static_cast<std::int32_t>(100 + i));
    tp::Complex d = tp::Complex::from_simplices(c.vertex_count(), listing);
    d.set_coords(c.coords(), 3);
    d.set_attribute("gmsh:physical", tp::Location::Listed, 1, physical);
    cases.push_back({"tets interpolated with labelled faces", std::move(d), true});
  }
  {  // a .tpx file (the CLI's `topoplex save`), opened and exported
    char path[] = "/tmp/topoplex-dmplex-XXXXXX.tpx";
    const int fd = mkstemps(path, 4);
    CHECK(fd >= 0);
    close(fd);
    std::remove(path);
    freudenthal(2).save(path);
    cases.push_back({"tets from a .tpx", tp::Complex::open(path), true});
    std::remove(path);
  }
  for (const InterpolationCase &k : cases) {
    DM dm = dx::to_dm(PETSC_COMM_SELF, &k.c, dx::ExportOptions{k.interpolate, true});
    const dx::RankMesh rm = dx::RankMesh::from_dm(dm);
    CHECK_MSG(rm.interpolated() == (k.interpolate && k.c.dimension() > 1), k.name);
    CHECK_MSG(rm.complex().vertex_count() == k.c.vertex_count(), k.name);
    CHECK_MSG(tops_wound(rm.complex()) == tops_wound(k.c), k.name << ": tops or winding differ");
    CHECK_MSG(!label_values(k.c, "gmsh:physical").empty(), k.name << ": a case without labels");
    CHECK_MSG(rm.complex().coords() == k.c.coords(), k.name);
    for (const char *label : {"gmsh:physical", "medit:ref"}) {
      CHECK_MSG(label_values(rm.complex(), label) == label_values(k.c, label), k.name << ": label " << label);
    }
    // Point <-> id maps both ways.
    for (std::size_t i = 0; i < rm.listing_count(); ++i) CHECK(rm.listing_of_point(rm.point_of_listing(i)) == i);
    for (std::uint32_t v = 0; v < rm.vertex_count(); ++v) CHECK(rm.point_of(std::vector<std::uint32_t>{v}) == rm.point_of_vertex(v));
    // One past the end of either map is refused.
    CHECK(code_of([&] { rm.point_of_listing(rm.listing_count()); }) == dx::Code::InvalidArgument);
    CHECK(code_of([&] { rm.point_of_vertex(rm.vertex_count()); }) == dx::Code::InvalidArgument);
    // Every simplex with a point (all of them when interpolated, else the tops and vertices)
    // finds it on demand, and the point's closure vertices are the simplex.
    {
      const tp::Structure ig(rm.complex(), tp::Kind::IG);
      std::size_t found = 0;
      for (std::uint32_t p = 0; p <= ig.dimension(); ++p) {
        for (auto r : ig.simplices(p)) {
          const Simplex sx(r.begin(), r.end());
          const PetscInt pt = rm.point_of(sx);
          if (pt == dx::NO_POINT) {
            CHECK_MSG(!rm.interpolated() && p > 0, k.name << ": a simplex of an interpolated DM has no point");
            continue;
          }
          Simplex back = rm.simplex_of_point(pt);
          std::sort(back.begin(), back.end());
          CHECK_MSG(back == sx, k.name << ": point_of then simplex_of_point is not the simplex");
          ++found;
        }
      }
      CHECK_MSG(found >= rm.listing_count(), k.name);
    }
    // Back again: the re-imported complex exports to the same DM sizes.
    DM again = dx::to_dm(PETSC_COMM_SELF, &rm.complex(), dx::ExportOptions{k.interpolate, true});
    PetscInt a0, a1, b0, b1;
    PetscCallAbort(PETSC_COMM_SELF, DMPlexGetChart(dm, &a0, &a1));
    PetscCallAbort(PETSC_COMM_SELF, DMPlexGetChart(again, &b0, &b1));
    CHECK_MSG(a1 - a0 == b1 - b0, k.name);
    PetscCallAbort(PETSC_COMM_SELF, DMDestroy(&again));
    PetscCallAbort(PETSC_COMM_SELF, DMDestroy(&dm));
  }
}

void interpolated_closure_order_is_the_cell_list_order() {
  // DMPlexInterpolate must not change a cell's vertex order as the bridge reads it back.
  const tp::Complex c = freudenthal(2);
  DM plain = dx::to_dm(PETSC_COMM_SELF, &c, dx::ExportOptions{false, false});
  DM interp = dx::to_dm(PETSC_COMM_SELF, &c, dx::ExportOptions{true, false});
  const dx::RankMesh a = dx::RankMesh::from_dm(plain), b = dx::RankMesh::from_dm(interp);
  CHECK(a.listing_count() == b.listing_count());
  for (std::size_t i = 0; i < a.listing_count(); ++i) {
    CHECK(a.simplex_of_point(a.point_of_listing(i)) == b.simplex_of_point(b.point_of_listing(i)));
  }
  // Interpolated: every face and edge is a point with an owner and a simplex.
  tp::Structure s(b.complex(), tp::Kind::IG);
  for (std::uint32_t p = 0; p <= 3; ++p)
    for (auto r : s.simplices(p)) CHECK(b.point_of(Simplex(r.begin(), r.end())) != dx::NO_POINT);
  PetscCallAbort(PETSC_COMM_SELF, DMDestroy(&plain));
  PetscCallAbort(PETSC_COMM_SELF, DMDestroy(&interp));
}

// Every point's vertices as from_dm keeps them (walked from cones and orientations) against
// PETSc's own DMPlexGetTransitiveClosure order (tetrahedra tops with vertices 0 and 1 swapped back:
// the bridge's winding), on serial and distributed DMs (distribution reorients cones).
std::size_t check_closure_orders(DM dm, const char *name) {
  dx::RankMesh rm = dx::RankMesh::from_dm(dm);
  PetscInt pStart, pEnd, vStart, vEnd;
  PetscCallAbort(PETSC_COMM_SELF, DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCallAbort(PETSC_COMM_SELF, DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  std::size_t checked = 0;
  for (PetscInt p = pStart; p < pEnd; ++p) {
    PetscInt n = 0, *cl = nullptr, support = 0;
    Simplex petsc;
    PetscCallAbort(PETSC_COMM_SELF, DMPlexGetTransitiveClosure(dm, p, PETSC_TRUE, &n, &cl));
    for (PetscInt k = 0; k < n; ++k)
      if (cl[2 * k] >= vStart && cl[2 * k] < vEnd) petsc.push_back(static_cast<std::uint32_t>(cl[2 * k] - vStart));
    PetscCallAbort(PETSC_COMM_SELF, DMPlexRestoreTransitiveClosure(dm, p, PETSC_TRUE, &n, &cl));
    PetscCallAbort(PETSC_COMM_SELF, DMPlexGetSupportSize(dm, p, &support));
    if (support == 0 && petsc.size() == 4) std::swap(petsc[0], petsc[1]);
    const Simplex ours = rm.simplex_of_point(p);
    CHECK_MSG(ours == petsc, name << ": point " << p << " has vertices in another order than PETSc's closure");
    ++checked;
  }
  // The complex's tops as from_dm read them (PETSc's raw cone arrays on its fast paths) are
  // those points' closure vertices in the bridge's winding; then the complex moved out leaves
  // the maps working.
  if (!rm.empty()) {
    for (std::size_t i = 0; i < rm.listing_count(); ++i) {
      std::uint32_t top = 0;
      CHECK_MSG(rm.complex().input_simplex(i, top) == rm.simplex_of_point(rm.point_of_listing(i)),
                name << ": top " << i << " read otherwise than its point's closure");
    }
    const std::size_t listed = rm.listing_count();
    const tp::Complex taken = rm.take_complex();
    CHECK(code_of([&] { rm.complex(); }) == dx::Code::Refused);
    CHECK(taken.input_stats().input_simplices == listed && rm.listing_count() == listed);
    for (std::size_t i = 0; i < listed; ++i) CHECK(rm.listing_of_point(rm.point_of_listing(i)) == i);
  }
  return checked;
}

void vertices_of_every_point_follow_petscs_closure_order() {
  struct Case {
    const char *name;
    tp::Complex c;
    bool distributed; /* dangling simplices do not distribute (see distribute) */
  };
  std::vector<Case> cases;
  cases.push_back({"freudenthal 3", freudenthal(3), true});
  cases.push_back({"triangles 6", triangles(6), true});
  cases.push_back({"non-manifold triangles", nonmanifold_triangles(), false});
  std::size_t checked = 0;
  for (const Case &k : cases) {
    DM serial = dx::to_dm(PETSC_COMM_WORLD, g_rank == 0 ? &k.c : nullptr, dx::ExportOptions{true, false});
    checked += check_closure_orders(serial, k.name);  // collective: the points are on rank 0
    if (k.distributed) {
      DM dist = dx::distribute(serial, 1);
      checked += check_closure_orders(dist, k.name);
      PetscCallAbort(PETSC_COMM_WORLD, DMDestroy(&dist));
    }
    PetscCallAbort(PETSC_COMM_WORLD, DMDestroy(&serial));
  }
  // PETSc's Gmsh reader, interpolated by PETSc and distributed (optional real data).
  std::string path = std::string(TOPOPLEX_DMPLEX_SHARED_DATA_DIR) + "/labelled/gmsh_t2.msh";
  if (const char *env = std::getenv("TOPOPLEX_DATA_DIR")) path = std::string(env) + "/labelled/gmsh_t2.msh";
  int present = std::ifstream(path).good() ? 1 : 0;
  MPI_Bcast(&present, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  if (present) {
    // Read cell-vertex (its labelled faces are no facets PETSc's interpolating reader finds),
    // then interpolated by PETSc.
    DM plain, read, dist = nullptr;
    PetscCallAbort(PETSC_COMM_WORLD, DMPlexCreateFromFile(PETSC_COMM_WORLD, path.c_str(), "read", PETSC_FALSE, &plain));
    PetscCallAbort(PETSC_COMM_WORLD, DMPlexInterpolate(plain, &read));
    PetscCallAbort(PETSC_COMM_WORLD, DMDestroy(&plain));
    PetscCallAbort(PETSC_COMM_WORLD, DMPlexDistribute(read, 1, nullptr, &dist));
    checked += check_closure_orders(dist ? dist : read, "gmsh_t2");
    if (dist) PetscCallAbort(PETSC_COMM_WORLD, DMDestroy(&dist));
    PetscCallAbort(PETSC_COMM_WORLD, DMDestroy(&read));
  } else if (g_rank == 0) {
    std::printf("    skipped: %s absent\n", path.c_str());
  }
  unsigned long n = checked, sum = 0;
  MPI_Allreduce(&n, &sum, 1, MPI_UNSIGNED_LONG, MPI_SUM, PETSC_COMM_WORLD);
  CHECK(sum > 0);
  if (g_rank == 0) std::printf("    %lu points' vertex orders checked\n", sum);
}

void owned_relations_equal_serial_answers_with_overlap_1() {
  std::vector<InterpolationCase> cases;
  cases.push_back({"freudenthal 3 interpolated", freudenthal(3), true});
  cases.push_back({"freudenthal 3 cell-vertex", freudenthal(3), false});
  cases.push_back({"triangles 6 interpolated", triangles(6), true});
  cases.push_back({"non-manifold triangles interpolated", nonmanifold_triangles(), true});
  cases.push_back({"non-manifold triangles cell-vertex", nonmanifold_triangles(), false});
  for (const InterpolationCase &k : cases) {
    const DistributedReport r = check_distributed(k.c, k.interpolate, 1, true);
    unsigned long local[2] = {r.owned_checked, r.ghosts}, sum[2];
    MPI_Allreduce(local, sum, 2, MPI_UNSIGNED_LONG, MPI_SUM, PETSC_COMM_WORLD);
    CHECK_MSG(sum[0] > 0, k.name);
    if (g_size > 1) CHECK_MSG(sum[1] > 0, k.name << ": no ghost on " << g_size << " ranks");
    if (g_rank == 0) std::printf("    %s: %lu owned simplices checked, %lu ghosts\n", k.name, sum[0], sum[1]);
  }
}

void overlap_0_cuts_stars_and_is_refused() {
  if (g_size == 1) return;  // nothing is cut on one rank
  const DistributedReport r = check_distributed(freudenthal(3), true, 0, false);
  int cut = r.cut_star_seen ? 1 : 0, any = 0;
  MPI_Allreduce(&cut, &any, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  CHECK_MSG(any == 1, "with overlap 0 some owned vertex's star must be cut on some rank");
}

void face_adjacency_overlap_is_refused() {
  if (g_size == 1) return;
  // Overlap grown by face adjacency (finite volumes): layers of face neighbours need not hold a
  // vertex's star, so owned_relation refuses q >= p; the boundary (q < p) is still answered.
  const tp::Complex c = freudenthal(2);
  DM serial = dx::to_dm(PETSC_COMM_WORLD, g_rank == 0 ? &c : nullptr, dx::ExportOptions{true, false});
  PetscCallAbort(PETSC_COMM_WORLD, DMSetBasicAdjacency(serial, PETSC_TRUE, PETSC_FALSE));
  DM local = dx::distribute(serial, 1);
  const dx::RankMesh rm = dx::RankMesh::from_dm(local);
  if (!rm.empty()) {
    tp::Structure s(rm.complex(), tp::Kind::IG);
    for (auto r : s.simplices(1)) {
      const Simplex e(r.begin(), r.end());
      if (!rm.owned(s, e)) continue;
      CHECK(code_of([&] { rm.owned_relation(s, e, 3); }) == dx::Code::OverlapTooSmall);
      CHECK(rm.owned_relation(s, e, 0).size() == 2);
    }
  }
  PetscCallAbort(PETSC_COMM_WORLD, DMDestroy(&local));
  PetscCallAbort(PETSC_COMM_WORLD, DMDestroy(&serial));
}

void non_simplicial_cells_are_refused() {
  for (PetscBool interpolate : {PETSC_FALSE, PETSC_TRUE}) {
    DM box;
    const PetscInt faces[3] = {2, 1, 1};
    PetscCallAbort(PETSC_COMM_SELF, DMPlexCreateBoxMesh(PETSC_COMM_SELF, 3, PETSC_FALSE, faces, nullptr, nullptr, nullptr, interpolate, &box));
    CHECK(code_of([&] { dx::RankMesh::from_dm(box); }) == dx::Code::NotSimplicial);
    PetscCallAbort(PETSC_COMM_SELF, DMDestroy(&box));
    // Quadrilaterals in 2D: 4 vertices like a tetrahedron, told apart by the cell type.
    DM quads;
    PetscCallAbort(PETSC_COMM_SELF, DMPlexCreateBoxMesh(PETSC_COMM_SELF, 2, PETSC_FALSE, faces, nullptr, nullptr, nullptr, interpolate, &quads));
    CHECK(code_of([&] { dx::RankMesh::from_dm(quads); }) == dx::Code::NotSimplicial);
    PetscCallAbort(PETSC_COMM_SELF, DMDestroy(&quads));
  }
}

void reference_cells_simplices_in_others_refused_by_name() {
  for (DMPolytopeType ct : {DM_POLYTOPE_SEGMENT, DM_POLYTOPE_TRIANGLE, DM_POLYTOPE_TETRAHEDRON}) {
    DM dm;
    PetscCallAbort(PETSC_COMM_SELF, DMPlexCreateReferenceCell(PETSC_COMM_SELF, ct, &dm));
    const dx::RankMesh rm = dx::RankMesh::from_dm(dm);
    const std::uint32_t d = static_cast<std::uint32_t>(DMPolytopeTypeGetDim(ct));
    CHECK(rm.complex().dimension() == d);
    CHECK(rm.complex().top_count(d) == 1);
    CHECK(rm.interpolated());  // reference cells are interpolated (a segment trivially)
    PetscCallAbort(PETSC_COMM_SELF, DMDestroy(&dm));
  }
  for (DMPolytopeType ct : {DM_POLYTOPE_QUADRILATERAL, DM_POLYTOPE_HEXAHEDRON, DM_POLYTOPE_TRI_PRISM,
                            DM_POLYTOPE_PYRAMID}) {
    DM dm;
    PetscCallAbort(PETSC_COMM_SELF, DMPlexCreateReferenceCell(PETSC_COMM_SELF, ct, &dm));
    try {
      dx::RankMesh::from_dm(dm);
      CHECK_MSG(false, DMPolytopeTypes[ct] << " accepted");
    } catch (const dx::Error &e) {
      CHECK(e.code() == dx::Code::NotSimplicial);
      CHECK_MSG(std::string(e.what()).find(DMPolytopeTypes[ct]) != std::string::npos, e.what());
    }
    PetscCallAbort(PETSC_COMM_SELF, DMDestroy(&dm));
  }
}

void refusals_are_clear() {
  const tp::Complex m = mixed(true);
  // Interpolation of mixed dimensions: refused on every rank.
  CHECK(code_of([&] { dx::to_dm(PETSC_COMM_WORLD, g_rank == 0 ? &m : nullptr, dx::ExportOptions{true, true}); }) == dx::Code::Refused);
  // A vertex in no cell would be lost by the distribution; cells of several dimensions are
  // beyond PETSc 3.18's migration: both refused on every rank before DMPlexDistribute.
  for (bool isolated : {true, false}) {
    const tp::Complex k = mixed(isolated);
    DM dm = dx::to_dm(PETSC_COMM_WORLD, g_rank == 0 ? &k : nullptr, dx::ExportOptions{false, true});
    CHECK(code_of([&] { dx::distribute(dm, 1); }) == dx::Code::Refused);
    PetscCallAbort(PETSC_COMM_WORLD, DMDestroy(&dm));
  }
  // The same for an interpolated DM.
  {
    const tp::Complex k = tp::Complex::from_simplices(5, {{0, 1, 2, 3}});
    DM dm = dx::to_dm(PETSC_COMM_WORLD, g_rank == 0 ? &k : nullptr, dx::ExportOptions{true, false});
    CHECK(code_of([&] { dx::distribute(dm, 1); }) == dx::Code::Refused);  // vertex 4 is in no cell
    PetscCallAbort(PETSC_COMM_WORLD, DMDestroy(&dm));
  }
  // A labelled face has no point in a cell-vertex DM.
  tp::Complex c = tp::Complex::from_simplices(4, {{0, 1, 2, 3}, {0, 1, 2}});
  c.set_attribute("gmsh:physical", tp::Location::Listed, 1, std::vector<std::int32_t>{-1, 5});
  CHECK(code_of([&] { dx::to_dm(PETSC_COMM_SELF, &c, dx::ExportOptions{false, true}); }) == dx::Code::Refused);
}

void dm_without_coordinates_gives_a_complex_without() {
  const tp::Complex c = tp::Complex::from_simplices(5, {{0, 1, 2}, {1, 2, 3}, {3, 4}});
  DM dm = dx::to_dm(PETSC_COMM_SELF, &c, dx::ExportOptions{false, false});
  Vec coords = nullptr;
  PetscCallAbort(PETSC_COMM_SELF, DMGetCoordinatesLocal(dm, &coords));
  CHECK(coords == nullptr);
  const dx::RankMesh rm = dx::RankMesh::from_dm(dm);
  CHECK(rm.complex().coord_dim() == 0);
  CHECK(tops_wound(rm.complex()) == tops_wound(c));
  PetscCallAbort(PETSC_COMM_SELF, DMDestroy(&dm));
}

void gmsh_file_read_by_petsc_matches_topoplex_reader() {
  // A Gmsh file Topoplex wrote, read by PETSc's own reader: same tetrahedra, same winding (matched
  // through coordinates), and the physical tags arrive as PETSc's "Cell Sets" label.
  char path[] = "/tmp/topoplex-dmplex-XXXXXX.msh";
  int fd = -1;
  if (g_rank == 0) fd = mkstemps(path, 4);
  MPI_Bcast(path, sizeof path, MPI_CHAR, 0, PETSC_COMM_WORLD);
  tp::Complex c = freudenthal(2);
  c.remove_attribute("medit:ref");  // Gmsh has no place for it
  if (g_rank == 0) {
    CHECK(fd >= 0);
    close(fd);
    c.write(path, tp::Format::MSH2);
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  DM dm;
  PetscCallAbort(PETSC_COMM_WORLD, DMPlexCreateFromFile(PETSC_COMM_WORLD, path, "topoplex", PETSC_TRUE, &dm));
  if (g_rank == 0) std::remove(path);
  const dx::RankMesh rm = dx::RankMesh::from_dm(dm);
  CHECK(rm.empty() == (g_rank != 0));  // PETSc reads the file on rank 0
  if (g_rank != 0) CHECK(code_of([&] { rm.complex(); }) == dx::Code::Refused);
  if (g_rank == 0) {
    const tp::Complex &r = rm.complex();
    CHECK(r.vertex_count() == c.vertex_count());
    const std::vector<double> rx = r.coords(), cx = c.coords();
    std::map<std::vector<double>, std::uint32_t> by_xyz;
    for (std::uint32_t v = 0; v < c.vertex_count(); ++v) by_xyz[{cx[3 * v], cx[3 * v + 1], cx[3 * v + 2]}] = v;
    std::map<Simplex, std::int64_t> got;  // wound tet in c's ids -> Cell Sets value
    const auto cell_sets = r.attribute<std::int32_t>("Cell Sets", tp::Location::Listed);
    const TpxInputStats st = r.input_stats();
    for (std::size_t i = 0; i < st.input_simplices; ++i) {
      std::uint32_t top = 0;
      Simplex s = r.input_simplex(i, top);
      if (s.size() != 4) continue;
      for (auto &v : s) v = by_xyz.at({rx[3 * v], rx[3 * v + 1], rx[3 * v + 2]});
      CHECK_MSG(signed_volume(cx, s) > 0, "a tetrahedron read through PETSc is inverted");
      got[s] = cell_sets[i];
    }
    std::map<Simplex, std::int64_t> want;
    const auto physical = c.attribute<std::int32_t>("gmsh:physical", tp::Location::Listed);
    for (std::size_t i = 0; i < c.input_stats().input_simplices; ++i) {
      std::uint32_t top = 0;
      want[c.input_simplex(i, top)] = physical[i];
    }
    CHECK(got == want);
  }
  PetscCallAbort(PETSC_COMM_WORLD, DMDestroy(&dm));
}

void shared_gmsh_meshes_distribute_exactly() {
  // Real meshes (optional): /work/shared/data/labelled, or $TOPOPLEX_DATA_DIR/labelled.
  std::string dir = TOPOPLEX_DMPLEX_SHARED_DATA_DIR;
  if (const char *env = std::getenv("TOPOPLEX_DATA_DIR")) dir = env;
  // gmsh_t2 (2,422 tets): every owned simplex's relations; gmsh_t16 (15,078 tets in 6 volumes
  // sharing interfaces): owned vertices' relations (and the ownership partition of all), to keep
  // the 4-rank oversubscribed run short.
  for (const char *name : {"labelled/gmsh_t2.msh", "labelled/gmsh_t16.msh"}) {
    const bool vertices_only = std::string(name) == "labelled/gmsh_t16.msh";
    const std::string path = dir + "/" + name;
    int present = std::ifstream(path).good() ? 1 : 0;
    MPI_Bcast(&present, 1, MPI_INT, 0, PETSC_COMM_WORLD);
    if (!present) {
      if (g_rank == 0) std::printf("    skipped: %s absent\n", path.c_str());
      continue;
    }
    // The serial complex: PETSc's reading on this rank alone, through the bridge (the serial
    // answer is the same code on the whole mesh).
    DM one;
    PetscCallAbort(PETSC_COMM_SELF, DMPlexCreateFromFile(PETSC_COMM_SELF, path.c_str(), "serial", PETSC_FALSE, &one));
    const dx::RankMesh whole = dx::RankMesh::from_dm(one);
    PetscCallAbort(PETSC_COMM_SELF, DMDestroy(&one));
    const DistributedReport r = check_distributed(cells_only(whole.complex()), false, 1, true, vertices_only);
    unsigned long n = r.owned_checked, sum = 0;
    MPI_Allreduce(&n, &sum, 1, MPI_UNSIGNED_LONG, MPI_SUM, PETSC_COMM_WORLD);
    if (g_rank == 0) std::printf("    %s: %lu owned simplices checked\n", name, sum);
  }
}

}  // namespace

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  MPI_Comm_rank(PETSC_COMM_WORLD, &g_rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &g_size);
  const std::vector<std::pair<const char *, void (*)()>> tests = {
      {"tetrahedra_exported_have_positive_petsc_jacobians", tetrahedra_exported_have_positive_petsc_jacobians},
      {"serial_round_trip_keeps_simplices_winding_and_labels", serial_round_trip_keeps_simplices_winding_and_labels},
      {"interpolated_closure_order_is_the_cell_list_order", interpolated_closure_order_is_the_cell_list_order},
      {"vertices_of_every_point_follow_petscs_closure_order", vertices_of_every_point_follow_petscs_closure_order},
      {"owned_relations_equal_serial_answers_with_overlap_1", owned_relations_equal_serial_answers_with_overlap_1},
      {"overlap_0_cuts_stars_and_is_refused", overlap_0_cuts_stars_and_is_refused},
      {"face_adjacency_overlap_is_refused", face_adjacency_overlap_is_refused},
      {"non_simplicial_cells_are_refused", non_simplicial_cells_are_refused},
      {"reference_cells_simplices_in_others_refused_by_name", reference_cells_simplices_in_others_refused_by_name},
      {"refusals_are_clear", refusals_are_clear},
      {"dm_without_coordinates_gives_a_complex_without", dm_without_coordinates_gives_a_complex_without},
      {"gmsh_file_read_by_petsc_matches_topoplex_reader", gmsh_file_read_by_petsc_matches_topoplex_reader},
      {"shared_gmsh_meshes_distribute_exactly", shared_gmsh_meshes_distribute_exactly},
  };
  for (const auto &t : tests) {
    try {
      t.second();
    } catch (const std::exception &e) {
      std::fprintf(stderr, "[FAIL] %s: %s\n", t.first, e.what());
      std::fflush(stderr);
      MPI_Abort(PETSC_COMM_WORLD, 1);
    }
    MPI_Barrier(PETSC_COMM_WORLD);
    if (g_rank == 0) std::printf("[ OK ] %s (%d ranks)\n", t.first, g_size);
  }
  PetscCall(PetscFinalize());
  return 0;
}
