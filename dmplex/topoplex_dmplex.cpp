// The PETSc DMPlex bridge (include/topoplex_dmplex.hpp): one rank's DMPlex part <-> a Topoplex
// complex over the C ABI's C++ wrapper. Conventions and costs are in the header and docs/dmplex.md.
#include "topoplex_dmplex.hpp"

#include <algorithm>
#include <map>
#include <memory>
#include <sstream>
#include <utility>

namespace topoplex {
namespace dmplex {

namespace {

void petsc_check(PetscErrorCode ierr, const char *call) {
  if (ierr != 0) {
    std::ostringstream m;
    m << "PETSc call " << call << " failed with error " << static_cast<int>(ierr);
    throw Error(Code::Petsc, m.str());
  }
}
#define TPX_PETSC(call) petsc_check((call), #call)

// Tetrahedra: PETSc's cone order is Topoplex's winding with vertices 0 and 1 swapped.
void petsc_winding(std::vector<std::uint32_t> &vs) {
  if (vs.size() == 4) std::swap(vs[0], vs[1]);
}

bool skipped_label(const char *name) {
  const std::string n(name);
  return n == "depth" || n == "celltype";
}

std::vector<std::uint32_t> sorted(std::vector<std::uint32_t> v) {
  std::sort(v.begin(), v.end());
  return v;
}

// Appends to `vs` the vertex ids (point - vStart) of point p: p itself when a vertex, else the
// vertices of its transitive closure in closure order.
void append_vertices(DM dm, PetscInt p, PetscInt vStart, PetscInt vEnd,
                     std::vector<std::uint32_t> &vs) {
  if (p >= vStart && p < vEnd) {
    vs.push_back(static_cast<std::uint32_t>(p - vStart));
    return;
  }
  PetscInt n = 0;
  PetscInt *closure = nullptr;
  TPX_PETSC(DMPlexGetTransitiveClosure(dm, p, PETSC_TRUE, &n, &closure));
  for (PetscInt k = 0; k < n; ++k) {
    const PetscInt q = closure[2 * k];
    if (q >= vStart && q < vEnd) vs.push_back(static_cast<std::uint32_t>(q - vStart));
  }
  TPX_PETSC(DMPlexRestoreTransitiveClosure(dm, p, PETSC_TRUE, &n, &closure));
}

}  // namespace

PetscInt overlap_needed(std::uint32_t p, std::uint32_t q) { return q < p ? 0 : 1; }

namespace {

// The triangle and segment arrangements PETSc's closure applies to a cone reached with
// orientation o (DMPolytopeTypeGetArrangment), read once into tables for the tight loops.
struct Arrangements {
  // Triangle reached with o (-3 .. 2): its first and second arranged edges (cone indices) and
  // the first edge's arranged orientation.
  PetscInt tri_first[6], tri_second[6], tri_first_o[6];
  Arrangements() {
    for (PetscInt o = -3; o < 3; ++o) {
      const PetscInt *arr = DMPolytopeTypeGetArrangment(DM_POLYTOPE_TRIANGLE, o);
      tri_first[o + 3] = arr[0];
      tri_first_o[o + 3] = arr[1];
      tri_second[o + 3] = arr[2];
    }
  }
};

// PETSc's raw cone arrays of a DM and the cone section's offsets.
struct Cones {
  PetscSection section = nullptr;
  PetscInt *cone = nullptr, *ornt = nullptr;
  PetscInt storage = 0;  // the cone arrays' length (PetscSectionGetStorageSize sums every dof: once)
  explicit Cones(DM dm) {
    TPX_PETSC(DMPlexGetConeSection(dm, &section));
    TPX_PETSC(DMPlexGetCones(dm, &cone));
    TPX_PETSC(DMPlexGetConeOrientations(dm, &ornt));
    TPX_PETSC(PetscSectionGetStorageSize(section, &storage));
  }
};

// Sets supported[c - pStart] for every point c of [pStart, pEnd) that cone[0 .. n) names. Plain
// values, not a lambda's captures by reference: a byte store may alias anything, so there every
// store reloaded the bounds and pointers (three times slower).
void mark_named(const PetscInt *cone, PetscInt n, PetscInt pStart, PetscInt pEnd, unsigned char *supported) {
  const PetscInt span = pEnd - pStart;
  for (PetscInt k = 0; k < n; ++k) {
    const PetscInt c = cone[k] - pStart;
    if (c >= 0 && c < span) supported[c] = 1;
  }
}

// The raw arrays of a fully interpolated simplicial DM whose strata are fixed-width blocks of
// cones, and how to read a simplex's vertices from them in PETSc's closure order: an edge is its
// cone; a triangle reached with orientation o lists its first arranged edge's vertices (swapped
// when that edge's composed orientation is not 0), then the vertex its second arranged edge adds;
// a tetrahedron lists its first face's vertices as that triangle reached with its cone
// orientation, then the vertex of its second face's first two edges that is missing. Each read
// checks that the points it meets lie in the strata it expects (false otherwise).
struct SimplexCones {
  const PetscInt *C = nullptr, *O = nullptr;
  PetscInt at[4] = {0, 0, 0, 0};  // point q of depth d's cone: C[at[d] + (d + 1) q]
  PetscInt lo[4] = {0, 0, 0, 0}, hi[4] = {0, 0, 0, 0};  // stratum d: [lo[d], hi[d])
  Arrangements arr;

  bool in(PetscInt q, int d) const { return q >= lo[d] && q < hi[d]; }
  bool edge(PetscInt e, PetscInt *v) const {
    if (!in(e, 1)) return false;
    const PetscInt *c = C + at[1] + 2 * e;
    v[0] = c[0];
    v[1] = c[1];
    return in(v[0], 0) && in(v[1], 0);
  }
  bool triangle(PetscInt f, PetscInt o, PetscInt *v) const {
    if (!in(f, 2) || o < -3 || o > 2) return false;
    const PetscInt k = at[2] + 3 * f;
    const PetscInt i0 = arr.tri_first[o + 3], i1 = arr.tri_second[o + 3];
    PetscInt a[2], b[2];
    if (!edge(C[k + i0], a) || !edge(C[k + i1], b)) return false;
    const PetscInt co = DMPolytopeTypeComposeOrientation(DM_POLYTOPE_SEGMENT, arr.tri_first_o[o + 3], O[k + i0]);
    v[0] = co == 0 ? a[0] : a[1];
    v[1] = co == 0 ? a[1] : a[0];
    v[2] = b[0] == a[0] || b[0] == a[1] ? b[1] : b[0];
    return true;
  }
  bool tetrahedron(PetscInt t, PetscInt *v) const {
    const PetscInt k = at[3] + 4 * t;
    if (!triangle(C[k], O[k], v)) return false;
    const PetscInt f1 = C[k + 1];
    if (!in(f1, 2)) return false;
    // The second face shares one edge with the first: its first edge that is not shared holds
    // the missing vertex (the first edge is shared one time in three).
    for (int i = 0; i < 2; ++i) {
      PetscInt e[2];
      if (!edge(C[at[2] + 3 * f1 + i], e)) return false;
      for (PetscInt x : e) {
        if (x != v[0] && x != v[1] && x != v[2]) {
          v[3] = x;
          return true;
        }
      }
    }
    return false;
  }
};

// Writes the tops among the points [start, end) of depth d (those whose `supported` byte, indexed
// from start, is 0): point to *tops, vertex ids (Topoplex winding) to *ids, each top's end to
// *ends (counting from `base` ids), advancing the three. `r` by value and the outputs as local
// pointers: a store of an id may alias a PetscInt, and the reader's fields must stay in registers.
// False when a point is not read as a simplex (the caller takes the general path).
bool read_tops(const SimplexCones r, PetscInt start, PetscInt end, int d, const unsigned char *supported,
               PetscInt vStart, PetscInt *&tops, std::uint32_t *&ids, std::size_t *&ends, std::size_t base) {
  PetscInt *t = tops;
  std::uint32_t *w = ids;
  std::size_t *e = ends;
  const std::uint32_t *first = w;
  for (PetscInt p = start; p < end; ++p) {
    if (supported[p - start]) continue;
    PetscInt v[4] = {p, 0, 0, 0};
    const bool ok = d == 0 ? true : d == 1 ? r.edge(p, v) : d == 2 ? r.triangle(p, 0, v) : r.tetrahedron(p, v);
    if (!ok) return false;
    if (d == 3) std::swap(v[0], v[1]);  // petsc_winding
    for (int k = 0; k <= d; ++k) w[k] = static_cast<std::uint32_t>(v[k] - vStart);
    w += d + 1;
    *t++ = p;
    *e++ = base + static_cast<std::size_t>(w - first);
  }
  tops = t;
  ids = w;
  ends = e;
  return true;
}

// The tops among the cells [start, end) of a cell-vertex DM (depth 1), written as read_tops does:
// each cell's cone is its vertices, laid out from cone[0] in chart order (fixed_width checked the
// block's ends); a cone of 2, 3 or 4 vertices is a simplex unless `others` (cells of the DM with
// other types of those sizes) asks the cell type. A plain function for the same reason as
// read_tops. False when a cone names a point that is not a vertex; throws NotSimplicial naming
// the first other cell.
bool read_cell_vertex_tops(DM dm, PetscSection section, const PetscInt *cone, PetscInt start, PetscInt end,
                           const unsigned char *supported, PetscInt vStart, PetscInt vEnd, bool others, int rank,
                           PetscInt *&tops, std::uint32_t *&ids, std::size_t *&ends, std::size_t base) {
  PetscInt *t = tops;
  std::uint32_t *w = ids;
  std::size_t *e = ends;
  const std::uint32_t *first = w;
  for (PetscInt p = start; p < end; ++p) {
    PetscInt nc = 0;
    TPX_PETSC(PetscSectionGetDof(section, p, &nc));
    DMPolytopeType ct = nc == 2 ? DM_POLYTOPE_SEGMENT : nc == 3 ? DM_POLYTOPE_TRIANGLE : DM_POLYTOPE_TETRAHEDRON;
    if (others || nc < 2 || nc > 4) TPX_PETSC(DMPlexGetCellType(dm, p, &ct));
    if (!((ct == DM_POLYTOPE_SEGMENT && nc == 2) || (ct == DM_POLYTOPE_TRIANGLE && nc == 3) ||
          (ct == DM_POLYTOPE_TETRAHEDRON && nc == 4))) {
      std::ostringstream m;
      m << "DMPlex point " << p << " (rank " << rank << ") is a " << DMPolytopeTypes[ct] << " with " << nc
        << " vertices at depth 1: Topoplex holds simplicial complexes only (points, segments, triangles, tetrahedra)";
      throw Error(Code::NotSimplicial, m.str());
    }
    const PetscInt *c = cone;
    cone += nc;
    if (supported[p - start]) continue;
    for (PetscInt k = 0; k < nc; ++k) {
      if (c[k] < vStart || c[k] >= vEnd) return false;
      w[k] = static_cast<std::uint32_t>(c[k] - vStart);
    }
    if (nc == 4) std::swap(w[0], w[1]);  // petsc_winding
    w += nc;
    *t++ = p;
    *e++ = base + static_cast<std::size_t>(w - first);
  }
  tops = t;
  ids = w;
  ends = e;
  return true;
}

}  // namespace

RankMesh::RankMesh(RankMesh &&o) noexcept { *this = std::move(o); }

RankMesh &RankMesh::operator=(RankMesh &&o) noexcept {
  if (this == &o) return *this;
  release();
  complex_ = std::move(o.complex_);
  o.complex_.reset();
  dm_ = std::exchange(o.dm_, nullptr);
  sf_ = std::exchange(o.sf_, nullptr);
  global_ = std::move(o.global_);
  rank_ = o.rank_;
  size_ = o.size_;
  overlap_ = o.overlap_;
  vertex_adjacency_ = o.vertex_adjacency_;
  interpolated_ = o.interpolated_;
  p_start_ = o.p_start_;
  p_end_ = o.p_end_;
  v_start_ = o.v_start_;
  v_end_ = o.v_end_;
  strata_ = std::move(o.strata_);
  top_run_point_ = std::move(o.top_run_point_);
  top_run_listing_ = std::move(o.top_run_listing_);
  top_listings_ = o.top_listings_;
  extra_point_ = std::move(o.extra_point_);
  extra_listing_ = std::move(o.extra_listing_);
  leaf_ = std::exchange(o.leaf_, nullptr);
  remote_ = std::exchange(o.remote_, nullptr);
  nleaves_ = std::exchange(o.nleaves_, 0);
  ghost_point_ = std::move(o.ghost_point_);
  ghost_owner_ = std::move(o.ghost_owner_);
  return *this;
}

RankMesh::~RankMesh() { release(); }

// Drops the references from_dm took (errors ignored: a destructor cannot report them).
void RankMesh::release() noexcept {
  if (sf_) PetscSFDestroy(&sf_);
  if (dm_) DMDestroy(&dm_);
}

PetscInt RankMesh::depth_of(PetscInt p) const {
  for (std::size_t d = 0; d < strata_.size(); ++d) {
    if (p >= strata_[d].first && p < strata_[d].second) return static_cast<PetscInt>(d);
  }
  PetscInt pd = 0;  // not stratified by ranges: ask PETSc
  TPX_PETSC(DMPlexGetPointDepth(dm_, p, &pd));
  return pd;
}

void RankMesh::closure_vertices(PetscInt p, std::vector<std::uint32_t> &out) const {
  if (p >= v_start_ && p < v_end_) {
    out.push_back(static_cast<std::uint32_t>(p - v_start_));
    return;
  }
  const PetscInt pdepth = depth_of(p);
  if (pdepth == 1) {  // an edge, or a cell of a cell-vertex DM: its cone
    PetscInt nc = 0;
    const PetscInt *cone = nullptr;
    TPX_PETSC(DMPlexGetConeSize(dm_, p, &nc));
    TPX_PETSC(DMPlexGetCone(dm_, p, &cone));
    for (PetscInt k = 0; k < nc; ++k) {
      if (cone[k] >= v_start_ && cone[k] < v_end_) out.push_back(static_cast<std::uint32_t>(cone[k] - v_start_));
    }
    return;
  }
  // An interpolated simplex: a breadth-first walk down the cones, each cone arranged by the
  // orientation its point is reached with (PETSc's closure order, without its cell-type
  // lookups); PETSc's own closure when a cone on the way has not a simplex's size or depth.
  const DMPolytopeType simplex_type[4] = {DM_POLYTOPE_POINT, DM_POLYTOPE_SEGMENT, DM_POLYTOPE_TRIANGLE,
                                          DM_POLYTOPE_TETRAHEDRON};
  auto walk = [&]() -> bool {
    if (pdepth > 3) return false;
    PetscInt pts[15], oris[15], deps[15];
    int n = 1, head = 0;
    pts[0] = p;
    oris[0] = 0;
    deps[0] = pdepth;
    while (head < n) {
      const PetscInt q = pts[head], o = oris[head], dq = deps[head];
      ++head;
      if (dq == 0) continue;
      PetscInt nc = 0;
      const PetscInt *cone = nullptr, *ornt = nullptr;
      TPX_PETSC(DMPlexGetConeSize(dm_, q, &nc));
      if (nc != dq + 1) return false;
      TPX_PETSC(DMPlexGetCone(dm_, q, &cone));
      TPX_PETSC(DMPlexGetConeOrientation(dm_, q, &ornt));
      const PetscInt *arr = DMPolytopeTypeGetArrangment(simplex_type[dq], o);
      for (PetscInt t = 0; t < nc; ++t) {
        const PetscInt i = arr[2 * t];
        const PetscInt cp = cone[i];
        if (depth_of(cp) != dq - 1) return false;
        if (std::find(pts, pts + n, cp) != pts + n) continue;
        if (n == 15) return false;
        pts[n] = cp;
        oris[n] = dq > 1 ? DMPolytopeTypeComposeOrientation(simplex_type[dq - 1], arr[2 * t + 1], ornt[i]) : 0;
        deps[n] = dq - 1;
        ++n;
      }
    }
    for (int k = 0; k < n; ++k) {
      if (deps[k] == 0) out.push_back(static_cast<std::uint32_t>(pts[k] - v_start_));
    }
    return true;
  };
  const std::size_t first = out.size();
  if (!walk()) {
    out.resize(first);
    append_vertices(dm_, p, v_start_, v_end_, out);
  }
}

RankMesh RankMesh::from_dm(DM dm, const ImportOptions &options) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(dm));
  RankMesh out;
  MPI_Comm_rank(comm, &out.rank_);
  MPI_Comm_size(comm, &out.size_);
  const int rank = out.rank_;
  TPX_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(dm)));
  out.dm_ = dm;

  PetscInt pStart, pEnd, vStart, vEnd, depth;
  TPX_PETSC(DMPlexGetChart(dm, &pStart, &pEnd));
  TPX_PETSC(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  TPX_PETSC(DMPlexGetDepth(dm, &depth));
  DMPlexInterpolatedFlag interp;
  TPX_PETSC(DMPlexIsInterpolated(dm, &interp));
  TPX_PETSC(DMPlexGetOverlap(dm, &out.overlap_));
  // The adjacency the overlap was grown with (DMPlexDistribute copies it to the parallel DM).
  PetscBool use_cone = PETSC_FALSE, use_closure = PETSC_TRUE;
  TPX_PETSC(DMGetBasicAdjacency(dm, &use_cone, &use_closure));
  out.vertex_adjacency_ = !use_cone && use_closure;
  out.interpolated_ = interp == DMPLEX_INTERPOLATED_FULL;
  out.p_start_ = pStart;
  out.p_end_ = pEnd;
  out.v_start_ = vStart;
  out.v_end_ = vEnd;
  // The point SF: its leaves are the ghosts (for the numbering and the owners below).
  PetscSF sf;
  TPX_PETSC(DMGetPointSF(dm, &sf));
  PetscInt nroots = -1, nleaves = 0;
  const PetscInt *ilocal = nullptr;
  const PetscSFNode *iremote = nullptr;
  TPX_PETSC(PetscSFGetGraph(sf, &nroots, &nleaves, &ilocal, &iremote));
  // Global vertex numbers, by DMPlexGetVertexNumbering's rule: a rank's owned vertices (those
  // that are no leaf of the point SF) in point order after the owned vertices of the ranks
  // before it, a ghost its owner's number as -(g + 1). Made here from the point SF's vertex
  // leaves alone, one exclusive scan and one broadcast over those leaves: PETSc's own goes
  // through a global section over the whole chart (16 ms for 200k vertices among 5M points).
  // Collective, so first: every rank reaches it before any check below can throw on one rank
  // alone, and ranks that enter together wait least (the local work after it differs between
  // ranks: a rank whose tops need a sort).
  {
    std::vector<PetscInt> leaf_points;
    std::vector<PetscSFNode> leaf_roots;
    out.global_.assign(static_cast<std::size_t>(vEnd - vStart), 0);
    for (PetscInt i = 0; nroots >= 0 && i < nleaves; ++i) {
      const PetscInt p = ilocal ? ilocal[i] : i;
      if (p < vStart || p >= vEnd) continue;
      leaf_points.push_back(p);
      leaf_roots.push_back(iremote[i]);
      out.global_[static_cast<std::size_t>(p - vStart)] = -1;  // a ghost, numbered below
    }
    const PetscInt owned = static_cast<PetscInt>(std::count(out.global_.begin(), out.global_.end(), 0));
    PetscInt next = 0;
    MPI_Exscan(&owned, &next, 1, MPIU_INT, MPI_SUM, comm);
    if (rank == 0) next = 0;  // MPI_Exscan leaves rank 0's result undefined
    for (PetscInt &g : out.global_) {
      if (g == 0) g = next++;
    }
    if (out.size_ > 1) {
      // Root and leaf data indexed by point; only vertex points are read or written, so the
      // chart-sized arrays are never touched (nor paged in) elsewhere.
      const PetscInt nchart = std::max(pEnd, nroots);
      std::unique_ptr<PetscInt[]> root(new PetscInt[static_cast<std::size_t>(nchart)]),
          leaf(new PetscInt[static_cast<std::size_t>(nchart)]);
      for (PetscInt v = vStart; v < vEnd; ++v) root[v] = out.global_[static_cast<std::size_t>(v - vStart)];
      PetscSF vertex_sf;
      TPX_PETSC(PetscSFCreate(comm, &vertex_sf));
      TPX_PETSC(PetscSFSetGraph(vertex_sf, nchart, static_cast<PetscInt>(leaf_points.size()), leaf_points.data(),
                                PETSC_COPY_VALUES, leaf_roots.data(), PETSC_COPY_VALUES));
      TPX_PETSC(PetscSFBcastBegin(vertex_sf, MPIU_INT, root.get(), leaf.get(), MPI_REPLACE));
      TPX_PETSC(PetscSFBcastEnd(vertex_sf, MPIU_INT, root.get(), leaf.get(), MPI_REPLACE));
      TPX_PETSC(PetscSFDestroy(&vertex_sf));
      for (PetscInt p : leaf_points) out.global_[static_cast<std::size_t>(p - vStart)] = -(leaf[p] + 1);
    }
  }
  const std::size_t npoints = static_cast<std::size_t>(pEnd - pStart);
  for (PetscInt d = 0; d <= depth; ++d) {
    PetscInt a = 0, b = 0;
    TPX_PETSC(DMPlexGetDepthStratum(dm, d, &a, &b));
    out.strata_.emplace_back(a, b);
  }

  // The tops (points with no support, ascending) and their vertices (closure order, Topoplex
  // winding), flat.
  std::vector<PetscInt> tops;
  std::vector<std::uint32_t> ids;
  std::vector<std::size_t> offsets{0};
  const Cones raw(dm);
  auto offset_of = [&](PetscInt p) {
    PetscInt off = 0;
    TPX_PETSC(PetscSectionGetOffset(raw.section, p, &off));
    return off;
  };
  // The strata as ranges in chart order with d + 1 cone points per point of depth d >= 1 (PETSc
  // lays the cones out in chart order: each stratum's cones are one block at a fixed width,
  // checked at both ends of the block and by its size); false otherwise.
  struct Block {
    PetscInt start, end, depth, cone0;
  };
  std::vector<Block> blocks;
  auto fixed_width = [&](bool cell_vertex) -> bool {
    if (depth > 3 || (cell_vertex && depth != 1)) return false;
    for (PetscInt d = 0; d <= depth; ++d) {
      const auto [a, b] = out.strata_[static_cast<std::size_t>(d)];
      if (b > a) blocks.push_back({a, b, d, 0});
    }
    std::sort(blocks.begin(), blocks.end(), [](const Block &x, const Block &y) { return x.start < y.start; });
    PetscInt next = pStart, off = 0;
    for (Block &bl : blocks) {
      if (bl.start != next) return false;
      next = bl.end;
      if (bl.depth == 0 || cell_vertex) {  // vertices: no cone; cells: cones vary (checked later)
        PetscInt nc0 = 0, nc1 = 0;
        TPX_PETSC(PetscSectionGetDof(raw.section, bl.start, &nc0));
        TPX_PETSC(PetscSectionGetDof(raw.section, bl.end - 1, &nc1));
        if (bl.depth == 0 && (nc0 != 0 || nc1 != 0)) return false;
        bl.cone0 = offset_of(bl.start);
        if (bl.depth > 0) off = offset_of(bl.end - 1) + nc1;
        continue;
      }
      const PetscInt w = bl.depth + 1;
      PetscInt nc = 0;
      TPX_PETSC(PetscSectionGetDof(raw.section, bl.end - 1, &nc));
      bl.cone0 = offset_of(bl.start);
      if (nc != w || bl.cone0 != off || offset_of(bl.end - 1) != off + (bl.end - 1 - bl.start) * w) return false;
      off += (bl.end - bl.start) * w;
    }
    return next == pEnd && off == raw.storage;
  };
  // Which points some cone names (the others have no support: tops), from the raw cones.
  std::vector<unsigned char> supported;
  auto mark_supported = [&]() {
    supported.assign(npoints, 0);
    mark_named(raw.cone, raw.storage, pStart, pEnd, supported.data());
  };
  const Arrangements arr;
  // Fast path 1: a fully interpolated simplicial DM (SimplexCones), read block by block into
  // arrays sized first from the marks.
  auto interpolated_fill = [&]() -> bool {
    if (interp != DMPLEX_INTERPOLATED_FULL || !fixed_width(false)) return false;
    SimplexCones r;
    r.C = raw.cone;
    r.O = raw.ornt;
    r.arr = arr;
    for (std::size_t d = 0; d < out.strata_.size(); ++d) {
      r.lo[d] = out.strata_[d].first;
      r.hi[d] = out.strata_[d].second;
    }
    for (const Block &bl : blocks) r.at[bl.depth] = bl.cone0 - (bl.depth + 1) * bl.start;
    mark_supported();
    std::size_t ntops = 0, nids = 0;
    for (const Block &bl : blocks) {
      const auto from = supported.begin() + (bl.start - pStart), to = supported.begin() + (bl.end - pStart);
      const std::size_t n = static_cast<std::size_t>(std::count(from, to, 0));
      ntops += n;
      nids += n * static_cast<std::size_t>(bl.depth + 1);
    }
    tops.resize(ntops);
    ids.resize(nids);
    offsets.resize(ntops + 1);
    PetscInt *t = tops.data();
    std::uint32_t *w = ids.data();
    std::size_t *e = offsets.data() + 1;
    for (const Block &bl : blocks) {
      const std::size_t base = static_cast<std::size_t>(w - ids.data());
      if (!read_tops(r, bl.start, bl.end, static_cast<int>(bl.depth), supported.data() + (bl.start - pStart), vStart, t, w,
                     e, base)) {
        return false;
      }
    }
    return true;
  };
  // Fast path 2: a cell-vertex DM (depth 1): each cell's cone is its vertices; its cell type
  // tells a tetrahedron from a quadrilateral.
  auto cell_vertex_fill = [&]() -> bool {
    if (interp == DMPLEX_INTERPOLATED_FULL || !fixed_width(true)) return false;
    // A cone of 2, 3 or 4 vertices is a segment, triangle or tetrahedron unless the DM has cells
    // of the other types with those vertex counts (point and segment tensor prisms,
    // quadrilaterals): counted once in the cell-type label, so that a simplicial DM needs no
    // per-cell lookup.
    DMLabel types = nullptr;
    TPX_PETSC(DMPlexGetCellTypeLabel(dm, &types));
    PetscInt others = 0;
    for (DMPolytopeType t : {DM_POLYTOPE_POINT_PRISM_TENSOR, DM_POLYTOPE_SEG_PRISM_TENSOR, DM_POLYTOPE_QUADRILATERAL}) {
      PetscInt n = 0;
      TPX_PETSC(DMLabelGetStratumSize(types, static_cast<PetscInt>(t), &n));
      others += n;
    }
    mark_supported();
    // Sized from the marks: each top holds at most 4 ids (1 for a vertex), trimmed after.
    std::size_t ntops = 0;
    for (const Block &bl : blocks) {
      ntops += static_cast<std::size_t>(
          std::count(supported.begin() + (bl.start - pStart), supported.begin() + (bl.end - pStart), 0));
    }
    tops.resize(ntops);
    ids.resize(4 * ntops);
    offsets.resize(ntops + 1);
    PetscInt *t = tops.data();
    std::uint32_t *w = ids.data();
    std::size_t *e = offsets.data() + 1;
    for (const Block &bl : blocks) {
      const unsigned char *marks = supported.data() + (bl.start - pStart);
      if (bl.depth == 0) {  // isolated vertices
        for (PetscInt p = bl.start; p < bl.end; ++p) {
          if (marks[p - bl.start]) continue;
          *w++ = static_cast<std::uint32_t>(p - vStart);
          *t++ = p;
          *e++ = static_cast<std::size_t>(w - ids.data());
        }
        continue;
      }
      const std::size_t base = static_cast<std::size_t>(w - ids.data());
      if (!read_cell_vertex_tops(dm, raw.section, raw.cone + bl.cone0, bl.start, bl.end, marks, vStart, vEnd, others > 0,
                                 rank, t, w, e, base)) {
        return false;
      }
    }
    ids.resize(static_cast<std::size_t>(w - ids.data()));
    return true;
  };
  // Any other DM: each top's transitive closure, judged simplicial by its vertex count and cell
  // type.
  auto general_fill = [&]() {
    tops.clear();
    ids.clear();
    offsets.assign(1, 0);
    for (PetscInt p = pStart; p < pEnd; ++p) {
      PetscInt support = 0;
      TPX_PETSC(DMPlexGetSupportSize(dm, p, &support));
      if (support != 0) continue;
      const std::size_t first = ids.size();
      const PetscInt pdepth = p >= vStart && p < vEnd ? 0 : out.depth_of(p);
      out.closure_vertices(p, ids);
      const std::size_t nv = ids.size() - first;
      if (pdepth > 0) {
        bool simplex = false;
        DMPolytopeType ct = DM_POLYTOPE_UNKNOWN;
        if (pdepth >= 2 || (pdepth == 1 && nv == 2 && interp != DMPLEX_INTERPOLATED_NONE)) {
          simplex = nv == static_cast<std::size_t>(pdepth) + 1;
        } else {
          TPX_PETSC(DMPlexGetCellType(dm, p, &ct));
          simplex = (ct == DM_POLYTOPE_SEGMENT && nv == 2) || (ct == DM_POLYTOPE_TRIANGLE && nv == 3) ||
                    (ct == DM_POLYTOPE_TETRAHEDRON && nv == 4);
        }
        if (!simplex) {
          if (ct == DM_POLYTOPE_UNKNOWN) TPX_PETSC(DMPlexGetCellType(dm, p, &ct));
          std::ostringstream m;
          m << "DMPlex point " << p << " (rank " << rank << ") is a " << DMPolytopeTypes[ct] << " with " << nv
            << " vertices at depth " << pdepth
            << ": Topoplex holds simplicial complexes only (points, segments, triangles, tetrahedra)";
          throw Error(Code::NotSimplicial, m.str());
        }
        if (nv == 4) std::swap(ids[first], ids[first + 1]);  // petsc_winding
      }
      tops.push_back(p);
      offsets.push_back(ids.size());
    }
  };
  if (!interpolated_fill()) {
    blocks.clear();
    tops.clear();
    ids.clear();
    offsets.assign(1, 0);
    if (!cell_vertex_fill()) general_fill();
  }
  std::vector<unsigned char>().swap(supported);
  // The tops as runs of consecutive points.
  for (std::size_t i = 0; i < tops.size(); ++i) {
    if (i == 0 || tops[i] != tops[i - 1] + 1) {
      out.top_run_point_.push_back(tops[i]);
      out.top_run_listing_.push_back(static_cast<std::uint32_t>(i));
    }
  }
  out.top_run_listing_.push_back(static_cast<std::uint32_t>(tops.size()));
  out.top_listings_ = tops.size();

  // Labels: integer values per point; points with a value that are not listed yet (faces of an
  // interpolated DM) are listed after the tops.
  struct LabelValues {
    std::string name;
    std::vector<std::pair<PetscInt, PetscInt>> point_value;
  };
  std::vector<LabelValues> labels;
  if (options.labels) {
    PetscInt nlabels = 0;
    TPX_PETSC(DMGetNumLabels(dm, &nlabels));
    for (PetscInt l = 0; l < nlabels; ++l) {
      const char *name = nullptr;
      TPX_PETSC(DMGetLabelName(dm, l, &name));
      if (skipped_label(name)) continue;
      DMLabel label;
      TPX_PETSC(DMGetLabelByNum(dm, l, &label));
      LabelValues lv{name, {}};
      IS valueIS;
      TPX_PETSC(DMLabelGetValueIS(label, &valueIS));
      PetscInt nvalues = 0;
      const PetscInt *values = nullptr;
      TPX_PETSC(ISGetLocalSize(valueIS, &nvalues));
      TPX_PETSC(ISGetIndices(valueIS, &values));
      for (PetscInt i = 0; i < nvalues; ++i) {
        IS pointIS;
        TPX_PETSC(DMLabelGetStratumIS(label, values[i], &pointIS));
        if (!pointIS) continue;
        PetscInt n = 0;
        const PetscInt *pts = nullptr;
        TPX_PETSC(ISGetLocalSize(pointIS, &n));
        TPX_PETSC(ISGetIndices(pointIS, &pts));
        for (PetscInt k = 0; k < n; ++k) {
          if (pts[k] >= pStart && pts[k] < pEnd) lv.point_value.emplace_back(pts[k], values[i]);
        }
        TPX_PETSC(ISRestoreIndices(pointIS, &pts));
        TPX_PETSC(ISDestroy(&pointIS));
      }
      TPX_PETSC(ISRestoreIndices(valueIS, &values));
      TPX_PETSC(ISDestroy(&valueIS));
      std::sort(lv.point_value.begin(), lv.point_value.end());
      for (std::size_t k = 1; k < lv.point_value.size(); ++k) {
        if (lv.point_value[k].first == lv.point_value[k - 1].first) {
          std::ostringstream m;
          m << "DMLabel '" << name << "' gives point " << lv.point_value[k].first << " two values ("
            << lv.point_value[k - 1].second << " and " << lv.point_value[k].second
            << "): a Topoplex attribute holds one value per simplex";
          throw Error(Code::Refused, m.str());
        }
      }
      if (!lv.point_value.empty()) labels.push_back(std::move(lv));
    }
  }
  std::vector<std::uint32_t> vs;
  for (const LabelValues &lv : labels) {
    for (const auto &pv : lv.point_value) {
      const PetscInt p = pv.first;
      if ((p >= vStart && p < vEnd) || out.listing_of_point(p) != NO_LISTING) continue;
      if (interp == DMPLEX_INTERPOLATED_NONE) continue;  // a face is no point here
      vs.clear();
      out.closure_vertices(p, vs);
      const std::uint32_t listing = static_cast<std::uint32_t>(out.listing_count());
      out.extra_point_.push_back(p);
      out.extra_listing_.insert(std::upper_bound(out.extra_listing_.begin(), out.extra_listing_.end(),
                                                 std::make_pair(p, listing)),
                                std::make_pair(p, listing));
      ids.insert(ids.end(), vs.begin(), vs.end());
      offsets.push_back(ids.size());
    }
  }

  // Coordinates of the vertices (none when the DM has none).
  std::vector<double> coords;
  std::size_t cdim = 0;
  if (options.coordinates) {
    Vec local = nullptr;
    TPX_PETSC(DMGetCoordinatesLocal(dm, &local));
    if (local) {
      PetscInt d = 0;
      TPX_PETSC(DMGetCoordinateDim(dm, &d));
      PetscSection section;
      TPX_PETSC(DMGetCoordinateSection(dm, &section));
      const PetscScalar *a = nullptr;
      TPX_PETSC(VecGetArrayRead(local, &a));
      cdim = static_cast<std::size_t>(d);
      coords.resize(cdim * static_cast<std::size_t>(vEnd - vStart));
      for (PetscInt v = vStart; v < vEnd; ++v) {
        PetscInt off = 0, dof = 0;
        TPX_PETSC(PetscSectionGetDof(section, v, &dof));
        TPX_PETSC(PetscSectionGetOffset(section, v, &off));
        if (dof != d) {
          VecRestoreArrayRead(local, &a);
          std::ostringstream m;
          m << "DMPlex vertex point " << v << " has " << dof << " coordinates, not " << d;
          throw Error(Code::Refused, m.str());
        }
        for (PetscInt k = 0; k < d; ++k) {
          coords[static_cast<std::size_t>(v - vStart) * cdim + static_cast<std::size_t>(k)] =
              static_cast<double>(PetscRealPart(a[off + k]));
        }
      }
      TPX_PETSC(VecRestoreArrayRead(local, &a));
    }
  }

  if (vEnd > vStart) {
    out.complex_.emplace(Complex::from_arrays(static_cast<std::uint32_t>(vEnd - vStart), ids, offsets, coords, cdim));
  }
  std::vector<std::uint32_t>().swap(ids);
  std::vector<std::size_t>().swap(offsets);

  // Attributes from the labels.
  const std::size_t nlisted = out.listing_count();
  for (const LabelValues &lv : labels) {
    std::vector<std::int32_t> at_vertices(static_cast<std::size_t>(vEnd - vStart), -1), at_listed(nlisted, -1);
    bool any_vertex = false, any_listed = false;
    for (const auto &pv : lv.point_value) {
      const PetscInt p = pv.first;
      const std::int32_t value = static_cast<std::int32_t>(pv.second);
      if (p >= vStart && p < vEnd) {
        at_vertices[static_cast<std::size_t>(p - vStart)] = value;
        any_vertex = true;
      }
      const std::size_t i = out.listing_of_point(p);
      if (i != NO_LISTING) {
        at_listed[i] = value;
        any_listed = true;
      }
    }
    if (any_vertex) out.complex_->set_attribute(lv.name, Location::Vertices, 1, at_vertices);
    if (any_listed) out.complex_->set_attribute(lv.name, Location::Listed, 1, at_listed);
  }

  // Owners from the point SF: leaves are ghosts owned by their root's rank; every other point is
  // this rank's. The SF's own arrays when its leaves are ascending (referenced), else a sorted
  // copy of the ghosts.
  if (nroots >= 0 && nleaves > 0) {
    bool ascending = ilocal != nullptr;
    for (PetscInt i = 1; ascending && i < nleaves; ++i) ascending = ilocal[i - 1] < ilocal[i];
    if (ascending) {
      TPX_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(sf)));
      out.sf_ = sf;
      out.leaf_ = ilocal;
      out.remote_ = iremote;
      out.nleaves_ = nleaves;
    } else {
      std::vector<std::pair<PetscInt, int>> ghosts;
      for (PetscInt i = 0; i < nleaves; ++i) {
        const PetscInt p = ilocal ? ilocal[i] : i;
        if (p >= pStart && p < pEnd) ghosts.emplace_back(p, static_cast<int>(iremote[i].rank));
      }
      std::sort(ghosts.begin(), ghosts.end());
      for (const auto &g : ghosts) {
        if (!out.ghost_point_.empty() && out.ghost_point_.back() == g.first) continue;
        out.ghost_point_.push_back(g.first);
        out.ghost_owner_.push_back(g.second);
      }
    }
  }

  return out;
}

std::size_t RankMesh::bytes() const noexcept {
  return top_run_point_.capacity() * sizeof(PetscInt) + top_run_listing_.capacity() * sizeof(std::uint32_t) +
         extra_point_.capacity() * sizeof(PetscInt) +
         extra_listing_.capacity() * sizeof(std::pair<PetscInt, std::uint32_t>) +
         ghost_point_.capacity() * sizeof(PetscInt) + ghost_owner_.capacity() * sizeof(int) +
         strata_.capacity() * sizeof(std::pair<PetscInt, PetscInt>) +
         global_.capacity() * sizeof(PetscInt);
}

const Complex &RankMesh::complex() const {
  if (empty()) throw Error(Code::Refused, "rank " + std::to_string(rank_) + " holds no point: no complex");
  if (!complex_) throw Error(Code::Refused, "rank " + std::to_string(rank_) + ": the complex was taken (take_complex)");
  return *complex_;
}

Complex &RankMesh::complex() {
  return const_cast<Complex &>(static_cast<const RankMesh &>(*this).complex());
}

Complex RankMesh::take_complex() {
  Complex c = std::move(complex());
  complex_.reset();
  return c;
}

PetscInt RankMesh::point_of_vertex(std::uint32_t v) const {
  if (v >= vertex_count()) {
    throw Error(Code::InvalidArgument, "vertex " + std::to_string(v) + " out of range (" +
                                           std::to_string(vertex_count()) + " vertices)");
  }
  return v_start_ + static_cast<PetscInt>(v);
}

std::uint32_t RankMesh::vertex_of_point(PetscInt p) const {
  return p >= v_start_ && p < v_end_ ? static_cast<std::uint32_t>(p - v_start_) : NO_VERTEX;
}

PetscInt RankMesh::point_of_listing(std::size_t i) const {
  if (i >= listing_count()) {
    throw Error(Code::InvalidArgument, "listing " + std::to_string(i) + " out of range (" +
                                           std::to_string(listing_count()) + " listed)");
  }
  if (i >= top_listings_) return extra_point_[i - top_listings_];
  // The run holding listing i: the last run starting at or before it.
  const auto it = std::upper_bound(top_run_listing_.begin(), top_run_listing_.end(), static_cast<std::uint32_t>(i));
  const std::size_t k = static_cast<std::size_t>(it - top_run_listing_.begin()) - 1;
  return top_run_point_[k] + static_cast<PetscInt>(i - top_run_listing_[k]);
}

std::size_t RankMesh::listing_of_point(PetscInt p) const {
  if (p < p_start_ || p >= p_end_) return NO_LISTING;
  // Tops: the run starting at or before p, if p is inside it.
  const auto it = std::upper_bound(top_run_point_.begin(), top_run_point_.end(), p);
  if (it != top_run_point_.begin()) {
    const std::size_t k = static_cast<std::size_t>(it - top_run_point_.begin()) - 1;
    const PetscInt len = static_cast<PetscInt>(top_run_listing_[k + 1] - top_run_listing_[k]);
    if (p - top_run_point_[k] < len) return top_run_listing_[k] + static_cast<std::size_t>(p - top_run_point_[k]);
  }
  const auto e = std::lower_bound(extra_listing_.begin(), extra_listing_.end(), std::make_pair(p, std::uint32_t(0)));
  return e != extra_listing_.end() && e->first == p ? e->second : NO_LISTING;
}

PetscInt RankMesh::point_of(std::vector<std::uint32_t> simplex) const {
  if (simplex.empty() || simplex.size() > 4) return NO_POINT;
  std::sort(simplex.begin(), simplex.end());
  if (simplex.back() >= vertex_count()) return NO_POINT;
  const PetscInt v0 = v_start_ + static_cast<PetscInt>(simplex[0]);
  if (simplex.size() == 1) return v0;
  // Up from the first vertex: supports whose closure vertices all lie in `simplex`, until one
  // has them all (each step adds a vertex in an interpolated DM; a cell-vertex DM reaches its
  // cells in one).
  PetscInt stack[64], seen[64];
  int nstack = 0, nseen = 0;
  stack[nstack++] = v0;
  std::vector<std::uint32_t> vs;
  while (nstack > 0) {
    const PetscInt q = stack[--nstack];
    PetscInt ns = 0;
    const PetscInt *support = nullptr;
    TPX_PETSC(DMPlexGetSupportSize(dm_, q, &ns));
    TPX_PETSC(DMPlexGetSupport(dm_, q, &support));
    for (PetscInt k = 0; k < ns; ++k) {
      const PetscInt s = support[k];
      if (std::find(seen, seen + nseen, s) != seen + nseen) continue;
      if (nseen < 64) seen[nseen++] = s;
      vs.clear();
      closure_vertices(s, vs);
      std::sort(vs.begin(), vs.end());
      if (!std::includes(simplex.begin(), simplex.end(), vs.begin(), vs.end())) continue;
      if (vs.size() == simplex.size()) return s;
      if (nstack < 64) stack[nstack++] = s;
    }
  }
  return NO_POINT;
}

std::vector<std::uint32_t> RankMesh::simplex_of_point(PetscInt p) const {
  if (p < p_start_ || p >= p_end_) {
    throw Error(Code::InvalidArgument, "point " + std::to_string(p) + " outside the chart [" +
                                           std::to_string(p_start_) + ", " + std::to_string(p_end_) + ")");
  }
  std::vector<std::uint32_t> vs;
  closure_vertices(p, vs);
  if (vs.size() == 4 && listing_of_point(p) < top_listings_) std::swap(vs[0], vs[1]);  // petsc_winding
  return vs;
}

int RankMesh::point_owner(PetscInt p) const {
  if (p < p_start_ || p >= p_end_) {
    throw Error(Code::InvalidArgument, "point " + std::to_string(p) + " outside the chart [" +
                                           std::to_string(p_start_) + ", " + std::to_string(p_end_) + ")");
  }
  if (leaf_) {
    const PetscInt *it = std::lower_bound(leaf_, leaf_ + nleaves_, p);
    return it != leaf_ + nleaves_ && *it == p ? static_cast<int>(remote_[it - leaf_].rank) : rank_;
  }
  const auto it = std::lower_bound(ghost_point_.begin(), ghost_point_.end(), p);
  return it != ghost_point_.end() && *it == p ? ghost_owner_[static_cast<std::size_t>(it - ghost_point_.begin())] : rank_;
}

int RankMesh::owner(const StructureView &s, const std::vector<std::uint32_t> &simplex) const {
  const PetscInt p = point_of(simplex);
  if (p != NO_POINT) return point_owner(p);
  if (simplex.empty()) throw Error(Code::InvalidArgument, "owner of an empty simplex");
  // No point: the smallest rank owning a cell (a top) that contains the simplex.
  int best = -1;
  const std::uint32_t d = s.dimension();
  for (std::uint32_t q = static_cast<std::uint32_t>(simplex.size()); q <= d; ++q) {
    for (auto row : s.relation(simplex, q)) {
      const std::vector<std::uint32_t> cell(row.begin(), row.end());
      const PetscInt c = point_of(cell);
      if (c == NO_POINT || listing_of_point(c) == NO_LISTING) continue;
      const int o = point_owner(c);
      if (best < 0 || o < best) best = o;
    }
  }
  if (best < 0) throw Error(Code::InvalidArgument, "simplex is in no cell of this rank");
  // A rank that owns no cell around the simplex may see part of its star only: the smallest
  // owner it sees (not this rank: it owns none of them), a ghost here either way.
  return best;
}

PetscInt RankMesh::global_vertex(std::uint32_t v) const {
  if (v >= vertex_count()) throw Error(Code::InvalidArgument, "vertex " + std::to_string(v) + " out of range");
  const PetscInt g = global_[v];
  return g < 0 ? -(g + 1) : g;  // PETSc marks vertices owned elsewhere -(g + 1)
}

Rows RankMesh::owned_relation(const StructureView &s, const std::vector<std::uint32_t> &simplex,
                              std::uint32_t q) const {
  const std::uint32_t p = static_cast<std::uint32_t>(simplex.size()) - 1;
  if (size_ > 1 && q >= p && overlap_ > 0 && !vertex_adjacency_) {
    std::ostringstream m;
    m << "R(" << p << "," << q << ") on rank " << rank_
      << ": the overlap was grown with an adjacency other than PETSc's default (useCone = false, "
         "useClosure = true), so layers need not hold whole vertex stars";
    throw Error(Code::OverlapTooSmall, m.str());
  }
  if (size_ > 1 && overlap_ < overlap_needed(p, q)) {
    std::ostringstream m;
    m << "R(" << p << "," << q << ") needs overlap " << overlap_needed(p, q) << " to be exact on rank "
      << rank_ << ", the DM has overlap " << overlap_;
    throw Error(Code::OverlapTooSmall, m.str());
  }
  if (!owned(s, simplex)) {
    std::ostringstream m;
    m << "simplex {";
    for (std::size_t i = 0; i < simplex.size(); ++i) m << (i ? "," : "") << simplex[i];
    m << "} is a ghost on rank " << rank_ << ": its relations may be cut by the overlap";
    throw Error(Code::Ghost, m.str());
  }
  if (q > s.dimension()) return Rows({}, q + 1);
  return s.relation(simplex, q);
}

DM to_dm(MPI_Comm comm, const Complex *complex, const ExportOptions &options, int root) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  // Root decides; the others learn the dimensions and whether to refuse (collective either way).
  std::vector<std::vector<std::uint32_t>> cells;  // vertex ids, PETSc winding
  std::vector<std::size_t> cell_listing;
  long header[5] = {0, 0, 0, 0, 0};  // dim, nverts, cdim, refused, top-dimension count
  std::string refusal;
  if (rank == root) {
    if (!complex) throw Error(Code::InvalidArgument, "to_dm: no complex on the root rank");
    const TpxInputStats st = complex->input_stats();
    std::vector<bool> dims(complex->dimension() + 1, false);
    for (std::size_t i = 0; i < st.input_simplices; ++i) {
      std::uint32_t top = 0;
      std::vector<std::uint32_t> vs = complex->input_simplex(i, top);
      if (top == UINT32_MAX || vs.size() < 2) continue;
      dims[vs.size() - 1] = true;
      petsc_winding(vs);
      cells.push_back(std::move(vs));
      cell_listing.push_back(i);
    }
    header[0] = static_cast<long>(complex->dimension());
    header[1] = static_cast<long>(complex->vertex_count());
    header[2] = static_cast<long>(complex->coord_dim());
    header[4] = static_cast<long>(std::count(dims.begin(), dims.end(), true));
    if (options.interpolate && header[4] > 1) {
      header[3] = 1;
    }
  }
  MPI_Bcast(header, 5, MPI_LONG, root, comm);
  if (header[3]) {
    throw Error(Code::Refused,
                "to_dm: the complex has top simplices of " + std::to_string(header[4]) +
                    " dimensions; DMPlexInterpolate needs one cell dimension (export it with "
                    "interpolate = false: a cell-vertex DM holds mixed dimensions)");
  }
  const PetscInt dim = static_cast<PetscInt>(header[0]);
  const PetscInt nverts = rank == root ? static_cast<PetscInt>(header[1]) : 0;
  const PetscInt ncells = static_cast<PetscInt>(cells.size());

  DM dm;
  TPX_PETSC(DMCreate(comm, &dm));
  TPX_PETSC(DMSetType(dm, DMPLEX));
  TPX_PETSC(DMSetDimension(dm, dim));
  TPX_PETSC(DMPlexSetChart(dm, 0, ncells + nverts));
  for (PetscInt c = 0; c < ncells; ++c) TPX_PETSC(DMPlexSetConeSize(dm, c, static_cast<PetscInt>(cells[static_cast<std::size_t>(c)].size())));
  TPX_PETSC(DMSetUp(dm));
  std::vector<PetscInt> cone;
  for (PetscInt c = 0; c < ncells; ++c) {
    cone.clear();
    for (std::uint32_t v : cells[static_cast<std::size_t>(c)]) cone.push_back(ncells + static_cast<PetscInt>(v));
    TPX_PETSC(DMPlexSetCone(dm, c, cone.data()));
  }
  TPX_PETSC(DMPlexSymmetrize(dm));
  TPX_PETSC(DMPlexStratify(dm));
  if (header[2] > 0) {
    std::vector<PetscReal> xyz;
    if (rank == root) {
      const std::vector<double> c = complex->coords();
      xyz.assign(c.begin(), c.end());
    }
    TPX_PETSC(DMPlexBuildCoordinatesFromCellList(dm, static_cast<PetscInt>(header[2]), xyz.data()));
  }
  if (options.interpolate) {
    DM idm;
    TPX_PETSC(DMPlexInterpolate(dm, &idm));
    TPX_PETSC(DMPlexCopyCoordinates(dm, idm));
    TPX_PETSC(DMDestroy(&dm));
    dm = idm;
  }

  // Labels from integer one-component attributes (root only; DMPlexDistribute sends them on).
  if (options.labels && rank == root) {
    PetscInt pStart, pEnd, vStart, vEnd;
    TPX_PETSC(DMPlexGetChart(dm, &pStart, &pEnd));
    TPX_PETSC(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
    // Simplex (sorted vertex ids) -> point, for every point.
    std::map<std::vector<std::uint32_t>, PetscInt> point_of;
    for (PetscInt p = pStart; p < pEnd; ++p) {
      std::vector<std::uint32_t> vs;
      append_vertices(dm, p, vStart, vEnd, vs);
      point_of.emplace(sorted(vs), p);
    }
    const TpxInputStats st = complex->input_stats();
    for (const AttributeInfo &a : complex->attributes()) {
      if (a.components != 1 || (a.type != ValueType::I32 && a.type != ValueType::I64)) continue;
      DMLabel label;
      TPX_PETSC(DMCreateLabel(dm, a.name.c_str()));
      TPX_PETSC(DMGetLabel(dm, a.name.c_str(), &label));
      auto set = [&](PetscInt p, std::int64_t value, const std::string &what) {
        if (value == -1) return;
        PetscInt old = -1;
        TPX_PETSC(DMLabelGetValue(label, p, &old));
        if (old == value) return;
        if (old != -1) {
          throw Error(Code::Refused, "to_dm: attribute '" + a.name + "' gives point " + std::to_string(p) + " (" +
                                         what + ") the values " + std::to_string(old) + " and " +
                                         std::to_string(value));
        }
        TPX_PETSC(DMLabelSetValue(label, p, static_cast<PetscInt>(value)));
      };
      auto value_at = [&](std::size_t i) -> std::int64_t {
        if (a.type == ValueType::I32) return complex->attribute<std::int32_t>(a.name, a.location)[i];
        return complex->attribute<std::int64_t>(a.name, a.location)[i];
      };
      if (a.location == Location::Vertices) {
        for (std::uint32_t v = 0; v < complex->vertex_count(); ++v) set(vStart + static_cast<PetscInt>(v), value_at(v), "vertex " + std::to_string(v));
      } else {
        for (std::size_t i = 0; i < st.input_simplices; ++i) {
          const std::int64_t value = value_at(i);
          if (value == -1) continue;
          std::uint32_t top = 0;
          const std::vector<std::uint32_t> vs = complex->input_simplex(i, top);
          const auto it = point_of.find(sorted(vs));
          if (it == point_of.end()) {
            throw Error(Code::Refused, "to_dm: attribute '" + a.name + "' labels listed simplex " + std::to_string(i) +
                                           ", a face with no DMPlex point in a non-interpolated DM (export with "
                                           "interpolate = true)");
          }
          set(it->second, value, "listed simplex " + std::to_string(i));
        }
      }
    }
  }
  return dm;
}

DM distribute(DM serial, PetscInt overlap, PetscSF *migration) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(serial));
  // What PETSc 3.18's DMPlexDistribute cannot carry (checked on every rank, refused on all):
  //  - a point with no support that is not a cell (height 0): an isolated vertex, or a dangling
  //    lower-dimensional simplex of an interpolated DM: only cells and their closures migrate;
  //  - cells of several dimensions: DMPlexStratifyMigrationSF orders the received points by the
  //    cell types of the DM's dimension only, and fails ("ilocal has duplicate entries").
  PetscInt pStart, pEnd, cStart, cEnd;
  TPX_PETSC(DMPlexGetChart(serial, &pStart, &pEnd));
  TPX_PETSC(DMPlexGetHeightStratum(serial, 0, &cStart, &cEnd));
  long bad[2] = {-1, -1};  // a lost point, a cell of another dimension
  PetscInt cdim = -1;
  for (PetscInt p = pStart; p < pEnd; ++p) {
    PetscInt support = 0;
    TPX_PETSC(DMPlexGetSupportSize(serial, p, &support));
    const bool cell = p >= cStart && p < cEnd;
    if (support == 0 && !cell && bad[0] < 0) bad[0] = p;
    if (cell) {
      DMPolytopeType ct;
      TPX_PETSC(DMPlexGetCellType(serial, p, &ct));
      const PetscInt d = DMPolytopeTypeGetDim(ct);
      if (cdim < 0) cdim = d;
      if (d != cdim && bad[1] < 0) bad[1] = p;
    }
  }
  long any[2];
  MPI_Allreduce(bad, any, 2, MPI_LONG, MPI_MAX, comm);
  if (any[0] >= 0) {
    throw Error(Code::Refused, "distribute: point " + std::to_string(any[0]) +
                                   " has no support and is not a cell; DMPlexDistribute moves cells and their "
                                   "closures only, so it would be lost");
  }
  if (any[1] >= 0) {
    throw Error(Code::Refused, "distribute: cell " + std::to_string(any[1]) +
                                   " has another dimension than the first cell; PETSc 3.18's DMPlexDistribute "
                                   "cannot migrate cells of several dimensions");
  }
  DM parallel = nullptr;
  PetscSF sf = nullptr;
  TPX_PETSC(DMPlexDistribute(serial, overlap, migration ? &sf : nullptr, &parallel));
  if (!parallel) {  // one rank: PETSc leaves the DM where it is
    TPX_PETSC(DMClone(serial, &parallel));
    if (migration) {
      TPX_PETSC(PetscSFCreate(comm, &sf));
      std::vector<PetscSFNode> remote(static_cast<std::size_t>(pEnd - pStart));
      for (PetscInt p = pStart; p < pEnd; ++p) {
        remote[static_cast<std::size_t>(p - pStart)].rank = 0;
        remote[static_cast<std::size_t>(p - pStart)].index = p;
      }
      TPX_PETSC(PetscSFSetGraph(sf, pEnd - pStart, pEnd - pStart, nullptr, PETSC_COPY_VALUES, remote.data(), PETSC_COPY_VALUES));
    }
  }
  if (migration) *migration = sf;
  return parallel;
}

std::vector<PetscInt> serial_points(DM local, PetscSF migration) {
  PetscInt pStart, pEnd;
  TPX_PETSC(DMPlexGetChart(local, &pStart, &pEnd));
  std::vector<PetscInt> out(static_cast<std::size_t>(pEnd - pStart), -1);
  PetscInt nroots = 0, nleaves = 0;
  const PetscInt *ilocal = nullptr;
  const PetscSFNode *iremote = nullptr;
  TPX_PETSC(PetscSFGetGraph(migration, &nroots, &nleaves, &ilocal, &iremote));
  for (PetscInt i = 0; i < nleaves; ++i) {
    const PetscInt p = ilocal ? ilocal[i] : i;
    if (p >= pStart && p < pEnd) out[static_cast<std::size_t>(p - pStart)] = iremote[i].index;
  }
  return out;
}

}  // namespace dmplex
}  // namespace topoplex
