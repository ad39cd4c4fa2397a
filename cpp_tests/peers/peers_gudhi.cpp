// GUDHI's Simplex_tree as the peer in any dimension, on non-manifold mixed-dimensional complexes
// (CGAL Fixed_alpha_shape_3 of real point sets: tetrahedra with dangling triangles, wire edges
// and isolated vertices), on Vietoris-Rips complexes of dimension 5 over real points, and on the
// project's non-manifold triangle meshes (read by CGAL as polygon soups; skipped when the
// shared data folder is absent).
// The tree answers boundaries (R_{p,q}, q < p, by repeated boundary_simplex_range), cofaces
// (cofaces_simplex_range(sh, q - p)) and adjacencies (through the cofaces of the boundary).
// On the alpha complexes the alpha shape's own triangulation queries answer too.
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fixed_alpha_shape_3.h>
#include <CGAL/Fixed_alpha_shape_cell_base_3.h>
#include <CGAL/Fixed_alpha_shape_vertex_base_3.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <gtest/gtest.h>
#include <gudhi/Rips_complex.h>
#include <gudhi/distance_functions.h>

#include <array>
#include <map>
#include <set>

#include "gudhi_peer.hpp"
#include "peer_check.hpp"
#include "t3_peer.hpp"

namespace {

using peers::Ids;
using peers::Stree;
using peers::gudhi_relations;

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Fixed_alpha_shape_vertex_base_3<K>;
using Cb = CGAL::Fixed_alpha_shape_cell_base_3<K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
using Dt = CGAL::Delaunay_triangulation_3<K, Tds>;
using Alpha = CGAL::Fixed_alpha_shape_3<Dt>;

// The alpha complex: every simplex the shape does not classify EXTERIOR (cells: INTERIOR).
struct AlphaMembers {
  const Alpha& as;
  bool cell(Alpha::Cell_handle c) const { return !as.is_infinite(c) && as.classify(c) == Alpha::INTERIOR; }
  bool facet(const Alpha::Facet& f) const { return !as.is_infinite(f) && as.classify(f) != Alpha::EXTERIOR; }
  bool edge(const Alpha::Edge& e) const { return !as.is_infinite(e) && as.classify(e) != Alpha::EXTERIOR; }
  bool vertex(Alpha::Vertex_handle v) const { return !as.is_infinite(v) && as.classify(v) != Alpha::EXTERIOR; }
};

struct AlphaCase {
  const char* file;
  double alpha;  // squared radius; chosen so that every kind of singular simplex appears
};

class AlphaShapePeer : public ::testing::TestWithParam<AlphaCase> {};

TEST_P(AlphaShapePeer, MixedComplexMatchesCgalAndGudhiOnEveryKind) {
  PEERS_REQUIRE_DATA(path, GetParam().file);
  const auto xyz = peers::read_xyz(path);
  ASSERT_GT(xyz.size(), 300u) << path;
  std::vector<K::Point_3> points;
  for (size_t i = 0; i < xyz.size(); i += 3) points.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  Dt dt(points.begin(), points.end());
  const Alpha as(dt, GetParam().alpha);

  // The shape's own census of singular simplices (in the complex, on no higher member).
  std::array<size_t, 4> singular{0, 0, 0, 0};
  size_t interior_cells = 0;
  for (auto v : as.finite_vertex_handles()) singular[0] += as.classify(v) == Alpha::SINGULAR;
  for (const auto& e : as.finite_edges()) singular[1] += as.classify(e) == Alpha::SINGULAR;
  for (const auto& f : as.finite_facets()) singular[2] += as.classify(f) == Alpha::SINGULAR;
  for (auto c : as.finite_cell_handles()) interior_cells += as.classify(c) == Alpha::INTERIOR;
  ASSERT_GT(singular[0], 0u) << "no isolated vertex at this alpha";
  ASSERT_GT(singular[1], 0u) << "no wire edge at this alpha";
  ASSERT_GT(singular[2], 0u) << "no dangling triangle at this alpha";
  ASSERT_GT(interior_cells, 0u) << "no tetrahedron at this alpha";

  peers::PeerComplex cx;
  cx.name = std::string("Fixed_alpha_shape_3 of ") + GetParam().file + " alpha=" + std::to_string(GetParam().alpha);
  std::vector<peers::Relation> rels;
  peers::t3_peer(as, AlphaMembers{as}, [](Alpha::Vertex_handle v) { return v->point(); }, "Fixed_alpha_shape_3",
                 /*with_all_faces=*/true, cx, rels);
  // The tops the triangulation's incidences found are the shape's singular simplices.
  ASSERT_EQ(cx.expected_tops, (std::vector<size_t>{singular[0], singular[1], singular[2], interior_cells}));

  // GUDHI's tree over the same simplices, in the same vertex numbering.
  Stree st;
  for (size_t i = 0; i < cx.simplex_count(); ++i)
    st.insert_simplex_and_subfaces(std::vector<int>(cx.ids.begin() + cx.offsets[i], cx.ids.begin() + cx.offsets[i + 1]));
  ASSERT_EQ(st.num_vertices(), cx.n_vertices);
  const auto gudhi_tops = gudhi_relations(st, rels);
  EXPECT_EQ(gudhi_tops, cx.expected_tops) << "GUDHI and CGAL disagree on the top simplices";

  std::cout << "[peers] alpha complex: " << interior_cells << " tetrahedra, " << singular[2] << " dangling triangles, "
            << singular[1] << " wire edges, " << singular[0] << " isolated vertices; " << st.num_simplices()
            << " simplices" << std::endl;
  const auto report = peers::check_all_kinds(cx, rels);
  EXPECT_FALSE(report.checked.empty());
}

// fin90: a scanned fin whose uneven sampling leaves every kind of singular simplex at one alpha;
// blobby: a denser blob with thousands of dangling triangles and wire edges.
INSTANTIATE_TEST_SUITE_P(CgalSamplePoints, AlphaShapePeer,
                         ::testing::Values(AlphaCase{"points_3/fin90_with_PCA_normals.xyz", 0.001},
                                           AlphaCase{"points_3/blobby.xyz", 0.0002}),
                         [](const auto& info) { return peers::test_name_of(info.param.file); });

struct RipsCase {
  const char* file;
  size_t n_points;   // a prefix of the file's points
  double threshold;  // edge length bound
  int max_dimension;
};

class RipsPeer : public ::testing::TestWithParam<RipsCase> {};

TEST_P(RipsPeer, HighDimensionalRipsComplexMatchesGudhiOnEveryKind) {
  const RipsCase c = GetParam();
  PEERS_REQUIRE_DATA(path, c.file);
  const auto xyz = peers::read_xyz(path);
  ASSERT_GE(xyz.size(), 3 * c.n_points) << path;
  std::vector<std::array<double, 3>> points;
  for (size_t i = 0; i < c.n_points; ++i) points.push_back({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]});

  Stree st;
  Gudhi::rips_complex::Rips_complex<Stree::Filtration_value> rips(points, c.threshold, Gudhi::Euclidean_distance());
  rips.create_complex(st, c.max_dimension);
  ASSERT_GE(st.dimension(), 4) << "Rips complex too thin for a high-dimensional test";

  peers::PeerComplex cx;
  cx.name = std::string("Rips of ") + std::to_string(c.n_points) + " points of " + c.file;
  cx.n_vertices = uint32_t(c.n_points);
  for (auto& p : points) cx.coords.insert(cx.coords.end(), p.begin(), p.end());
  peers::add_tops(st, cx);
  std::vector<peers::Relation> rels;
  cx.expected_tops = gudhi_relations(st, rels);

  std::string sizes;
  for (int p = 0; p <= st.dimension(); ++p) {
    size_t n = 0;
    for (auto sh : st.skeleton_simplex_range(p)) n += st.dimension(sh) == p;
    sizes += " " + std::to_string(n);
  }
  std::cout << "[peers] Rips: simplices per dimension:" << sizes << std::endl;
  const auto report = peers::check_all_kinds(cx, rels);
  EXPECT_FALSE(report.checked.empty());
}

INSTANTIATE_TEST_SUITE_P(CgalSamplePoints, RipsPeer,
                         ::testing::Values(RipsCase{"points_3/fin90_with_PCA_normals.xyz", 120, 0.09, 5},
                                           RipsCase{"points_3/kitten.xyz", 250, 0.05, 5}),
                         [](const auto& info) { return peers::test_name_of(info.param.file); });

class NonManifoldSurfacePeer : public ::testing::TestWithParam<const char*> {};

TEST_P(NonManifoldSurfacePeer, TriangleSoupMatchesGudhiOnEveryKind) {
  const std::string path = peers::shared_data_file(GetParam());
  if (path.empty()) GTEST_SKIP() << "shared data file " << GetParam() << " not found";
  std::vector<K::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  ASSERT_TRUE(CGAL::IO::read_polygon_soup(path, points, polygons)) << path;

  peers::PeerComplex cx;
  cx.name = std::string("CGAL polygon soup ") + GetParam();
  cx.n_vertices = uint32_t(points.size());
  for (const auto& p : points) cx.coords.insert(cx.coords.end(), {p.x(), p.y(), p.z()});
  Stree st;
  for (uint32_t v = 0; v < cx.n_vertices; ++v) st.insert_simplex(std::vector<int>{int(v)});
  for (const auto& poly : polygons) {
    ASSERT_EQ(poly.size(), 3u) << path << " has a polygon that is not a triangle";
    const Ids t{uint32_t(poly[0]), uint32_t(poly[1]), uint32_t(poly[2])};
    cx.add(t);
    st.insert_simplex_and_subfaces(std::vector<int>(t.begin(), t.end()));
  }
  std::vector<peers::Relation> rels;
  cx.expected_tops = gudhi_relations(st, rels);

  size_t fins = 0;  // edges on more than two triangles: what OpenMesh and Surface_mesh refuse
  for (auto sh : st.skeleton_simplex_range(1))
    if (st.dimension(sh) == 1 && st.cofaces_simplex_range(sh, 1).size() > 2) ++fins;
  std::cout << "[peers] " << GetParam() << ": " << fins << " edges on more than two triangles" << std::endl;
  const auto report = peers::check_all_kinds(cx, rels);
  EXPECT_FALSE(report.checked.empty());
}

INSTANTIATE_TEST_SUITE_P(SharedData, NonManifoldSurfacePeer,
                         ::testing::Values("nonmanifold/fan3.obj", "nonmanifold/hourglass_ico.obj",
                                           "nonmanifold/triple_vierbein.obj", "nonmanifold/truck.obj"),
                         [](const auto& info) { return peers::test_name_of(info.param); });

}  // namespace
