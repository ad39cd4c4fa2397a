// topoplex_bench_adapters SURFACE.off [TETS.mesh]: the in-memory adapters (include/topoplex/*.hpp)
// against the peers' own readers and a file round trip, and CGAL Polygon_mesh_processing on a
// Topoplex live mesh (topoplex/cgal_graph_traits.hpp) against the same on a Surface_mesh.
// Benchmarks, not tests: nothing here is asserted on time (docs/adapters.md holds the table).
//
// Names are <op>/<lib>. Surface ops, each on the mesh of SURFACE.off:
//   read/openmesh, read/cgal_sm, read/tpx   the file into a TriMesh (OpenMesh::IO::read_mesh),
//                                           a Surface_mesh (CGAL::IO::read_polygon_mesh), a
//                                           Complex (Complex::from_file)
//   to_tpx/<peer>        peer mesh in memory -> Complex (openmesh::to_complex, cgal::to_complex)
//   from_tpx/<peer>      Complex -> peer mesh (openmesh::to_openmesh, cgal::to_surface_mesh)
//   to_tpx_file/<peer>   the same through a file: the peer writes .off, Complex::from_file
//   from_tpx_file/<peer> Complex::write .off, the peer's reader
//   graph/tpx            a SurfaceGraph over a Live whose facet adjacency is built (the tables)
//   live_graph/tpx       Live(complex) + SurfaceGraph: the adjacency built too
//   normals/<lib>        PMP::compute_face_normals into a face map (lib cgal_sm or tpx_graph)
//   area/<lib>           PMP::area
//   relax/<lib>          PMP::tangential_relaxation, 1 iteration (points reset between
//                        iterations, untimed); on the graph it writes through Live::set_coords
// Tetrahedral ops (TETS.mesh given):
//   read/cgal_t3, read/tpx_tets  CGAL::IO::read_MEDIT into a Mesh_3 triangulation;
//                             Complex::from_file
//   to_tpx/cgal_t3            cgal::triangulation_to_complex (finite cells)
//   to_tpx/cgal_c3t3          cgal::c3t3_to_complex (cells and facets with their labels)
//   to_tpx_file/cgal_t3       CGAL::IO::write_MEDIT + Complex::from_file
//   from_tpx/cgal_c3t3        cgal::complex_to_c3t3 (its own build of the TDS)
//   from_tpx_file/cgal_t3     Complex::write .mesh + CGAL::IO::read_MEDIT
// Every benchmark measures the process's CPU time (Topoplex's reader and adjacency may use the
// library's threads) beside the wall time. Scratch files go to $TMPDIR (default /tmp); the
// inputs are first copied there without their comment lines (uncommented() below).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/File_medit.h>
#include <CGAL/version.h>
#if CGAL_VERSION_NR < CGAL_VERSION_NUMBER(5, 6, 0)
#include <CGAL/Mesh_3/tet_soup_to_c3t3.h>  // read_MEDIT's loader (CGAL 5.5 declares it there)
#endif
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/tangential_relaxation.h>
#include <CGAL/Surface_mesh.h>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <benchmark/benchmark.h>
#include <topoplex/cgal.hpp>
#include <topoplex/cgal_graph_traits.hpp>
#include <topoplex/cgal_tds3.hpp>
#include <topoplex/openmesh.hpp>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <unistd.h>

namespace {

using K = CGAL::Epick;
using SM = CGAL::Surface_mesh<K::Point_3>;
struct OmTraits : OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using OM = OpenMesh::TriMesh_ArrayKernelT<OmTraits>;
// int patch indices: what CGAL 5.5's MEDIT reader (Mesh_3/tet_soup_to_c3t3.h) reads.
using Domain = CGAL::Labeled_mesh_domain_3<K, int, int>;
using MTr = CGAL::Mesh_triangulation_3<Domain>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<MTr>;
using Graph = topoplex::cgal::SurfaceGraph;
namespace PMP = CGAL::Polygon_mesh_processing;

std::string scratch(const std::string &ext) {
  const char *t = std::getenv("TMPDIR");
  return std::string(t ? t : "/tmp") + "/topoplex_bench_adapters_" + std::to_string(getpid()) + ext;
}

void fail(benchmark::State &state, const std::string &what) { state.SkipWithError(what.c_str()); }

template <class F>
benchmark::internal::Benchmark *reg(const std::string &name, F &&f) {
  return benchmark::RegisterBenchmark(name.c_str(), std::forward<F>(f))
      ->MeasureProcessCPUTime()
      ->Unit(benchmark::kMillisecond);
}

// A copy of `given` without its comment lines ('#' first): CGAL 5.5's MEDIT reader takes none,
// and OpenMesh's OFF reader reads nothing from a file with one (and says it succeeded). Every
// library reads this copy.
std::string uncommented(const std::string &given, const std::string &ext) {
  const std::string path = scratch(ext);
  std::ifstream in(given);
  std::ofstream out(path);
  std::string line;
  while (std::getline(in, line))
    if (line.empty() || line[0] != '#') out << line << '\n';
  if (!in.eof() || !out) throw std::runtime_error("cannot copy " + given + " to " + path);
  return path;
}

// read/<lib>, to_tpx/<lib>, from_tpx/<lib>, to_tpx_file/<lib> and from_tpx_file/<lib> for a
// surface peer whose mesh type is M: `read(m, path)` and `write(m, path)` its own file I/O
// (false on failure), `to(m)` and `from(cx)` the in-memory adapters; `m` and `cx` the inputs
// made once, `off` the scratch file of the round trips.
template <class M, class Items, class Read, class Write, class To, class From>
void peer_surface(const std::string &lib, const std::string &path, const std::string &off, const M &m,
                  const topoplex::Complex &cx, Items items, Read read, Write write, To to, From from) {
  reg("read/" + lib, [=](benchmark::State &s) {
    for (auto _ : s) {
      M got;
      if (!read(got, path)) return fail(s, lib + " cannot read " + path);
      benchmark::DoNotOptimize(got);
    }
    items(s);
  });
  reg("to_tpx/" + lib, [=, &m](benchmark::State &s) {
    for (auto _ : s) benchmark::DoNotOptimize(to(m).get());
    items(s);
  });
  reg("from_tpx/" + lib, [=, &cx](benchmark::State &s) {
    for (auto _ : s) {
      M got = from(cx);
      benchmark::DoNotOptimize(got);
    }
    items(s);
  });
  reg("to_tpx_file/" + lib, [=, &m](benchmark::State &s) {
    for (auto _ : s) {
      if (!write(m, off)) return fail(s, lib + " cannot write " + off);
      benchmark::DoNotOptimize(topoplex::Complex::from_file(off).get());
    }
    items(s);
  });
  reg("from_tpx_file/" + lib, [=, &cx](benchmark::State &s) {
    for (auto _ : s) {
      cx.write(off);
      M got;
      if (!read(got, off)) return fail(s, lib + " cannot read " + off);
      benchmark::DoNotOptimize(got);
    }
    items(s);
  });
}

void surface(const std::string &given) {
  static const std::string path = uncommented(given, "_input.off");
  // The inputs every op starts from, made once.
  static OM om;
  static SM sm;
  static std::unique_ptr<topoplex::Complex> cx;
  static std::unique_ptr<topoplex::Live> live;
  static std::unique_ptr<Graph> graph;
  if (!OpenMesh::IO::read_mesh(om, path) || om.n_faces() == 0)
    throw std::runtime_error("OpenMesh cannot read " + path);
  if (!CGAL::IO::read_polygon_mesh(path, sm)) throw std::runtime_error("CGAL cannot read " + path);
  cx = std::make_unique<topoplex::Complex>(topoplex::Complex::from_file(path));
  live = std::make_unique<topoplex::Live>(*cx);
  graph = std::make_unique<Graph>(*live);
  static const std::string off = scratch(".off");
  const double faces = double(sm.num_faces());
  const auto items = [faces](benchmark::State &s) {
    s.counters["faces"] = faces;
    s.SetItemsProcessed(int64_t(s.iterations() * faces));
  };

  const auto om_read = [](OM &m, const std::string &p) { return OpenMesh::IO::read_mesh(m, p); };
  const auto om_write = [](const OM &m, const std::string &p) {
    OpenMesh::IO::Options o;
    return OpenMesh::IO::write_mesh(m, p, o, 17);
  };
  const auto om_to = [](const OM &m) { return topoplex::openmesh::to_complex(m); };
  const auto om_from = [](const topoplex::Complex &c) { return topoplex::openmesh::to_openmesh<OM>(c); };
  peer_surface("openmesh", path, off, om, *cx, items, om_read, om_write, om_to, om_from);
  const auto sm_read = [](SM &m, const std::string &p) { return CGAL::IO::read_polygon_mesh(p, m); };
  const auto sm_write = [](const SM &m, const std::string &p) {
    return CGAL::IO::write_polygon_mesh(p, m, CGAL::parameters::stream_precision(17));
  };
  const auto sm_to = [](const SM &m) { return topoplex::cgal::to_complex(m); };
  const auto sm_from = [](const topoplex::Complex &c) { return topoplex::cgal::to_surface_mesh<SM>(c); };
  peer_surface("cgal_sm", path, off, sm, *cx, items, sm_read, sm_write, sm_to, sm_from);
  reg("read/tpx", [=](benchmark::State &s) {
    for (auto _ : s) benchmark::DoNotOptimize(topoplex::Complex::from_file(path).get());
    items(s);
  });

  reg("graph/tpx", [=](benchmark::State &s) {
    for (auto _ : s) {
      Graph g(*live);
      benchmark::DoNotOptimize(g.border_halfedge_count());
    }
    s.counters["graph_bytes"] = double(graph->bytes());
    items(s);
  });
  reg("live_graph/tpx", [=](benchmark::State &s) {
    for (auto _ : s) {
      topoplex::Live l(*cx);
      Graph g(l);
      benchmark::DoNotOptimize(g.border_halfedge_count());
    }
    items(s);
  });

  reg("normals/cgal_sm", [=](benchmark::State &s) {
    auto n = sm.add_property_map<SM::Face_index, K::Vector_3>("f:bench_n").first;
    for (auto _ : s) PMP::compute_face_normals(sm, n);
    sm.remove_property_map(n);
    items(s);
  });
  reg("normals/tpx_graph", [=](benchmark::State &s) {
    auto n = get(CGAL::dynamic_face_property_t<K::Vector_3>(), *graph);
    for (auto _ : s) PMP::compute_face_normals(*graph, n);
    items(s);
  });
  reg("area/cgal_sm", [=](benchmark::State &s) {
    for (auto _ : s) benchmark::DoNotOptimize(PMP::area(sm));
    items(s);
  });
  reg("area/tpx_graph", [=](benchmark::State &s) {
    for (auto _ : s) benchmark::DoNotOptimize(PMP::area(*graph));
    items(s);
  });
  reg("relax/cgal_sm", [=](benchmark::State &s) {
    const std::vector<K::Point_3> start(sm.points().begin(), sm.points().end());
    for (auto _ : s) {
      PMP::tangential_relaxation(sm, CGAL::parameters::number_of_iterations(1));
      s.PauseTiming();
      std::copy(start.begin(), start.end(), sm.points().begin());
      s.ResumeTiming();
    }
    items(s);
  });
  reg("relax/tpx_graph", [=](benchmark::State &s) {
    const topoplex::CoordsView c = live->all_coords();
    const std::vector<double> start(c.begin(), c.end());
    for (auto _ : s) {
      PMP::tangential_relaxation(*graph, CGAL::parameters::number_of_iterations(1));
      s.PauseTiming();
      live->set_all_coords(start);
      s.ResumeTiming();
    }
    items(s);
  });
}

void tets(const std::string &given) {
  static MTr tr;
  static C3t3 c3t3;
  static std::unique_ptr<topoplex::Complex> cx;
  static const std::string path = uncommented(given, "_input.mesh");
  {
    std::ifstream in(path);
    if (!CGAL::IO::read_MEDIT(in, tr)) throw std::runtime_error("CGAL cannot read " + path);
  }
  c3t3.triangulation() = tr;
  c3t3.rescan_after_load_of_triangulation();
  cx = std::make_unique<topoplex::Complex>(topoplex::Complex::from_file(path));
  static const std::string mesh = scratch(".mesh");
  const double cells = double(tr.number_of_finite_cells());
  const auto items = [cells](benchmark::State &s) {
    s.counters["cells"] = cells;
    s.SetItemsProcessed(int64_t(s.iterations() * cells));
  };
  reg("read/cgal_t3", [=](benchmark::State &s) {
    for (auto _ : s) {
      MTr t;
      std::ifstream in(path);
      if (!CGAL::IO::read_MEDIT(in, t)) return fail(s, "read_MEDIT failed");
      benchmark::DoNotOptimize(t.number_of_vertices());
    }
    items(s);
  });
  reg("read/tpx_tets", [=](benchmark::State &s) {
    for (auto _ : s) benchmark::DoNotOptimize(topoplex::Complex::from_file(path).get());
    items(s);
  });
  reg("to_tpx/cgal_t3", [=](benchmark::State &s) {
    for (auto _ : s) benchmark::DoNotOptimize(topoplex::cgal::triangulation_to_complex(tr).get());
    items(s);
  });
  reg("to_tpx/cgal_c3t3", [=](benchmark::State &s) {
    for (auto _ : s) benchmark::DoNotOptimize(topoplex::cgal::c3t3_to_complex(c3t3).get());
    items(s);
  });
  reg("to_tpx_file/cgal_t3", [=](benchmark::State &s) {
    for (auto _ : s) {
      {
        std::ofstream out(mesh);
        out.precision(17);
        CGAL::IO::write_MEDIT(out, tr);
      }
      benchmark::DoNotOptimize(topoplex::Complex::from_file(mesh).get());
    }
    items(s);
  });
#ifdef TOPOPLEX_HAVE_COMPLEX_TO_C3T3
  reg("from_tpx/cgal_c3t3", [=](benchmark::State &s) {
    for (auto _ : s) {
      C3t3 out;
      std::vector<topoplex::Dropped> dropped;  // the file's other labels (medit:ref)
      try {
        topoplex::cgal::complex_to_c3t3(*cx, out, &dropped);
      } catch (const std::exception &e) {
        return fail(s, e.what());
      }
      benchmark::DoNotOptimize(out.number_of_cells_in_complex());
    }
    items(s);
  });
#endif
  reg("from_tpx_file/cgal_t3", [=](benchmark::State &s) {
    for (auto _ : s) {
      cx->write(mesh);
      MTr t;
      std::ifstream in(mesh);
      if (!CGAL::IO::read_MEDIT(in, t)) return fail(s, "read_MEDIT failed");
      benchmark::DoNotOptimize(t.number_of_vertices());
    }
    items(s);
  });
}

}  // namespace

int main(int argc, char **argv) {
  benchmark::Initialize(&argc, argv);
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: %s [benchmark options] SURFACE.off [TETS.mesh]\n", argv[0]);
    return 2;
  }
  try {
    surface(argv[1]);
    if (argc > 2) tets(argv[2]);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::remove(scratch(".off").c_str());
  std::remove(scratch(".mesh").c_str());
  std::remove(scratch("_input.mesh").c_str());
  std::remove(scratch("_input.off").c_str());
  return 0;
}
