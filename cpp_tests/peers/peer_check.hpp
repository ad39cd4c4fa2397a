// Shared machinery of the peer tests: a peer (OpenMesh, CGAL, GUDHI) describes a complex in its
// own vertex numbering and answers relations R_{p,q} for every p-simplex; `check_all_kinds`
// hands the complex to Topoplex through the C ABI, builds every structure kind that accepts it,
// and compares each relation as sets, walking whole relations with `tpx_relation_table`.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace peers {

using Ids = std::vector<uint32_t>;

// A complex in the peer's vertex numbering (ids 0..n_vertices-1, as the peer enumerates them).
struct PeerComplex {
  std::string name;
  uint32_t n_vertices = 0;
  size_t coord_dim = 3;
  std::vector<double> coords;  // n_vertices * coord_dim values, or empty
  std::vector<uint32_t> ids;
  std::vector<size_t> offsets{0};
  // Top simplex counts per dimension as the peer sees them (index p); empty = not checked.
  // When given, its size - 1 is also the expected dimension.
  std::vector<size_t> expected_tops;

  void add(const Ids& simplex) {
    ids.insert(ids.end(), simplex.begin(), simplex.end());
    offsets.push_back(ids.size());
  }
  size_t simplex_count() const { return offsets.size() - 1; }
};

// The peer's answer to R_{p,q} for every p-simplex of the complex. The p-simplices answered
// must be exactly the complex's p-simplices: the comparison checks that set too.
class Relation {
 public:
  Relation(uint32_t p, uint32_t q, std::string name) : p_(p), q_(q), name_(std::move(name)) {}

  // Records R_{p,q}(sigma); sigma and rows in any vertex order, rows in any order.
  // A peer that lists a row twice or answers a simplex twice is reported as a failure: the
  // harness would otherwise hide a misreading of the peer's API.
  void add(Ids sigma, std::vector<Ids> rows);

  uint32_t p() const { return p_; }
  uint32_t q() const { return q_; }
  const std::string& name() const { return name_; }

  struct Entry {
    Ids sigma;                  // ascending
    std::vector<uint32_t> rows; // flat rows of q+1 ascending ids, lexicographic order
  };
  // Entries sorted by sigma (lexicographic): the order of tpx_structure_simplices.
  const std::vector<Entry>& entries();

 private:
  uint32_t p_, q_;
  std::string name_;
  std::vector<Entry> entries_;
  bool sorted_ = false;
};

// The relations R_{p,q}, p, q <= dim, that add_relations appended: R(p, q) (by index, so it
// stays valid while `rels` grows).
struct RelationGrid {
  std::vector<Relation>& rels;
  size_t first;
  uint32_t dim;
  Relation& operator()(uint32_t p, uint32_t q) const { return rels[first + p * (dim + 1) + q]; }
  // R_{p,0}, R_{p,1}, R_{p,2} of sigma at once (a surface peer): its vertices, edges, faces.
  void add_rows(uint32_t p, const Ids& sigma, std::vector<Ids> verts, std::vector<Ids> edges,
                std::vector<Ids> faces) const {
    (*this)(p, 0).add(sigma, std::move(verts));
    (*this)(p, 1).add(sigma, std::move(edges));
    (*this)(p, 2).add(sigma, std::move(faces));
  }
};

// Appends R_{p,q} for every p, q <= dim to `rels`, p major, each named "<peer> <what>": `what`
// from `names` in that order, or "p->q" when `names` is empty.
RelationGrid add_relations(std::vector<Relation>& rels, const std::string& peer, uint32_t dim,
                           const std::vector<std::string>& names = {});

struct KindsReport {
  std::vector<std::string> checked;  // kind names
  std::vector<std::string> skipped;  // "name: status: message"
};

// Builds the complex through tpx_complex_from_arrays, then for each kind 0..8 builds the
// structure (skipping NOT_IMPLEMENTED and UNSUPPORTED_COMPLEX, except for the IG, which must
// always build) and compares every relation. Reports failures through GoogleTest and prints
// which kinds were checked.
KindsReport check_all_kinds(const PeerComplex& complex, std::vector<Relation>& relations);

// Path of a CGAL sample data file (relative to CGAL's data/ directory, e.g.
// "meshes/elephant.off"), looked up in $TOPOPLEX_CGAL_DATA, then in the directory CMake
// extracted libcgal-demo's data into. Empty when absent.
std::string data_file(const std::string& relative);

// Path of a file of the project's shared real-data folder (relative to it, e.g.
// "nonmanifold/truck.obj"), looked up in $TOPOPLEX_SHARED_DATA, then in ../shared/data next to
// the repository. Empty when absent.
std::string shared_data_file(const std::string& relative);

// The first three numbers of every non-empty, non-comment line of an .xyz file (normals and
// other trailing columns ignored).
std::vector<double> read_xyz(const std::string& path);

// Vertex and face counts from an OFF header (to detect a reader that added or dropped some).
bool off_counts(const std::string& path, size_t* vertices, size_t* faces);

// All (q+1)-subsets of sorted `sigma`, as rows (the combinatorial boundary R_{p,q}, q < p).
std::vector<Ids> faces_of(const Ids& sigma, uint32_t q);

// A GoogleTest parameter name from a data path: "meshes/elephant-with-holes.off" ->
// "elephant_with_holes".
std::string test_name_of(const std::string& path);

}  // namespace peers

// Skips the current test when a sample data file is missing.
#define PEERS_REQUIRE_DATA(var, relative)                                                 \
  const std::string var = ::peers::data_file(relative);                                 \
  if (var.empty())                                                                       \
  GTEST_SKIP() << "sample data file " << (relative)                                      \
               << " not found (install libcgal-demo or set TOPOPLEX_CGAL_DATA)"
