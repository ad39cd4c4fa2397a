/*
 * Non-manifold triangle complexes for half-edge libraries: the complex cut into surface parts
 * that OpenMesh or CGAL's Surface_mesh hold, with the maps back (no peer library needed here;
 * openmesh.hpp and cgal.hpp turn a part into a mesh).
 *
 *   topoplex::SurfaceParts parts = topoplex::SurfaceParts::iqm(c);      // the IQM components
 *   // or SurfaceParts::cut(c, extra_edges): split at every edge not in exactly two triangles
 *   // and at the caller's edges, vertices split per fan
 *   for (const auto &p : parts.parts()) { mesh = part_to_openmesh(p, xyz); run(mesh); ... }
 *   std::vector<double> moved = parts.gather_coords(per_part_xyz, xyz);   // back, per vertex
 *   std::vector<double> normals = parts.gather_faces(per_part_normals, 3, true);  // per triangle
 *
 * A part is a set of the complex's top triangles joined through edges of exactly two of its
 * triangles, over local vertex ids: a vertex gets one local copy per fan of its triangles in the
 * part (so a vertex pinching two surfaces is split), and part_vertex -> original vertex is
 * `original_vertex`. Faces keep their input winding, turned where needed to orient the part
 * consistently (`flipped`: the first face of each connected piece keeps its own); a part that
 * cannot be oriented (a Moebius strip), or whose cut leaves an edge in three of its faces, has
 * `problem` set and the part_to_* functions refuse it. Triangles are numbered as
 * Complex::top_simplices(2) (`original_triangle`); top simplices of lower dimension (wire edges,
 * isolated vertices; tetrahedra and up) are in no part (`left_out`). Costs: iqm() one IQM decomposition
 * (tpx_decomposition_build) plus O(T log T) here; cut() O(T log T) for T top triangles, both
 * with O(T) memory.
 */
#ifndef TOPOPLEX_MANIFOLD_PARTS_HPP
#define TOPOPLEX_MANIFOLD_PARTS_HPP

#include "../topoplex.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstddef>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace topoplex {

struct SurfacePart {
  std::size_t index = 0;                   /* its place in SurfaceParts::parts() */
  std::vector<std::uint32_t> triangles;    /* 3 local vertex ids per face, oriented */
  std::vector<std::uint32_t> original_vertex;   /* local vertex -> vertex of the complex */
  std::vector<std::uint32_t> original_triangle; /* face -> index in Complex::top_simplices(2) */
  std::vector<std::uint8_t> flipped;       /* face turned against its input winding */
  bool orientable = true;
  std::string problem; /* empty when a half-edge mesh holds the part */
  std::size_t face_count() const noexcept { return original_triangle.size(); }
  std::size_t vertex_count() const noexcept { return original_vertex.size(); }
  /* Face f as the adapters' messages name it. */
  std::string face_name(std::size_t f) const {
    return "face " + std::to_string(f) + " of surface part " + std::to_string(index);
  }
};

class SurfaceParts {
 public:
  /* The 2-dimensional IQM components of `c` (Decomposition: the standard decomposition), in its
   * order; components of lower dimension are counted in left_out(). */
  static SurfaceParts iqm(const Complex &c) {
    SurfaceParts out(c);
    const Rows tops = c.dimension() >= 2 ? c.top_simplices(2) : Rows();
    const Decomposition d(c);
    std::vector<std::uint32_t> key(3);
    for (std::size_t i = 0; i < d.size(); ++i) {
      const Decomposition::Component comp = d[i];
      if (comp.dimension != 2) {
        out.left_out_ += comp.tops.size();
        continue;
      }
      SurfacePart p;
      p.index = out.parts_.size();
      p.original_vertex.assign(comp.original_ids, comp.original_ids + comp.local_vertex_count);
      p.triangles.assign(comp.tops.data(), comp.tops.data() + comp.tops.ids_size());
      p.original_triangle.reserve(comp.tops.size());
      for (SimplexView t : comp.tops) {
        for (int k = 0; k < 3; ++k) key[k] = p.original_vertex[t[k]];
        std::sort(key.begin(), key.end());
        p.original_triangle.push_back(std::uint32_t(find_row(tops, key)));
      }
      out.finish(p);
      out.parts_.push_back(std::move(p));
    }
    return out;
  }

  /* `c` cut at every edge that is not in exactly two triangles and at `extra_cuts` (vertex
   * pairs, any order; an edge that is not in the complex is ignored): parts are the classes of
   * triangles joined through the other edges, numbered by their first triangle. */
  static SurfaceParts cut(const Complex &c,
                          const std::vector<std::array<std::uint32_t, 2>> &extra_cuts = {}) {
    SurfaceParts out(c);
    const std::size_t T = c.dimension() >= 2 ? c.top_count(2) : 0;
    for (std::uint32_t p = 0; p <= c.dimension(); ++p)
      if (p != 2) out.left_out_ += c.top_count(p);
    std::vector<std::array<std::uint32_t, 3>> tri(T);
    for (std::size_t t = 0; t < T; ++t) {
      const SimplexView s = c.top_oriented(2, std::uint32_t(t));
      tri[t] = {s[0], s[1], s[2]};
    }
    // (edge key, triangle) for the three edges of each triangle, sorted by edge.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> edges;
    edges.reserve(3 * T);
    for (std::size_t t = 0; t < T; ++t)
      for (int k = 0; k < 3; ++k)
        edges.emplace_back(edge_key(tri[t][k], tri[t][(k + 1) % 3]), std::uint32_t(t));
    std::sort(edges.begin(), edges.end());
    std::vector<std::uint64_t> cuts;
    cuts.reserve(extra_cuts.size());
    for (const auto &e : extra_cuts) cuts.push_back(edge_key(e[0], e[1]));
    std::sort(cuts.begin(), cuts.end());
    // Union-find over triangles (parts) and over corners 3t+k (vertex copies).
    std::vector<std::uint32_t> part(T), corner(3 * T);
    std::iota(part.begin(), part.end(), 0u);
    std::iota(corner.begin(), corner.end(), 0u);
    auto corner_of = [&](std::uint32_t t, std::uint32_t v) {
      return 3 * t + std::uint32_t(tri[t][0] == v ? 0 : tri[t][1] == v ? 1 : 2);
    };
    for (std::size_t a = 0; a < edges.size();) {
      std::size_t b = a;
      while (b < edges.size() && edges[b].first == edges[a].first) ++b;
      const std::uint64_t e = edges[a].first;
      if (b - a == 2 && !std::binary_search(cuts.begin(), cuts.end(), e)) {
        const std::uint32_t t0 = edges[a].second, t1 = edges[a + 1].second;
        unite(part, t0, t1);
        const auto u = std::uint32_t(e >> 32), w = std::uint32_t(e);
        unite(corner, corner_of(t0, u), corner_of(t1, u));
        unite(corner, corner_of(t0, w), corner_of(t1, w));
      }
      a = b;
    }
    // Parts in order of their first triangle; local ids in order of first appearance.
    std::vector<std::uint32_t> part_of(T, UINT32_MAX), local(3 * T, UINT32_MAX);
    for (std::uint32_t t = 0; t < T; ++t) {
      const std::uint32_t r = find(part, t);
      if (part_of[r] == UINT32_MAX) {
        part_of[r] = std::uint32_t(out.parts_.size());
        out.parts_.emplace_back();
        out.parts_.back().index = part_of[r];
      }
      SurfacePart &p = out.parts_[part_of[r]];
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t cr = find(corner, 3 * t + k);
        if (local[cr] == UINT32_MAX) {
          local[cr] = std::uint32_t(p.original_vertex.size());
          p.original_vertex.push_back(tri[t][k]);
        }
        p.triangles.push_back(local[cr]);
      }
      p.original_triangle.push_back(t);
    }
    for (SurfacePart &p : out.parts_) out.finish(p);
    return out;
  }

  const std::vector<SurfacePart> &parts() const noexcept { return parts_; }
  std::size_t size() const noexcept { return parts_.size(); }
  const SurfacePart &operator[](std::size_t i) const { return parts_.at(i); }
  /* Top simplices of dimension below 2 (wire edges, isolated vertices): in no part. */
  std::size_t left_out() const noexcept { return left_out_; }
  std::uint32_t vertex_count() const noexcept { return n_vertices_; }
  std::size_t triangle_count() const noexcept { return n_triangles_; }

  /* Coordinates back on the complex's vertices: per_part[i] holds `dim` numbers per local
   * vertex of part i; a vertex takes its copies' value when they all agree bit for bit, else
   * their mean; a vertex in no part keeps `original` (dim per vertex). O(V + copies). */
  std::vector<double> gather_coords(const std::vector<std::vector<double>> &per_part,
                                    const std::vector<double> &original,
                                    std::size_t dim = 3) const {
    check_parts(per_part.size());
    check_size(original.size(), std::size_t(n_vertices_) * dim, SIZE_MAX, "original coordinates");
    std::vector<double> sum(std::size_t(n_vertices_) * dim, 0.0), out = original;
    std::vector<std::uint32_t> copies(n_vertices_, 0);
    std::vector<std::uint8_t> differ(n_vertices_, 0);
    for (const SurfacePart &p : parts_) {
      const std::vector<double> &x = per_part[p.index];
      check_size(x.size(), p.vertex_count() * dim, p.index, "coordinates");
      for (std::size_t l = 0; l < p.vertex_count(); ++l) {
        const std::uint32_t v = p.original_vertex[l];
        for (std::size_t k = 0; k < dim; ++k) {
          const double y = x[l * dim + k];
          if (copies[v] == 0) {
            out[v * dim + k] = y;
          } else if (out[v * dim + k] != y) {
            differ[v] = 1;
          }
          sum[v * dim + k] += y;
        }
        ++copies[v];
      }
    }
    for (std::size_t v = 0; v < n_vertices_; ++v)
      if (differ[v])
        for (std::size_t k = 0; k < dim; ++k) out[v * dim + k] = sum[v * dim + k] / copies[v];
    return out;
  }

  /* Per-face values back on the complex's triangles (index of Complex::top_simplices(2)):
   * per_part[i] holds k values per face of part i; with negate_flipped, a flipped face's values
   * are negated (normals: then they follow the input winding). Triangles in no part: `fill`. */
  template <class T>
  std::vector<T> gather_faces(const std::vector<std::vector<T>> &per_part, std::size_t k,
                              bool negate_flipped = false, T fill = T()) const {
    check_parts(per_part.size());
    std::vector<T> out(n_triangles_ * k, fill);
    for (const SurfacePart &p : parts_) {
      const std::vector<T> &x = per_part[p.index];
      check_size(x.size(), p.face_count() * k, p.index, "face values");
      for (std::size_t f = 0; f < p.face_count(); ++f)
        for (std::size_t j = 0; j < k; ++j) {
          const T y = x[f * k + j];
          out[std::size_t(p.original_triangle[f]) * k + j] = negate_flipped && p.flipped[f] ? T(-y) : y;
        }
    }
    return out;
  }

  /* Per-triangle values (k per top triangle) as an array for Complex::set_attribute at
   * Location::Listed: listing i gets its triangle's values, other listings `fill`. O(listing). */
  template <class T>
  static std::vector<T> to_listed(const Complex &c, const std::vector<T> &per_triangle,
                                  std::size_t k, T fill = T()) {
    const std::size_t n = c.input_stats().input_simplices;
    const std::size_t first = c.dimension() >= 2 ? c.top_count(0) + c.top_count(1) : 0;
    check_size(per_triangle.size(), (c.dimension() >= 2 ? c.top_count(2) : 0) * k, SIZE_MAX,
               "per-triangle values");
    std::vector<T> out(n * k, fill);
    std::uint32_t buf[16];
    for (std::size_t i = 0; i < n; ++i) {
      std::size_t len = 0;
      std::uint32_t top = 0;
      detail::check(tpx_complex_input_simplex(c.get(), i, buf, 16, &len, &top));
      if (len != 3 || top == UINT32_MAX) continue;
      const std::size_t t = top - first;
      for (std::size_t j = 0; j < k; ++j) out[i * k + j] = per_triangle[t * k + j];
    }
    return out;
  }

 private:
  explicit SurfaceParts(const Complex &c)
      : n_vertices_(c.vertex_count()), n_triangles_(c.dimension() >= 2 ? c.top_count(2) : 0) {}

  static std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t(a) << 32) | b;
  }
  static std::uint32_t find(std::vector<std::uint32_t> &uf, std::uint32_t x) {
    while (uf[x] != x) x = uf[x] = uf[uf[x]];
    return x;
  }
  static void unite(std::vector<std::uint32_t> &uf, std::uint32_t a, std::uint32_t b) {
    a = find(uf, a);
    b = find(uf, b);
    if (a != b) uf[std::max(a, b)] = std::min(a, b);
  }
  static std::size_t find_row(const Rows &rows, const std::vector<std::uint32_t> &key) {
    std::size_t lo = 0, hi = rows.size();
    while (lo < hi) {
      const std::size_t mid = (lo + hi) / 2;
      const SimplexView r = rows[mid];
      if (std::lexicographical_compare(r.begin(), r.end(), key.begin(), key.end())) {
        lo = mid + 1;
      } else {
        hi = mid;
      }
    }
    if (lo == rows.size() || !std::equal(key.begin(), key.end(), rows[lo].begin())) {
      throw Error(TPX_STATUS_INVALID_COMPLEX, "a component triangle is not a top triangle");
    }
    return lo;
  }

  /* Orients p by a walk over edges of exactly two of its faces; records flips and problems. */
  static void finish(SurfacePart &p) {
    const std::size_t F = p.face_count();
    p.flipped.assign(F, 0);
    std::vector<std::pair<std::uint64_t, std::uint32_t>> edges;
    edges.reserve(3 * F);
    for (std::uint32_t f = 0; f < F; ++f)
      for (int k = 0; k < 3; ++k)
        edges.emplace_back(edge_key(p.triangles[3 * f + k], p.triangles[3 * f + (k + 1) % 3]), f);
    std::sort(edges.begin(), edges.end());
    std::vector<std::uint32_t> adj_off(F + 1, 0), adj;  // neighbours across shared edges
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (std::size_t a = 0; a < edges.size();) {
      std::size_t b = a;
      while (b < edges.size() && edges[b].first == edges[a].first) ++b;
      if (b - a > 2 && p.problem.empty()) {
        const std::uint64_t e = edges[a].first;
        p.problem = "surface part " + std::to_string(p.index) + " has the edge {" +
                    std::to_string(p.original_vertex[std::uint32_t(e >> 32)]) + ", " +
                    std::to_string(p.original_vertex[std::uint32_t(e)]) + "} in " +
                    std::to_string(b - a) + " of its faces";
      } else if (b - a == 2) {
        pairs.emplace_back(edges[a].second, edges[a + 1].second);
      }
      a = b;
    }
    for (const auto &q : pairs) {
      ++adj_off[q.first + 1];
      ++adj_off[q.second + 1];
    }
    std::partial_sum(adj_off.begin(), adj_off.end(), adj_off.begin());
    adj.resize(adj_off[F]);
    std::vector<std::uint32_t> fill(adj_off.begin(), adj_off.end() - 1);
    for (const auto &q : pairs) {
      adj[fill[q.first]++] = q.second;
      adj[fill[q.second]++] = q.first;
    }
    // Breadth-first: a neighbour must run the shared edge the other way.
    std::vector<std::uint8_t> seen(F, 0);
    std::vector<std::uint32_t> queue;
    queue.reserve(F);
    auto runs = [&](std::uint32_t f, std::uint32_t u, std::uint32_t w) {
      const std::uint32_t *t = &p.triangles[3 * f];
      for (int k = 0; k < 3; ++k)
        if (t[k] == u && t[(k + 1) % 3] == w) return true;
      return false;
    };
    for (std::uint32_t s = 0; s < F; ++s) {
      if (seen[s]) continue;
      seen[s] = 1;
      queue.assign(1, s);
      for (std::size_t qi = 0; qi < queue.size(); ++qi) {
        const std::uint32_t f = queue[qi];
        const std::uint32_t *t = &p.triangles[3 * f];
        for (std::uint32_t j = adj_off[f]; j < adj_off[f + 1]; ++j) {
          const std::uint32_t g = adj[j];
          // The edge f and g share, as f runs it.
          std::uint32_t u = 0, w = 0;
          for (int k = 0; k < 3; ++k)
            if (runs(g, t[k], t[(k + 1) % 3]) || runs(g, t[(k + 1) % 3], t[k])) {
              u = t[k];
              w = t[(k + 1) % 3];
            }
          const bool consistent = runs(g, w, u);
          if (!seen[g]) {
            seen[g] = 1;
            if (!consistent) {
              std::swap(p.triangles[3 * g + 1], p.triangles[3 * g + 2]);
              p.flipped[g] ^= 1;
            }
            queue.push_back(g);
          } else if (!consistent) {
            p.orientable = false;
          }
        }
      }
    }
    if (!p.orientable && p.problem.empty())
      p.problem = "surface part " + std::to_string(p.index) + " is not orientable";
  }

  void check_parts(std::size_t n) const {
    if (n != parts_.size())
      throw Error(TPX_STATUS_INVALID_ARGUMENT, "got values for " + std::to_string(n) +
                                                   " parts, there are " +
                                                   std::to_string(parts_.size()));
  }
  static void check_size(std::size_t got, std::size_t want, std::size_t part, const char *what) {
    if (got != want)
      throw Error(TPX_STATUS_INVALID_ARGUMENT,
                  std::string(what) +
                      (part == SIZE_MAX ? std::string() : " of surface part " + std::to_string(part)) +
                      ": " + std::to_string(got) + " numbers, expected " + std::to_string(want));
  }

  std::vector<SurfacePart> parts_;
  std::size_t left_out_ = 0;
  std::uint32_t n_vertices_ = 0;
  std::size_t n_triangles_ = 0;
};

}  // namespace topoplex

#endif /* TOPOPLEX_MANIFOLD_PARTS_HPP */
