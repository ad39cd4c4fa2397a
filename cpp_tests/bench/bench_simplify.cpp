// topoplex_bench_simplify FILE.off: quadric-error simplification of a triangle mesh to 1% of
// its triangles (TOPOPLEX_BENCH_SIMPLIFY_RATIO overrides), Topoplex next to OpenMesh's
// Decimater with ModQuadric and CGAL's Surface_mesh_simplification with the Garland–Heckbert
// plane policies (see bench_common.hpp for names and counters).
//
// Each op times the whole job from the same in-memory triangle soup (the file's faces and
// coordinates): build the library's mesh, simplify, and (untimed) free it.
//   simplify/openmesh      TriMesh add_vertex/add_face, Decimater + ModQuadric (collapse to an
//                          existing vertex, unlimited error), decimate_to_faces(0, target),
//                          garbage_collection
//   simplify/cgal_sm       Surface_mesh add_vertex/add_face, edge_collapse with
//                          GarlandHeckbert_plane_policies (cost and optimal placement) and a
//                          stop predicate on the face count
//   simplify/tpx           tpx_complex_from_arrays (with coordinates) + tpx_simplify_in_place
//   simplify/tpx_preserve  the same with the link condition checked on every contraction
// Counters: `elements` = input triangles, `faces_out` = triangles left, and `heap_bytes` /
// `peak_heap_bytes` of one more untimed run (peak: the highest live heap during build +
// simplify above the level at its start; for Topoplex it includes the input complex, the live
// complex, the quadrics and queue, and the output complex).
//
// topoplex_bench_simplify --peers-on FILE.obj|FILE.off prints, one line per library, what it
// does with a (possibly non-manifold) mesh: whether it loads it whole, how many triangles it
// keeps, and what simplifying it to half does.
//
// topoplex_bench_simplify --file-job openmesh|cgal_sm IN.off OUT.off runs the job the way
// `topoplex simplify IN --out OUT --ratio 0.01` does (the library's own reader, simplify to 1%
// or TOPOPLEX_BENCH_SIMPLIFY_RATIO, its writer), once (OpenMesh reads no '#' comment line:
// strip it first), so that a whole process's peak RSS and
// time compare with the CLI's (docs/benchmarks.md, Simplification).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

#include "bench_halfedge.hpp"

namespace {

using namespace tpxbench;

namespace SMS = CGAL::Surface_mesh_simplification;

double ratio_from_env() {
  const char* r = std::getenv("TOPOPLEX_BENCH_SIMPLIFY_RATIO");
  return r && *r ? std::atof(r) : 0.01;
}

// The triangles and coordinates of an OFF file (orientation as given); "" or an error.
std::string read_off_soup(const std::string& path, Soup* soup) {
  std::ifstream in(path);
  if (!in) return "cannot open " + path;
  std::string head;
  in >> head;
  if (head != "OFF") return path + ": not a plain OFF file";
  while (in >> std::ws && in.peek() == '#') in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  size_t nv = 0, nf = 0, ne = 0;
  if (!(in >> nv >> nf >> ne)) return path + ": bad counts";
  soup->n_vertices = uint32_t(nv);
  soup->coord_dim = 3;
  soup->coords.resize(3 * nv);
  for (size_t i = 0; i < 3 * nv; ++i)
    if (!(in >> soup->coords[i])) return path + ": bad vertex";
  for (size_t f = 0; f < nf; ++f) {
    size_t k = 0;
    uint32_t t[3];
    if (!(in >> k) || k != 3 || !(in >> t[0] >> t[1] >> t[2])) return path + ": bad or non-triangle face";
    soup->add(t, 3);
  }
  return "";
}

struct Omesh {
  std::unique_ptr<OMesh> mesh;
  size_t faces = 0;
};

// OpenMesh's decimation to `target` faces; returns the faces left.
size_t openmesh_decimate(OMesh& m, size_t target) {
  using Decimater = OpenMesh::Decimater::DecimaterT<OMesh>;
  using Quadric = OpenMesh::Decimater::ModQuadricT<OMesh>::Handle;
  Decimater dec(m);
  Quadric q;
  dec.add(q);
  dec.module(q).unset_max_err();
  dec.initialize();
  dec.decimate_to_faces(0, target);
  m.garbage_collection();
  return m.n_faces();
}

// Stops CGAL's edge collapse once the mesh has at most `target` faces.
struct FaceCountStop {
  size_t target;
  const SMesh* mesh;
  template <class FT, class Profile>
  bool operator()(const FT&, const Profile&, std::size_t, std::size_t) const {
    return mesh->number_of_faces() <= target;
  }
};

size_t cgal_decimate(SMesh& m, size_t target) {
  SMS::GarlandHeckbert_plane_policies<SMesh, K> gh(m);
  SMS::edge_collapse(m, FaceCountStop{target, &m},
                     CGAL::parameters::get_cost(gh.get_cost()).get_placement(gh.get_placement()));
  m.collect_garbage();
  return m.number_of_faces();
}

// Topoplex: complex from the soup, simplified, both freed; returns the top simplices left.
size_t tpx_run(const Soup& soup, double ratio, bool preserve, std::string* why) {
  TpxComplex* in = nullptr;
  TpxStatus st = tpx_complex_from_arrays(soup.n_vertices, soup.ids.data(), soup.offsets.data(), soup.size(),
                                         soup.coords.data(), soup.coord_dim, &in);
  if (st != TPX_STATUS_OK) {
    *why = tpx_message();
    return 0;
  }
  // In place, as the peers decimate their meshes in place.
  st = tpx_simplify_in_place(in, ratio, preserve);
  if (st != TPX_STATUS_OK) {
    *why = tpx_message();
    tpx_complex_free(in);
    return 0;
  }
  size_t n = 0;
  tpx_complex_top_count(in, 2, &n);
  tpx_complex_free(in);
  return n;
}

// Times `run` (which returns the faces left, 0 on failure with `why` set) and measures the heap
// of one more run.
void time_simplify(benchmark::State& state, size_t faces_in, const std::function<size_t(std::string*)>& run) {
  slot().clear();
  size_t left = 0;
  std::string why;
  for (auto _ : state) {
    left = run(&why);
    if (left == 0) {
      fail(state, why);
      return;
    }
  }
  HeapUse use;
  measure_heap([&] { return run(&why); }, &use);
  set_heap_counters(state, use);
  set_elements(state, faces_in);
  state.counters["faces_out"] = double(left);
}

// ---------------------------------------------------------------------------------------------
// --peers-on: what each library does with a possibly non-manifold mesh.

int peers_on(const std::string& path) {
  std::vector<K::Point_3> points;
  std::vector<std::vector<size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(path, points, polygons)) {
    std::printf("%s: cannot read as a polygon soup\n", path.c_str());
    return 1;
  }
  const size_t faces = polygons.size();
  std::printf("%s: %zu vertices, %zu faces in the file\n", path.c_str(), points.size(), faces);
  // OpenMesh: its reader, then the decimater on what it kept.
  {
    OMesh m;
    OpenMesh::IO::Options opt;
    std::streambuf* old = std::cerr.rdbuf();
    std::ostringstream sink;
    std::cerr.rdbuf(sink.rdbuf());  // its "complex edge" / "complex vertex" warnings
    const bool ok = OpenMesh::IO::read_mesh(m, path, opt);
    std::cerr.rdbuf(old);
    if (!ok) {
      std::printf("openmesh: read_mesh refuses the file\n");
    } else {
      const size_t kept = m.n_faces(), verts = m.n_vertices();
      const size_t left = openmesh_decimate(m, kept / 2);
      std::printf("openmesh: read_mesh keeps %zu of %zu faces (%zu vertices for %zu in the file: %s); "
                  "decimate to half: %zu faces\n",
                  kept, faces, verts, points.size(),
                  kept < faces ? "drops faces" : (verts > points.size() ? "tears: duplicates vertices" : "whole"),
                  left);
    }
  }
  // CGAL: the mesh reader (refuses non-manifold input), then the soup route (orient, which
  // duplicates the non-manifold vertices and edges) and edge_collapse on that.
  {
    SMesh m;
    const bool ok = CGAL::IO::read_polygon_mesh(path, m) && CGAL::is_valid_polygon_mesh(m);
    std::printf("cgal_sm: read_polygon_mesh %s\n", ok ? "loads it" : "refuses it");
    auto pts = points;
    auto polys = polygons;
    const bool oriented = CGAL::Polygon_mesh_processing::orient_polygon_soup(pts, polys);
    SMesh torn;
    CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(pts, polys, torn);
    const size_t kept = torn.number_of_faces();
    const size_t left = CGAL::is_triangle_mesh(torn) ? cgal_decimate(torn, kept / 2) : 0;
    std::printf("cgal_sm: orient_polygon_soup %s (%zu vertices for %zu: %s), %zu faces; "
                "edge_collapse to half: %zu faces\n",
                oriented ? "succeeds" : "had to duplicate points", pts.size(), points.size(),
                pts.size() > points.size() ? "tears" : "whole", kept, left);
  }
  // Topoplex, whole complex.
  for (bool preserve : {false, true}) {
    TpxComplex* in = nullptr;
    if (tpx_complex_from_file(path.c_str(), &in) != TPX_STATUS_OK) {
      std::printf("topoplex: %s\n", tpx_message().c_str());
      break;
    }
    size_t tops = 0;
    tpx_complex_top_count(in, 2, &tops);
    TpxComplex* out = nullptr;
    TpxStatus st = tpx_simplify(in, 0.5, preserve, &out);
    size_t left = 0;
    if (st == TPX_STATUS_OK) tpx_complex_top_count(out, 2, &left);
    std::printf("topoplex%s: loads %zu triangles whole; simplify to half: %s%zu triangles\n",
                preserve ? " (preserve topology)" : "", tops, st == TPX_STATUS_OK ? "" : "refused ", left);
    tpx_complex_free(out);
    tpx_complex_free(in);
  }
  return 0;
}

// --file-job: one peer's read + simplify + write, once; the faces left on stdout.
int file_job(const std::string& lib, const std::string& in, const std::string& out) {
  const double ratio = ratio_from_env();
  if (lib == "openmesh") {
    OMesh m;
    // Its OFF reader accepts a '#' comment line as an empty mesh: refuse that.
    if (!OpenMesh::IO::read_mesh(m, in) || m.n_faces() == 0) return std::fprintf(stderr, "openmesh: cannot read %s\n", in.c_str()), 1;
    const size_t left = openmesh_decimate(m, size_t(std::ceil(ratio * double(m.n_faces()))));
    if (!OpenMesh::IO::write_mesh(m, out)) return std::fprintf(stderr, "openmesh: cannot write %s\n", out.c_str()), 1;
    std::printf("openmesh: %zu faces\n", left);
    return 0;
  }
  if (lib == "cgal_sm") {
    SMesh m;
    if (!CGAL::IO::read_polygon_mesh(in, m)) return std::fprintf(stderr, "cgal_sm: cannot read %s\n", in.c_str()), 1;
    const size_t left = cgal_decimate(m, size_t(std::ceil(ratio * double(m.number_of_faces()))));
    if (!CGAL::IO::write_polygon_mesh(out, m)) return std::fprintf(stderr, "cgal_sm: cannot write %s\n", out.c_str()), 1;
    std::printf("cgal_sm: %zu faces\n", left);
    return 0;
  }
  std::fprintf(stderr, "--file-job: unknown library %s (openmesh or cgal_sm)\n", lib.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::strcmp(argv[1], "--peers-on") == 0) return peers_on(argv[2]);
  if (argc == 5 && std::strcmp(argv[1], "--file-job") == 0) return file_job(argv[2], argv[3], argv[4]);
  const std::string path = init(&argc, argv, "FILE.off");
  Soup soup;
  const std::string err = read_off_soup(path, &soup);
  if (!err.empty()) {
    std::fprintf(stderr, "%s\n", err.c_str());
    return 1;
  }
  const double ratio = ratio_from_env();
  const size_t faces = soup.size();
  const size_t target = size_t(std::ceil(ratio * double(faces)));
  add("simplify", "openmesh", Unit::Build, [&](benchmark::State& st) {
    time_simplify(st, faces, [&](std::string* why) -> size_t {
      auto m = openmesh_from_soup(soup, why);
      if (!m) return 0;
      return openmesh_decimate(*m, target);
    });
  });
  add("simplify", "cgal_sm", Unit::Build, [&](benchmark::State& st) {
    time_simplify(st, faces, [&](std::string* why) -> size_t {
      auto m = cgal_from_soup(soup, why);
      if (!m) return 0;
      return cgal_decimate(*m, target);
    });
  });
  for (bool preserve : {false, true}) {
    add("simplify", preserve ? "tpx_preserve" : "tpx", Unit::Build, [&, preserve](benchmark::State& st) {
      time_simplify(st, faces, [&](std::string* why) { return tpx_run(soup, ratio, preserve, why); });
    });
  }
  return run();
}
