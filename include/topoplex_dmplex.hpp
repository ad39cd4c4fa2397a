/*
 * Topoplex <-> PETSc DMPlex bridge (C++17, library Topoplex::dmplex, libtopoplex_dmplex.so).
 *
 *   find_package(Topoplex CONFIG REQUIRED COMPONENTS dmplex)
 *   target_link_libraries(app PRIVATE Topoplex::dmplex)
 *
 *   DM dm = ...;                                   // distributed or not, interpolated or not
 *   auto rank = topoplex::dmplex::RankMesh::from_dm(dm);         // collective on dm's comm
 *   topoplex::Structure ia(rank.complex(), topoplex::Kind::IA);   // any structure, or Live
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

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
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
 * Topoplex ids and each simplex's owner. Memory: the complex, plus per local point its vertex
 * ids (4 B each) in flat arrays (plus an 8 B offset unless the DM is fully interpolated and
 * simplicial), per listing its point (4 B), per ghost point its owner (8 B), per vertex its
 * point and global number (8 B), and once point_of or owner is first called, a table from
 * sorted vertex ids to points (8 to 16 B per point with vertices): see bytes(). */
class RankMesh {
 public:
  /* Collective on the DM's communicator (global vertex numbering). Cost: O(points): a fully
   * interpolated simplicial DM is read stratum by stratum (each point's vertices from its cone,
   * its cone orientations and its faces' vertices: a few PETSc calls per point); any other DM
   * walks each top's and each vertex-bearing point's transitive closure (depth-1 points: the
   * cone). Plus Complex::from_arrays on the tops. Throws Error NotSimplicial naming the first
   * non-simplicial cell, Refused for a point in two strata of one label. */
  static RankMesh from_dm(DM dm, const ImportOptions &options = {});

  /* A rank with no point (a serial DM's other ranks, a tiny mesh on many ranks) has no complex:
   * Topoplex complexes have at least one vertex. complex() then throws Refused. */
  bool empty() const noexcept { return !complex_.has_value(); }
  const Complex &complex() const;
  Complex &complex();

  int rank() const noexcept { return rank_; }
  int size() const noexcept { return size_; }
  PetscInt overlap() const noexcept { return overlap_; }
  bool interpolated() const noexcept { return interpolated_; }

  /* Heap bytes of the maps (everything but the complex): their arrays' capacities, the point
   * table's once built. O(1). */
  std::size_t bytes() const noexcept;

  /* ---- point <-> Topoplex ids (O(1) each; point_of: a hash lookup) ---- */
  std::uint32_t vertex_count() const noexcept { return static_cast<std::uint32_t>(vertex_point_.size()); }
  PetscInt point_of_vertex(std::uint32_t v) const;
  std::uint32_t vertex_of_point(PetscInt p) const; /* NO_VERTEX when p is not a vertex */
  /* Listing i of the complex (tops in point order, then labelled non-top points) and back. */
  std::size_t listing_count() const noexcept { return listed_point_.size(); }
  PetscInt point_of_listing(std::size_t i) const;
  std::size_t listing_of_point(PetscInt p) const; /* NO_LISTING when p is not listed; O(log listed) */
  /* The point whose closure's vertices are `simplex` (vertex ids, any order): NO_POINT for a
   * simplex that is no point (faces of a non-interpolated DM) or not in the complex. The first
   * call builds the table from vertex ids to points (O(points)); then a hash probe. */
  PetscInt point_of(std::vector<std::uint32_t> simplex) const;
  /* The vertices of point p's closure, in Topoplex winding for tops. */
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
  /* Global vertex number (DMPlexGetVertexNumbering, the same on every rank holding the vertex). */
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
  /* The table from sorted vertex ids to points, built by the first point_of / owner (once, under
   * std::call_once, so concurrent queries stay safe). */
  struct PointTable {
    std::once_flag once;
    std::atomic<bool> built{false};
    /* Open addressing (linear probing, a power of two at least twice the entries): the point -
     * p_start of every point with vertices, at the hash of its sorted vertices; -1 empty. */
    std::vector<PetscInt> slots;
  };
  const std::vector<PetscInt> &point_slots() const;
  /* Slot of `sorted` (ascending vertex ids) in `slots`: its point's slot, or an empty one. */
  std::size_t slot_of(const std::vector<PetscInt> &slots, const std::uint32_t *sorted, std::size_t n) const noexcept;
  std::optional<Complex> complex_;
  int rank_ = 0, size_ = 1;
  PetscInt overlap_ = 0;
  bool vertex_adjacency_ = true; /* the DM's basic adjacency is PETSc's default (FEM) */
  bool interpolated_ = false;
  PetscInt p_start_ = 0, p_end_ = 0, v_start_ = 0, v_end_ = 0;
  std::vector<PetscInt> vertex_point_;      /* v -> point */
  std::vector<PetscInt> listed_point_;      /* listing -> point */
  std::size_t top_listings_ = 0;            /* listings 0 .. top_listings_: the tops, ascending points */
  std::vector<std::pair<PetscInt, std::uint32_t>> extra_listing_; /* (point, listing) of the others, by point */
  std::vector<PetscInt> ghost_point_;       /* the point SF's leaves here, ascending */
  std::vector<int> ghost_owner_;            /* their owners (root ranks); other points: rank_ */
  std::vector<PetscInt> global_vertex_;     /* v -> global number */
  /* Where point p's vertices are in simplex_ids_ (closure order, tops in Topoplex winding; none
   * for faces of a non-interpolated DM). A fully interpolated simplicial DM, whose strata are
   * contiguous ranges of points with depth + 1 vertices each: at base + (p - start) x width of
   * p's stratum, no per-point offset; any other DM: offsets[p - p_start] .. [p - p_start + 1]. */
  struct Layout {
    struct Stratum {
      PetscInt start, end;
      std::uint64_t base, width;
    };
    std::vector<Stratum> strata; /* by start, covering the chart; empty: offsets */
    std::vector<std::uint64_t> offsets;
    std::pair<std::uint64_t, std::uint64_t> range(std::size_t ip, PetscInt p_start) const noexcept {
      if (strata.empty()) return {offsets[ip], offsets[ip + 1]};
      const PetscInt p = p_start + static_cast<PetscInt>(ip);
      for (const Stratum &st : strata) {
        if (p < st.end) {
          const std::uint64_t a = st.base + static_cast<std::uint64_t>(p - st.start) * st.width;
          return {a, a + st.width};
        }
      }
      return {0, 0};
    }
  };
  Layout layout_;
  std::vector<std::uint32_t> simplex_ids_;
  std::unique_ptr<PointTable> table_ = std::make_unique<PointTable>();
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
