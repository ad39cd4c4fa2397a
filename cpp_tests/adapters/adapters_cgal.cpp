// The CGAL adapters (include/topoplex/cgal.hpp, cgal_tds3.hpp): Surface_mesh and Polyhedron_3
// round trips each way compared element by element (vertex order, winding, coordinates bit for
// bit, property map values), refusals, a Delaunay triangulation's cells, and the surface parts
// of a non-manifold complex as Surface_mesh with CGAL Polygon_mesh_processing run per part, its
// normals and areas brought back and checked against a direct computation.
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/version.h>
#if CGAL_VERSION_NR < CGAL_VERSION_NUMBER(5, 6, 0)
#include <CGAL/Mesh_3/tet_soup_to_c3t3.h>  // the oracle of the direct C3T3 build
#endif
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Triangulation_3.h>
#include <topoplex/cgal.hpp>
#include <topoplex/cgal_tds3.hpp>

#include <fstream>
#include <map>

#include "fixtures.hpp"

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SM = CGAL::Surface_mesh<K::Point_3>;
using VI = SM::Vertex_index;
using FI = SM::Face_index;
using Poly = CGAL::Polyhedron_3<K>;
namespace cg = topoplex::cgal;
namespace PMP = CGAL::Polygon_mesh_processing;

std::vector<std::uint32_t> face_ids(const SM &m, FI f) {
  std::vector<std::uint32_t> out;
  for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) out.push_back(std::uint32_t(v));
  return out;
}

void expect_same_mesh(const SM &a, const SM &b) {
  ASSERT_EQ(a.number_of_vertices(), b.number_of_vertices());
  ASSERT_EQ(a.number_of_faces(), b.number_of_faces());
  for (auto v : a.vertices()) EXPECT_EQ(a.point(v), b.point(v));
  for (auto f : a.faces()) EXPECT_EQ(face_ids(a, f), face_ids(b, f));
}

SM grid_mesh(int n) {
  SM m;
  std::uint64_t s = 21;
  std::vector<VI> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      v.push_back(m.add_vertex(K::Point_3(i + 0.3 * fixtures::unit(s), j + 0.3 * fixtures::unit(s),
                                          fixtures::unit(s))));
  m.add_vertex(K::Point_3(-5, -5, -5));  // isolated
  auto at = [&](int i, int j) { return v[j * (n + 1) + i]; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return m;
}

TEST(SurfaceMeshAdapter, MeshToComplexAndBackKeepsOrderWindingPointsAndMaps) {
  SM m = grid_mesh(6);
  auto weight = m.add_property_map<VI, double>("v:weight", 0.0).first;
  auto label = m.add_property_map<FI, std::int32_t>("f:label", 0).first;
  auto normal = m.add_property_map<FI, K::Vector_3>("f:normal", CGAL::NULL_VECTOR).first;
  std::uint64_t s = 5;
  for (auto v : m.vertices()) weight[v] = fixtures::unit(s);
  for (auto f : m.faces()) label[f] = std::int32_t(f) * 3 - 7;
  PMP::compute_face_normals(m, normal);

  const topoplex::Complex c = cg::to_complex(m);
  ASSERT_EQ(c.vertex_count(), m.number_of_vertices());
  const auto listed = fixtures::listing(c);
  ASSERT_EQ(listed.size(), m.number_of_faces());
  for (auto f : m.faces()) EXPECT_EQ(listed[std::size_t(f)], face_ids(m, f));
  const std::vector<double> xyz = c.coords();
  for (auto v : m.vertices())
    for (int k = 0; k < 3; ++k) EXPECT_EQ(xyz[3 * std::size_t(v) + k], m.point(v)[k]);
  const auto w = c.attribute<double>("v:weight", topoplex::Location::Vertices);
  const auto l = c.attribute<std::int32_t>("f:label", topoplex::Location::Listed);
  const auto n = c.attribute<double>("f:normal", topoplex::Location::Listed);
  for (auto v : m.vertices()) EXPECT_EQ(w[std::size_t(v)], weight[v]);
  for (auto f : m.faces()) {
    EXPECT_EQ(l[std::size_t(f)], label[f]);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(n.element(std::size_t(f))[k], normal[f][k]);
  }

  const SM back = cg::to_surface_mesh<SM>(c);
  expect_same_mesh(m, back);
  auto weight2 = back.property_map<VI, double>("v:weight");
  auto label2 = back.property_map<FI, std::int32_t>("f:label");
  auto normal2 = back.property_map<FI, K::Vector_3>("f:normal");
  ASSERT_TRUE(weight2.second && label2.second && normal2.second);
  for (auto v : m.vertices()) EXPECT_EQ(weight2.first[v], weight[v]);
  for (auto f : m.faces()) {
    EXPECT_EQ(label2.first[f], label[f]);
    EXPECT_EQ(normal2.first[f], normal[f]);
  }
}

// Listed values go to the face made from their listing; those of listings that make no face
// are refused, or left behind by name.
TEST(SurfaceMeshAdapter, ListedValuesFollowTheirListingAndTheRestAreNamed) {
  const SM m = fixtures::listed_beside_through([](const topoplex::Complex &c, std::vector<topoplex::Dropped> *d) {
    return cg::to_surface_mesh<SM>(c, d);
  });
  ASSERT_EQ(m.number_of_faces(), 2u);
  EXPECT_EQ(face_ids(m, FI(1)), (std::vector<std::uint32_t>{1, 3, 2}));
  const auto label = m.property_map<FI, std::int32_t>("label");
  ASSERT_TRUE(label.second);
  EXPECT_EQ(label.first[FI(0)], 10);
  EXPECT_EQ(label.first[FI(1)], 12);
  // A Polyhedron_3 holds no attribute at all.
  const topoplex::Complex c = fixtures::listed_beside();
  EXPECT_THROW(cg::to_polyhedron<Poly>(c), topoplex::Refused);
  std::vector<topoplex::Dropped> dropped;
  EXPECT_EQ(cg::to_polyhedron<Poly>(c, &dropped).size_of_facets(), 2u);
  ASSERT_EQ(dropped.size(), 1u);
}

TEST(SurfaceMeshAdapter, GarbageAndUnheldMapsAreRefused) {
  SM m = grid_mesh(2);
  m.add_property_map<VI, std::string>("v:name", "");
  EXPECT_THROW(cg::to_complex(m), topoplex::Refused);
  std::vector<topoplex::Dropped> dropped;
  cg::to_complex(m, &dropped);
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_EQ(dropped[0].name, "v:name");
  m.remove_face(*m.faces().begin());
  EXPECT_THROW(cg::to_complex(m, &dropped), topoplex::Refused);
}

TEST(SurfaceMeshAdapter, RealSurfacesGoBothWaysUnchanged) {
  const int ran = fixtures::for_each_shared(
      {"surfaces/elephant.off", "surfaces/fandisk.off"},
      [&](const char *name, const std::string &path) {
    const topoplex::Complex c = topoplex::Complex::from_file(path);
    const SM m = cg::to_surface_mesh<SM>(c);
    const topoplex::Complex back = cg::to_complex(m);
    EXPECT_EQ(fixtures::listing(back), fixtures::listing(c)) << name;
    EXPECT_EQ(back.coords(), c.coords()) << name;
    SM read;
    std::ifstream in(path);
    ASSERT_TRUE(CGAL::IO::read_OFF(in, read)) << name;
    expect_same_mesh(read, cg::to_surface_mesh<SM>(cg::to_complex(read)));
    // Polyhedron_3 both ways on the same mesh.
    const Poly P = cg::to_polyhedron<Poly>(c);
    ASSERT_EQ(P.size_of_facets(), c.top_count(2));
    const topoplex::Complex from_p = cg::polyhedron_to_complex(P);
    EXPECT_EQ(fixtures::listing(from_p), fixtures::listing(c)) << name;
    EXPECT_EQ(from_p.coords(), c.coords()) << name;
  });
  if (ran == 0) GTEST_SKIP() << "shared data folder absent";
}

TEST(SurfaceMeshAdapter, NonManifoldInputIsRefusedByBothMeshes) {
  const topoplex::Complex fan = topoplex::Complex::from_simplices(5, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  fixtures::expect_refused_naming([&] { cg::to_surface_mesh<SM>(fan); }, "{0, 1, 4}",
                                  "three triangles on one edge went into a Surface_mesh");
  fixtures::expect_refused_naming([&] { cg::to_polyhedron<Poly>(fan); }, "{0, 1, 4}",
                                  "three triangles on one edge went into a Polyhedron_3");
  // A vertex closed by one fan refuses a face of another (the pinched tetrahedra of the
  // fixture, without its wire edge and fin).
  const fixtures::NonManifold nm;
  std::vector<std::vector<std::uint32_t>> pinched(nm.simplices.begin(), nm.simplices.begin() + 4);
  pinched.insert(pinched.end(), {{3, 6, 5}, {3, 5, 7}, {5, 6, 7}, {3, 7, 6}});
  const topoplex::Complex closed = topoplex::Complex::from_simplices(8, pinched);
  EXPECT_THROW(cg::to_surface_mesh<SM>(closed), topoplex::Refused);
  EXPECT_THROW(cg::to_polyhedron<Poly>(closed), topoplex::Refused);
  // Two open fans at vertex 0 (a bowtie): Surface_mesh holds it as a non-manifold vertex, and
  // gives it back unchanged.
  const topoplex::Complex bowtie = topoplex::Complex::from_simplices(5, {{0, 1, 2}, {0, 3, 4}});
  const SM b = cg::to_surface_mesh<SM>(bowtie);
  EXPECT_EQ(fixtures::listing(cg::to_complex(b)), fixtures::listing(bowtie));
}

using DT = CGAL::Delaunay_triangulation_3<K>;

// The finite vertices of triangulation `tr` numbered in its order, and their coordinates: what
// its complex must list.
template <class Tr>
std::pair<std::map<typename Tr::Vertex_handle, std::uint32_t>, std::vector<double>>
finite_vertices(const Tr &tr) {
  std::map<typename Tr::Vertex_handle, std::uint32_t> id;
  std::vector<double> xyz;
  for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v) {
    id.emplace(v, std::uint32_t(id.size()));
    xyz.insert(xyz.end(), {v->point().x(), v->point().y(), v->point().z()});
  }
  return {id, xyz};
}

// The Delaunay triangulation of `n` pseudo-random points of the unit cube (seed `seed`).
DT random_delaunay(std::uint64_t seed, int n) {
  std::vector<K::Point_3> pts;
  for (int i = 0; i < n; ++i)
    pts.emplace_back(fixtures::unit(seed), fixtures::unit(seed), fixtures::unit(seed));
  return DT(pts.begin(), pts.end());
}

TEST(TriangulationAdapter, DelaunayCellsBecomeListedTetrahedraInOrder) {
  const DT dt = random_delaunay(9, 60);
  const topoplex::Complex c = cg::triangulation_to_complex(dt);
  ASSERT_EQ(c.vertex_count(), dt.number_of_vertices());
  ASSERT_EQ(c.top_count(3), dt.number_of_finite_cells());
  const auto [id, want_xyz] = finite_vertices(dt);
  EXPECT_EQ(c.coords(), want_xyz);
  const auto listed = fixtures::listing(c);
  std::size_t i = 0;
  for (auto cell = dt.finite_cells_begin(); cell != dt.finite_cells_end(); ++cell, ++i) {
    std::vector<std::uint32_t> want;
    for (int k = 0; k < 4; ++k) want.push_back(id.at(cell->vertex(k)));
    EXPECT_EQ(listed[i], want);
  }
  // Topoplex answers on it: every interior triangle in two tetrahedra, hull ones in one.
  const topoplex::Structure st(c, topoplex::Kind::IA);
  std::size_t hull = 0;
  for (auto f = dt.finite_facets_begin(); f != dt.finite_facets_end(); ++f) {
    std::vector<std::uint32_t> tri;
    for (int j = 0; j < 3; ++j) tri.push_back(id.at(f->first->vertex(DT::vertex_triple_index(f->second, j))));
    const bool on_hull = dt.is_infinite(f->first) || dt.is_infinite(dt.mirror_facet(*f).first);
    hull += on_hull;
    EXPECT_EQ(st.relation(tri, 3).size(), on_hull ? 1u : 2u);
  }
  EXPECT_GT(hull, 0u);
}

// Back into a plain Triangulation_3 (complex_to_triangulation): a Delaunay triangulation's
// complex comes back with the same vertices in order and the same cells in listing order
// (triangulation_to_complex gives the complex again, coordinates bit for bit), a valid TDS and a
// valid Delaunay triangulation (its cells are Delaunay's), every finite cell positive; a
// negatively wound tetrahedron is turned and counted; a pinched pair and a complex with an
// attribute are refused (the attribute taken when left behind), the triangulation left empty.
TEST(TriangulationAdapter, ComplexBackToAPlainTriangulationKeepsVerticesAndCells) {
  const DT dt = random_delaunay(11, 80);
  const topoplex::Complex c = cg::triangulation_to_complex(dt);
  DT back;
  EXPECT_EQ(cg::complex_to_triangulation(c, back), 0u);
  EXPECT_TRUE(back.tds().is_valid());
  EXPECT_TRUE(back.is_valid());
  EXPECT_EQ(back.number_of_vertices(), dt.number_of_vertices());
  EXPECT_EQ(back.number_of_finite_cells(), dt.number_of_finite_cells());
  const topoplex::Complex again = cg::triangulation_to_complex(back);
  EXPECT_EQ(again.coords(), c.coords());
  EXPECT_EQ(fixtures::listing(again), fixtures::listing(c));
  for (auto cell = back.finite_cells_begin(); cell != back.finite_cells_end(); ++cell)
    EXPECT_EQ(CGAL::orientation(cell->vertex(0)->point(), cell->vertex(1)->point(),
                                cell->vertex(2)->point(), cell->vertex(3)->point()),
              CGAL::POSITIVE);
  using T3 = CGAL::Triangulation_3<K>;
  T3 one;
  const topoplex::Complex negative = topoplex::Complex::from_arrays(
      4, {0, 2, 1, 3}, {0, 4}, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}, 3);
  EXPECT_EQ(cg::complex_to_triangulation(negative, one), 1u);
  EXPECT_EQ(one.number_of_finite_cells(), 1u);
  EXPECT_TRUE(one.is_valid());
  const topoplex::Complex pinched = topoplex::Complex::from_arrays(
      7, {0, 1, 2, 3, 0, 4, 5, 6}, {0, 4, 8},
      {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1}, 3);
  EXPECT_THROW(cg::complex_to_triangulation(pinched, one), topoplex::Refused);
  EXPECT_EQ(one.number_of_vertices(), 0u);
  topoplex::Complex labelled = topoplex::Complex::from_arrays(
      4, {0, 2, 1, 3}, {0, 4}, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}, 3);
  labelled.set_attribute("region", topoplex::Location::Listed, 1, std::vector<std::int32_t>{7});
  EXPECT_THROW(cg::complex_to_triangulation(labelled, one), topoplex::Refused);
  std::vector<topoplex::Dropped> dropped;
  EXPECT_EQ(cg::complex_to_triangulation(labelled, one, &dropped), 1u);
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_EQ(dropped[0].name, "region");
}

// A Mesh_complex_3_in_triangulation_3 labelled by hand (two subdomains split at x = 0.5, the
// facets between different subdomains or the outside in the complex): its cells in complex
// listed in order with their subdomain, then its facets with their pair of subdomains, each
// facet (c, i) wound so that its normal points into c (c's fourth vertex on the positive side:
// CGAL's vertex_triple_index order), coordinates bit for bit.
TEST(TriangulationAdapter, C3t3CellsAndFacetsComeWithSubdomainAndPatchLabels) {
  using Domain = CGAL::Labeled_mesh_domain_3<K>;
  using MTr = CGAL::Mesh_triangulation_3<Domain>::type;
  using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<MTr>;
  C3t3 c3t3;
  MTr &tr = c3t3.triangulation();
  std::uint64_t s = 17;
  for (int i = 0; i < 80; ++i)
    tr.insert(MTr::Weighted_point(MTr::Bare_point(fixtures::unit(s), fixtures::unit(s), fixtures::unit(s)), 0));
  auto label = [&](MTr::Cell_handle c) {
    if (tr.is_infinite(c)) return 0;
    double x = 0;
    for (int k = 0; k < 4; ++k) x += tr.point(c, k).x();
    return x < 2.0 ? 1 : (x < 2.6 ? 0 : 2);  // a slab in the middle stays outside the complex
  };
  for (auto c = tr.finite_cells_begin(); c != tr.finite_cells_end(); ++c)
    if (label(c) != 0) c3t3.add_to_complex(c, label(c));
  for (auto f = tr.finite_facets_begin(); f != tr.finite_facets_end(); ++f) {
    const int a = label(f->first), b = label(tr.mirror_facet(*f).first);
    if (a != b) c3t3.add_to_complex(*f, C3t3::Surface_patch_index(std::min(a, b), std::max(a, b)));
  }
  ASSERT_GT(c3t3.number_of_cells_in_complex(), 0u);
  ASSERT_GT(c3t3.number_of_facets_in_complex(), 0u);

  const topoplex::Complex c = cg::c3t3_to_complex(c3t3);
  const auto [id, xyz] = finite_vertices(tr);
  EXPECT_EQ(c.coords(), xyz);
  const auto listed = fixtures::listing(c);
  ASSERT_EQ(listed.size(), c3t3.number_of_cells_in_complex() + c3t3.number_of_facets_in_complex());
  const auto sub = c.attribute<std::int32_t>("c3t3:subdomain", topoplex::Location::Listed);
  const auto patch = c.attribute<std::int32_t>("c3t3:patch", topoplex::Location::Listed);
  ASSERT_EQ(patch.components(), 2u);
  std::size_t i = 0;
  for (auto cell = c3t3.cells_in_complex_begin(); cell != c3t3.cells_in_complex_end(); ++cell, ++i) {
    std::vector<std::uint32_t> want;
    for (int k = 0; k < 4; ++k) want.push_back(id.at(cell->vertex(k)));
    EXPECT_EQ(listed[i], want);
    EXPECT_EQ(sub[i], label(cell));
    EXPECT_EQ(patch.element(i)[0], 0);
  }
  for (auto f = c3t3.facets_in_complex_begin(); f != c3t3.facets_in_complex_end(); ++f, ++i) {
    ASSERT_EQ(listed[i].size(), 3u);
    std::set<std::uint32_t> got(listed[i].begin(), listed[i].end()), want;
    for (int k = 0; k < 4; ++k)
      if (k != f->second) want.insert(id.at(f->first->vertex(k)));
    EXPECT_EQ(got, want);
    const auto p = [&](std::uint32_t v) { return K::Point_3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]); };
    if (!tr.is_infinite(f->first->vertex(f->second))) {
      const K::Point_3 fourth = f->first->vertex(f->second)->point().point();
      EXPECT_EQ(CGAL::orientation(p(listed[i][0]), p(listed[i][1]), p(listed[i][2]), fourth),
                CGAL::POSITIVE);
    }
    EXPECT_EQ(sub[i], 0);
    const auto sp = c3t3.surface_patch_index(*f);
    EXPECT_EQ(patch.element(i)[0], sp.first);
    EXPECT_EQ(patch.element(i)[1], sp.second);
  }
  EXPECT_EQ(c.top_count(3), c3t3.number_of_cells_in_complex());

#ifdef TOPOPLEX_HAVE_COMPLEX_TO_C3T3
  // Back: every finite cell (subdomain 0 outside the complex) to a new C3T3 and out again: the
  // same vertices, cells in order with their subdomains, and facets with their patches.
  const topoplex::Complex all = cg::c3t3_to_complex(c3t3, true);
  C3t3 again;
  EXPECT_EQ(cg::complex_to_c3t3(all, again), 0u);  // CGAL's cells are positive already
  EXPECT_TRUE(again.triangulation().is_valid());
  EXPECT_EQ(again.number_of_cells_in_complex(), c3t3.number_of_cells_in_complex());
  EXPECT_EQ(again.number_of_facets_in_complex(), c3t3.number_of_facets_in_complex());
  const topoplex::Complex all2 = cg::c3t3_to_complex(again, true);
  EXPECT_EQ(all2.coords(), all.coords());
  const auto l1 = fixtures::listing(all), l2 = fixtures::listing(all2);
  const auto s1 = all.attribute<std::int32_t>("c3t3:subdomain", topoplex::Location::Listed);
  const auto s2 = all2.attribute<std::int32_t>("c3t3:subdomain", topoplex::Location::Listed);
  const auto p1 = all.attribute<std::int32_t>("c3t3:patch", topoplex::Location::Listed);
  const auto p2 = all2.attribute<std::int32_t>("c3t3:patch", topoplex::Location::Listed);
  ASSERT_EQ(l1.size(), l2.size());
  std::set<std::pair<std::vector<std::uint32_t>, std::pair<int, int>>> f1, f2;
  for (std::size_t j = 0; j < l1.size(); ++j) {
    if (l1[j].size() == 4) {
      EXPECT_EQ(l2[j], l1[j]);
      EXPECT_EQ(s2[j], s1[j]);
      continue;
    }
    std::vector<std::uint32_t> a = l1[j], b = l2[j];
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    f1.emplace(a, std::make_pair(p1.element(j)[0], p1.element(j)[1]));
    f2.emplace(b, std::make_pair(p2.element(j)[0], p2.element(j)[1]));
  }
  EXPECT_EQ(f1, f2);
  // A negatively oriented tetrahedron is turned (and counted); a triangle in three tetrahedra,
  // a triangle complex and a complex without coordinates are refused.
  const std::vector<double> corners{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1, -1, -1, 1};
  const topoplex::Complex negative = topoplex::Complex::from_arrays(4, {0, 2, 1, 3}, {0, 4},
      std::vector<double>(corners.begin(), corners.begin() + 12), 3);
  C3t3 one;
  EXPECT_EQ(cg::complex_to_c3t3(negative, one), 1u);
  EXPECT_EQ(one.number_of_cells_in_complex(), 1u);
  const topoplex::Complex three = topoplex::Complex::from_arrays(
      6, {0, 1, 2, 3, 0, 2, 1, 4, 0, 1, 2, 5}, {0, 4, 8, 12}, corners, 3);
  EXPECT_THROW(cg::complex_to_c3t3(three, one), topoplex::Refused);
  EXPECT_EQ(one.number_of_cells_in_complex(), 0u);
  // Two tetrahedra on the same side of their shared triangle (overlapping), and two sharing
  // nothing but a vertex (no ball): refused, as the TDS's is_valid() would find them.
  const topoplex::Complex overlapping = topoplex::Complex::from_arrays(
      5, {0, 1, 2, 3, 0, 1, 2, 4}, {0, 4, 8},
      std::vector<double>(corners.begin(), corners.begin() + 15), 3);
  EXPECT_THROW(cg::complex_to_c3t3(overlapping, one), topoplex::Refused);
  const topoplex::Complex pinched = topoplex::Complex::from_arrays(
      7, {0, 1, 2, 3, 0, 4, 5, 6}, {0, 4, 8},
      {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1}, 3);
  EXPECT_THROW(cg::complex_to_c3t3(pinched, one), topoplex::Refused);
  EXPECT_EQ(one.number_of_cells_in_complex(), 0u);
  // And the two tetrahedra side by side across it are taken.
  const topoplex::Complex two = topoplex::Complex::from_arrays(
      5, {0, 1, 2, 3, 0, 2, 1, 4}, {0, 4, 8}, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.2, 0.2, -1}, 3);
  EXPECT_EQ(cg::complex_to_c3t3(two, one), 0u);
  EXPECT_EQ(one.number_of_cells_in_complex(), 2u);
  EXPECT_TRUE(one.triangulation().tds().is_valid());
  EXPECT_THROW(cg::complex_to_c3t3(topoplex::Complex::from_simplices(3, {{0, 1, 2}}), one),
               topoplex::Refused);
  EXPECT_THROW(cg::complex_to_c3t3(topoplex::Complex::from_simplices(4, {{0, 1, 2, 3}}), one),
               topoplex::Refused);
#endif
}

#if CGAL_VERSION_NR < CGAL_VERSION_NUMBER(5, 6, 0)
// complex_to_c3t3 builds the triangulation itself; CGAL 5.5's tetrahedron-soup loader
// (CGAL::build_triangulation) is the oracle: on the shared data's tetrahedral meshes, and on a
// C3T3 of random points with its complement's cells in subdomain 0, the same finite vertices in
// order, the same cells in order with their subdomains and neighbours (as cell numbers, the
// infinite ones by their finite facet), the same facets' surface patches on both sides, the same
// number of cells; both pass Triangulation_3::is_valid and the TDS's is_valid.
TEST(TriangulationAdapter, C3t3BuiltDirectlyIsWhatCgalsSoupLoaderBuilds) {
  using Domain = CGAL::Labeled_mesh_domain_3<K, int, int>;
  using MTr = CGAL::Mesh_triangulation_3<Domain>::type;
  using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<MTr>;
  using CH = MTr::Cell_handle;
  // Cell numbers: finite cells in iteration order; an infinite cell named by its finite facet.
  const auto describe = [](const MTr &tr) {
    std::map<CH, long> number;
    long next = 0;
    for (auto c = tr.finite_cells_begin(); c != tr.finite_cells_end(); ++c) number[c] = next++;
    std::map<MTr::Vertex_handle, int> vid;
    int v = 0;
    for (auto x = tr.finite_vertices_begin(); x != tr.finite_vertices_end(); ++x) vid[x] = v++;
    const auto name = [&](CH c) {
      if (!tr.is_infinite(c)) return std::vector<long>{number.at(c)};
      std::vector<long> f;
      for (int k = 0; k < 4; ++k)
        if (!tr.is_infinite(c->vertex(k))) f.push_back(vid.at(c->vertex(k)));
      std::sort(f.begin(), f.end());
      return f;
    };
    std::vector<std::vector<long>> out;
    for (auto c = tr.finite_cells_begin(); c != tr.finite_cells_end(); ++c) {
      std::vector<long> row{c->subdomain_index()};
      for (int k = 0; k < 4; ++k) row.push_back(vid.at(c->vertex(k)));
      for (int k = 0; k < 4; ++k) {
        const std::vector<long> n = name(c->neighbor(k));
        row.push_back(-1);
        row.insert(row.end(), n.begin(), n.end());
        row.push_back(c->surface_patch_index(k));
        row.push_back(c->neighbor(k)->surface_patch_index(c->neighbor(k)->index(c)));
      }
      out.push_back(row);
    }
    out.push_back({long(tr.number_of_cells()), long(tr.number_of_vertices())});
    return out;
  };
  // The checks of Triangulation_3::is_valid (the TDS's, every finite cell positive); the
  // Regular_triangulation_3 it is also asks for the regular (Delaunay) property, which a mesh
  // read from a file need not have (asked of the random points only).
  const auto compare = [&](const topoplex::Complex &c, const std::string &what) {
    std::vector<topoplex::Dropped> dropped;
    C3t3 direct;
    cg::complex_to_c3t3(c, direct, &dropped);
    const MTr &dt = direct.triangulation();
    EXPECT_TRUE(dt.tds().is_valid(false, 1)) << what;
    EXPECT_EQ(dt.dimension(), 3) << what;
    std::size_t negative = 0;
    for (auto x = dt.finite_cells_begin(); x != dt.finite_cells_end(); ++x)
      negative += CGAL::orientation(dt.point(x, 0).point(), dt.point(x, 1).point(),
                                    dt.point(x, 2).point(), dt.point(x, 3).point()) != CGAL::POSITIVE;
    EXPECT_EQ(negative, 0u) << what;
    if (what == "random points") {
      EXPECT_TRUE(dt.is_valid()) << what;
    }
    // The oracle's input: the same tetrahedra turned positive, subdomains and patches.
    const std::vector<double> xyz = c.coords();
    std::vector<MTr::Point> points;
    for (std::size_t v = 0; v < c.vertex_count(); ++v)
      points.emplace_back(K::Point_3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]));
    bool sub = false, patch = false;
    for (const auto &a : c.attributes()) {
      sub = sub || a.name == "c3t3:subdomain";
      patch = patch || a.name == "c3t3:patch";
    }
    std::vector<std::array<int, 5>> cells;
    std::map<std::array<int, 3>, int> border;
    const auto listed = fixtures::listing(c);
    for (std::size_t i = 0; i < listed.size(); ++i) {
      const auto &t = listed[i];
      if (t.size() == 4) {
        std::array<int, 5> x{int(t[0]), int(t[1]), int(t[2]), int(t[3]),
                             sub ? c.attribute<std::int32_t>("c3t3:subdomain",
                                                             topoplex::Location::Listed)[i]
                                 : 1};
        if (CGAL::orientation(points[x[0]].point(), points[x[1]].point(), points[x[2]].point(),
                              points[x[3]].point()) == CGAL::NEGATIVE)
          std::swap(x[0], x[1]);
        cells.push_back(x);
      } else if (t.size() == 3 && patch) {
        std::array<int, 3> f{int(t[0]), int(t[1]), int(t[2])};
        std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
        border[f] = c.attribute<std::int32_t>("c3t3:patch", topoplex::Location::Listed)[i];
      }
    }
    C3t3 oracle;
    std::vector<MTr::Vertex_handle> handles;
    ASSERT_TRUE((CGAL::build_triangulation<MTr, false>(oracle.triangulation(), points, cells,
                                                       border, handles)))
        << what;
    oracle.rescan_after_load_of_triangulation();
    EXPECT_EQ(describe(direct.triangulation()), describe(oracle.triangulation())) << what;
    EXPECT_EQ(direct.number_of_cells_in_complex(), oracle.number_of_cells_in_complex()) << what;
    EXPECT_EQ(direct.number_of_facets_in_complex(), oracle.number_of_facets_in_complex()) << what;
    EXPECT_EQ(cg::c3t3_to_complex(direct, true).coords(), c.coords()) << what;
  };
  // Random points: every finite cell, subdomain 0 on a slab, patches between subdomains.
  C3t3 made;
  MTr &tr = made.triangulation();
  std::uint64_t s = 23;
  for (int i = 0; i < 150; ++i)
    tr.insert(MTr::Weighted_point(
        MTr::Bare_point(fixtures::unit(s), fixtures::unit(s), fixtures::unit(s)), 0));
  for (auto c = tr.finite_cells_begin(); c != tr.finite_cells_end(); ++c) {
    const double x = tr.point(c, 0).x() + tr.point(c, 1).x() + tr.point(c, 2).x();
    if (x < 1.2 || x > 1.8) made.add_to_complex(c, x < 1.2 ? 1 : 2);
  }
  for (auto f = tr.finite_facets_begin(); f != tr.finite_facets_end(); ++f) {
    const CH a = f->first, b = a->neighbor(f->second);
    const int la = tr.is_infinite(a) ? 0 : a->subdomain_index();
    const int lb = tr.is_infinite(b) ? 0 : b->subdomain_index();
    if (la != lb) made.add_to_complex(*f, 3 + la + lb);
  }
  compare(cg::c3t3_to_complex(made, true), "random points");
  const int ran = fixtures::for_each_shared(
      {"tetrahedral/slug.mesh", "tetrahedral/hand.mesh"},
      [&](const char *name, const std::string &path) {
    compare(topoplex::Complex::from_file(path), name);
  });
  if (ran == 0) GTEST_SKIP() << "shared data folder absent (the random points ran)";
}
#endif

// The surface parts of the non-manifold fixture and of the real non-manifold meshes as
// Surface_mesh: CGAL PMP face normals, face areas and connected components per part, brought
// back onto the complex's triangles, equal a direct computation.
TEST(SurfaceMeshParts, PmpNormalsAndAreasPerPartComeBackRight) {
  std::vector<std::pair<std::string, topoplex::Complex>> inputs;
  inputs.emplace_back("fixture", fixtures::NonManifold().complex());
  for (const char *name : {"nonmanifold/truck.obj", "nonmanifold/hourglass_ico.obj"}) {
    const std::string path = fixtures::shared(name);
    if (!path.empty()) inputs.emplace_back(name, topoplex::Complex::from_file(path));
  }
  for (const auto &in : inputs) {
    const topoplex::Complex &c = in.second;
    const topoplex::SurfaceParts parts = topoplex::SurfaceParts::cut(c);
    fixtures::check_parts(c, parts);
    const std::vector<double> xyz = topoplex::adapt::xyz3(c, "test");
    std::vector<std::vector<double>> normals, areas;
    for (const auto &p : parts.parts()) {
      std::vector<double> n, a;
      if (p.problem.empty()) {
        SM m = cg::part_to_surface_mesh<SM>(p, xyz);
        auto fn = m.add_property_map<FI, K::Vector_3>("f:n", CGAL::NULL_VECTOR).first;
        PMP::compute_face_normals(m, fn);
        auto comp = m.add_property_map<FI, std::size_t>("f:c", 0).first;
        EXPECT_EQ(PMP::connected_components(m, comp), 1u) << in.first << " part " << p.index;
        for (auto f : m.faces()) {
          n.insert(n.end(), {fn[f].x(), fn[f].y(), fn[f].z()});
          a.push_back(PMP::face_area(f, m));
        }
      } else {
        EXPECT_THROW(cg::part_to_surface_mesh<SM>(p, xyz), topoplex::Refused);
        n.assign(3 * p.face_count(), 0.0);
        a.assign(p.face_count(), 0.0);
      }
      normals.push_back(n);
      areas.push_back(a);
    }
    const std::vector<double> per_n = parts.gather_faces(normals, 3, true);
    const std::vector<double> per_a = parts.gather_faces(areas, 1);
    std::vector<bool> held(c.top_count(2), false);
    for (const auto &p : parts.parts())
      for (std::uint32_t t : p.original_triangle) held[t] = p.problem.empty();
    for (std::size_t t = 0; t < held.size(); ++t) {
      if (!held[t]) continue;
      const std::uint32_t *tri = c.top_oriented(2, std::uint32_t(t)).data();
      const auto want = fixtures::unit_normal(xyz, tri);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(per_n[3 * t + k], want[k], 1e-9) << in.first << " " << t;
      EXPECT_NEAR(per_a[t], fixtures::area(xyz, tri), 1e-12 * (1 + per_a[t])) << in.first << " " << t;
    }
  }
}

}  // namespace
