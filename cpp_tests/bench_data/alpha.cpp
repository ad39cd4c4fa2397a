// Alpha complexes (GUDHI Alpha_complex_3d over CGAL's alpha shapes) of real point sets: the
// maximal simplices at the smallest alpha^2 that gives the wanted number of them. Below the full
// Delaunay tetrahedralization an alpha complex mixes tetrahedra, dangling triangles, wire edges
// and isolated vertices: a non-manifold 3-complex.
#include "common.hpp"
#include "st_tops.hpp"

#include <gudhi/Alpha_complex_3d.h>
#include <gudhi/Simplex_tree.h>

#include <cstdio>
#include <limits>
#include <optional>

namespace bench_data {

Made make_alpha(const Env& env, const Spec& spec) {
  std::string src_desc, stem;
  std::vector<Point> pts = spec_points(env, spec, &src_desc, &stem);
  using Alpha = Gudhi::alpha_complex::Alpha_complex_3d<Gudhi::alpha_complex::complexity::FAST,
                                                       false, false>;
  std::vector<Alpha::Bare_point_3> bare;
  bare.reserve(pts.size());
  for (const auto& p : pts) bare.emplace_back(p[0], p[1], p[2]);
  Alpha alpha(bare);
  // The eligible cut lies a few point spacings up; bounding alpha keeps the tree (and the time)
  // far below the full Delaunay complex's. Widened until the target is reached or unbounded.
  double s = spacing(pts);
  double bound = 16 * s * s;
  std::optional<Gudhi::Simplex_tree<>> st;
  Cut cut;
  for (int round = 0;; ++round) {
    st.emplace();
    if (round == 4) bound = std::numeric_limits<double>::infinity();
    alpha.create_complex(*st, bound);
    cut = cut_for_target(*st, static_cast<std::size_t>(spec.target), 3, false);
    if ((cut.rich && cut.count >= static_cast<std::size_t>(spec.target)) || round == 4) break;
    bound *= 16;
  }
  cut = cut_for_target(*st, static_cast<std::size_t>(spec.target), 3, true);

  // Simplex-tree vertex ids are GUDHI's (duplicate points merged); coordinates from it.
  std::vector<Point> vpts(st->num_vertices());
  for (std::size_t v = 0; v < vpts.size(); ++v) {
    const auto& p = alpha.get_point(v);
    vpts[v] = {p.x(), p.y(), p.z()};
  }
  char buf[300];
  std::snprintf(buf, sizeof buf,
                "GUDHI Alpha_complex_3d (FAST) of %zu points, alpha^2 <= %.6g; maximal "
                "simplices%s",
                pts.size(), cut.threshold, cut.rich ? "" : " (no eligible cut)");
  return write_complex(env, "alpha-" + stem, vpts, std::move(cut.tops), "alpha complex", src_desc,
                       buf);
}

}  // namespace bench_data
