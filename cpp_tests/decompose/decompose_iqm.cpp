// The IQM standard decomposition seen from the C ABI, on real non-manifold triangle complexes:
// non-manifold OBJ meshes of the shared data folder and the regular + singular triangles of
// CGAL alpha shapes of CGAL sample point sets.
//
// For each 2-dimensional component: it is connected through edges of exactly two triangles and
// no edge has more than two (the star of every vertex copy is one manifold-connected class, so
// its link is a path or a cycle: the component is a 2-manifold with boundary). An orientable
// one, oriented by a breadth-first walk over shared edges, must then load into OpenMesh and
// CGAL's Surface_mesh — both refuse non-manifold edges and vertices — without a rejected face,
// with the component's vertex, face and (independently counted) edge numbers. Non-orientable
// components cannot be given to a halfedge structure and are only counted.
//
// For the whole decomposition: the component triangles mapped back through `original_ids` are
// exactly the complex's triangles, each once; the copy tables agree with the components; the
// split vertices are the vertices with two or more copies, all mapping back to them; and the
// number of copies of each vertex, as well as the number of 2-dimensional components, equal
// what the definitions of src/structures/iqm.rs give when recomputed here by brute force.
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fixed_alpha_shape_3.h>
#include <CGAL/Fixed_alpha_shape_cell_base_3.h>
#include <CGAL/Fixed_alpha_shape_vertex_base_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <gtest/gtest.h>
#include <topoplex.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../c_ptr.hpp"
#include "../find_data.hpp"

namespace {

using Tri = std::array<uint32_t, 3>;

using ComplexPtr = topoplex_tests::CPtr<TpxComplex, tpx_complex_free>;
using DecompositionPtr = topoplex_tests::CPtr<TpxDecomposition, tpx_decomposition_free>;

// A triangle complex as read here, independently of Topoplex's readers: 3 coordinates per
// vertex and the distinct triangles, each ascending, in lexicographic order.
struct Input {
  std::string name;
  uint32_t n_vertices = 0;
  std::vector<double> coords;
  std::vector<Tri> triangles;
};

Tri sorted(Tri t) {
  std::sort(t.begin(), t.end());
  return t;
}

void normalise(std::vector<Tri>& tris) {
  for (auto& t : tris) t = sorted(t);
  std::sort(tris.begin(), tris.end());
  tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
}

// `v` and `f` statements only (the shared non-manifold meshes have nothing else that matters);
// `f` corners may be `i`, `i/t`, `i//n`, `i/t/n`, 1-based or negative (relative).
bool read_obj(const std::string& path, Input& out, std::string& error) {
  std::ifstream in(path);
  std::string line;
  size_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ls(line.substr(0, line.find('#')));
    std::string kw;
    if (!(ls >> kw)) continue;
    if (kw == "v") {
      double x, y, z;
      if (!(ls >> x >> y >> z)) {
        error = path + ":" + std::to_string(line_no) + ": bad vertex";
        return false;
      }
      out.coords.insert(out.coords.end(), {x, y, z});
      ++out.n_vertices;
    } else if (kw == "f") {
      std::vector<uint32_t> corners;
      std::string tok;
      while (ls >> tok) {
        const long i = std::stol(tok.substr(0, tok.find('/')));
        const long id = i > 0 ? i - 1 : long(out.n_vertices) + i;
        if (i == 0 || id < 0) {
          error = path + ":" + std::to_string(line_no) + ": bad index";
          return false;
        }
        corners.push_back(uint32_t(id));
      }
      if (corners.size() != 3) {
        error = path + ":" + std::to_string(line_no) + ": face is not a triangle";
        return false;
      }
      out.triangles.push_back({corners[0], corners[1], corners[2]});
    }
  }
  for (const auto& t : out.triangles)
    for (uint32_t v : t)
      if (v >= out.n_vertices) {
        error = path + ": index out of range";
        return false;
      }
  normalise(out.triangles);
  return true;
}

uint64_t edge_key(uint32_t a, uint32_t b) {
  if (a > b) std::swap(a, b);
  return (uint64_t(a) << 32) | b;
}

// Entries (edge, 3*t + k) for edge k = {tri[k], tri[(k+1)%3]} of every triangle t, sorted by
// edge: equal edges form consecutive groups.
std::vector<std::pair<uint64_t, uint32_t>> edge_incidences(const std::vector<Tri>& tris) {
  std::vector<std::pair<uint64_t, uint32_t>> inc;
  inc.reserve(3 * tris.size());
  for (uint32_t t = 0; t < tris.size(); ++t)
    for (uint32_t k = 0; k < 3; ++k) inc.emplace_back(edge_key(tris[t][k], tris[t][(k + 1) % 3]), 3 * t + k);
  std::sort(inc.begin(), inc.end());
  return inc;
}

struct UnionFind {
  std::vector<uint32_t> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t find(uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(uint32_t a, uint32_t b) { parent[find(a)] = find(b); }
};

// The definitions of src/structures/iqm.rs on a pure triangle complex, by brute force: a joint
// is an edge of exactly two triangles; slots (t, v) and (u, v) are identified when t and u share
// a joint containing v. Gives the number of classes (copies) of each vertex (0 when its star is
// empty) and the number of classes of triangles joined by chains of joints.
struct BruteForce {
  std::vector<uint32_t> copies;
  size_t components = 0;
};

BruteForce brute_force(const Input& in) {
  const auto& tris = in.triangles;
  UnionFind slots(3 * tris.size()), comps(tris.size());
  const auto inc = edge_incidences(tris);
  for (size_t i = 0; i < inc.size();) {
    size_t j = i;
    while (j < inc.size() && inc[j].first == inc[i].first) ++j;
    if (j - i == 2) {
      const uint32_t t = inc[i].second / 3, u = inc[i + 1].second / 3;
      comps.unite(t, u);
      for (uint32_t v : {uint32_t(inc[i].first >> 32), uint32_t(inc[i].first)}) {
        const auto slot = [&](uint32_t s) {
          return 3 * s + uint32_t(std::find(tris[s].begin(), tris[s].end(), v) - tris[s].begin());
        };
        slots.unite(slot(t), slot(u));
      }
    }
    i = j;
  }
  BruteForce out;
  out.copies.assign(in.n_vertices, 0);
  for (uint32_t s = 0; s < 3 * tris.size(); ++s)
    if (slots.find(s) == s) ++out.copies[tris[s / 3][s % 3]];
  for (uint32_t t = 0; t < tris.size(); ++t) out.components += comps.find(t) == t;
  return out;
}

using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SMesh = CGAL::Surface_mesh<K::Point_3>;

struct Summary {
  size_t components[3] = {0, 0, 0};  // by dimension
  size_t orientable = 0, non_orientable = 0, loaded = 0;
  size_t split_vertices = 0, split_copies = 0, split_inside = 0;
};

// A copy of everything OpenMesh writes to omerr (it still reaches std::cerr). Connected once for
// the whole run: OpenMesh 9's mostream::disconnect does not free the target it allocated in
// connect, which LeakSanitizer reports.
std::ostringstream& omerr_capture() {
  static std::ostringstream* capture = [] {
    auto* out = new std::ostringstream;
    omerr().connect(*out);
    return out;
  }();
  return *capture;
}

// One 2-dimensional component (local ids): checks its shape, orients it and loads it into
// OpenMesh and Surface_mesh. Returns false when it is non-orientable (not loaded).
bool check_component(const Input& in, size_t index, const std::vector<Tri>& tris,
                     const uint32_t* original_ids, size_t n_local, bool* loaded) {
  *loaded = false;
  const std::string where = in.name + " component " + std::to_string(index);
  std::vector<bool> used(n_local, false);
  for (const auto& t : tris)
    for (uint32_t l : t) used[l] = true;
  EXPECT_EQ(size_t(std::count(used.begin(), used.end(), true)), n_local)
      << where << ": a local vertex is in none of its triangles";

  // Neighbour across each triangle edge, when exactly two triangles share it.
  const auto inc = edge_incidences(tris);
  std::vector<uint32_t> across(3 * tris.size(), UINT32_MAX);
  size_t n_edges = 0, crowded = 0;
  for (size_t i = 0; i < inc.size();) {
    size_t j = i;
    while (j < inc.size() && inc[j].first == inc[i].first) ++j;
    ++n_edges;
    if (j - i == 2) {
      across[inc[i].second] = inc[i + 1].second;
      across[inc[i + 1].second] = inc[i].second;
    } else if (j - i > 2) {
      ++crowded;
    }
    i = j;
  }
  EXPECT_EQ(crowded, 0u) << where << ": edges in more than two of its triangles";

  // Orientation: +1 keeps a triangle's vertex order, -1 reverses it. Two triangles on a shared
  // edge are consistent when they run along it in opposite directions.
  std::vector<int> orient(tris.size(), 0);
  std::vector<uint32_t> order{0};
  orient[0] = 1;
  bool orientable = true;
  for (size_t head = 0; head < order.size(); ++head) {
    const uint32_t t = order[head];
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t other = across[3 * t + k];
      if (other == UINT32_MAX) continue;
      const uint32_t u = other / 3, m = other % 3;
      const bool same_direction = tris[t][k] == tris[u][m];
      const int want = same_direction ? -orient[t] : orient[t];
      if (orient[u] == 0) {
        orient[u] = want;
        order.push_back(u);
      } else if (orient[u] != want) {
        orientable = false;
      }
    }
  }
  EXPECT_EQ(order.size(), tris.size()) << where << ": not connected through edges of two triangles";
  if (!orientable || order.size() != tris.size() || crowded != 0) return orientable;

  const auto oriented = [&](uint32_t t) {
    Tri f = tris[t];
    if (orient[t] < 0) std::swap(f[1], f[2]);
    return f;
  };
  const auto point = [&](uint32_t local, int axis) { return in.coords[3 * size_t(original_ids[local]) + axis]; };

  // OpenMesh reports refused faces ("complex edge", "complex vertex") on omerr besides
  // returning an invalid handle: both are checked.
  OMesh om;
  std::vector<OMesh::VertexHandle> ovh(n_local);
  for (uint32_t l = 0; l < n_local; ++l)
    ovh[l] = om.add_vertex(OMesh::Point(point(l, 0), point(l, 1), point(l, 2)));
  std::ostringstream& om_messages = omerr_capture();
  om_messages.str("");
  size_t om_rejected = 0;
  for (uint32_t t : order) {
    const Tri f = oriented(t);
    om_rejected += !om.add_face(ovh[f[0]], ovh[f[1]], ovh[f[2]]).is_valid();
  }
  omerr().flush();
  EXPECT_EQ(om_rejected, 0u) << where << ": OpenMesh refused faces";
  EXPECT_EQ(om_messages.str(), "") << where << ": OpenMesh complained";
  EXPECT_EQ(om.n_vertices(), n_local) << where;
  EXPECT_EQ(om.n_faces(), tris.size()) << where;
  EXPECT_EQ(om.n_edges(), n_edges) << where;

  SMesh sm;
  std::vector<SMesh::Vertex_index> svh(n_local);
  for (uint32_t l = 0; l < n_local; ++l) svh[l] = sm.add_vertex(K::Point_3(point(l, 0), point(l, 1), point(l, 2)));
  size_t sm_rejected = 0;
  for (uint32_t t : order) {
    const Tri f = oriented(t);
    sm_rejected += sm.add_face(svh[f[0]], svh[f[1]], svh[f[2]]) == SMesh::null_face();
  }
  EXPECT_EQ(sm_rejected, 0u) << where << ": Surface_mesh refused faces";
  EXPECT_TRUE(sm.is_valid(false)) << where << ": Surface_mesh is not valid";
  EXPECT_EQ(sm.number_of_vertices(), n_local) << where;
  EXPECT_EQ(sm.number_of_faces(), tris.size()) << where;
  EXPECT_EQ(sm.number_of_edges(), n_edges) << where;

  *loaded = om_rejected == 0 && sm_rejected == 0 && om_messages.str().empty();
  return true;
}

// Everything about the decomposition of `c`, which must be the complex of `in`. (Fills `s`
// rather than returning it: ASSERT_* needs a void function.)
void check_decomposition(const Input& in, const TpxComplex* c, Summary& s) {
  uint32_t n = 0, dim = 0;
  size_t tops[3] = {0, 0, 0};
  EXPECT_EQ(tpx_complex_vertex_count(c, &n), TPX_STATUS_OK);
  EXPECT_EQ(tpx_complex_dimension(c, &dim), TPX_STATUS_OK);
  for (uint32_t p = 0; p < 3; ++p) EXPECT_EQ(tpx_complex_top_count(c, p, &tops[p]), TPX_STATUS_OK);
  std::vector<bool> in_triangle(in.n_vertices, false);
  for (const auto& t : in.triangles)
    for (uint32_t v : t) in_triangle[v] = true;
  const size_t isolated = size_t(std::count(in_triangle.begin(), in_triangle.end(), false));
  EXPECT_EQ(n, in.n_vertices) << in.name;
  EXPECT_EQ(dim, 2u) << in.name;
  EXPECT_EQ(tops[2], in.triangles.size()) << in.name;
  EXPECT_EQ(tops[1], 0u) << in.name;
  EXPECT_EQ(tops[0], isolated) << in.name;

  TpxDecomposition* raw = nullptr;
  EXPECT_EQ(tpx_decomposition_build(c, &raw), TPX_STATUS_OK) << tpx_last_error_message();
  const DecompositionPtr d(raw);
  if (!d) return;

  size_t n_components = 0;
  EXPECT_EQ(tpx_decomposition_component_count(d.get(), &n_components), TPX_STATUS_OK);
  const uint32_t *copy_vertex = nullptr, *copy_component = nullptr;
  size_t n_copies = 0;
  EXPECT_EQ(tpx_decomposition_copies(d.get(), &copy_vertex, &copy_component, &n_copies), TPX_STATUS_OK);

  std::vector<Tri> glued;
  std::vector<uint32_t> occurrences(in.n_vertices, 0);  // copies of each vertex, all components
  std::vector<size_t> first_copy(n_components + 1, 0);  // global id of each component's local 0
  std::vector<std::pair<const uint32_t*, size_t>> originals(n_components);
  size_t mapped_tops[3] = {0, 0, 0};
  for (size_t i = 0; i < n_components; ++i) {
    uint32_t k = 0;
    const uint32_t *rows = nullptr, *original_ids = nullptr;
    size_t rows_len = 0, n_local = 0;
    EXPECT_EQ(tpx_decomposition_component(d.get(), i, &k, &rows, &rows_len, &original_ids, &n_local),
              TPX_STATUS_OK);
    first_copy[i + 1] = first_copy[i] + n_local;
    originals[i] = {original_ids, n_local};
    if (k > 2 || rows_len % (k + 1) != 0 || rows_len == 0) {
      ADD_FAILURE() << in.name << " component " << i << ": dimension " << k << ", " << rows_len << " ids";
      continue;
    }
    ++s.components[k];
    mapped_tops[k] += rows_len / (k + 1);
    for (size_t l = 0; l < n_local; ++l) {
      ASSERT_LT(original_ids[l], in.n_vertices) << in.name;
      ++occurrences[original_ids[l]];
      const size_t global = first_copy[i] + l;
      if (global < n_copies) {
        EXPECT_EQ(copy_vertex[global], original_ids[l]) << in.name << " copy " << global;
        EXPECT_EQ(copy_component[global], i) << in.name << " copy " << global;
      }
    }
    if (k != 2) continue;
    std::vector<Tri> local(rows_len / 3);
    bool in_range = true;
    for (size_t t = 0; t < local.size(); ++t) {
      local[t] = {rows[3 * t], rows[3 * t + 1], rows[3 * t + 2]};
      for (uint32_t l : local[t]) in_range = in_range && l < n_local;
    }
    ASSERT_TRUE(in_range) << in.name << " component " << i << ": local id out of range";
    for (const auto& t : local) glued.push_back(sorted({original_ids[t[0]], original_ids[t[1]], original_ids[t[2]]}));
    bool loaded = false;
    if (check_component(in, i, local, original_ids, n_local, &loaded)) {
      ++s.orientable;
      s.loaded += loaded;
    } else {
      ++s.non_orientable;
    }
  }
  EXPECT_EQ(first_copy[n_components], n_copies) << in.name << ": copy table and components disagree";
  for (uint32_t p = 0; p < 3; ++p) EXPECT_EQ(mapped_tops[p], tops[p]) << in.name << ": top " << p << "-simplices";

  // Gluing: the mapped triangles, as a multiset, are the complex's triangles.
  std::sort(glued.begin(), glued.end());
  EXPECT_EQ(glued.size(), in.triangles.size()) << in.name;
  EXPECT_TRUE(glued == in.triangles) << in.name << ": glued components differ from the complex";

  // Split vertices: exactly the vertices with two or more copies, each copy mapping back.
  const uint32_t *split = nullptr, *offsets = nullptr, *copies = nullptr;
  size_t n_split = 0, copies_len = 0;
  EXPECT_EQ(tpx_decomposition_split_vertices(d.get(), &split, &n_split, &offsets, &copies, &copies_len),
            TPX_STATUS_OK);
  std::vector<uint32_t> expected_split;
  for (uint32_t v = 0; v < in.n_vertices; ++v)
    if (occurrences[v] >= 2) expected_split.push_back(v);
  EXPECT_EQ(std::vector<uint32_t>(split, split + n_split), expected_split) << in.name;
  s.split_vertices = n_split;
  if (n_split > 0) {
    EXPECT_EQ(offsets[n_split], copies_len) << in.name;
  }
  for (size_t a = 0; a < n_split; ++a) {
    const uint32_t v = split[a];
    const size_t count = offsets[a + 1] - offsets[a];
    EXPECT_GE(count, 2u) << in.name << ": split vertex " << v;
    if (v < in.n_vertices) {
      EXPECT_EQ(count, occurrences[v]) << in.name << ": split vertex " << v;
    }
    s.split_copies += count;
    std::vector<uint32_t> comps;
    for (uint32_t j = offsets[a]; j < offsets[a + 1]; ++j) {
      const uint32_t cp = copies[j];
      ASSERT_LT(cp, n_copies) << in.name;
      EXPECT_EQ(copy_vertex[cp], v) << in.name << ": copy " << cp << " of split vertex " << v;
      const uint32_t i = copy_component[cp];
      ASSERT_LT(i, n_components) << in.name;
      const size_t local = cp - first_copy[i];
      ASSERT_LT(local, originals[i].second) << in.name << ": copy " << cp;
      EXPECT_EQ(originals[i].first[local], v) << in.name << ": copy " << cp << " of split vertex " << v;
      comps.push_back(i);
    }
    std::sort(comps.begin(), comps.end());
    s.split_inside += std::adjacent_find(comps.begin(), comps.end()) != comps.end();
  }

  // The definitions, recomputed: copies per vertex and 2-dimensional components.
  const BruteForce bf = brute_force(in);
  size_t wrong_copies = 0;
  for (uint32_t v = 0; v < in.n_vertices; ++v) {
    const uint32_t want = std::max(bf.copies[v], 1u);  // an isolated vertex is one copy
    if (occurrences[v] != want && ++wrong_copies <= 5)
      ADD_FAILURE() << in.name << ": vertex " << v << " has " << occurrences[v] << " copies, the definition gives "
                    << want;
  }
  EXPECT_EQ(wrong_copies, 0u) << in.name;
  EXPECT_EQ(s.components[2], bf.components) << in.name;

  std::cout << "[decompose] " << in.name << ": " << in.n_vertices << " vertices, " << in.triangles.size()
            << " triangles -> " << n_components << " components (" << s.components[2] << " of dim 2, "
            << s.components[1] << " of dim 1, " << s.components[0] << " of dim 0); dim 2: " << s.orientable
            << " orientable, " << s.non_orientable << " non-orientable (skipped), " << s.loaded
            << " loaded into OpenMesh and Surface_mesh; " << s.split_vertices << " split vertices with "
            << s.split_copies << " copies (" << s.split_inside << " with two copies in one component)"
            << std::endl;
}

size_t edges_on_more_than_two(const std::vector<Tri>& tris) {
  const auto inc = edge_incidences(tris);
  size_t fins = 0;
  for (size_t i = 0; i < inc.size();) {
    size_t j = i;
    while (j < inc.size() && inc[j].first == inc[i].first) ++j;
    fins += j - i > 2;
    i = j;
  }
  return fins;
}

// ---------------------------------------------------------------------------------------------
// Non-manifold meshes of the shared data folder.

struct ObjCase {
  const char* file;
  // What the data README says the shape is, where that fixes the decomposition (-1: unchecked).
  int components = -1;
  int split_vertices = -1;
};

class SharedObj : public ::testing::TestWithParam<ObjCase> {};

TEST_P(SharedObj, ComponentsLoadIntoHalfedgeMeshesAndGlueBack) {
  TOPOPLEX_REQUIRE_DATA_FILE(path, "TOPOPLEX_SHARED_DATA", TOPOPLEX_DECOMPOSE_SHARED_DATA_DIR,
                             std::string("nonmanifold/") + GetParam().file);
  Input in;
  in.name = GetParam().file;
  std::string error;
  ASSERT_TRUE(read_obj(path, in, error)) << error;
  TpxComplex* raw = nullptr;
  ASSERT_EQ(tpx_complex_from_file(path.c_str(), &raw), TPX_STATUS_OK) << tpx_last_error_message();
  const ComplexPtr c(raw);
  const size_t fins = edges_on_more_than_two(in.triangles);
  std::cout << "[decompose] " << in.name << ": " << fins << " edges on more than two triangles" << std::endl;
  Summary s;
  check_decomposition(in, c.get(), s);
  if (GetParam().components >= 0) {
    EXPECT_EQ(s.components[2], size_t(GetParam().components)) << in.name;
  }
  if (GetParam().split_vertices >= 0) {
    EXPECT_EQ(s.split_vertices, size_t(GetParam().split_vertices)) << in.name;
  }
  EXPECT_GT(s.split_vertices, 0u) << in.name << " is non-manifold: some vertex must be split";
}

INSTANTIATE_TEST_SUITE_P(
    NonManifold, SharedObj,
    // fan3: three triangles on one edge, no joint: three components, both ends of the edge split.
    // hourglass_ico: two icospheres pinched at one vertex: two components, that vertex split.
    ::testing::Values(ObjCase{"fan3.obj", 3, 2}, ObjCase{"hourglass_ico.obj", 2, 1}, ObjCase{"triple_vierbein.obj"},
                      ObjCase{"truck.obj"}),
    [](const auto& info) {
      std::string name = info.param.file;
      return name.substr(0, name.find('.'));
    });

// ---------------------------------------------------------------------------------------------
// The orientation check itself: the 5-vertex Moebius strip, triangles {i, i+1, i+2} mod 5. Every
// edge {i, i+1} is a joint, so the strip is one component with no split vertex, and it has no
// consistent orientation: it must be counted as non-orientable, not loaded.
//
//   0---2---4---1      the left edge 0-1 (0 on top) is glued to the right edge 1-0 (1 on top):
//    \ / \ / \ /       a half twist
//     1---3---0

TEST(MoebiusStrip, IsOneNonOrientableComponent) {
  Input in;
  in.name = "moebius5";
  in.n_vertices = 5;
  std::vector<uint32_t> ids;
  std::vector<size_t> offsets{0};
  for (uint32_t i = 0; i < 5; ++i) {
    const double a = 2 * 3.141592653589793 * i / 5;
    in.coords.insert(in.coords.end(), {std::cos(a), std::sin(a), 0.3 * std::cos(a / 2)});
    const Tri t{i, (i + 1) % 5, (i + 2) % 5};
    in.triangles.push_back(t);
    ids.insert(ids.end(), t.begin(), t.end());
    offsets.push_back(ids.size());
  }
  normalise(in.triangles);
  TpxComplex* raw = nullptr;
  ASSERT_EQ(tpx_complex_from_arrays(5, ids.data(), offsets.data(), 5, in.coords.data(), 3, &raw), TPX_STATUS_OK)
      << tpx_last_error_message();
  const ComplexPtr c(raw);
  Summary s;
  check_decomposition(in, c.get(), s);
  EXPECT_EQ(s.components[2], 1u);
  EXPECT_EQ(s.non_orientable, 1u);
  EXPECT_EQ(s.orientable, 0u);
  EXPECT_EQ(s.split_vertices, 0u);
}

// ---------------------------------------------------------------------------------------------
// Alpha shapes of CGAL sample point sets: the regular and singular triangles (the boundary of
// the alpha solid and the dangling triangles), a non-manifold triangle complex.

using Vb = CGAL::Fixed_alpha_shape_vertex_base_3<K, CGAL::Triangulation_vertex_base_with_info_3<uint32_t, K>>;
using Cb = CGAL::Fixed_alpha_shape_cell_base_3<K>;
using Delaunay = CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<Vb, Cb>>;
using AlphaShape = CGAL::Fixed_alpha_shape_3<Delaunay>;

struct AlphaCase {
  const char* file;
  double alpha;  // squared radius, relative to the squared diagonal of the bounding box
};

class AlphaComplex : public ::testing::TestWithParam<AlphaCase> {};

TEST_P(AlphaComplex, ComponentsLoadIntoHalfedgeMeshesAndGlueBack) {
  // The CGAL data directory comes with Debian's libcgal-demo.
  TOPOPLEX_REQUIRE_DATA_FILE(path, "TOPOPLEX_CGAL_DATA", TOPOPLEX_DECOMPOSE_CGAL_DATA_DIR,
                             std::string("points_3/") + GetParam().file);

  std::vector<std::pair<K::Point_3, uint32_t>> points;
  {
    std::ifstream f(path);
    std::string line;
    while (std::getline(f, line)) {
      std::istringstream ls(line);
      double x, y, z;
      if (!line.empty() && line[0] != '#' && (ls >> x >> y >> z)) points.emplace_back(K::Point_3(x, y, z), uint32_t(points.size()));
    }
  }
  ASSERT_GT(points.size(), 100u) << path;
  CGAL::Bbox_3 box;
  for (const auto& p : points) box += p.first.bbox();
  const double diag2 = CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                       CGAL::square(box.zmax() - box.zmin());
  Delaunay dt(points.begin(), points.end());
  AlphaShape shape(dt, GetParam().alpha * diag2);

  std::vector<AlphaShape::Facet> facets;
  shape.get_alpha_shape_facets(std::back_inserter(facets), AlphaShape::REGULAR);
  const size_t regular = facets.size();
  shape.get_alpha_shape_facets(std::back_inserter(facets), AlphaShape::SINGULAR);
  const size_t singular = facets.size() - regular;

  // Compact numbering over the vertices the triangles use, in point-file order.
  std::vector<Tri> raw_tris;
  for (const auto& [cell, i] : facets)
    raw_tris.push_back({cell->vertex((i + 1) & 3)->info(), cell->vertex((i + 2) & 3)->info(),
                        cell->vertex((i + 3) & 3)->info()});
  std::vector<uint32_t> local(points.size(), UINT32_MAX);
  for (const auto& t : raw_tris)
    for (uint32_t v : t) local[v] = 0;
  Input in;
  in.name = std::string(GetParam().file) + " alpha " + std::to_string(GetParam().alpha);
  for (uint32_t v = 0; v < points.size(); ++v) {
    if (local[v] == UINT32_MAX) continue;
    local[v] = in.n_vertices++;
    const auto& p = points[v].first;
    in.coords.insert(in.coords.end(), {p.x(), p.y(), p.z()});
  }
  std::vector<uint32_t> ids;
  std::vector<size_t> offsets{0};
  for (auto& t : raw_tris) {
    for (auto& v : t) v = local[v];
    ids.insert(ids.end(), t.begin(), t.end());
    offsets.push_back(ids.size());
  }
  in.triangles = raw_tris;
  normalise(in.triangles);
  ASSERT_EQ(in.triangles.size(), raw_tris.size()) << "CGAL listed a facet twice";

  TpxComplex* raw = nullptr;
  ASSERT_EQ(tpx_complex_from_arrays(in.n_vertices, ids.data(), offsets.data(), raw_tris.size(), in.coords.data(), 3,
                                    &raw),
            TPX_STATUS_OK)
      << tpx_last_error_message();
  const ComplexPtr c(raw);
  const size_t fins = edges_on_more_than_two(in.triangles);
  std::cout << "[decompose] " << in.name << ": " << points.size() << " points, " << regular << " regular and "
            << singular << " singular triangles, " << fins << " edges on more than two triangles" << std::endl;
  EXPECT_GT(fins + singular, 0u) << in.name << ": choose an alpha giving a non-manifold complex";
  Summary s;
  check_decomposition(in, c.get(), s);
  EXPECT_GT(s.split_vertices, 0u) << in.name << ": choose an alpha giving a non-manifold complex";
}

INSTANTIATE_TEST_SUITE_P(CgalSamplePoints, AlphaComplex,
                         ::testing::Values(AlphaCase{"fin90_with_PCA_normals.xyz", 1e-3},
                                           AlphaCase{"kitten.xyz", 1e-3}),
                         [](const auto& info) {
                           std::string name = info.param.file;
                           return name.substr(0, name.find_first_of("_."));
                         });

}  // namespace
