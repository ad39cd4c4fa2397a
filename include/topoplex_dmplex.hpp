/*
 * Topoplex <-> PETSc DMPlex bridge (C++17, library Topoplex::dmplex, libtopoplex_dmplex.so).
 *
 *   find_package(Topoplex CONFIG REQUIRED COMPONENTS dmplex)
 *   target_link_libraries(app PRIVATE Topoplex::dmplex)
 *
 *   DM dm = ...;                                   // distributed or not, interpolated or not
 *   auto rank = topoplex::dmplex::RankMesh::from_dm(dm);         // collective on dm's comm
 *   topoplex::Structure ia(rank.complex(), topoplex::Kind::IA);   // any structure, or Live
 *   rank.take_complex();            // optional: the IA holds the tops; the maps keep working
 *   for (auto v : ...) if (rank.vertex_owned(v)) ... ia.relation({v}, 3) ...
 *
 *   DM serial = topoplex::dmplex::to_dm(PETSC_COMM_WORLD, &complex);  // complex on rank 0
 *   DM parallel = topoplex::dmplex::distribute(serial, 1, &migration);
 *
 * Conventions (docs/dmplex.md has the whole story):
 *  - tops of a rank's complex are the local points with no support (any depth), so dangling
 *    edges, triangles and isolated vertices are tops; their vertices are the closure's vertices;
 *  - winding is Topoplex's (Gmsh/VTK/medit: a tetrahedron has a positive volume): PETSc orders a
 *    tetrahedron's cone inverted (DMPlexInvertCell swaps vertices 0 and 1), so the bridge swaps
 *    vertices 0 and 1 of every tetrahedron both ways; segments and triangles keep their order;
 *  - owner: the point SF's root rank for a simplex that is a DM point (leaf = ghost); a simplex
 *    with no point (faces of a non-interpolated DM) belongs to the smallest rank owning a cell
 *    that contains it, and is owned here only if this rank owns such a cell;
 *  - labels: a DMLabel with integer values becomes a Topoplex int32 attribute of the same name:
 *    values on vertex points -> Location::Vertices, on other points (and on isolated-vertex tops)
 *    -> Location::Listed; -1 (DMLabel's default value) means "no value" both ways.
 * Every failure throws topoplex::dmplex::Error with a Code and a message naming the point,
 * simplex, label or PETSc call.
 */
#ifndef TOPOPLEX_DMPLEX_HPP
#define TOPOPLEX_DMPLEX_HPP

#include "topoplex.hpp"

#include <petscdmplex.h>
#include <petscsf.h>

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace topoplex {
namespace dmplex {

enum class Code {
  Petsc,           /* a PETSc call returned an error (the message names the call and its code) */
  NotSimplicial,   /* a cell that is not a point, segment, triangle or tetrahedron (prism, hex...) */
  Ghost,           /* an owned-only query asked about a ghost simplex */
  OverlapTooSmall, /* the DM's overlap is below the reach of the asked relation */
  Refused,         /* a DM or complex the bridge cannot carry (named in the message) */
  InvalidArgument, /* an id, point or simplex out of range or unknown */
};

class Error : public std::runtime_error {
 public:
  Error(Code code, const std::string &what) : std::runtime_error(what), code_(code) {}
  Code code() const noexcept { return code_; }

 private:
  Code code_;
};

/* "No such id / point" in the maps below. */
constexpr std::uint32_t NO_VERTEX = UINT32_MAX;
constexpr std::size_t NO_LISTING = SIZE_MAX;
constexpr PetscInt NO_POINT = -1;

/* The overlap a relation R_{p,q} of an OWNED simplex needs to be answered on the rank exactly as
 * on the whole mesh, with PETSc's default adjacency (DMSetBasicAdjacency(dm, PETSC_FALSE,
 * PETSC_TRUE): an overlap layer is every cell sharing a vertex with the cells inside it): 0 for the boundary (q < p: the closure is always local), 1 for everything
 * else (coboundary q > p, adjacency q == p, star, link: all inside the stars of the simplex's
 * vertices, which overlap 1 brings whole because every owned simplex lies in an owned cell).
 * Two-step questions (relations of the simplices a first answer returned, vertex 2-rings) need 2.
 * On one rank every reach is 0. */
PetscInt overlap_needed(std::uint32_t p, std::uint32_t q);

struct ImportOptions {
  bool coordinates = true; /* copy vertex coordinates (a DM without them gives a complex without) */
  bool labels = true;      /* carry integer DMLabels as attributes ("depth", "celltype" skipped) */
};

/* One rank's part of a DMPlex as a Topoplex complex, with the maps between DM points and
 * Topoplex ids and each simplex's owner. The maps copy next to nothing: vertex v is point
 * vStart + v and the tops are kept as runs of consecutive points, so both ways are offsets; any
 * other point is answered on demand from the DM's cones and supports. For that the RankMesh
 * holds a reference to the DM (and to its point SF), released by its
 * destructor: do not change the DM's topology while a RankMesh of it lives, and destroy the
 * RankMesh before PetscFinalize. point_of, simplex_of_point and owner call PETSc's getters
 * (DMPlexGetCone, DMPlexGetSupport, ...): call them from one thread at a time unless PETSc was
 * built thread-safe. Memory besides the complex: bytes(). The complex can be moved
 * out (take_complex) once a structure is built on it; the maps keep working. */
class RankMesh {
 public:
  /* Collective on the DM's communicator (global vertex numbering). Cost: O(points): a fully
   * interpolated simplicial DM (contiguous strata, d + 1 cone points at depth d) is read from
   * PETSc's raw cone and orientation arrays (each top's vertices from its cone, its first face's
   * edges and its second face's: no per-point PETSc call); a cell-vertex DM from its raw cones
   * and cell types; any other DM walks each top's transitive closure. Plus Complex::from_arrays
   * on the tops. Throws Error NotSimplicial naming the first non-simplicial cell, Refused for a
   * point in two strata of one label. */
  static RankMesh from_dm(DM dm, const ImportOptions &options = {});

  RankMesh(RankMesh &&) noexcept;
  RankMesh &operator=(RankMesh &&) noexcept;
  RankMesh(const RankMesh &) = delete;
  RankMesh &operator=(const RankMesh &) = delete;
  ~RankMesh();

  /* A rank with no point (a serial DM's other ranks, a tiny mesh on many ranks) has no complex:
   * Topoplex complexes have at least one vertex. complex() then throws Refused. */
  bool empty() const noexcept { return v_end_ == v_start_; }
  const Complex &complex() const;
  Complex &complex();
  /* Moves the complex out (e.g. once a structure is built on it, to keep only the structure):
   * afterwards complex() throws Refused; every map and owner query keeps working. */
  Complex take_complex();

  int rank() const noexcept { return rank_; }
  int size() const noexcept { return size_; }
  PetscInt overlap() const noexcept { return overlap_; }
  bool interpolated() const noexcept { return interpolated_; }

  /* Heap bytes the maps keep (everything but the complex): the top runs, the labelled listings,
   * a sorted copy of the ghost points when the point SF's leaves are not sorted, and the global
   * vertex numbers (4 or 8 B per vertex). O(1). */
  std::size_t bytes() const noexcept;

  /* ---- point <-> Topoplex ids ---- */
  std::uint32_t vertex_count() const noexcept { return static_cast<std::uint32_t>(v_end_ - v_start_); }
  PetscInt point_of_vertex(std::uint32_t v) const; /* O(1) */
  std::uint32_t vertex_of_point(PetscInt p) const; /* NO_VERTEX when p is not a vertex; O(1) */
  /* Listing i of the complex (tops in point order, then labelled non-top points) and back:
   * O(log runs) (one run for a mesh whose tops are its cells), O(log labelled) for the others. */
  std::size_t listing_count() const noexcept { return top_listings_ + extra_point_.size(); }
  PetscInt point_of_listing(std::size_t i) const;
  std::size_t listing_of_point(PetscInt p) const; /* NO_LISTING when p is not listed */
  /* The point whose closure's vertices are `simplex` (vertex ids, any order): NO_POINT for a
   * simplex that is no point (faces of a non-interpolated DM) or not in the complex. On demand:
   * up from the first vertex's point through supports whose closure vertices lie in `simplex`,
   * O(star of the vertex x closure of each candidate) (PETSc's DMPlexGetSupport and cones). */
  PetscInt point_of(std::vector<std::uint32_t> simplex) const;
  /* The vertices of point p's closure in closure order (read from cones and cone orientations,
   * as PETSc's DMPlexGetTransitiveClosure lists them), in Topoplex winding for tops. On demand:
   * O(closure). */
  std::vector<std::uint32_t> simplex_of_point(PetscInt p) const;

  /* ---- ownership (point_owner: O(log ghosts), a search among the point SF's leaves) ---- */
  int point_owner(PetscInt p) const;
  int vertex_owner(std::uint32_t v) const { return point_owner(point_of_vertex(v)); }
  bool vertex_owned(std::uint32_t v) const { return vertex_owner(v) == rank_; }
  /* Owner of any simplex of the complex; `s` is any structure built on complex(). For a simplex
   * with no point the answer is exact on ranks that own a cell containing it, and the smallest
   * owner seen otherwise (a ghost either way). */
  int owner(const StructureView &s, const std::vector<std::uint32_t> &simplex) const;
  bool owned(const StructureView &s, const std::vector<std::uint32_t> &simplex) const {
    return owner(s, simplex) == rank_;
  }
  /* Global vertex number: DMPlexGetVertexNumbering's (each rank's owned vertices in point order
   * after the ranks before it), the same on every rank holding the vertex. O(1). */
  PetscInt global_vertex(std::uint32_t v) const;

  /* R_{p,q} of an owned p-simplex through `s`: throws Ghost for a ghost simplex and
   * OverlapTooSmall when overlap() < overlap_needed(p, q) on more than one rank, or for q >= p
   * when the DM's adjacency is not PETSc's default (useCone = false, useClosure = true: overlap
   * layers of cells sharing a vertex; a face adjacency grows thinner layers); otherwise the answer
   * equals the one on the whole mesh (through global numbers). */
  Rows owned_relation(const StructureView &s, const std::vector<std::uint32_t> &simplex,
                      std::uint32_t q) const;

 private:
  RankMesh() = default;
  void release() noexcept;
  /* Depth of point p (from the strata when they are ranges, else PETSc's). */
  PetscInt depth_of(PetscInt p) const;
  /* Appends p's closure vertices (ids) in closure order, PETSc's winding. */
  void closure_vertices(PetscInt p, std::vector<std::uint32_t> &out) const;
  std::optional<Complex> complex_;
  DM dm_ = nullptr;                 /* referenced */
  PetscSF sf_ = nullptr;            /* the point SF, referenced when its leaves are used in place */
  std::vector<PetscInt> global_; /* global vertex numbers, PETSc's: ghosts as -(g + 1) */
  int rank_ = 0, size_ = 1;
  PetscInt overlap_ = 0;
  bool vertex_adjacency_ = true; /* the DM's basic adjacency is PETSc's default (FEM) */
  bool interpolated_ = false;
  PetscInt p_start_ = 0, p_end_ = 0, v_start_ = 0, v_end_ = 0;
  std::vector<std::pair<PetscInt, PetscInt>> strata_; /* [start, end) of depth 0, 1, ... */
  /* The tops, ascending points, as runs of consecutive points: run k covers listings
   * top_run_listing_[k] .. top_run_listing_[k + 1] from point top_run_point_[k]. */
  std::vector<PetscInt> top_run_point_;
  std::vector<std::uint32_t> top_run_listing_;
  std::size_t top_listings_ = 0;
  std::vector<PetscInt> extra_point_;                              /* listing top_listings_ + i -> point */
  std::vector<std::pair<PetscInt, std::uint32_t>> extra_listing_;  /* (point, listing) of those, by point */
  /* Ghost points (the point SF's leaves here, ascending) and their owners: the SF's own arrays
   * when its leaves are sorted, else the copies below. */
  const PetscInt *leaf_ = nullptr;
  const PetscSFNode *remote_ = nullptr;
  PetscInt nleaves_ = 0;
  std::vector<PetscInt> ghost_point_;
  std::vector<int> ghost_owner_;
};

struct ExportOptions {
  bool interpolate = true; /* DMPlexInterpolate (refused for mixed dimensions: see docs) */
  bool labels = true;      /* integer attributes -> DMLabels */
};

/* A DMPlex on `comm` holding `complex` on rank `root` and nothing elsewhere (collective;
 * `complex` is read on root only and may be null elsewhere). Cells: the top simplices of
 * dimension >= 1 in listing order and winding; vertices after them; isolated vertices are
 * vertices with no support. Coordinates copied when the complex has them. Throws Refused for
 * interpolate with tops of several dimensions (DMPlexInterpolate needs one cell dimension), for a
 * listed non-top simplex with a label value when interpolate is off (it has no point), and for a
 * point given two values of one label. Cost O(simplices) plus PETSc's interpolation. */
DM to_dm(MPI_Comm comm, const Complex *complex, const ExportOptions &options = {}, int root = 0);

/* DMPlexDistribute(serial, overlap): the returned DM (the caller destroys both), and the
 * migration SF (serial point of each local point) when `migration` is not null. Collective.
 * On one rank, a clone and the identity SF. Throws Refused (on every rank) for what PETSc 3.18's
 * DMPlexDistribute cannot carry: a point with no support that is not a cell (an isolated vertex,
 * a dangling lower-dimensional simplex: only cells and their closures migrate), and cells of
 * several dimensions (the migration orders points by the cell types of the DM's dimension and
 * fails). Such complexes are imported fine on one rank (RankMesh::from_dm). */
DM distribute(DM serial, PetscInt overlap, PetscSF *migration = nullptr);

/* The serial point (root index) of every local point of a DM from distribute(): the leaves of the
 * migration SF, -1 for a point it does not reach. O(local points). */
std::vector<PetscInt> serial_points(DM local, PetscSF migration);

}  // namespace dmplex
}  // namespace topoplex

#endif
