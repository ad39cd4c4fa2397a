// Tetrahedralizations of closed real surfaces by CGAL Mesh_3 (polyhedral domain, sequential).
// The size is steered by the cell_size bound alone: a quick calibration mesh measures how many
// tetrahedra one unit of (bbox diagonal / cell_size)^3 gives, then the real run asks for the
// target with 15% margin. Perturbation and exudation are off: they only improve slivers, which
// the topology does not care about, and they would double the time at 10^6 tetrahedra.
#include "common.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <unordered_map>

namespace bench_data {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
using Domain = CGAL::Polyhedral_mesh_domain_3<Mesh, K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;
namespace params = CGAL::parameters;

// facet_size follows cell_size so the boundary is not refined more than the volume;
// facet_distance is loose for the same reason (the surface is already a fine mesh).
C3t3 mesh_with(const Domain& domain, double cell_size) {
  Criteria criteria(params::facet_angle = 25, params::facet_size = cell_size,
                    params::facet_distance = cell_size / 4, params::cell_radius_edge_ratio = 3,
                    params::cell_size = cell_size);
  return CGAL::make_mesh_3<C3t3>(domain, criteria, params::no_perturb(), params::no_exude(),
                                 params::no_lloyd(), params::no_odt());
}
}  // namespace

Made make_tets(const Env& env, const Spec& spec) {
  fs::path src = find_mesh(env, spec.source);
  Mesh surface;
  if (!CGAL::IO::read_polygon_mesh(src.string(), surface) || !CGAL::is_closed(surface))
    throw std::runtime_error("Mesh_3 needs a closed triangle mesh: " + src.string());
  CGAL::Bbox_3 bb = CGAL::Polygon_mesh_processing::bbox(surface);
  double diag = std::sqrt(std::pow(bb.xmax() - bb.xmin(), 2) + std::pow(bb.ymax() - bb.ymin(), 2) +
                          std::pow(bb.zmax() - bb.zmin(), 2));
  Domain domain(surface);

  // Calibration: tetrahedra per (diag / cell_size)^3.
  double cs0 = diag / 25;
  double per_unit = static_cast<double>(mesh_with(domain, cs0).number_of_cells_in_complex()) /
                    std::pow(diag / cs0, 3);
  double cs = diag / std::cbrt(1.15 * static_cast<double>(spec.target) / per_unit);
  C3t3 c3t3 = mesh_with(domain, cs);
  if (static_cast<double>(c3t3.number_of_cells_in_complex()) < 0.9 * spec.target) {
    // The surface share shrinks with size, so the estimate runs low on big meshes: once more.
    double got = static_cast<double>(c3t3.number_of_cells_in_complex());
    cs *= std::cbrt(got / (1.15 * static_cast<double>(spec.target)));
    c3t3 = mesh_with(domain, cs);
  }

  std::unordered_map<Tr::Vertex_handle, std::size_t> id;
  std::vector<Tr::Vertex_handle> order;
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c)
    for (int i = 0; i < 4; ++i)
      if (id.emplace(c->vertex(i), order.size()).second) order.push_back(c->vertex(i));

  Made made;
  made.top = c3t3.number_of_cells_in_complex();
  made.vertices = order.size();
  made.file = "tet-" + spec.source + "-" + std::to_string(made.top) + ".mesh";
  made.source = src.string();
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "CGAL Mesh_3, cell_size = facet_size = %.4g (bbox diagonal / %.1f), "
                "facet_distance %.4g, facet_angle 25, radius_edge_ratio 3, no optimizers",
                cs, diag / cs, cs / 4);
  made.params = buf;
  made.top_by_dim = "3:" + std::to_string(made.top);

  TmpFile out = open_tmp(env.out / made.file);
  std::FILE* f = out.f;
  std::fprintf(f, "# %s: tetrahedralization of %s\n# %s\nMeshVersionFormatted 1\nDimension 3\n",
               made.file.c_str(), src.filename().c_str(), made.params.c_str());
  std::fprintf(f, "Vertices\n%zu\n", order.size());
  for (auto v : order) {
    const auto& p = v->point().point();
    std::fprintf(f, "%.9g %.9g %.9g 0\n", p.x(), p.y(), p.z());
  }
  std::fprintf(f, "Tetrahedra\n%zu\n", made.top);
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c)
    std::fprintf(f, "%zu %zu %zu %zu 1\n", id[c->vertex(0)] + 1, id[c->vertex(1)] + 1,
                 id[c->vertex(2)] + 1, id[c->vertex(3)] + 1);
  std::fprintf(f, "End\n");
  commit(out);
  return made;
}

}  // namespace bench_data
