#include "common.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/read_points.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace bench_data {

fs::path find_mesh(const Env& env, const std::string& name) {
  fs::path shared = env.shared_data / "surfaces" / (name + ".off");
  if (!env.shared_data.empty() && fs::exists(shared)) return shared;
  fs::path cgal = env.cgal_data / "meshes" / (name + ".off");
  if (fs::exists(cgal)) return cgal;
  throw std::runtime_error("mesh " + name + ".off not found in " + shared.string() + " or " +
                           cgal.string());
}

fs::path find_points(const Env& env, const std::string& file) {
  fs::path p = env.cgal_data / "points_3" / file;
  if (!fs::exists(p)) throw std::runtime_error("point set not found: " + p.string());
  return p;
}

fs::path tmp_path(const fs::path& final_path) {
  return final_path.parent_path() / (".tmp-" + final_path.filename().string());
}

TmpFile open_tmp(const fs::path& final_path) {
  TmpFile t{final_path, tmp_path(final_path), nullptr};
  t.f = std::fopen(t.tmp.c_str(), "w");
  if (!t.f) throw std::runtime_error("cannot write " + t.tmp.string());
  return t;
}

void commit(TmpFile& t) {
  if (std::fclose(t.f) != 0) throw std::runtime_error("write failed: " + t.tmp.string());
  fs::rename(t.tmp, t.final_path);
}

std::string with_commas(std::size_t n) {
  std::string s = std::to_string(n);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(static_cast<size_t>(i), ",");
  return s;
}

std::string dims_string(const std::vector<std::size_t>& by_dim) {
  std::string s;
  for (std::size_t d = 0; d < by_dim.size(); ++d) {
    if (by_dim[d] == 0) continue;
    if (!s.empty()) s += ' ';
    s += std::to_string(d) + ":" + std::to_string(by_dim[d]);
  }
  return s;
}

double spacing(const std::vector<Point>& pts) {
  auto dist = [](const Point& a, const Point& b) {
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                     (a[2] - b[2]) * (a[2] - b[2]));
  };
  std::vector<double> nn;
  std::size_t step = std::max<std::size_t>(1, pts.size() / 200);
  for (std::size_t i = 0; i < pts.size(); i += step) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < pts.size(); ++j)
      if (j != i && dist(pts[i], pts[j]) > 0) best = std::min(best, dist(pts[i], pts[j]));
    nn.push_back(best);
  }
  std::nth_element(nn.begin(), nn.begin() + static_cast<long>(nn.size() / 2), nn.end());
  return nn[nn.size() / 2];
}

std::vector<Point> read_point_set(const fs::path& path) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<K::Point_3> pts;
  if (!CGAL::IO::read_points(path.string(), std::back_inserter(pts)) || pts.empty())
    throw std::runtime_error("cannot read points from " + path.string());
  std::vector<Point> out;
  out.reserve(pts.size());
  for (const auto& p : pts) out.push_back({p.x(), p.y(), p.z()});
  return out;
}

std::vector<Point> spec_points(const Env& env, const Spec& spec, std::string* desc,
                               std::string* stem) {
  *stem = spec.source;
  if (auto dot = stem->rfind('.'); dot != std::string::npos) stem->resize(dot);
  if (spec.sub < 0) {
    fs::path src = find_points(env, spec.source);
    *desc = src.string();
    return read_point_set(src);
  }
  *desc = "vertices of " + find_mesh(env, spec.source).string() + " after " +
          std::to_string(spec.sub) + " Loop subdivisions";
  *stem += "L" + std::to_string(spec.sub);
  return subdivided_vertices(env, spec.source, spec.sub);
}

Made write_simplices(const Env& env, const std::string& stem, const std::vector<Point>& points,
                     std::vector<std::vector<std::uint32_t>> tops, const std::string& header) {
  std::vector<std::uint32_t> renum(points.size(), UINT32_MAX);
  for (auto& t : tops) {
    std::sort(t.begin(), t.end());
    for (auto v : t) renum[v] = 0;
  }
  std::uint32_t next = 0;
  for (auto& r : renum)
    if (r == 0) r = next++;
  // Lexicographic order of the renumbered simplices, so that files are reproducible.
  for (auto& t : tops)
    for (auto& v : t) v = renum[v];
  std::sort(tops.begin(), tops.end());

  Made made;
  made.file = stem + "-" + std::to_string(tops.size()) + ".simplices";
  made.vertices = next;
  made.top = tops.size();
  std::vector<std::size_t> by_dim;
  for (const auto& t : tops) {
    if (by_dim.size() < t.size()) by_dim.resize(t.size());
    ++by_dim[t.size() - 1];
  }
  made.top_by_dim = dims_string(by_dim);

  TmpFile out = open_tmp(env.out / made.file);
  {
    std::FILE* f = out.f;
    std::size_t start = 0;
    while (start < header.size()) {
      std::size_t end = header.find('\n', start);
      if (end == std::string::npos) end = header.size();
      std::fprintf(f, "# %s\n", header.substr(start, end - start).c_str());
      start = end + 1;
    }
    std::fprintf(f, "# %zu vertices, %zu top simplices (by dimension %s)\n", made.vertices,
                 made.top, made.top_by_dim.c_str());
    for (std::size_t i = 0; i < points.size(); ++i)
      if (renum[i] != UINT32_MAX)
        std::fprintf(f, "v %.9g %.9g %.9g\n", points[i][0], points[i][1], points[i][2]);
    for (const auto& t : tops) {
      std::fputc('s', f);
      for (auto v : t) std::fprintf(f, " %u", v);
      std::fputc('\n', f);
    }
  }
  commit(out);
  return made;
}

Made write_complex(const Env& env, const std::string& stem, const std::vector<Point>& points,
                   std::vector<std::vector<std::uint32_t>> tops, const std::string& what,
                   const std::string& source, const std::string& params) {
  Made made =
      write_simplices(env, stem, points, std::move(tops), what + " of " + source + "\n" + params);
  made.source = source;
  made.params = params;
  return made;
}

}  // namespace bench_data
