// A Vietoris-Rips complex built by GUDHI, handed to Topoplex for co-face queries:
//
//   interop_gudhi_rips [N_POINTS] [THRESHOLD] [MAX_DIM]
//
// N_POINTS points on a trefoil knot (default 200), GUDHI's Rips complex of them up to MAX_DIM
// (default 3) at THRESHOLD (default 0.9) in a Simplex_tree; topoplex::gudhi::to_complex copies
// every simplex with its filtration value (the "gudhi:filtration" attribute) and the points as
// coordinates; the live complex (Kind::IASTAR) then answers the co-faces of every vertex and edge.
// Exits 0 only when Topoplex's co-faces of each vertex (edges, triangles) and of each edge
// (triangles) are GUDHI's, and the filtration value read back through Complex::listed_index is
// the tree's for every one of them.
#include <gudhi/Rips_complex.h>
#include <gudhi/Simplex_tree.h>
#include <gudhi/distance_functions.h>
#include <topoplex.hpp>
#include <topoplex/gudhi.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using ST = Gudhi::Simplex_tree<>;

std::vector<std::uint32_t> sorted_ids(ST &st, ST::Simplex_handle sh) {
  std::vector<std::uint32_t> out;
  for (auto v : st.simplex_vertex_range(sh)) out.push_back(std::uint32_t(v));
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

int main(int argc, char **argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 200;
  const double threshold = argc > 2 ? std::atof(argv[2]) : 0.9;
  const int max_dim = argc > 3 ? std::atoi(argv[3]) : 3;
  std::vector<std::array<double, 3>> points;
  std::vector<double> xyz;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    points.push_back({std::sin(t) + 2 * std::sin(2 * t), std::cos(t) - 2 * std::cos(2 * t),
                      -std::sin(3 * t)});
    xyz.insert(xyz.end(), points.back().begin(), points.back().end());
  }
  Gudhi::rips_complex::Rips_complex<double> rips(points, threshold, Gudhi::Euclidean_distance());
  ST st;
  rips.create_complex(st, max_dim);

  try {
    const topoplex::Complex c = topoplex::gudhi::to_complex(st, xyz, 3);
    const topoplex::Structure s(c, topoplex::Kind::IASTAR);
    const auto filtration =
        c.attribute<double>(topoplex::gudhi::filtration_attribute, topoplex::Location::Listed);
    std::printf("Rips complex of %d points at %g: %zu simplices, dimension %d; Topoplex: %zu "
                "vertices, %zu edges, %zu triangles\n",
                n, threshold, st.num_simplices(), st.dimension(), s.count(0), s.count(1),
                s.count(2));
    std::size_t checked = 0;
    auto same_cofaces = [&](const std::vector<std::uint32_t> &sigma, int codim) {
      std::vector<std::vector<std::uint32_t>> want, got;
      for (auto sh : st.cofaces_simplex_range(st.find(sigma), codim)) {
        want.push_back(sorted_ids(st, sh));
        const std::size_t i = c.listed_index(want.back());
        if (filtration[i] != st.filtration(sh)) return false;  // the value came along
      }
      const std::uint32_t q = std::uint32_t(sigma.size() - 1 + codim);
      if (q <= c.dimension())
        for (auto row : s.relation(sigma, q)) got.push_back(row.to_vector());
      std::sort(want.begin(), want.end());
      ++checked;
      return got == want;  // relation() answers in lexicographic order
    };
    for (std::uint32_t v = 0; v < c.vertex_count(); ++v) {
      if (!same_cofaces({v}, 1) || !same_cofaces({v}, 2)) {
        std::fprintf(stderr, "interop_gudhi_rips: co-faces of vertex %u differ\n", v);
        return 1;
      }
    }
    for (auto row : s.simplices(1)) {
      if (!same_cofaces(row.to_vector(), 1)) {
        std::fprintf(stderr, "interop_gudhi_rips: co-faces of edge {%u, %u} differ\n", row[0], row[1]);
        return 1;
      }
    }
    std::printf("%zu co-face queries: Topoplex's answers and filtration values are GUDHI's\n",
                checked);
    return 0;
  } catch (const topoplex::Error &e) {
    std::fprintf(stderr, "interop_gudhi_rips: %s\n", e.what());
    return 1;
  }
}
