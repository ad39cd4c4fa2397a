// CGAL tetrahedral complexes as peers: the finite cells of a Delaunay Triangulation_3 of a real
// point set, and the cells of a Delaunay triangulation of a real surface's vertices whose
// centroids lie inside that surface (a subset of the triangulation's cells, as a Mesh_3 C3T3's
// cells in the complex are). The triangulation's incidence queries answer all 16 relations
// R_{p,q}, p, q <= 3 (vertex stars, adjacent vertices, the cell and facet circulators around
// edges, cell neighbours); on the subset GUDHI's Simplex_tree answers them as well. (The subset
// was a Mesh_3 tetrahedralization until 2026-12: its mesher took four minutes of the sanitized
// build to compile, for the same checks on the same kind of complex; adapters_cgal still builds
// a C3T3.)
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/centroid.h>
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

TEST(CgalDelaunay3Peer, ElephantInteriorCellsMatchEveryKind) {
  PEERS_REQUIRE_DATA(path, "meshes/elephant.off");
  using Polyhedron = CGAL::Polyhedron_3<K>;
  using Dt = CGAL::Delaunay_triangulation_3<K>;
  Polyhedron polyhedron;
  std::ifstream in(path);
  ASSERT_TRUE(in >> polyhedron) << path;
  ASSERT_TRUE(polyhedron.is_closed());
  // Every third vertex of the surface: a few thousand cells inside, as many as the kitten's
  // triangulation has in all (the checks cost about 10 ms a cell under the sanitizers; the suite
  // runs them plainly, 19 s in all).
  std::vector<K::Point_3> points;
  std::size_t i = 0;
  for (auto p = polyhedron.points_begin(); p != polyhedron.points_end(); ++p, ++i)
    if (i % 3 == 0) points.push_back(*p);
  const Dt dt(points.begin(), points.end());
  const CGAL::Side_of_triangle_mesh<Polyhedron, K> side(polyhedron);
  auto in_complex = [&](Dt::Cell_handle c) {
    if (dt.is_infinite(c)) return false;
    return side(CGAL::centroid(dt.tetrahedron(c))) == CGAL::ON_BOUNDED_SIDE;
  };
  peers::CellsAndFaces<Dt, decltype(in_complex)> member{dt, in_complex};
  peers::PeerComplex cx;
  cx.name = "Delaunay_3 cells inside elephant.off";
  std::vector<peers::Relation> rels;
  peers::t3_peer(dt, member, [](Dt::Vertex_handle v) { return v->point(); }, "cells inside",
                 /*with_all_faces=*/false, cx, rels);
#ifdef TOPOPLEX_PEERS_HAVE_GUDHI
  peers::Stree st;
  for (size_t i = 0; i < cx.simplex_count(); ++i)
    st.insert_simplex_and_subfaces(std::vector<int>(cx.ids.begin() + cx.offsets[i], cx.ids.begin() + cx.offsets[i + 1]));
  EXPECT_EQ(peers::gudhi_relations(st, rels), cx.expected_tops);
#endif
  std::cout << "[peers] inside: " << cx.n_vertices << " vertices, " << cx.simplex_count() << " cells" << std::endl;
  const auto report = peers::check_all_kinds(cx, rels);
  EXPECT_FALSE(report.checked.empty());
}

}  // namespace
