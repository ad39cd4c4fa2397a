// CGAL Polygon_mesh_processing run directly on a Topoplex live mesh, no copy into a
// Surface_mesh (topoplex/cgal_graph_traits.hpp):
//
//   interop_cgal_pmp [INPUT] [OUTPUT]
//
// INPUT is a triangle mesh that is a 2-manifold with boundary (.off, .obj, .ply, ...); without
// one (or with "-"), a built-in wavy grid with a square hole. The mesh is read into a
// topoplex::Live; topoplex::cgal::SurfaceGraph makes it a CGAL FaceListGraph; PMP computes its
// area, face normals, connected components and boundary, then tangential_relaxation moves its
// interior vertices in the live mesh itself (through the graph's writable point map), and
// Topoplex's writer saves the result (OUTPUT, default interop_cgal_pmp.off). A non-manifold
// INPUT is refused with the simplex named (exit 2): examples/cpp/interop_parts.cpp shows the
// route for those (cut into surface parts first).
//
// Exits 0 only when what the comments below state holds.
#include <topoplex.hpp>
#include <topoplex/cgal_graph_traits.hpp>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/tangential_relaxation.h>
#include <CGAL/boost/graph/helpers.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Graph = topoplex::cgal::SurfaceGraph;
using Vector = CGAL::Epick::Vector_3;

// A 24 x 24 grid on a wave, split into triangles, with the middle 6 x 6 cells left out.
topoplex::Live built_in() {
  const std::uint32_t n = 24;
  std::vector<double> xyz;
  for (std::uint32_t j = 0; j <= n; ++j)
    for (std::uint32_t i = 0; i <= n; ++i) {
      const double x = i + 0.3 * std::sin(1.7 * j + i), y = j + 0.3 * std::cos(2.3 * i + j);
      xyz.insert(xyz.end(), {x, y, std::sin(0.4 * x) * std::cos(0.3 * y)});
    }
  std::vector<std::uint32_t> ids;
  std::vector<std::size_t> offsets{0};
  for (std::uint32_t j = 0; j < n; ++j)
    for (std::uint32_t i = 0; i < n; ++i) {
      if (i >= 9 && i < 15 && j >= 9 && j < 15) continue;
      const std::uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      ids.insert(ids.end(), {a, b, d, a, d, c});
      offsets.push_back(ids.size() - 3);
      offsets.push_back(ids.size());
    }
  // The hole's inner vertices are in no triangle: list only the used ones (CGAL's validity
  // check asks every vertex for a halfedge), renumbered in order.
  std::vector<std::uint32_t> renumber((n + 1) * (n + 1), UINT32_MAX);
  std::vector<double> used;
  for (std::uint32_t &v : ids) {
    if (renumber[v] == UINT32_MAX) {
      renumber[v] = static_cast<std::uint32_t>(used.size() / 3);
      used.insert(used.end(), &xyz[3 * v], &xyz[3 * v + 3]);
    }
    v = renumber[v];
  }
  const auto nv = static_cast<std::uint32_t>(used.size() / 3);
  return topoplex::Live(topoplex::Complex::from_arrays(nv, ids, offsets, used, 3));
}

int fail(const std::string &what) {
  std::fprintf(stderr, "interop_cgal_pmp: %s\n", what.c_str());
  return 1;
}

}  // namespace

int main(int argc, char **argv) {
  try {
    const bool given = argc > 1 && std::string(argv[1]) != "-";
    topoplex::Live live = given ? topoplex::Live::from_file(argv[1]) : built_in();
    const std::string output = argc > 2 ? argv[2] : "interop_cgal_pmp.off";

    Graph g;
    try {
      g = Graph(live);  // facet adjacency and boundary tables, built once
    } catch (const topoplex::Refused &e) {
      std::fprintf(stderr, "interop_cgal_pmp: %s\n", e.what());
      return 2;
    }
    if (!CGAL::is_triangle_mesh(g)) return fail("not a triangle mesh to CGAL");
    std::printf("%u vertices, %u faces, %u edges, %u border halfedges; the graph holds %zu "
                "bytes beside the mesh\n",
                num_vertices(g), num_faces(g), num_edges(g), g.border_halfedge_count(), g.bytes());

    // Area: PMP's sum equals the sum of its per-face areas taken in face order.
    const double area = PMP::area(g);
    double sum = 0;
    for (auto f : faces(g)) sum += PMP::face_area(f, g);
    if (area != sum) return fail("area differs from the sum of face areas");

    // Face normals: unit vectors, each facing the way its triangle winds (positive dot product
    // with the cross product of two of its edges, computed here from the live mesh's points).
    auto normals = get(CGAL::dynamic_face_property_t<Vector>(), g);
    PMP::compute_face_normals(g, normals);
    for (auto f : faces(g)) {
      const auto h = halfedge(f, g);
      const auto p = get(CGAL::vertex_point, g, source(h, g)), q = get(CGAL::vertex_point, g, target(h, g)),
                 r = get(CGAL::vertex_point, g, target(next(h, g), g));
      const Vector n = normals[f];
      if (std::abs(n.squared_length() - 1) > 1e-12) return fail("a face normal is not a unit vector");
      if (CGAL::cross_product(q - p, r - p) * n <= 0) return fail("a face normal faces backwards");
    }

    // Components, and the boundary: PMP's border halfedges are the graph's (no face, the
    // opposite in a face); their vertices are the border vertices.
    auto component = get(CGAL::dynamic_face_property_t<std::size_t>(), g);
    const std::size_t components = PMP::connected_components(g, component);
    std::vector<boost::graph_traits<Graph>::halfedge_descriptor> border;
    PMP::border_halfedges(faces(g), g, std::back_inserter(border));
    std::vector<char> on_border(num_vertices(g), 0);
    for (auto h : border) {
      if (!CGAL::is_border(h, g) || CGAL::is_border(opposite(h, g), g))
        return fail("a border halfedge is not between a face and the outside");
      on_border[source(h, g).idx()] = on_border[target(h, g).idx()] = 1;
    }
    if (border.size() != g.border_halfedge_count()) return fail("border halfedges miscounted");
    std::printf("area %.9g, %zu component(s), %zu boundary edge(s)\n", area, components,
                border.size());

    // Tangential relaxation, 5 iterations, straight into the live mesh: interior vertices move,
    // border vertices stay bit for bit (CGAL's default), and the graph stays valid (moving
    // points is no edit of the topology).
    const std::vector<double> before(live.all_coords().begin(), live.all_coords().end());
    PMP::tangential_relaxation(g, CGAL::parameters::number_of_iterations(5));
    const topoplex::CoordsView after = live.all_coords();
    double moved = 0;
    for (std::uint32_t v = 0; v < num_vertices(g); ++v)
      for (int k = 0; k < 3; ++k) {
        const double d = std::abs(after[3 * v + k] - before[3 * v + k]);
        if (on_border[v] && d != 0) return fail("a border vertex moved");
        moved = std::max(moved, d);
      }
    if (num_vertices(g) > 10 && moved == 0) return fail("relaxation moved nothing");
    if (!CGAL::is_valid_polygon_mesh(g)) return fail("the graph is no longer valid");
    live.validate();
    std::printf("relaxed: largest move %.3g, area now %.9g\n", moved, PMP::area(g));

    live.write(output);
    std::printf("wrote %s\n", output.c_str());
    return 0;
  } catch (const std::exception &e) {
    return fail(e.what());
  }
}
