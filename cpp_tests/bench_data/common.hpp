// Shared pieces of the dataset maker: where inputs are, what a made dataset records, writers.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace bench_data {

namespace fs = std::filesystem;

struct Env {
  fs::path out;          // datasets are written here
  fs::path cgal_data;    // CGAL's data/ directory (meshes/, points_3/)
  fs::path shared_data;  // ../shared/data (surfaces/...), may be absent
};

// One dataset to make. `target` is the wanted number of top simplices; the file name carries the
// number actually made.
struct Spec {
  std::string id;      // stable key for the cache, e.g. "tet-bunny00-1e6"
  std::string family;  // surf, tet, alpha, rips
  std::string source;  // mesh or point-set name
  long target;         // wanted top simplices
  int level;           // surf: Loop iterations; rips: maximal dimension; others: unused
  bool quick;          // part of --quick
  int sub = -1;        // alpha, rips: the points are the vertices of mesh `source` after `sub`
                       // Loop iterations (-1: `source` is a CGAL point-set file)
};

// What was made: one line of datasets.tsv.
struct Made {
  std::string file;        // name inside Env::out
  std::string source;      // where the input came from
  std::string params;      // how it was made
  std::size_t vertices = 0;
  std::size_t top = 0;     // top simplices
  std::string top_by_dim;  // e.g. "0:12 1:340 2:9000"
  double seconds = 0;      // generation time
};

using Point = std::array<double, 3>;

// The mesh NAME.off: ../shared/data/surfaces first, else CGAL's meshes/.
fs::path find_mesh(const Env& env, const std::string& name);
// CGAL's points_3/FILE.
fs::path find_points(const Env& env, const std::string& file);

// Files appear atomically (an interrupted run leaves no truncated dataset behind): write into
// tmp_path(final), then commit().
fs::path tmp_path(const fs::path& final_path);
struct TmpFile {
  fs::path final_path, tmp;
  std::FILE* f;
};
// tmp_path(final_path) opened for writing; throws when it cannot be.
TmpFile open_tmp(const fs::path& final_path);
// Closes the file (throws when the writes failed) and renames it to its final path.
void commit(TmpFile& t);

// Top simplices (any dimension, vertex ids into `points`) as a .simplices file with `header`
// (lines without '#') as comments. Vertices no simplex uses are dropped and ids renumbered in
// point order. Returns the counts.
Made write_simplices(const Env& env, const std::string& stem, const std::vector<Point>& points,
                     std::vector<std::vector<std::uint32_t>> tops, const std::string& header);
// The maximal simplices `tops` of a complex built on points from `source` (as write_simplices),
// its header "<what> of <source>" and `params`, which Made records with `source`.
Made write_complex(const Env& env, const std::string& stem, const std::vector<Point>& points,
                   std::vector<std::vector<std::uint32_t>> tops, const std::string& what,
                   const std::string& source, const std::string& params);

std::string dims_string(const std::vector<std::size_t>& by_dim);
std::string with_commas(std::size_t n);

// The four families; each returns what it wrote into env.out.
Made make_surf(const Env& env, const Spec& spec);
Made make_tets(const Env& env, const Spec& spec);
Made make_alpha(const Env& env, const Spec& spec);
Made make_rips(const Env& env, const Spec& spec);

// Vertices of NAME.off after `level` Loop subdivisions (alpha complexes of large point clouds).
std::vector<Point> subdivided_vertices(const Env& env, const std::string& name, int level);
// Median nearest-neighbour distance over a sample of ~200 points: the scale of a point set.
double spacing(const std::vector<Point>& pts);
// Points of a CGAL point-set file (.xyz, .ply, .off); normals and other properties ignored.
// The points a spec names (point-set file, or subdivided mesh vertices); `desc` says which.
std::vector<Point> spec_points(const Env& env, const Spec& spec, std::string* desc, std::string* stem);
std::vector<Point> read_point_set(const fs::path& path);

}  // namespace bench_data
