// topoplex_bench_tets FILE.mesh: tetrahedral meshes (MEDIT), Topoplex next to CGAL's
// Triangulation_3 (see bench_common.hpp for names, counters and the cross-check).
//
// Ops, each over all vertices:
//   load        read the file (Topoplex: tpx_complex_from_file + tpx_structure_build; CGAL 5.5 has
//               no MEDIT reader for a plain Triangulation_3: the bench parses Vertices and
//               Tetrahedra itself, then builds as below)
//   build       the structure from the same in-memory tetrahedra (Topoplex:
//               tpx_complex_from_arrays + tpx_structure_build; CGAL: t3_from_tets below)
//   star_cells  R_{0,3} of every vertex (CGAL finite_incident_cells)
//   star_edges  R_{0,1} of every vertex (CGAL finite_incident_edges)
//   TT          every tetrahedron's neighbours across its triangles (CGAL: each finite cell's
//               finite neighbor(i); Topoplex: the mesh only)
// `tpx_mesh` is the mesh (the live complex) read inline through topoplex::MeshView, per element,
// nothing prebuilt: star_cells = the tetrahedra of each vertex's star, star_edges = its
// neighbours, TT = for_each_adjacent_top; `tpx_mesh_adj`: TT read from the mesh's facet
// adjacency (tpx_live_adjacency, built before the timing; its bytes in `index_bytes`).
// The triangulation is CGAL::Triangulation_3<Epick> with its default (lightest) vertex and cell
// bases; its heap includes the points (3 doubles per vertex, counter `geometry_bytes`).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_3.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "bench_common.hpp"
#include "topoplex.hpp"

namespace {

using namespace tpxbench;

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using T3 = CGAL::Triangulation_3<K>;
using Vh = T3::Vertex_handle;
using Ch = T3::Cell_handle;

// A Triangulation_3 made of the given tetrahedra: CGAL 5.5 has no tetrahedron_soup_to_
// triangulation_3 (5.6 does), so this does what it does: create the vertices and cells, glue
// cells along shared facets, and close the boundary with infinite cells glued along boundary
// edges. Facets and boundary edges are matched by sorting (no hash map of vectors, unlike
// CGAL's Mesh_3 loader), which favours CGAL's build time. Returns "" or why the tetrahedra do
// not form a mesh a Triangulation_3 can hold (a facet in more than two tetrahedra, a boundary
// edge in more than two boundary triangles).
std::string t3_from_tets(T3& tr, const double* xyz, uint32_t n, const uint32_t* tets, size_t ntets) {
  auto& tds = tr.tds();
  tds.clear();
  const Vh inf = tds.create_vertex();
  tr.set_infinite_vertex(inf);
  std::vector<Vh> vh(n);
  for (uint32_t i = 0; i < n; ++i) {
    vh[i] = tds.create_vertex();
    vh[i]->set_point(K::Point_3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]));
  }
  // (sorted ids of the facet, cell, index of the opposite vertex)
  struct Side {
    std::array<uint32_t, 3> key;
    Ch c;
    int i;
  };
  std::vector<Side> sides;
  sides.reserve(4 * ntets);
  for (size_t t = 0; t < ntets; ++t) {
    const uint32_t* v = tets + 4 * t;
    const Ch c = tds.create_cell(vh[v[0]], vh[v[1]], vh[v[2]], vh[v[3]]);
    for (int j = 0; j < 4; ++j) {
      if (vh[v[j]]->cell() == Ch()) vh[v[j]]->set_cell(c);
      std::array<uint32_t, 3> f{v[(j + 1) & 3], v[(j + 2) & 3], v[(j + 3) & 3]};
      std::sort(f.begin(), f.end());
      sides.push_back({f, c, j});
    }
  }
  auto by_key = [](const Side& a, const Side& b) { return a.key < b.key; };
  std::sort(sides.begin(), sides.end(), by_key);
  std::vector<Side> rim;  // sides of the infinite cells opposite a finite vertex: key {a, b, -1}
  for (size_t i = 0; i < sides.size();) {
    size_t j = i + 1;
    while (j < sides.size() && sides[j].key == sides[i].key) ++j;
    if (j - i > 2) {
      std::ostringstream why;
      why << "facet [" << sides[i].key[0] << " " << sides[i].key[1] << " " << sides[i].key[2] << "] is in " << j - i
          << " tetrahedra";
      return why.str();
    }
    if (j - i == 2) {
      tds.set_adjacency(sides[i].c, sides[i].i, sides[i + 1].c, sides[i + 1].i);
    } else {
      // A boundary facet: an infinite cell on its other side, oriented as CGAL's loader does.
      const Ch c = sides[i].c;
      const int k = sides[i].i;
      const Ch o = (k == 0 || k == 2)
                       ? tds.create_cell(inf, c->vertex((k + 2) & 3), c->vertex((k + 1) & 3), c->vertex((k + 3) & 3))
                       : tds.create_cell(inf, c->vertex((k + 3) & 3), c->vertex((k + 1) & 3), c->vertex((k + 2) & 3));
      if (inf->cell() == Ch()) inf->set_cell(o);
      tds.set_adjacency(c, k, o, 0);
      // Ids of o's finite vertices, in o's slots 1..3.
      std::array<uint32_t, 4> id{};
      for (int s = 1; s < 4; ++s)
        for (int m = 0; m < 3; ++m)
          if (vh[sides[i].key[m]] == o->vertex(s)) id[s] = sides[i].key[m];
      for (int s = 1; s < 4; ++s) {
        std::array<uint32_t, 3> e{id[s == 1 ? 2 : 1], id[s == 3 ? 2 : 3], UINT32_MAX};
        if (e[0] > e[1]) std::swap(e[0], e[1]);
        rim.push_back({e, o, s});
      }
    }
    i = j;
  }
  std::sort(rim.begin(), rim.end(), by_key);
  for (size_t i = 0; i < rim.size(); i += 2) {
    if (i + 1 >= rim.size() || rim[i + 1].key != rim[i].key || (i + 2 < rim.size() && rim[i + 2].key == rim[i].key)) {
      std::ostringstream why;
      why << "boundary edge [" << rim[i].key[0] << " " << rim[i].key[1]
          << "] is not on exactly two boundary triangles (non-manifold boundary)";
      return why.str();
    }
    tds.set_adjacency(rim[i].c, rim[i].i, rim[i + 1].c, rim[i + 1].i);
  }
  tds.set_dimension(3);
  return "";
}

struct Tets {
  uint32_t n = 0;
  std::vector<double> xyz;
  std::vector<uint32_t> tets;
};

// MEDIT `Vertices` and `Tetrahedra` (1-based ids), other sections skipped by their arity.
std::string read_medit(const std::string& path, Tets* out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot open " + path;
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '#')
      while (i < text.size() && text[i] != '\n') text[i++] = ' ';
  const char* p = text.c_str();
  auto word = [&](std::string* w) {
    while (*p && std::isspace(static_cast<unsigned char>(*p))) ++p;
    const char* b = p;
    while (*p && !std::isspace(static_cast<unsigned char>(*p))) ++p;
    w->assign(b, p);
    return p != b;
  };
  auto number = [&] {
    char* end = nullptr;
    const double x = std::strtod(p, &end);
    p = end;
    return x;
  };
  int dim = 3;
  std::string w;
  while (word(&w)) {
    if (w == "End") break;
    if (w == "MeshVersionFormatted") {
      number();
    } else if (w == "Dimension") {
      dim = int(number());
    } else if (w == "Vertices") {
      out->n = uint32_t(number());
      out->xyz.resize(3 * size_t(out->n));
      for (uint32_t i = 0; i < out->n; ++i) {
        for (int k = 0; k < dim; ++k) {
          const double x = number();
          if (k < 3) out->xyz[3 * i + k] = x;
        }
        number();  // reference
      }
    } else if (w == "Tetrahedra") {
      const size_t m = size_t(number());
      out->tets.resize(4 * m);
      for (size_t t = 0; t < m; ++t) {
        for (int k = 0; k < 4; ++k) out->tets[4 * t + k] = uint32_t(number()) - 1;
        number();
      }
    } else {
      static const std::pair<const char*, int> arity[] = {
          {"Edges", 3},   {"Triangles", 4}, {"Quadrilaterals", 5}, {"Hexahedra", 9},        {"Corners", 1},
          {"Ridges", 1},  {"RequiredVertices", 1}, {"RequiredEdges", 1}, {"RequiredTriangles", 1}};
      int a = 0;
      for (auto& [name, k] : arity)
        if (w == name) a = k;
      if (a == 0) return path + ": unknown MEDIT section " + w;
      const size_t m = size_t(number());
      for (size_t i = 0; i < m * size_t(a); ++i) number();
    }
  }
  for (uint32_t v : out->tets)
    if (v >= out->n) return path + ": vertex id out of range";
  return "";
}

std::unique_ptr<T3> t3_of(const Tets& t) {
  auto tr = std::make_unique<T3>();
  if (!t3_from_tets(*tr, t.xyz.data(), t.n, t.tets.data(), t.tets.size() / 4).empty()) return nullptr;
  return tr;
}

struct T3Walk {
  std::unique_ptr<T3> tr;
  std::vector<Vh> vertices;  // finite vertices on a cell (isolated ones have no star in CGAL)
};

std::unique_ptr<T3Walk> t3_walk_of(const Tets& t) {
  auto w = std::make_unique<T3Walk>();
  w->tr = t3_of(t);
  if (!w->tr) return nullptr;
  for (auto v : w->tr->finite_vertex_handles())
    if (v->cell() != Ch()) w->vertices.push_back(v);
  return w;
}

// What CGAL lists around every vertex (`list(v, out)`: cells or edges), counted through one
// reused buffer.
template <class Item, class List>
uint64_t t3_star(const T3Walk& w, List list) {
  std::vector<Item> items;
  uint64_t n = 0;
  for (Vh v : w.vertices) {
    items.clear();
    list(v, std::back_inserter(items));
    n += items.size();
  }
  return n;
}

uint64_t t3_star_cells(const T3Walk& w) {
  return t3_star<Ch>(w, [&](Vh v, auto out) { w.tr->finite_incident_cells(v, out); });
}

uint64_t t3_tt(const T3Walk& w) {
  uint64_t n = 0;
  for (Ch c : w.tr->finite_cell_handles())
    for (int i = 0; i < 4; ++i) n += !w.tr->is_infinite(c->neighbor(i));
  return n;
}

uint64_t t3_star_edges(const T3Walk& w) {
  return t3_star<T3::Edge>(w, [&](Vh v, auto out) { w.tr->finite_incident_edges(v, out); });
}

struct Built : BuiltWalk {};

}  // namespace

int main(int argc, char** argv) {
  const std::string path = init(&argc, argv, "FILE.mesh");
  const auto cx = load_complex(path);
  static Soup soup;
  soup = soup_of(cx.get());
  uint32_t d = 0;
  tpx_check(tpx_complex_dimension(cx.get(), &d), "tpx_complex_dimension");
  if (d != 3) {
    std::fprintf(stderr, "%s: a tetrahedral mesh has dimension 3, this complex has %u\n", path.c_str(), d);
    return 2;
  }
  static Tets tets;
  tets.n = soup.n_vertices;
  tets.tets = top_simplices(cx.get(), 3);
  tets.xyz = soup.coords;

  const uint64_t simplices = soup_simplex_count(soup);

  // CGAL holds the tets only if they are all the complex has, with coordinates, and glue into
  // a Triangulation_3 whose vertex stars are whole (no pinched vertex).
  bool have_t3 = false;
  if (soup.coord_dim != 3) {
    note("cgal_t3 skipped: the file has no 3D coordinates");
  } else if (soup.size() != tets.tets.size() / 4) {
    note("cgal_t3 skipped: the complex has top simplices other than tetrahedra");
  } else {
    T3 tr;
    const std::string why = t3_from_tets(tr, tets.xyz.data(), tets.n, tets.tets.data(), tets.tets.size() / 4);
    if (!why.empty()) {
      note("cgal_t3 skipped: " + why);
    } else {
      std::vector<Ch> cells;
      for (auto v : tr.finite_vertex_handles())
        if (v->cell() != Ch()) tr.finite_incident_cells(v, std::back_inserter(cells));
      have_t3 = cells.size() == tets.tets.size();
      if (!have_t3)
        note("cgal_t3 skipped: a vertex star is not connected through facets (pinched vertex), which "
             "Triangulation_3 cannot hold");
    }
  }
  const double t3_geometry = double(tets.n) * sizeof(K::Point_3);

  const std::vector<Kind> kinds = kinds_that_build(soup);

  auto peer_build = [simplices, t3_geometry](benchmark::State& state, const std::function<std::unique_ptr<T3>()>& make) {
    time_peer_build<T3>(state, simplices, make, "triangulation", t3_geometry);
  };

  if (have_t3)
    add("load", "cgal_t3", Unit::Build, [=](benchmark::State& s) {
      peer_build(s, [&]() -> std::unique_ptr<T3> {
        Tets t;
        if (!read_medit(path, &t).empty()) return nullptr;
        return t3_of(t);
      });
    });
  for (const auto& k : kinds) add_tpx_load(path, k, simplices);
  if (have_t3) add("build", "cgal_t3", Unit::Build, [=](benchmark::State& s) { peer_build(s, [] { return t3_of(tets); }); });
  for (const auto& k : kinds) add_tpx_build(soup, k, simplices);
  // The mesh from the same arrays (tpx_complex_from_arrays + tpx_live_from_complex, the complex
  // freed): its time and heap next to CGAL's, no coordinates kept (geometry_bytes 0; CGAL's
  // points are in its geometry_bytes).
  add("build", "tpx_mesh", Unit::Build, [=](benchmark::State& s) {
    time_peer_build<MeshBuilt>(s, simplices, [] { return mesh_or_abort(soup); }, "mesh", 0);
  });

  if (have_t3) {
    const std::function<std::unique_ptr<T3Walk>()> make = [] { return t3_walk_of(tets); };
    for (auto [op, fn] : {std::make_pair("star_cells", &t3_star_cells), std::make_pair("star_edges", &t3_star_edges),
                          std::make_pair("TT", &t3_tt)}) {
      add_walk(op, "cgal_t3", make, fn);
    }
  }
  for (const auto& k : kinds) {
    const std::string lib = "tpx_" + k.name;
    const std::function<std::unique_ptr<Built>()> make = [k] { return build_walk<Built>(soup, k.id); };
    for (auto [op, q] : {std::make_pair("star_cells", 3u), std::make_pair("star_edges", 1u)}) {
      const std::string name = op;
      const std::vector<uint32_t> qs{q};
      add(name, lib, Unit::Walk, [=](benchmark::State& state) {
        const Built& b = slot().get<Built>(lib, make);
        Walker w;
        uint64_t count = 0;
        for (auto _ : state) {
          count = walk(state, b.s.get(), b.vertices, 0, qs, w);
          benchmark::DoNotOptimize(count);
        }
        check_count(state, name, lib, count);
        set_elements(state, count);
      });
      add_view_walk(name, lib, [lib, make] { return slot().get<Built>(lib, make).s.get(); }, 0, q);
    }
  }
  {
    const std::string lib = "tpx_mesh";
    const std::function<std::unique_ptr<MeshBuilt>()> make = [] { return mesh_or_abort(soup); };
    // Each op's count and a sum of what it saw (kept from the optimiser).
    const auto op = [&](const std::string& name, std::function<uint64_t(const topoplex::MeshView&, uint64_t&)> pass) {
      add(name, lib, Unit::Walk, [=](benchmark::State& state) {
        const topoplex::MeshView m(slot().get<MeshBuilt>(lib, make).arrays);
        uint64_t count = 0, sum = 0;
        for (auto _ : state) {
          count = pass(m, sum);
          benchmark::DoNotOptimize(sum);
        }
        check_count(state, name, lib, count);
        set_elements(state, count);
      });
    };
    op("star_cells", [](const topoplex::MeshView& m, uint64_t& sum) {
      uint64_t n = 0;
      for (uint32_t v = 0; v < m.vertex_slots(); ++v)
        for (topoplex::TopRef t : m.star(v))
          if (t.dim() == 3) {
            sum += t.slot();
            ++n;
          }
      return n;
    });
    op("star_edges", [](const topoplex::MeshView& m, uint64_t& sum) {
      topoplex::NeighbourMarks marks;
      uint64_t n = 0;
      for (uint32_t v = 0; v < m.vertex_slots(); ++v)
        m.for_each_neighbour(v, marks, [&](uint32_t w) {
          sum += w;
          ++n;
        });
      return n;
    });
    const auto tt = [](const topoplex::MeshView& m, uint64_t& sum) {
      uint64_t n = 0;
      for (uint32_t t = 0; t < m.slots(3); ++t)
        m.for_each_adjacent_top(topoplex::TopRef(3, t), [&](topoplex::TopRef u) {
          sum += u.slot();
          ++n;
        });
      return n;
    };
    op("TT", tt);
    add("TT", "tpx_mesh_adj", Unit::Walk, [=](benchmark::State& state) {
      const MeshBuilt& b = slot().get<MeshBuilt>(lib, make);
      TpxLiveAdjacency adj{};
      if (tpx_live_adjacency(b.live.get(), &adj) != TPX_STATUS_OK) {
        state.SkipWithError("tpx_live_adjacency failed");
        return;
      }
      const topoplex::MeshView m(b.arrays, adj);
      uint64_t count = 0, sum = 0;
      for (auto _ : state) {
        count = tt(m, sum);
        benchmark::DoNotOptimize(sum);
      }
      check_count(state, "TT", "tpx_mesh_adj", count);
      set_elements(state, count);
      state.counters["index_bytes"] = double(adj.bytes);
    });
  }
  return run();
}
