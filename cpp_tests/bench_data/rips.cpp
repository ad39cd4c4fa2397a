// Vietoris-Rips complexes (GUDHI Simplex_tree: insert_graph + expansion up to a maximal
// dimension) of real point sets: the maximal simplices at the smallest edge length that gives
// the wanted number of them. The neighbourhood graph comes from a uniform grid instead of
// Gudhi::Rips_complex's all-pairs loop (quadratic in the points), the rest is GUDHI's.
#include "common.hpp"
#include "st_tops.hpp"

#include <gudhi/Simplex_tree.h>
#include <gudhi/graph_simplicial_complex.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <unordered_map>

namespace bench_data {

namespace {
using ST = Gudhi::Simplex_tree<>;

double dist(const Point& a, const Point& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

void build_rips(ST& st, const std::vector<Point>& pts, double r, int max_dim) {
  auto cell = [&](const Point& p, int d) { return static_cast<long>(std::floor(p[d] / r)); };
  auto key = [](long x, long y, long z) {
    return (static_cast<std::uint64_t>(x & 0x1fffff) << 42) |
           (static_cast<std::uint64_t>(y & 0x1fffff) << 21) | static_cast<std::uint64_t>(z & 0x1fffff);
  };
  std::unordered_map<std::uint64_t, std::vector<int>> grid;
  for (std::size_t i = 0; i < pts.size(); ++i)
    grid[key(cell(pts[i], 0), cell(pts[i], 1), cell(pts[i], 2))].push_back(static_cast<int>(i));
  std::vector<std::pair<int, int>> edges;
  std::vector<double> fil;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    long x = cell(pts[i], 0), y = cell(pts[i], 1), z = cell(pts[i], 2);
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dz = -1; dz <= 1; ++dz) {
          auto it = grid.find(key(x + dx, y + dy, z + dz));
          if (it == grid.end()) continue;
          for (int j : it->second)
            if (static_cast<std::size_t>(j) > i) {
              double d = dist(pts[i], pts[static_cast<std::size_t>(j)]);
              if (d <= r) edges.emplace_back(static_cast<int>(i), j), fil.push_back(d);
            }
        }
  }
  Gudhi::Proximity_graph<ST> graph(edges.begin(), edges.end(), fil.begin(), pts.size());
  auto vprop = boost::get(Gudhi::vertex_filtration_t(), graph);
  for (auto v : boost::make_iterator_range(boost::vertices(graph))) boost::put(vprop, v, 0.);
  st.insert_graph(graph);
  st.expansion(max_dim);
}
}  // namespace

Made make_rips(const Env& env, const Spec& spec) {
  std::string src_desc, stem;
  std::vector<Point> pts = spec_points(env, spec, &src_desc, &stem);
  double r = 1.5 * spacing(pts);
  Cut cut;
  for (int round = 0;; ++round) {
    ST st;
    build_rips(st, pts, r, spec.level);
    cut = cut_for_target(st, static_cast<std::size_t>(spec.target), spec.level, false);
    if ((cut.rich && cut.count >= static_cast<std::size_t>(spec.target)) || round == 12 ||
        st.num_simplices() > 20'000'000) {
      cut = cut_for_target(st, static_cast<std::size_t>(spec.target), spec.level, true);
      break;
    }
    r *= 1.25;
  }
  char buf[300];
  std::snprintf(buf, sizeof buf,
                "GUDHI Rips (Simplex_tree expansion) of %zu points, edge length <= %.6g, "
                "maximal dimension %d; maximal simplices%s",
                pts.size(), cut.threshold, spec.level, cut.rich ? "" : " (no eligible cut)");
  return write_complex(env, "rips-" + stem, pts, std::move(cut.tops), "Vietoris-Rips complex",
                       src_desc, buf);
}

}  // namespace bench_data
