// Fixtures and brute-force oracles shared by the adapter tests (each test executable includes it).
#pragma once

#include <topoplex.hpp>
#include <topoplex/manifold_parts.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "../complex_of.hpp"
#include "../find_data.hpp"

namespace fixtures {

using Tri = std::array<std::uint32_t, 3>;

// A file of the shared real-data folder, or "" (the test then skips).
inline std::string shared(const std::string &relative) {
  return topoplex_tests::find_data_file("TOPOPLEX_SHARED_DATA", TOPOPLEX_ADAPTERS_SHARED_DATA_DIR,
                                        relative);
}

// Calls `run(name, path)` for each named file of the shared real-data folder that is present;
// returns how many ran (0: the folder is absent, which the caller says or skips on).
template <class Run>
int for_each_shared(std::initializer_list<const char *> names, Run run) {
  int ran = 0;
  for (const char *name : names) {
    const std::string path = shared(name);
    if (path.empty()) continue;
    ++ran;
    run(name, path);
  }
  return ran;
}

// Runs `convert`, which must throw topoplex::Refused with a message naming `needle`; `what`
// says what went through if it did not.
template <class Convert>
void expect_refused_naming(Convert convert, const std::string &needle, const std::string &what) {
  try {
    convert();
    ADD_FAILURE() << what;
  } catch (const topoplex::Refused &e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

// A deterministic pseudo-random double in [0, 1) (splitmix64).
inline double unit(std::uint64_t &s) {
  std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

using topoplex_tests::complex_of;

// The non-manifold fixture: a closed tetrahedron surface A (0 1 2 3) with a fin triangle on its
// edge {0, 1} (that edge is in three triangles), a second closed tetrahedron surface B
// (3 5 6 7) pinching A at vertex 3 with one face wound against the others (a part must turn
// it), a dangling edge {7, 8}, and an isolated vertex 9.
// Coordinates perturbed so that no two faces are parallel. Expected surface parts: A, the fin,
// B; left out: the wire edge and the isolated vertex.
struct NonManifold {
  std::vector<std::vector<std::uint32_t>> simplices{
      {0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2},  // A, outward
      {0, 1, 4},                                   // the fin on edge {0, 1}
      {3, 6, 5}, {3, 5, 7}, {5, 7, 6}, {3, 7, 6},  // B, pinched at 3; {5, 7, 6} wound inward
      {7, 8},                                      // dangling edge
      {9}};
  std::vector<double> xyz;
  NonManifold() {
    const double base[10][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, -1, 0.2},
                                {1, 0, 2}, {0, 1, 2}, {0, 0, 3}, {0.5, 0.5, 4}, {5, 5, 5}};
    std::uint64_t s = 7;
    for (auto &p : base)
      for (double x : p) xyz.push_back(x + 0.05 * unit(s));
  }
  topoplex::Complex complex() const { return complex_of(10, simplices, xyz); }
};

// Two triangles listed with an edge of theirs between them and one repeated, each listing with
// its own label (10 + listing index): the faces a mesh gets are listings 0 and 2 (the edge and
// the repeat have no face of their own).
inline topoplex::Complex listed_beside() {
  topoplex::Complex c = topoplex::Complex::from_arrays(
      4, {0, 1, 2, 1, 2, 1, 3, 2, 0, 1, 2}, {0, 3, 5, 8, 11},
      {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0.5}, 3);
  c.set_attribute<std::int32_t>("label", topoplex::Location::Listed, 1,
                                std::vector<std::int32_t>{10, 11, 12, 13});
  return c;
}

// listed_beside() through an adapter, `to_mesh(c, dropped)`: refused when nothing may be left
// behind (dropped null), else the mesh, with "label" named as left behind (listings that make
// no face hold values of it).
template <class ToMesh>
auto listed_beside_through(ToMesh to_mesh) {
  const topoplex::Complex c = listed_beside();
  EXPECT_THROW(to_mesh(c, nullptr), topoplex::Refused);
  std::vector<topoplex::Dropped> dropped;
  auto m = to_mesh(c, &dropped);
  EXPECT_EQ(dropped.size(), 1u);
  for (const auto &d : dropped) EXPECT_EQ(d.name, "label");
  return m;
}

inline Tri sorted(Tri t) {
  std::sort(t.begin(), t.end());
  return t;
}

// Every part's faces mapped back through original_vertex are the complex's top triangles, each
// exactly once, with the input winding unless `flipped` (then reversed); each part is
// consistently oriented (no shared edge run the same way twice). Returns the partition as sets
// of top-triangle indices.
inline std::set<std::set<std::uint32_t>> check_parts(const topoplex::Complex &c,
                                                     const topoplex::SurfaceParts &parts) {
  const std::size_t T = c.dimension() >= 2 ? c.top_count(2) : 0;
  std::vector<int> seen(T, 0);
  std::set<std::set<std::uint32_t>> partition;
  for (const auto &p : parts.parts()) {
    std::set<std::uint32_t> mine;
    std::set<std::pair<std::uint32_t, std::uint32_t>> runs;
    for (std::size_t f = 0; f < p.face_count(); ++f) {
      const std::uint32_t t = p.original_triangle[f];
      EXPECT_LT(t, T);
      ++seen[t];
      mine.insert(t);
      const topoplex::SimplexView given = c.top_oriented(2, t);
      Tri back{p.original_vertex[p.triangles[3 * f]], p.original_vertex[p.triangles[3 * f + 1]],
               p.original_vertex[p.triangles[3 * f + 2]]};
      Tri want{given[0], given[1], given[2]};
      if (p.flipped[f]) std::swap(want[1], want[2]);
      // Same cyclic order: some rotation of `back` is `want`.
      bool same = false;
      for (int r = 0; r < 3; ++r)
        same |= back[r] == want[0] && back[(r + 1) % 3] == want[1] && back[(r + 2) % 3] == want[2];
      EXPECT_TRUE(same) << "part " << p.index << " face " << f;
      for (int k = 0; k < 3 && p.orientable; ++k) {
        EXPECT_TRUE(runs.emplace(p.triangles[3 * f + k], p.triangles[3 * f + (k + 1) % 3]).second)
              << "part " << p.index << " runs an edge twice the same way";
      }
    }
    partition.insert(mine);
  }
  for (std::size_t t = 0; t < T; ++t) EXPECT_EQ(seen[t], 1) << "triangle " << t;
  return partition;
}

// The unit normal of triangle (a, b, c) by its winding, computed here.
inline std::array<double, 3> unit_normal(const std::vector<double> &xyz, const std::uint32_t *t) {
  const double *a = &xyz[3 * t[0]], *b = &xyz[3 * t[1]], *c = &xyz[3 * t[2]];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  std::array<double, 3> n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                          u[0] * v[1] - u[1] * v[0]};
  const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (double &x : n) x /= l;
  return n;
}

inline double area(const std::vector<double> &xyz, const std::uint32_t *t) {
  const double *a = &xyz[3 * t[0]], *b = &xyz[3 * t[1]], *c = &xyz[3 * t[2]];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

// The umbrella (mean of the one-ring) of every vertex, computed per part from the complex's own
// triangles: a vertex of several parts gets the mean of its per-part umbrellas (agreeing copies:
// that value), a vertex in no part keeps its coordinates. The oracle for a smoothing step run
// per part and gathered back.
inline std::vector<double> umbrella_oracle(const topoplex::Complex &c,
                                           const std::set<std::set<std::uint32_t>> &partition) {
  const std::vector<double> xyz = c.coords();
  std::vector<std::vector<std::array<double, 3>>> per_vertex(c.vertex_count());
  for (const auto &part : partition) {
    std::map<std::uint32_t, std::set<std::uint32_t>> ring;
    for (std::uint32_t t : part) {
      const topoplex::SimplexView s = c.top_oriented(2, t);
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
          if (j != k) ring[s[k]].insert(s[j]);
    }
    for (const auto &r : ring) {
      std::array<double, 3> m{0, 0, 0};
      for (std::uint32_t u : r.second)
        for (int k = 0; k < 3; ++k) m[k] += xyz[3 * u + k];
      for (double &x : m) x /= double(r.second.size());
      per_vertex[r.first].push_back(m);
    }
  }
  std::vector<double> out = xyz;
  for (std::size_t v = 0; v < per_vertex.size(); ++v) {
    if (per_vertex[v].empty()) continue;
    for (int k = 0; k < 3; ++k) {
      double s = 0;
      for (const auto &m : per_vertex[v]) s += m[k];
      out[3 * v + k] = s / double(per_vertex[v].size());
    }
  }
  return out;
}

// The listing of a complex: every listed simplex as given.
inline std::vector<std::vector<std::uint32_t>> listing(const topoplex::Complex &c) {
  std::vector<std::vector<std::uint32_t>> out;
  for (std::size_t i = 0; i < c.input_stats().input_simplices; ++i) {
    std::uint32_t top = 0;
    out.push_back(c.input_simplex(i, top));
  }
  return out;
}

}  // namespace fixtures
