// Maximal simplices of a filtered GUDHI Simplex_tree cut at a threshold chosen for a wanted count.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace bench_data {

struct Cut {
  double threshold = 0;
  std::size_t count = 0;  // maximal simplices at `threshold`
  std::size_t best = 0;   // largest count over the eligible thresholds
  bool rich = false;      // some threshold was eligible (see cut_for_target)
  std::vector<std::vector<std::uint32_t>> tops;
};

// A simplex s of the tree is in the complex at threshold a when filt(s) <= a, and maximal there
// when every cofacet has a larger filtration: min over cofacets of filt > a. So one tree built at
// the largest threshold gives the maximal simplices at every smaller threshold, by a sweep over
// those two values per simplex.
//
// Which threshold: the smallest count >= target alone picks degenerate complexes (at alpha = 0
// every point is an isolated vertex; just above, a graph of wire edges). So a threshold is
// eligible when the complex is "rich": at most 1% of the vertices isolated, wire edges at most
// half of the top simplices, and simplices of dimension `top_dim` at least 10% of them. Picks
// the smallest eligible threshold with at least `target` maximal simplices, else the eligible one
// with most; if none is eligible, the smallest with at least `target`. Fills `tops` only if
// `collect`.
template <class ST>
Cut cut_for_target(ST& st, std::size_t target, int top_dim, bool collect) {
  const double inf = std::numeric_limits<double>::infinity();
  std::size_t n = st.num_simplices();
  std::size_t nv = st.num_vertices();
  std::vector<double> filt(n), mincof(n, inf);
  std::vector<int> dim(n);
  int k = 0;
  for (auto sh : st.complex_simplex_range()) {
    st.assign_key(sh, k);
    filt[static_cast<std::size_t>(k)] = st.filtration(sh);
    dim[static_cast<std::size_t>(k)] = st.dimension(sh);
    ++k;
  }
  for (auto sh : st.complex_simplex_range()) {
    if (st.dimension(sh) == 0) continue;
    double f = st.filtration(sh);
    for (auto b : st.boundary_simplex_range(sh)) {
      double& m = mincof[static_cast<std::size_t>(st.key(b))];
      m = std::min(m, f);
    }
  }
  struct Ev {
    double at;
    int dim;
    int delta;
    bool operator<(const Ev& o) const { return at < o.at; }
  };
  std::vector<Ev> ev;
  ev.reserve(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    ev.push_back({filt[i], dim[i], 1});
    if (mincof[i] != inf) ev.push_back({mincof[i], dim[i], -1});
  }
  std::sort(ev.begin(), ev.end());
  Cut cut;
  std::vector<long> by_dim(static_cast<std::size_t>(std::max(top_dim, 1)) + 1, 0);
  long count = 0;
  bool reached = false, rich_seen = false, any_reached = false;
  double fallback = 0;
  std::size_t fallback_count = 0;
  for (std::size_t i = 0; i < ev.size();) {
    double a = ev[i].at;
    for (; i < ev.size() && ev[i].at == a; ++i) {
      count += ev[i].delta;
      if (static_cast<std::size_t>(ev[i].dim) < by_dim.size())
        by_dim[static_cast<std::size_t>(ev[i].dim)] += ev[i].delta;
    }
    auto c = static_cast<std::size_t>(count);
    bool rich = by_dim[0] * 100 <= static_cast<long>(nv) && by_dim[1] * 2 <= count &&
                by_dim[static_cast<std::size_t>(top_dim)] * 10 >= count;
    if (!any_reached && c >= target) any_reached = true, fallback = a, fallback_count = c;
    if (!rich || reached) continue;
    rich_seen = true;
    if (c > cut.best) cut.best = c, cut.threshold = a, cut.count = c;
    if (c >= target) reached = true, cut.threshold = a, cut.count = c;
  }
  cut.rich = rich_seen;
  if (!rich_seen) cut.threshold = fallback, cut.count = fallback_count;
  if (collect) {
    cut.tops.reserve(cut.count);
    for (auto sh : st.complex_simplex_range()) {
      auto i = static_cast<std::size_t>(st.key(sh));
      if (filt[i] <= cut.threshold && mincof[i] > cut.threshold) {
        std::vector<std::uint32_t> t;
        for (auto v : st.simplex_vertex_range(sh)) t.push_back(static_cast<std::uint32_t>(v));
        cut.tops.push_back(std::move(t));
      }
    }
  }
  return cut;
}

}  // namespace bench_data
