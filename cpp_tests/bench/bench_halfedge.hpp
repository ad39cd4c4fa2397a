// The halfedge peers of the triangle-mesh programs (bench_surface.cpp, bench_simplify.cpp):
// OpenMesh's TriMesh and CGAL's Surface_mesh, each built from a Soup as an application fills
// one (reserve, add_vertex, add_face in the soup's order and orientation).
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <memory>
#include <string>
#include <vector>

#include "bench_common.hpp"

namespace tpxbench {

using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SMesh = CGAL::Surface_mesh<K::Point_3>;

// The TriMesh of `soup` (3 coordinates per vertex, triangles); null, with the refused triangle
// in *why, if add_face refuses one (non-manifold or inconsistently oriented).
inline std::unique_ptr<OMesh> openmesh_from_soup(const Soup& soup, std::string* why) {
  auto m = std::make_unique<OMesh>();
  const size_t nf = soup.size();
  m->reserve(soup.n_vertices, 3 * nf / 2, nf);
  std::vector<OMesh::VertexHandle> vh(soup.n_vertices);
  for (uint32_t i = 0; i < soup.n_vertices; ++i)
    vh[i] = m->add_vertex(OMesh::Point(float(soup.coords[3 * i]), float(soup.coords[3 * i + 1]),
                                       float(soup.coords[3 * i + 2])));
  for (size_t f = 0; f < nf; ++f) {
    const uint32_t* t = &soup.ids[soup.offsets[f]];
    if (!m->add_face(vh[t[0]], vh[t[1]], vh[t[2]]).is_valid()) {
      *why = "OpenMesh add_face refused triangle #" + std::to_string(f) + " (non-manifold or inconsistent orientation)";
      return nullptr;
    }
  }
  return m;
}

// The Surface_mesh of `soup`, as openmesh_from_soup.
inline std::unique_ptr<SMesh> cgal_from_soup(const Soup& soup, std::string* why) {
  auto m = std::make_unique<SMesh>();
  const size_t nf = soup.size();
  m->reserve(SMesh::size_type(soup.n_vertices), SMesh::size_type(3 * nf / 2), SMesh::size_type(nf));
  std::vector<SMesh::Vertex_index> vh(soup.n_vertices);
  for (uint32_t i = 0; i < soup.n_vertices; ++i)
    vh[i] = m->add_vertex(K::Point_3(soup.coords[3 * i], soup.coords[3 * i + 1], soup.coords[3 * i + 2]));
  for (size_t f = 0; f < nf; ++f) {
    const uint32_t* t = &soup.ids[soup.offsets[f]];
    if (m->add_face(vh[t[0]], vh[t[1]], vh[t[2]]) == SMesh::null_face()) {
      *why = "Surface_mesh add_face refused triangle #" + std::to_string(f) + " (non-manifold or inconsistent orientation)";
      return nullptr;
    }
  }
  return m;
}

}  // namespace tpxbench
