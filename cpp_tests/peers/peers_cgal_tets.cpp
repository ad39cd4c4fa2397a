// CGAL tetrahedral meshes as peers: a Delaunay Triangulation_3 of a real point set (its finite
// cells) and a Mesh_3 tetrahedralization of a real surface (the C3T3's cells in the complex).
// The triangulation's incidence queries answer all 16 relations R_{p,q}, p, q <= 3 (vertex
// stars, adjacent vertices, the cell and facet circulators around edges, cell neighbours); on the
// Mesh_3 complex GUDHI's Simplex_tree answers them as well.
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_3.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/make_mesh_3.h>
#include <gtest/gtest.h>

#include <fstream>

#include "peer_check.hpp"
#ifdef TOPOPLEX_PEERS_HAVE_GUDHI
#include "gudhi_peer.hpp"
#endif
#include "t3_peer.hpp"

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

TEST(CgalDelaunay3Peer, FiniteCellsOfKittenPointsMatchEveryKind) {
  PEERS_REQUIRE_DATA(path, "points_3/kitten.xyz");
  const auto xyz = peers::read_xyz(path);
  ASSERT_GT(xyz.size(), 300u) << path;
  std::vector<K::Point_3> points;
  for (size_t i = 0; i < xyz.size(); i += 3) points.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);

  using Dt = CGAL::Delaunay_triangulation_3<K>;
  const Dt dt(points.begin(), points.end());
  ASSERT_EQ(dt.dimension(), 3);

  peers::PeerComplex cx;
  cx.name = "Delaunay_triangulation_3 of kitten.xyz";
  std::vector<peers::Relation> rels;
  peers::t3_peer(dt, peers::FiniteSimplices<Dt>{dt}, [](Dt::Vertex_handle v) { return v->point(); },
                 "Delaunay_3 finite", /*with_all_faces=*/false, cx, rels);
  ASSERT_EQ(cx.n_vertices, dt.number_of_vertices());
  ASSERT_EQ(cx.simplex_count(), dt.number_of_finite_cells());
  // Every finite vertex, edge and facet is a face of a finite cell, so only cells are tops.
  EXPECT_EQ(cx.expected_tops, (std::vector<size_t>{0, 0, 0, dt.number_of_finite_cells()}));

  const auto report = peers::check_all_kinds(cx, rels);
  EXPECT_FALSE(report.checked.empty());
}

TEST(CgalMesh3Peer, ElephantTetrahedralizationMatchesEveryKind) {
  PEERS_REQUIRE_DATA(path, "meshes/elephant.off");
  using Polyhedron = CGAL::Polyhedron_3<K>;
  using Domain = CGAL::Polyhedral_mesh_domain_3<Polyhedron, K>;
  using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
  using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
  using Criteria = CGAL::Mesh_criteria_3<Tr>;
  namespace params = CGAL::parameters;

  Polyhedron polyhedron;
  std::ifstream in(path);
  ASSERT_TRUE(in >> polyhedron) << path;
  ASSERT_TRUE(polyhedron.is_closed());
  const Domain domain(polyhedron);
  // Coarse on purpose: a few thousand cells keep the test fast; quality does not matter here.
  const Criteria criteria(params::facet_angle = 25, params::facet_size = 0.15, params::facet_distance = 0.01,
                          params::cell_radius_edge_ratio = 3);
  const C3t3 c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, params::no_perturb(), params::no_exude());
  const Tr& tr = c3t3.triangulation();
  ASSERT_GT(c3t3.number_of_cells_in_complex(), 0u);

  auto in_complex = [&](Tr::Cell_handle c) { return c3t3.is_in_complex(c); };
  peers::CellsAndFaces<Tr, decltype(in_complex)> member{tr, in_complex};
  peers::PeerComplex cx;
  cx.name = "Mesh_3 C3T3 of elephant.off";
  std::vector<peers::Relation> rels;
  peers::t3_peer(tr, member, [&](Tr::Vertex_handle v) { return tr.point(v).point(); }, "Mesh_3 cells in complex",
                 /*with_all_faces=*/false, cx, rels);
  ASSERT_EQ(cx.simplex_count(), size_t(c3t3.number_of_cells_in_complex()));
#ifdef TOPOPLEX_PEERS_HAVE_GUDHI
  // GUDHI answers too, over the same cells.
  peers::Stree st;
  for (size_t i = 0; i < cx.simplex_count(); ++i)
    st.insert_simplex_and_subfaces(std::vector<int>(cx.ids.begin() + cx.offsets[i], cx.ids.begin() + cx.offsets[i + 1]));
  EXPECT_EQ(peers::gudhi_relations(st, rels), cx.expected_tops);
#endif
  std::cout << "[peers] Mesh_3: " << cx.n_vertices << " vertices, " << cx.simplex_count() << " cells" << std::endl;

  const auto report = peers::check_all_kinds(cx, rels);
  EXPECT_FALSE(report.checked.empty());
}

}  // namespace
