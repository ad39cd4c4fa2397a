// The small geometry application of issue 13, on the mesh (topoplex::Live): load a triangle
// mesh, 10 rounds of Laplacian smoothing over one-rings, a valence histogram with the boundary
// and non-manifold edges, every face's neighbouring faces summed into per-face data, then write
// the mesh back with its input winding and order. Non-manifold input is taken as it is.
//
// Every pass reads the mesh's own arrays inline (topoplex::MeshView: no library call per query),
// with two indices the mesh builds on request and reports: the one-rings stored for the passes
// repeated over them (52 bytes a vertex) and the facet adjacency for face neighbours (12 bytes
// a triangle); without them the same calls answer from the stars alone. The smoothed coordinates go back into the mesh after
// each round (Live::set_all_coords, in place) and the library's writer writes it (Live::write):
// top simplices in input order and winding, coordinates bit for bit, format from the name.
//
//   mesh_app INPUT [OUTPUT]
#include <topoplex.hpp>

#include <cstdio>
#include <map>
#include <vector>

int main(int argc, char **argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: mesh_app INPUT [OUTPUT]\n");
    return 1;
  }
  try {
    // The file read straight into the mesh (no frozen complex kept or built for a plain file).
    topoplex::Live mesh = topoplex::Live::from_file(argv[1]);
    const std::size_t dim = mesh.coord_dim();
    const std::uint32_t slots = mesh.vertex_slots();

    // Smoothing: each vertex moves to the mean of its one-ring, read from the mesh's own
    // coordinates; the new ones go back into the mesh after each round. for_each_ring is the
    // pass over every vertex's one-ring (for one vertex: m.for_each_neighbour(v, marks, f)),
    // here reading the rings the mesh stores on request: built in the first round, kept while
    // only coordinates change (mesh.mesh() alone answers the same from the stars).
    std::vector<double> next(std::size_t(slots) * dim), ring_sum(dim);
    topoplex::NeighbourMarks marks;  // one-ring scratch, reused: no allocation once warm
    for (int round = 0; round < 10; ++round) {
      const topoplex::MeshView m = mesh.mesh_with_rings();
      m.for_each_ring(marks, [&](std::uint32_t v, topoplex::SimplexView ring) {
        std::fill(ring_sum.begin(), ring_sum.end(), 0.0);
        for (std::uint32_t w : ring)
          for (std::size_t k = 0; k < dim; ++k) ring_sum[k] += m.coords(w)[k];
        for (std::size_t k = 0; k < dim; ++k)
          next[v * dim + k] = ring.size() == 0 ? m.coords(v)[k] : ring_sum[k] / ring.size();
      });
      mesh.set_all_coords(next.data(), next.size());  // in place: m stays valid
    }

    // Valence histogram; boundary and non-manifold edges: one pass over every edge with the
    // number of triangles through it (read from the same rings on a mesh of triangles only).
    const topoplex::MeshView m = mesh.mesh_with_rings();
    std::vector<std::uint32_t> valence_of(slots);
    std::size_t boundary = 0, nonmanifold = 0;
    m.for_each_edge(2, marks, [&](std::uint32_t a, std::uint32_t b, std::size_t triangles) {
      ++valence_of[a];
      ++valence_of[b];
      boundary += triangles == 1;
      nonmanifold += triangles > 2;
    });
    std::map<std::size_t, std::size_t> valence;
    for (std::uint32_t v = 0; v < slots; ++v)
      if (m.is_vertex(v)) ++valence[valence_of[v]];

    // Face neighbours: per-face data indexed by the face's slot (after a build, its place
    // among the input's top simplices; kept across edits until compact()), the
    // neighbours of face f across its edges (every other triangle at a non-manifold edge),
    // read from the facet adjacency the mesh builds on request (12 bytes a triangle).
    const topoplex::MeshView ma = mesh.mesh_with_adjacency();
    const std::uint32_t faces = ma.slots(2);
    std::vector<std::uint64_t> sum(faces);
    for (std::uint32_t f = 0; f < faces; ++f)
      ma.for_each_adjacent_top(topoplex::TopRef(2, f),
                               [&](topoplex::TopRef g) { sum[f] += g.slot() + 1; });
    std::uint64_t checksum = 0;
    for (std::uint32_t f = 0; f < faces; ++f) checksum += sum[f] * (f + 1);

    // Circulator: the tops around vertex 0.
    const std::size_t around0 = m.is_vertex(0) ? m.star(0).size() : 0;

    std::printf("vertices %u, faces %u, boundary edges %zu, non-manifold edges %zu, "
                "tops at vertex 0: %zu, checksum %llu\nvalence:",
                mesh.vertex_count(), faces, boundary, nonmanifold, around0,
                static_cast<unsigned long long>(checksum));
    for (const auto &kv : valence) std::printf(" %zu:%zu", kv.first, kv.second);
    std::printf("\n");

    // Write back with the library's writer: every top simplex once, in input order and
    // winding, straight from the mesh (no frozen complex built).
    if (argc > 2) mesh.write(argv[2]);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "mesh_app: %s\n", e.what());
    return 1;
  }
  return 0;
}
