// CGAL's Surface_mesh as the peer on the same manifold triangle meshes as the OpenMesh test
// (Surface_mesh refuses edges shared by more than two triangles). Its halfedge circulators give
// VV, VE, VF, EV, EE, EF, FV, FE, FF; compared with R_{p,q} for p, q <= 2 on every kind.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <gtest/gtest.h>

#include <fstream>

#include "peer_check.hpp"

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
using peers::Ids;

uint32_t id(Mesh::Vertex_index v) { return uint32_t(v.idx()); }

Ids edge_ids(const Mesh& m, Mesh::Edge_index e) { return {id(m.vertex(e, 0)), id(m.vertex(e, 1))}; }

Ids face_ids(const Mesh& m, Mesh::Face_index f) {
  Ids out;
  for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) out.push_back(id(v));
  return out;
}

class SurfaceMeshPeer : public ::testing::TestWithParam<const char*> {};

TEST_P(SurfaceMeshPeer, EveryRelationOfEveryKindMatches) {
  PEERS_REQUIRE_DATA(path, GetParam());
  size_t file_vertices = 0, file_faces = 0;
  ASSERT_TRUE(peers::off_counts(path, &file_vertices, &file_faces)) << path;

  Mesh m;
  std::ifstream in(path);
  ASSERT_TRUE(CGAL::IO::read_OFF(in, m)) << "Surface_mesh refused " << path;
  // Vertex indices are file positions only if the reader kept every vertex, in order.
  ASSERT_EQ(m.number_of_vertices(), file_vertices) << path;
  ASSERT_EQ(m.number_of_faces(), file_faces) << path;
  ASSERT_FALSE(m.has_garbage());
  ASSERT_TRUE(CGAL::is_triangle_mesh(m)) << path;

  peers::PeerComplex cx;
  cx.name = std::string("Surface_mesh ") + GetParam();
  cx.n_vertices = uint32_t(m.number_of_vertices());
  size_t isolated = 0;
  for (auto v : m.vertices()) {
    const auto& pt = m.point(v);
    cx.coords.insert(cx.coords.end(), {pt.x(), pt.y(), pt.z()});
    isolated += m.is_isolated(v) ? 1 : 0;
  }
  for (auto f : m.faces()) cx.add(face_ids(m, f));
  cx.expected_tops = {isolated, 0, m.number_of_faces()};

  std::vector<peers::Relation> rels;
  const auto R = peers::add_relations(rels, "Surface_mesh", 2,
                                      {"vertices_around_target", "halfedges_around_target",
                                       "faces_around_target", "vertex(e, i)",
                                       "halfedges_around_target of both ends",
                                       "face(halfedge(e)), face(opposite)", "vertices_around_face",
                                       "halfedges_around_face", "faces_around_face"});

  // A vertex's or a face's rows from the circulators around halfedge h (to its target, or
  // around its face); null faces (the border) skipped.
  const auto add_rows = [&](uint32_t p, const Ids& sigma, auto vs, auto hs, auto fs) {
    std::vector<Ids> verts, edges, faces;
    for (auto u : vs) verts.push_back({id(u)});
    for (auto h : hs) edges.push_back(edge_ids(m, m.edge(h)));
    for (auto g : fs)
      if (g != Mesh::null_face()) faces.push_back(face_ids(m, g));
    R.add_rows(p, sigma, verts, edges, faces);
  };
  for (auto v : m.vertices()) {
    const Ids sigma{id(v)};
    if (m.is_isolated(v)) {
      R.add_rows(0, sigma, {}, {}, {});
      continue;
    }
    const auto h = m.halfedge(v);
    add_rows(0, sigma, CGAL::vertices_around_target(h, m), CGAL::halfedges_around_target(h, m),
             CGAL::faces_around_target(h, m));
  }
  for (auto e : m.edges()) {
    const Ids sigma = edge_ids(m, e);
    std::vector<Ids> edges, faces;
    for (int i = 0; i < 2; ++i) {
      auto h = m.halfedge(e, i);
      if (!m.is_border(h)) faces.push_back(face_ids(m, m.face(h)));
      for (auto h2 : CGAL::halfedges_around_target(h, m))
        if (m.edge(h2) != e) edges.push_back(edge_ids(m, m.edge(h2)));
    }
    R.add_rows(1, sigma, {{sigma[0]}, {sigma[1]}}, edges, faces);
  }
  for (auto f : m.faces()) {
    const auto h = m.halfedge(f);
    add_rows(2, face_ids(m, f), CGAL::vertices_around_face(h, m), CGAL::halfedges_around_face(h, m),
             CGAL::faces_around_face(h, m));
  }

  const auto report = peers::check_all_kinds(cx, rels);
  EXPECT_FALSE(report.checked.empty());
}

INSTANTIATE_TEST_SUITE_P(CgalSampleMeshes, SurfaceMeshPeer,
                         ::testing::Values("meshes/elephant.off", "meshes/elephant-with-holes.off",
                                           "meshes/fandisk.off"),
                         [](const auto& info) { return peers::test_name_of(info.param); });

}  // namespace
