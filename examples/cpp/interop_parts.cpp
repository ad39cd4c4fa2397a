// A non-manifold triangle mesh smoothed with OpenMesh, one manifold part at a time, and put back
// together by Topoplex:
//
//   interop_parts [INPUT] [OUTPUT.vtu]
//
// INPUT is any triangle complex Topoplex reads (.obj, .off, .ply, ...; edges in three triangles,
// vertices pinching two surfaces and dangling edges allowed); without one, a built-in complex
// with all three (also when INPUT is "-"). It is cut into its IQM components (topoplex::SurfaceParts::iqm), each
// orientable part becomes an OpenMesh TriMesh (topoplex::openmesh::part_to_openmesh), OpenMesh's
// Jacobi-Laplace smoother runs on it and OpenMesh computes its face normals; the moved
// coordinates come back onto the original vertices (a vertex shared by several parts takes the
// mean of its copies) and the normals onto the original triangles (in their input winding),
// and Topoplex's writer saves the complex, wire edges and all, with a "normal" attribute on the
// triangles (OUTPUT, default interop_parts.vtu; the input's own attributes are dropped, each
// named on stdout).
//
// Exits 0 only when what the comments below state holds.
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Smoother/JacobiLaplaceSmootherT.hh>
#include <topoplex.hpp>
#include <topoplex/openmesh.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

struct Traits : OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;

// Two tetrahedron surfaces pinched at vertex 3, a fin on the edge {0, 1} (three triangles
// there), a dangling edge {7, 8}.
topoplex::Complex built_in() {
  const std::vector<double> xyz = {0, 0, 0,   1, 0, 0,   0, 1, 0,   0, 0, 1,   0.5, -1, 0.2,
                                   1, 0, 2,   0, 1, 2,   0, 0, 3,   0.5, 0.5, 4};
  const std::vector<std::uint32_t> ids = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2, 0, 1, 4,
                                          3, 6, 5, 3, 5, 7, 5, 6, 7, 3, 7, 6, 7, 8};
  std::vector<std::size_t> offsets;
  for (std::size_t i = 0; i <= 27; i += 3) offsets.push_back(i);
  offsets.push_back(29);
  return topoplex::Complex::from_arrays(9, ids, offsets, xyz, 3);
}

int fail(const std::string &what) {
  std::fprintf(stderr, "interop_parts: %s\n", what.c_str());
  return 1;
}

}  // namespace

int main(int argc, char **argv) {
  try {
    const bool given = argc > 1 && std::string(argv[1]) != "-";
    topoplex::Complex c = given ? topoplex::Complex::from_file(argv[1]) : built_in();
    const std::string output = argc > 2 ? argv[2] : "interop_parts.vtu";
    const std::vector<double> xyz = topoplex::adapt::xyz3(c, "OpenMesh");

    const topoplex::SurfaceParts parts = topoplex::SurfaceParts::iqm(c);
    std::vector<std::vector<double>> moved, normals;
    std::size_t skipped = 0;
    for (const topoplex::SurfacePart &p : parts.parts()) {
      if (!p.problem.empty()) {  // a Moebius strip: no half-edge mesh holds it; left as it is
        ++skipped;
        std::vector<double> same;
        for (std::uint32_t v : p.original_vertex) same.insert(same.end(), &xyz[3 * v], &xyz[3 * v + 3]);
        moved.push_back(same);
        normals.emplace_back(3 * p.face_count(), 0.0);
        continue;
      }
      Mesh m = topoplex::openmesh::part_to_openmesh<Mesh>(p, xyz);
      m.request_face_normals();
      m.request_vertex_normals();
      m.update_normals();
      OpenMesh::Smoother::JacobiLaplaceSmootherT<Mesh> smoother(m);
      smoother.initialize(OpenMesh::Smoother::SmootherT<Mesh>::Tangential_and_Normal,
                          OpenMesh::Smoother::SmootherT<Mesh>::C0);
      smoother.smooth(5);
      m.update_face_normals();
      moved.push_back(topoplex::openmesh::coordinates(m));
      std::vector<double> n;
      for (auto f : m.faces()) n.insert(n.end(), {m.normal(f)[0], m.normal(f)[1], m.normal(f)[2]});
      normals.push_back(n);
    }
    const std::vector<double> smoothed = parts.gather_coords(moved, xyz);
    const std::vector<double> per_triangle = parts.gather_faces(normals, 3, /*negate_flipped=*/true);

    // The output carries this example's "normal" only: the input's own data (OBJ groups, PLY
    // properties, ...) is dropped, saying so, rather than refused by a format that cannot hold it.
    for (const topoplex::AttributeInfo &a : c.attributes()) {
      std::printf("dropping the input's attribute '%s'\n", a.name.c_str());
      c.remove_attribute(a.name);
    }
    c.set_coords(smoothed, 3);
    c.set_attribute<double>("normal", topoplex::Location::Listed, 3,
                            topoplex::SurfaceParts::to_listed(c, per_triangle, 3, 0.0));
    c.write(output);
    std::printf("%zu surface parts (%zu not orientable, left as they were), %zu other top "
                "simplices kept as they were; written to %s\n",
                parts.size(), skipped, parts.left_out(), output.c_str());

    // What the file holds: the same complex (listing and winding), the smoothed coordinates bit
    // for bit, and each triangle's normal of unit length pointing along its own winding's
    // normal (positive dot product with the smoothed triangle's cross product).
    const topoplex::Complex back = topoplex::Complex::from_file(output);
    if (back.input_stats().input_simplices != c.input_stats().input_simplices)
      return fail("the written file lists another number of simplices");
    if (back.coords() != smoothed) return fail("the written coordinates differ");
    const auto normal = back.attribute<double>("normal", topoplex::Location::Listed);
    for (std::uint32_t t = 0; t < back.top_count(2); ++t) {
      const topoplex::SimplexView s = back.top_oriented(2, t);
      const double *n = normal.element(back.listed_index(s.to_vector()));
      const double *a = &smoothed[3 * s[0]], *b = &smoothed[3 * s[1]], *d = &smoothed[3 * s[2]];
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
      const double x[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (len == 0) continue;  // a part no half-edge mesh held
      if (std::fabs(len - 1) > 1e-9 || n[0] * x[0] + n[1] * x[1] + n[2] * x[2] <= 0)
        return fail("triangle " + std::to_string(t) + ": its normal does not follow its winding");
    }
    return 0;
  } catch (const topoplex::Error &e) {
    return fail(e.what());
  }
}
