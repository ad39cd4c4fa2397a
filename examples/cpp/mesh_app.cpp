// The small geometry application of issue 13, on handles: load a triangle mesh, 10 rounds of
// Laplacian smoothing over one-rings, a valence histogram with the boundary and non-manifold
// edges, a checksum over every face's neighbouring faces, then write the mesh back with its
// input winding and order. No re-parsing, no binary search: per-vertex data is indexed by
// handle. The repeated walks read lent relation views inline (no library call per query; a
// one-time index for relations the structure does not store, 4 bytes per id).
//
//   mesh_app INPUT.off [OUTPUT.off]
#include <topoplex.hpp>

#include <cstdio>
#include <map>
#include <vector>

int main(int argc, char **argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: mesh_app INPUT [OUTPUT.off]\n");
    return 1;
  }
  try {
    const topoplex::Complex complex = topoplex::Complex::from_file(argv[1]);
    const topoplex::Structure mesh(complex, topoplex::Kind::TS);
    const std::size_t dim = complex.coord_dim();
    std::vector<double> xyz = complex.coords();

    // Smoothing: each vertex moves to the mean of its one-ring (VV, read from the view).
    const topoplex::RelationView vv = mesh.view(0, 0);
    std::vector<double> next(xyz.size());
    for (int round = 0; round < 10; ++round) {
      for (std::uint32_t v = 0; v < complex.vertex_count(); ++v) {
        const topoplex::SimplexSpan ring = vv[v];
        for (std::size_t k = 0; k < dim; ++k) {
          double sum = 0;
          for (topoplex::Simplex w : ring) sum += xyz[w.index() * dim + k];
          next[v * dim + k] = ring.empty() ? xyz[v * dim + k] : sum / ring.size();
        }
      }
      xyz.swap(next);
    }

    // Valence histogram; boundary and non-manifold edges by degree.
    std::map<std::size_t, std::size_t> valence;
    for (std::uint32_t v = 0; v < complex.vertex_count(); ++v) ++valence[vv.degree(v)];
    std::size_t boundary = 0, nonmanifold = 0;
    for (std::uint32_t e = 0; e < mesh.count(1); ++e) {
      const std::size_t k = mesh.degree(mesh.handle(1, e), 2);
      boundary += k == 1;
      nonmanifold += k > 2;
    }

    // Face neighbours as indices, and per-face data indexed by handle.
    topoplex::SimplexData<std::uint64_t> sum(mesh, 2);
    std::uint64_t checksum = 0;
    const topoplex::RelationView ff = mesh.view(2, 2);
    for (std::uint32_t f = 0; f < mesh.count(2); ++f) {
      const topoplex::Simplex face = mesh.handle(2, f);
      for (topoplex::Simplex g : ff[face]) sum[face] += g.index();
      checksum += sum[face] * (f + 1);
    }

    // Circulator: the triangles around vertex 0, fan by fan, counter-clockwise.
    std::size_t around0 = 0;
    for (auto t : mesh.triangles_around(mesh.vertex(0))) around0 += t.dim() == 2;

    std::printf("vertices %u, faces %zu, boundary edges %zu, non-manifold edges %zu, "
                "triangles at vertex 0: %zu, checksum %llu\nvalence:",
                complex.vertex_count(), mesh.count(2), boundary, nonmanifold, around0,
                static_cast<unsigned long long>(checksum));
    for (const auto &kv : valence) std::printf(" %zu:%zu", kv.first, kv.second);
    std::printf("\n");

    // Write back: every face as given in the input (winding kept), in input order, each top
    // simplex once (absorbed and repeated listings skipped).
    if (argc > 2) {
      std::FILE *out = std::fopen(argv[2], "w");
      if (!out) throw std::runtime_error("cannot write output");
      std::fprintf(out, "OFF\n%u %u 0\n", complex.vertex_count(), mesh.top_total());
      for (std::uint32_t v = 0; v < complex.vertex_count(); ++v) {
        for (std::size_t k = 0; k < dim; ++k) std::fprintf(out, "%.17g ", xyz[v * dim + k]);
        std::fprintf(out, "\n");
      }
      std::vector<bool> written(mesh.top_total(), false);
      for (std::size_t i = 0; i < complex.input_stats().input_simplices; ++i) {
        std::uint32_t top = 0;
        const std::vector<std::uint32_t> face = complex.input_simplex(i, top);
        if (top == UINT32_MAX || written[top]) continue;
        written[top] = true;
        std::fprintf(out, "%zu", face.size());
        for (std::uint32_t v : face) std::fprintf(out, " %u", v);
        std::fprintf(out, "\n");
      }
      std::fclose(out);
    }
  } catch (const std::exception &e) {
    std::fprintf(stderr, "mesh_app: %s\n", e.what());
    return 1;
  }
  return 0;
}
