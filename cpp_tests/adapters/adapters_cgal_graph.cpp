// CGAL's graph concepts on a Topoplex live mesh (include/topoplex/cgal_graph_traits.hpp): the
// halfedge structure the graph derives against a Surface_mesh built from the same file, CGAL
// PMP functions run on both and compared, and the non-manifold meshes it refuses, by name.
#include <topoplex/cgal_graph_traits.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/tangential_relaxation.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/graph_concepts.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/io.h>
#include <boost/graph/graph_concepts.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "fixtures.hpp"

namespace {

using K = CGAL::Epick;
using Point = K::Point_3;
using Vector = K::Vector_3;
using SM = CGAL::Surface_mesh<Point>;
using G = topoplex::cgal::SurfaceGraph;
namespace PMP = CGAL::Polygon_mesh_processing;

// The concepts CGAL's PMP functions name, checked by CGAL's and Boost's own concept classes.
BOOST_CONCEPT_ASSERT((CGAL::HalfedgeListGraphConcept<G>));
BOOST_CONCEPT_ASSERT((CGAL::FaceListGraphConcept<G>));
BOOST_CONCEPT_ASSERT((boost::VertexListGraphConcept<G>));
BOOST_CONCEPT_ASSERT((boost::EdgeListGraphConcept<G>));
BOOST_CONCEPT_ASSERT((boost::IncidenceGraphConcept<G>));
BOOST_CONCEPT_ASSERT((boost::BidirectionalGraphConcept<G>));
BOOST_CONCEPT_ASSERT(
    (boost::ReadWritePropertyMapConcept<boost::property_map<G, boost::vertex_point_t>::type,
                                        boost::graph_traits<G>::vertex_descriptor>));

// Distance in units in the last place between two doubles of the same sign (0 when equal).
std::uint64_t ulps(double a, double b) {
  if (a == b) return 0;
  if ((a < 0) != (b < 0)) return UINT64_MAX;
  std::int64_t x, y;
  std::memcpy(&x, &a, 8);
  std::memcpy(&y, &b, 8);
  return static_cast<std::uint64_t>(x > y ? x - y : y - x);
}

// A surface as OFF text with its vertex count, triangles and points.
struct Surface {
  std::string name;
  std::vector<double> xyz;
  std::vector<std::array<std::uint32_t, 3>> tris;
  std::uint32_t n() const { return static_cast<std::uint32_t>(xyz.size() / 3); }
  std::string write_off(const std::string &dir) const {
    const std::string path = dir + "/" + name + ".off";
    std::ofstream f(path);
    f.precision(17);
    f << "OFF\n" << n() << ' ' << tris.size() << " 0\n";
    for (std::size_t i = 0; i < xyz.size(); i += 3)
      f << xyz[i] << ' ' << xyz[i + 1] << ' ' << xyz[i + 2] << '\n';
    for (const auto &t : tris) f << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    return path;
  }
  topoplex::Live live() const { return topoplex::Live(fixtures::complex_of(n(), tris, xyz)); }
};

// An nx × ny grid of quads, each split in two, heights perturbed (a disc: one boundary loop).
// With `hole`, the two triangles of every cell in the middle block are left out (a second
// boundary loop); with `second`, a closed octahedron is added away from it (a second component).
Surface grid(std::uint32_t nx, std::uint32_t ny, bool hole, bool second, std::uint64_t seed) {
  Surface s;
  s.name = "grid" + std::to_string(nx) + "x" + std::to_string(ny) + (hole ? "h" : "") +
           (second ? "o" : "");
  for (std::uint32_t j = 0; j <= ny; ++j)
    for (std::uint32_t i = 0; i <= nx; ++i) {
      s.xyz.push_back(i + 0.3 * fixtures::unit(seed));
      s.xyz.push_back(j + 0.3 * fixtures::unit(seed));
      s.xyz.push_back(0.5 * fixtures::unit(seed));
    }
  const auto at = [&](std::uint32_t i, std::uint32_t j) { return j * (nx + 1) + i; };
  for (std::uint32_t j = 0; j < ny; ++j)
    for (std::uint32_t i = 0; i < nx; ++i) {
      if (hole && i >= nx / 3 && i < 2 * nx / 3 && j >= ny / 3 && j < 2 * ny / 3) continue;
      if ((i + j) % 2) {
        s.tris.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        s.tris.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      } else {
        s.tris.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        s.tris.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  if (second) {
    const std::uint32_t b = s.n();
    const double c[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (auto &p : c)
      for (int k = 0; k < 3; ++k) s.xyz.push_back(p[k] + (k == 2 ? 10.0 : 0.0) + 0.01 * fixtures::unit(seed));
    const std::uint32_t f[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (auto &t : f) s.tris.push_back({b + t[0], b + t[1], b + t[2]});
  }
  return s;
}

// An open tube (two boundary loops) of n × m quads, split in two.
Surface tube(std::uint32_t n, std::uint32_t m, std::uint64_t seed) {
  Surface s;
  s.name = "tube" + std::to_string(n) + "x" + std::to_string(m);
  for (std::uint32_t j = 0; j <= m; ++j)
    for (std::uint32_t i = 0; i < n; ++i) {
      const double a = 2 * M_PI * i / n;
      s.xyz.push_back(std::cos(a) * (1 + 0.05 * fixtures::unit(seed)));
      s.xyz.push_back(std::sin(a) * (1 + 0.05 * fixtures::unit(seed)));
      s.xyz.push_back(0.4 * j + 0.05 * fixtures::unit(seed));
    }
  for (std::uint32_t j = 0; j < m; ++j)
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t a = j * n + i, b = j * n + (i + 1) % n;
      s.tris.push_back({a, b, b + n});
      s.tris.push_back({a, b + n, a + n});
    }
  return s;
}

std::vector<double> to_vector(topoplex::CoordsView c) { return {c.begin(), c.end()}; }

// A fresh directory for the generated files, removed at exit.
struct ScratchDir {
  std::string path;
  ScratchDir() {
    const char *t = std::getenv("TMPDIR");
    std::string d = std::string(t ? t : "/tmp") + "/topoplex-cgal-graph-XXXXXX";
    std::vector<char> buf(d.begin(), d.end());
    buf.push_back('\0');
    if (mkdtemp(buf.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path = buf.data();
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

// The files the comparison runs on: generated ones (with boundary, holes, two components), and
// the shared data's surfaces when that folder exists.
std::vector<std::string> surface_files() {
  static const ScratchDir scratch;
  const std::string &dir = scratch.path;
  std::vector<std::string> files{grid(12, 9, false, false, 1).write_off(dir),
                                 grid(15, 15, true, true, 2).write_off(dir),
                                 tube(17, 6, 3).write_off(dir)};
  // tet.obj sits among the non-manifold files but is one closed tetrahedron surface.
  for (const char *f : {"surfaces/bunny00.off", "surfaces/elephant.off", "surfaces/fandisk.off",
                        "nonmanifold/tet.obj"}) {
    const std::string p = fixtures::shared(f);
    if (!p.empty()) files.push_back(p);
  }
  return files;
}

using Key = std::array<std::uint32_t, 3>;
Key sorted_key(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  Key k{a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}

// Both meshes of one file, and the face of the graph matching each Surface_mesh face.
struct Pair {
  std::string path;
  SM sm;
  topoplex::Live live;
  G g;
  std::vector<boost::graph_traits<G>::face_descriptor> face_of;  // by SM face index
  explicit Pair(const std::string &p) : path(p), live(topoplex::Live::from_file(p)), g(live) {
    if (!CGAL::IO::read_polygon_mesh(p, sm)) throw std::runtime_error("CGAL cannot read " + p);
    std::map<Key, boost::graph_traits<G>::face_descriptor> by_key;
    for (auto f : faces(g)) {
      auto h = halfedge(f, g);
      by_key[sorted_key(target(h, g).idx(), target(next(h, g), g).idx(),
                        target(prev(h, g), g).idx())] = f;
    }
    face_of.resize(sm.num_faces());
    for (auto f : faces(sm)) {
      auto h = halfedge(f, sm);
      const auto it = by_key.find(
          sorted_key(target(h, sm), target(next(h, sm), sm), target(prev(h, sm), sm)));
      if (it == by_key.end()) throw std::runtime_error("face missing from the graph");
      face_of[f.idx()] = it->second;
    }
  }
};

TEST(CgalGraphTraits, SameVerticesFacesHalfedgesAndBorderAsSurfaceMesh) {
  for (const std::string &path : surface_files()) {
    SCOPED_TRACE(path);
    Pair m(path);
    ASSERT_EQ(num_vertices(m.g), m.sm.num_vertices());
    ASSERT_EQ(num_faces(m.g), m.sm.num_faces());
    ASSERT_EQ(num_edges(m.g), m.sm.num_edges());
    ASSERT_EQ(num_halfedges(m.g), m.sm.num_halfedges());
    // Valid as CGAL checks it exactly when the Surface_mesh is (an isolated vertex, as the
    // holed grid has, makes both invalid: CGAL asks every vertex for a halfedge).
    std::size_t isolated = 0;
    for (auto v : vertices(m.sm)) isolated += m.sm.is_isolated(v);
    EXPECT_EQ(CGAL::is_valid_polygon_mesh(m.g), CGAL::is_valid_polygon_mesh(m.sm));
    EXPECT_EQ(CGAL::is_valid_polygon_mesh(m.g), isolated == 0);
    EXPECT_TRUE(CGAL::is_triangle_mesh(m.g));
    // Vertex order and coordinates bit for bit.
    for (auto v : vertices(m.sm)) {
      const Point a = m.sm.point(v), b = get(CGAL::vertex_point, m.g, G::vertex_descriptor(v.idx()));
      ASSERT_TRUE(a.x() == b.x() && a.y() == b.y() && a.z() == b.z()) << "vertex " << v.idx();
    }
    // Every halfedge u -> v of the Surface_mesh is one of the graph, with the same next and
    // prev targets, opposite, face (the matched one) and border flag; the edges iterate once.
    std::size_t border = 0;
    for (auto h : halfedges(m.sm)) {
      const G::vertex_descriptor u(source(h, m.sm).idx()), v(target(h, m.sm).idx());
      const auto gh = halfedge(u, v, m.g);
      ASSERT_TRUE(gh.second) << "halfedge " << u << " -> " << v;
      const auto x = gh.first;
      ASSERT_EQ(source(x, m.g), u);
      ASSERT_EQ(target(x, m.g), v);
      ASSERT_EQ(target(next(x, m.g), m.g).idx(), target(next(h, m.sm), m.sm).idx());
      ASSERT_EQ(source(prev(x, m.g), m.g).idx(), source(prev(h, m.sm), m.sm).idx());
      ASSERT_EQ(opposite(opposite(x, m.g), m.g), x);
      ASSERT_EQ(target(opposite(x, m.g), m.g), u);
      ASSERT_EQ(next(prev(x, m.g), m.g), x);
      ASSERT_EQ(CGAL::is_border(x, m.g), CGAL::is_border(h, m.sm));
      if (!CGAL::is_border(h, m.sm)) {
        ASSERT_EQ(face(x, m.g), m.face_of[face(h, m.sm).idx()]);
      }
      border += CGAL::is_border(h, m.sm);
    }
    EXPECT_EQ(m.g.border_halfedge_count(), border);
    std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
    for (auto e : edges(m.g)) {
      const auto a = source(e, m.g).idx(), b = target(e, m.g).idx();
      ASSERT_TRUE(seen.insert({std::min(a, b), std::max(a, b)}).second);
      ASSERT_EQ(edge(opposite(halfedge(e, m.g), m.g), m.g), e);
    }
    EXPECT_EQ(seen.size(), m.sm.num_edges());
    // Degrees and the border convention of halfedge(v).
    for (auto v : vertices(m.sm)) {
      const G::vertex_descriptor w(v.idx());
      EXPECT_EQ(degree(w, m.g), degree(v, m.sm));
      EXPECT_EQ(bool(CGAL::is_border(w, m.g)), bool(CGAL::is_border(v, m.sm)));
      if (halfedge(w, m.g) != boost::graph_traits<G>::null_halfedge()) {
        EXPECT_EQ(target(halfedge(w, m.g), m.g), w);
      }
    }
  }
}

TEST(CgalGraphTraits, PmpNormalsAreasComponentsAndBorderEqualSurfaceMesh) {
  for (const std::string &path : surface_files()) {
    SCOPED_TRACE(path);
    Pair m(path);
    // compute_face_normals: each component within 1 ulp (the same three points summed from the
    // face's first halfedge; where the file's rotation of a face differs, summation order does).
    auto gn = get(CGAL::dynamic_face_property_t<Vector>(), m.g);
    auto sn = m.sm.add_property_map<SM::Face_index, Vector>("f:n").first;
    PMP::compute_face_normals(m.g, gn);
    PMP::compute_face_normals(m.sm, sn);
    std::uint64_t worst = 0;
    for (auto f : faces(m.sm)) {
      const Vector a = sn[f], b = gn[m.face_of[f.idx()]];
      for (int k = 0; k < 3; ++k) worst = std::max(worst, ulps(a[k], b[k]));
    }
    EXPECT_LE(worst, 1u) << "face normals differ by " << worst << " ulp";
    // face_area within 1 ulp each; area (the sum in face order) to F·2^-52 relative.
    double sum = 0;
    for (auto f : faces(m.sm)) {
      const double a = PMP::face_area(f, m.sm), b = PMP::face_area(m.face_of[f.idx()], m.g);
      EXPECT_LE(ulps(a, b), 1u) << "face " << f.idx();
      sum += a;
    }
    const double ga = PMP::area(m.g), sa = PMP::area(m.sm);
    EXPECT_LE(std::abs(ga - sa), sum * num_faces(m.g) * 0x1.0p-52) << ga << " vs " << sa;
    EXPECT_GT(ga, 0);
    // connected_components: the same partition (labels in order of first appearance).
    auto gc = get(CGAL::dynamic_face_property_t<std::size_t>(), m.g);
    auto sc = m.sm.add_property_map<SM::Face_index, std::size_t>("f:cc").first;
    const std::size_t gk = PMP::connected_components(m.g, gc);
    const std::size_t sk = PMP::connected_components(m.sm, sc);
    ASSERT_EQ(gk, sk);
    std::map<std::size_t, std::size_t> g_to_s;
    for (auto f : faces(m.sm)) {
      const auto ins = g_to_s.emplace(gc[m.face_of[f.idx()]], sc[f]);
      ASSERT_EQ(ins.first->second, sc[f]) << "face " << f.idx() << " in another component";
    }
    EXPECT_EQ(g_to_s.size(), sk);
    // border_halfedges: the same boundary edges as (source, target) vertex pairs.
    std::vector<G::halfedge_descriptor> gb;
    std::vector<SM::Halfedge_index> sb;
    PMP::border_halfedges(faces(m.g), m.g, std::back_inserter(gb));
    PMP::border_halfedges(faces(m.sm), m.sm, std::back_inserter(sb));
    std::set<std::pair<std::uint32_t, std::uint32_t>> gp, sp;
    for (auto h : gb) gp.insert({source(h, m.g).idx(), target(h, m.g).idx()});
    for (auto h : sb) sp.insert({source(h, m.sm).idx(), target(h, m.sm).idx()});
    EXPECT_EQ(gp, sp);
    EXPECT_EQ(gb.size(), sb.size());
  }
}

TEST(CgalGraphTraits, TangentialRelaxationMovesTheLiveMeshAsOnSurfaceMesh) {
  int ran = 0;
  for (const std::string &path : surface_files()) {
    SCOPED_TRACE(path);
    Pair m(path);
    if (num_faces(m.g) > 60000) continue;  // the large shared meshes: the others suffice
    ++ran;
    // CGAL's vertex normals at creases (fandisk's) depend on the halfedge a vertex's walk
    // starts from: start the Surface_mesh's where the graph's start (halfedge(v), a border one
    // on the boundary in both).
    for (auto v : vertices(m.sm)) {
      const auto h = halfedge(G::vertex_descriptor(v.idx()), m.g);
      if (h == boost::graph_traits<G>::null_halfedge()) continue;
      const auto sh = halfedge(SM::Vertex_index(source(h, m.g).idx()), v, m.sm);
      ASSERT_TRUE(sh.second);
      m.sm.set_halfedge(v, sh.first);
    }
    const std::vector<double> before = to_vector(m.live.all_coords());
    const unsigned iterations = 3;
    PMP::tangential_relaxation(m.g, CGAL::parameters::number_of_iterations(iterations));
    PMP::tangential_relaxation(m.sm, CGAL::parameters::number_of_iterations(iterations));
    // The points moved in the live mesh itself (through the writable point map), as they did
    // in the Surface_mesh, up to the order in which each vertex's neighbours are summed.
    const std::vector<double> after = to_vector(m.live.all_coords());
    double diag = 0, worst = 0, moved = 0;
    for (auto v : vertices(m.sm)) {
      const Point p = m.sm.point(v);
      const double *q = &after[3 * v.idx()];
      for (int k = 0; k < 3; ++k) {
        diag = std::max(diag, std::abs(before[3 * v.idx() + k]));
        worst = std::max(worst, std::abs(p[k] - q[k]));
        moved = std::max(moved, std::abs(q[k] - before[3 * v.idx() + k]));
      }
    }
    // (A tetrahedron's corners are a fixed point of the relaxation: only equality there.)
    if (num_vertices(m.g) > 10) {
      EXPECT_GT(moved, 1e-6 * diag) << "nothing moved";
    }
    EXPECT_LE(worst, 1e-12 * diag) << "relaxed coordinates differ by " << worst;
    // Border vertices stay where they were (CGAL's default keeps the boundary).
    for (auto v : vertices(m.g))
      if (CGAL::is_border(v, m.g)) {
        const double *q = &after[3 * v.idx()];
        for (int k = 0; k < 3; ++k) ASSERT_EQ(q[k], before[3 * v.idx() + k]);
      }
  }
  EXPECT_GE(ran, 3);
}

TEST(CgalGraphTraits, AGraphOfAnEmptyAndOfAClosedMeshIsValid) {
  G empty;
  EXPECT_EQ(num_vertices(empty), 0u);
  EXPECT_EQ(num_faces(empty), 0u);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(empty));
  Surface oct = grid(1, 1, false, true, 9);  // a grid cell and an octahedron
  topoplex::Live live = oct.live();
  G g(live);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(g));
  EXPECT_EQ(g.border_halfedge_count(), 4u);
  EXPECT_EQ(num_halfedges(g), 3 * 10u + 4u);
  EXPECT_EQ(g.bytes(), 4 * (10 + 3 * 4u));
  // The octahedron's vertices are interior: no border halfedge at them.
  for (std::uint32_t v = 4; v < 10; ++v) EXPECT_FALSE(bool(CGAL::is_border(G::vertex_descriptor(v), g)));
}

// A Live from listed simplices over `n` points on a parabola (all distinct).
topoplex::Live live_of(std::uint32_t n, const std::vector<std::vector<std::uint32_t>> &simplices) {
  std::vector<double> xyz;
  for (std::uint32_t i = 0; i < n; ++i) {
    xyz.push_back(i);
    xyz.push_back(0.5 * i * i);
    xyz.push_back(i % 3);
  }
  return topoplex::Live(fixtures::complex_of(n, simplices, xyz));
}

std::string refusal(topoplex::Live &live) {
  try {
    G g(live);
  } catch (const topoplex::Refused &e) {
    EXPECT_EQ(e.status(), TPX_STATUS_UNSUPPORTED_COMPLEX);
    return e.what();
  }
  return "";
}

TEST(CgalGraphTraits, NonManifoldMeshesAreRefusedNamingTheSimplex) {
  const auto has = [](const std::string &m, const std::string &part) {
    return m.find(part) != std::string::npos;
  };
  {  // an edge in three triangles
    topoplex::Live l = live_of(5, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
    const std::string m = refusal(l);
    EXPECT_TRUE(has(m, "edge {0, 1} lies in three or more triangles")) << m;
    EXPECT_TRUE(has(m, "topoplex/manifold_parts.hpp")) << m;
  }
  {  // a bowtie: two triangles sharing vertex 0 only
    topoplex::Live l = live_of(5, {{0, 1, 2}, {0, 3, 4}});
    const std::string m = refusal(l);
    EXPECT_TRUE(has(m, "vertex 0 is on two boundary fans")) << m;
  }
  {  // two closed tetrahedron surfaces pinched at vertex 3
    topoplex::Live l = live_of(7, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2},
                                   {3, 5, 4}, {3, 4, 6}, {4, 5, 6}, {3, 6, 5}});
    const std::string m = refusal(l);
    EXPECT_TRUE(has(m, "at vertex 3 form more than one fan")) << m;
  }
  {  // two triangles running their shared edge the same way
    topoplex::Live l = live_of(4, {{0, 1, 2}, {0, 1, 3}});
    const std::string m = refusal(l);
    EXPECT_TRUE(has(m, "not consistently oriented")) << m;
    EXPECT_TRUE(has(m, "{0, 1, 2}") && has(m, "{0, 1, 3}")) << m;
  }
  {  // a wire edge beside a triangle, and a tetrahedron
    topoplex::Live l = live_of(5, {{0, 1, 2}, {3, 4}});
    EXPECT_TRUE(has(refusal(l), "top simplex {3, 4} has dimension 1")) << refusal(l);
    topoplex::Live t = live_of(4, {{0, 1, 2, 3}});
    EXPECT_TRUE(has(refusal(t), "has dimension 3")) << refusal(t);
  }
  {  // a removed triangle leaves a tombstone: compact first, then the graph is built
    topoplex::Live l = live_of(5, {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}});
    l.remove_top({0, 4, 1});
    EXPECT_TRUE(has(refusal(l), "compact()")) << refusal(l);
    l.compact();
    G g(l);
    EXPECT_EQ(num_faces(g), 3u);
    EXPECT_TRUE(CGAL::is_valid_polygon_mesh(g));
  }
  {  // the shared non-manifold meshes are all refused
    const int ran = fixtures::for_each_shared(
        {"nonmanifold/fan3.obj", "nonmanifold/hourglass_ico.obj", "nonmanifold/truck.obj",
         "nonmanifold/triple_vierbein.obj"},
        [](const char *f, const std::string &p) {
          topoplex::Live l = topoplex::Live::from_file(p);
          EXPECT_FALSE(refusal(l).empty()) << f;
        });
    if (ran == 0) std::cout << "shared non-manifold meshes absent: skipped that part\n";
  }
}

TEST(CgalGraphTraits, PointMapWritesThroughTheLiveMeshAndRefusesNaN) {
  Surface s = grid(3, 3, false, false, 4);
  topoplex::Live live = s.live();
  G g(live);
  auto vpm = get(CGAL::vertex_point, g);
  const G::vertex_descriptor v(5);
  put(vpm, v, Point(1.5, -2.25, 7));
  EXPECT_EQ(live.coords(5), (std::vector<double>{1.5, -2.25, 7}));
  EXPECT_EQ(get(vpm, v), Point(1.5, -2.25, 7));
  EXPECT_THROW(put(vpm, v, Point(std::nan(""), 0, 0)), topoplex::Error);
  EXPECT_EQ(live.coords(5), (std::vector<double>{1.5, -2.25, 7}));
}

}  // namespace
