// Per-rank Topoplex meshes on a distributed DMPlex: read a mesh with PETSc's own reader (Gmsh,
// Exodus, ... whatever DMPlexCreateFromFile reads) or a Topoplex .tpx on rank 0, distribute with
// overlap 1, build each rank's complex and an IA on it, compute every owned vertex's star, and
// reduce a census over the ranks.
//
//   mpiexec -n 4 ./dmplex_census mesh.msh
//
// With overlap 1 every owned vertex's star is whole on its rank, so the totals are the same on
// any number of ranks (run it with -n 1 and -n 4 to see).
#include "topoplex_dmplex.hpp"

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace dx = topoplex::dmplex;

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (argc < 2) {
    if (rank == 0) std::fprintf(stderr, "usage: mpiexec -n N %s MESH (.msh, .tpx, ...)\n", argv[0]);
    PetscCall(PetscFinalize());
    return 1;
  }
  const std::string path = argv[1];
  int status = 0;
  try {
    DM serial = nullptr;
    if (path.size() > 4 && path.compare(path.size() - 4, 4, ".tpx") == 0) {
      // A .tpx on rank 0 only, then the bridge's export (interpolated, labels as DMLabels).
      std::optional<topoplex::Complex> c;
      if (rank == 0) c.emplace(topoplex::Complex::open(path));
      serial = dx::to_dm(PETSC_COMM_WORLD, c ? &*c : nullptr);
    } else {
      // PETSc's reader: the mesh on rank 0, interpolated.
      PetscCall(DMPlexCreateFromFile(PETSC_COMM_WORLD, path.c_str(), "mesh", PETSC_TRUE, &serial));
    }
    // PETSc's own distribution (a vertex in no cell, such as a Gmsh geometry point, is dropped
    // by it; dx::distribute would refuse such a mesh instead).
    DM dm = nullptr;
    PetscCall(DMPlexDistribute(serial, 1, nullptr, &dm));
    if (!dm) std::swap(dm, serial);  // one rank: nothing to distribute
    PetscCall(DMDestroy(&serial));

    const dx::RankMesh mesh = dx::RankMesh::from_dm(dm);
    // Census per rank: owned and ghost vertices and tops, owned vertices' star sizes, and the
    // owned boundary and non-manifold vertices (answered from the star, exact with overlap 1).
    long local[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    enum { OwnedV, GhostV, OwnedTops, GhostTops, StarSimplices, StarCells, BoundaryV, NonManifoldV };
    if (!mesh.empty()) {
      const topoplex::Structure ia(mesh.complex(), topoplex::Kind::IA);
      const std::uint32_t d = ia.dimension();
      for (std::uint32_t v = 0; v < mesh.vertex_count(); ++v) {
        if (!mesh.vertex_owned(v)) {
          ++local[GhostV];
          continue;
        }
        ++local[OwnedV];
        const topoplex::Simplex h = ia.vertex(v);
        local[StarSimplices] += static_cast<long>(ia.star(h).size());
        local[StarCells] += static_cast<long>(ia.degree(h, d));
        if (ia.is_boundary(h)) ++local[BoundaryV];
        if (!ia.is_manifold(h)) ++local[NonManifoldV];
      }
      for (std::size_t i = 0; i < mesh.listing_count(); ++i) {
        const PetscInt p = mesh.point_of_listing(i);
        if (mesh.listing_of_point(p) != i) continue;
        PetscInt support = 0;
        PetscCall(DMPlexGetSupportSize(dm, p, &support));
        if (support != 0) continue;  // a labelled face, not a top
        ++local[mesh.point_owner(p) == rank ? OwnedTops : GhostTops];
      }
    }
    std::vector<long> all(8 * static_cast<std::size_t>(size));
    MPI_Gather(local, 8, MPI_LONG, all.data(), 8, MPI_LONG, 0, PETSC_COMM_WORLD);
    long total[8];
    MPI_Reduce(local, total, 8, MPI_LONG, MPI_SUM, 0, PETSC_COMM_WORLD);
    if (rank == 0) {
      std::printf("%-6s %10s %10s %10s %10s %14s %10s %10s\n", "rank", "own V", "ghost V", "own tops", "ghost tops",
                  "star simplices", "boundary V", "non-mfd V");
      for (int r = 0; r < size; ++r) {
        const long *a = &all[8 * static_cast<std::size_t>(r)];
        std::printf("%-6d %10ld %10ld %10ld %10ld %14ld %10ld %10ld\n", r, a[OwnedV], a[GhostV], a[OwnedTops],
                    a[GhostTops], a[StarSimplices], a[BoundaryV], a[NonManifoldV]);
      }
      std::printf("%-6s %10ld %10s %10ld %10s %14ld %10ld %10ld\n", "total", total[OwnedV], "", total[OwnedTops], "",
                  total[StarSimplices], total[BoundaryV], total[NonManifoldV]);
      std::printf("cells in the owned vertices' stars, summed: %ld\n", total[StarCells]);
    }
    PetscCall(DMDestroy(&dm));
  } catch (const std::exception &e) {
    std::fprintf(stderr, "rank %d: %s\n", rank, e.what());
    status = 1;
    MPI_Abort(PETSC_COMM_WORLD, 1);
  }
  PetscCall(PetscFinalize());
  return status;
}
