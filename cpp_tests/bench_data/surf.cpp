// Real surfaces refined by Loop subdivision (CGAL Subdivision_method_3): each iteration splits
// every triangle in four and keeps the surface's topology, so one closed real mesh gives the
// 10^4 .. 10^6 triangle sizes.
#include "common.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/subdivision_method_3.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>

#include <cstdio>
#include <stdexcept>

namespace bench_data {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;

Mesh load_subdivided(const fs::path& path, int level) {
  Mesh mesh;
  if (!CGAL::IO::read_polygon_mesh(path.string(), mesh) || !CGAL::is_triangle_mesh(mesh))
    throw std::runtime_error("cannot read a triangle mesh from " + path.string());
  if (level > 0)
    CGAL::Subdivision_method_3::Loop_subdivision(
        mesh, CGAL::parameters::number_of_iterations(static_cast<unsigned>(level)));
  return mesh;
}
}  // namespace

std::vector<Point> subdivided_vertices(const Env& env, const std::string& name, int level) {
  Mesh mesh = load_subdivided(find_mesh(env, name), level);
  std::vector<Point> out;
  out.reserve(mesh.number_of_vertices());
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    out.push_back({p.x(), p.y(), p.z()});
  }
  return out;
}

Made make_surf(const Env& env, const Spec& spec) {
  fs::path src = find_mesh(env, spec.source);
  Mesh mesh = load_subdivided(src, spec.level);

  Made made;
  made.file = "surf-" + spec.source + "-" + std::to_string(mesh.number_of_faces()) + ".off";
  made.source = src.string();
  made.params = "Loop subdivision x" + std::to_string(spec.level);
  made.vertices = mesh.number_of_vertices();
  made.top = mesh.number_of_faces();
  made.top_by_dim = "2:" + std::to_string(made.top);

  TmpFile out = open_tmp(env.out / made.file);
  std::FILE* f = out.f;
  std::fprintf(f, "OFF\n# %s: %s, %s (CGAL Subdivision_method_3::Loop_subdivision)\n",
               made.file.c_str(), src.filename().c_str(), made.params.c_str());
  std::fprintf(f, "%zu %zu 0\n", made.vertices, made.top);
  // Surface_mesh indices are dense here (nothing was removed), but map them anyway.
  std::vector<std::size_t> id(mesh.number_of_vertices() + mesh.number_of_removed_vertices());
  std::size_t next = 0;
  for (auto v : mesh.vertices()) {
    id[v.idx()] = next++;
    const auto& p = mesh.point(v);
    std::fprintf(f, "%.9g %.9g %.9g\n", p.x(), p.y(), p.z());
  }
  for (auto face : mesh.faces()) {
    std::fputc('3', f);
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(face), mesh))
      std::fprintf(f, " %zu", id[v.idx()]);
    std::fputc('\n', f);
  }
  commit(out);
  return made;
}

}  // namespace bench_data
