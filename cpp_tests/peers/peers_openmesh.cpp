// OpenMesh as the peer on closed and bounded triangle meshes from CGAL's sample data.
// OpenMesh's halfedge structure answers VV, VE, VF, EV, EE, EF, FV, FE, FF; Topoplex must give
// the same sets as R_{0,0}, R_{0,1}, R_{0,2}, R_{1,0}, R_{1,1}, R_{1,2}, R_{2,0}, R_{2,1},
// R_{2,2} for each structure kind that encodes the mesh. OpenMesh splits vertices at edges
// shared by more than two triangles, so only manifold meshes are used (checked on load: the
// vertex and face counts must be the file's).
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <gtest/gtest.h>

#include "peer_check.hpp"

namespace {

using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;
using peers::Ids;

Ids edge_ids(const Mesh& m, Mesh::EdgeHandle e) {
  auto h = m.halfedge_handle(e, 0);
  return {uint32_t(m.from_vertex_handle(h).idx()), uint32_t(m.to_vertex_handle(h).idx())};
}

Ids face_ids(const Mesh& m, Mesh::FaceHandle f) {
  Ids out;
  for (auto v : m.fv_range(f)) out.push_back(uint32_t(v.idx()));
  return out;
}

class OpenMeshPeer : public ::testing::TestWithParam<const char*> {};

TEST_P(OpenMeshPeer, EveryRelationOfEveryKindMatches) {
  PEERS_REQUIRE_DATA(path, GetParam());
  size_t file_vertices = 0, file_faces = 0;
  ASSERT_TRUE(peers::off_counts(path, &file_vertices, &file_faces)) << path;

  Mesh m;
  ASSERT_TRUE(OpenMesh::IO::read_mesh(m, path)) << path;
  ASSERT_EQ(m.n_vertices(), file_vertices) << "OpenMesh added vertices: " << path << " is not manifold";
  ASSERT_EQ(m.n_faces(), file_faces) << "OpenMesh dropped faces of " << path;

  peers::PeerComplex cx;
  cx.name = std::string("OpenMesh ") + GetParam();
  cx.n_vertices = uint32_t(m.n_vertices());
  for (auto v : m.vertices()) {
    const auto& pt = m.point(v);
    cx.coords.insert(cx.coords.end(), {double(pt[0]), double(pt[1]), double(pt[2])});
  }
  size_t isolated = 0;
  for (auto v : m.vertices()) isolated += m.is_isolated(v) ? 1 : 0;
  for (auto f : m.faces()) cx.add(face_ids(m, f));
  // A triangle mesh's tops: its faces and its isolated vertices.
  cx.expected_tops = {isolated, 0, m.n_faces()};

  std::vector<peers::Relation> rels;
  const auto R = peers::add_relations(
      rels, "OpenMesh", 2, {"VV", "VE", "VF", "EV", "EE via VE of both ends", "EF", "FV", "FE", "FF"});
  // A vertex's or a face's rows from OpenMesh's circulators over its vertices, edges, faces.
  const auto add_rows = [&](uint32_t p, const Ids& sigma, auto vs, auto es, auto fs) {
    std::vector<Ids> verts, edges, faces;
    for (auto u : vs) verts.push_back({uint32_t(u.idx())});
    for (auto e : es) edges.push_back(edge_ids(m, e));
    for (auto g : fs) faces.push_back(face_ids(m, g));
    R.add_rows(p, sigma, verts, edges, faces);
  };
  for (auto v : m.vertices())
    add_rows(0, {uint32_t(v.idx())}, m.vv_range(v), m.ve_range(v), m.vf_range(v));
  for (auto e : m.edges()) {
    const Ids sigma = edge_ids(m, e);
    std::vector<Ids> edges, faces;
    for (int i = 0; i < 2; ++i) {
      auto h = m.halfedge_handle(e, i);
      if (!m.is_boundary(h)) faces.push_back(face_ids(m, m.face_handle(h)));
      for (auto e2 : m.ve_range(m.to_vertex_handle(h)))
        if (e2 != e) edges.push_back(edge_ids(m, e2));
    }
    R.add_rows(1, sigma, {{sigma[0]}, {sigma[1]}}, edges, faces);
  }
  for (auto f : m.faces()) add_rows(2, face_ids(m, f), m.fv_range(f), m.fe_range(f), m.ff_range(f));

  const auto report = peers::check_all_kinds(cx, rels);
  EXPECT_FALSE(report.checked.empty());
}

// elephant: closed genus-3 surface; elephant-with-holes: the same animal with boundary loops
// (exercises boundary edges with one face); fandisk: CAD part with sharp features.
INSTANTIATE_TEST_SUITE_P(CgalSampleMeshes, OpenMeshPeer,
                         ::testing::Values("meshes/elephant.off", "meshes/elephant-with-holes.off",
                                           "meshes/fandisk.off"),
                         [](const auto& info) { return peers::test_name_of(info.param); });

}  // namespace
