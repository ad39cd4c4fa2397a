/*
 * Topoplex C++17 wrapper: header-only, over the C ABI in topoplex.h.
 *
 *   topoplex::Complex c = topoplex::Complex::from_file("mesh.off");
 *   c.write("mesh.mesh");                                    // format from the extension
 *   topoplex::Structure s(c, topoplex::Kind::IG);
 *   for (auto tri : s.relation({2, 3}, 2)) { tri[0]; tri.size(); ... }   // rows of q+1 ids
 *   topoplex::RelationTable t = s.relation_table(0, 1);
 *   for (auto edges_of_v : t) for (auto edge : edges_of_v) ...
 *
 * Every failing call throws topoplex::Error (status + the library's message). Handles are
 * move-only RAII owners. A const Structure may be queried from many threads at once.
 */
#ifndef TOPOPLEX_HPP
#define TOPOPLEX_HPP

#include "topoplex.h"

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace topoplex {

/* The structure kinds (values of TPX_KIND_*). */
enum class Kind : std::uint32_t {
  IG = TPX_KIND_IG,
  SIG = TPX_KIND_SIG,
  IA = TPX_KIND_IA,
  IQM = TPX_KIND_IQM,
  NMIA = TPX_KIND_NMIA,
  TS = TPX_KIND_TS,
  PE = TPX_KIND_PE,
  LE = TPX_KIND_LE,
  DE = TPX_KIND_DE,
};

/* Output formats (values of TPX_FORMAT_*); FromExtension picks one from the file name. */
enum class Format : std::uint32_t {
  FromExtension = TPX_FORMAT_FROM_EXTENSION,
  OFF = TPX_FORMAT_OFF,
  OBJ = TPX_FORMAT_OBJ,
  MEDIT = TPX_FORMAT_MEDIT,
  Simplices = TPX_FORMAT_SIMPLICES,
  PLY = TPX_FORMAT_PLY,
  PLYBinary = TPX_FORMAT_PLY_BINARY,
  STL = TPX_FORMAT_STL,
  STLBinary = TPX_FORMAT_STL_BINARY,
  VTK = TPX_FORMAT_VTK,
  VTKBinary = TPX_FORMAT_VTK_BINARY,
  MSH = TPX_FORMAT_MSH,
  MSHBinary = TPX_FORMAT_MSH_BINARY,
  MSH2 = TPX_FORMAT_MSH2,
  MSH2Binary = TPX_FORMAT_MSH2_BINARY,
  VTU = TPX_FORMAT_VTU,
};

/* A failed call: the TpxStatus and tpx_last_error_message() at the time of failure. */
class Error : public std::runtime_error {
 public:
  Error(TpxStatus status, const std::string &message)
      : std::runtime_error(message), status_(status) {}
  TpxStatus status() const noexcept { return status_; }

 private:
  TpxStatus status_;
};

namespace detail {
inline void check(TpxStatus status) {
  if (status != TPX_STATUS_OK) {
    throw Error(status, tpx_last_error_message());
  }
}
}  // namespace detail

/* A non-owning view of one simplex: its ascending vertex ids. */
class SimplexView {
 public:
  SimplexView() = default;
  SimplexView(const std::uint32_t *ids, std::size_t size) : ids_(ids), size_(size) {}
  const std::uint32_t *begin() const noexcept { return ids_; }
  const std::uint32_t *end() const noexcept { return ids_ + size_; }
  const std::uint32_t *data() const noexcept { return ids_; }
  std::size_t size() const noexcept { return size_; }
  std::uint32_t operator[](std::size_t i) const noexcept { return ids_[i]; }
  std::vector<std::uint32_t> to_vector() const { return {begin(), end()}; }

 private:
  const std::uint32_t *ids_ = nullptr;
  std::size_t size_ = 0;
};

/* A non-owning view of consecutive rows of `arity` ids (a list of simplices). */
class RowsView {
 public:
  class iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = SimplexView;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = SimplexView;
    iterator() = default;
    iterator(const std::uint32_t *p, std::size_t arity) : p_(p), arity_(arity) {}
    SimplexView operator*() const noexcept { return SimplexView(p_, arity_); }
    iterator &operator++() noexcept {
      p_ += arity_;
      return *this;
    }
    iterator operator++(int) noexcept {
      iterator old = *this;
      ++*this;
      return old;
    }
    bool operator==(const iterator &o) const noexcept { return p_ == o.p_; }
    bool operator!=(const iterator &o) const noexcept { return p_ != o.p_; }

   private:
    const std::uint32_t *p_ = nullptr;
    std::size_t arity_ = 1;
  };

  RowsView() = default;
  RowsView(const std::uint32_t *ids, std::size_t len, std::size_t arity)
      : ids_(ids), len_(len), arity_(arity) {}
  /* Number of simplices. */
  std::size_t size() const noexcept { return arity_ == 0 ? 0 : len_ / arity_; }
  bool empty() const noexcept { return len_ == 0; }
  std::size_t arity() const noexcept { return arity_; }
  SimplexView operator[](std::size_t i) const noexcept {
    return SimplexView(ids_ + i * arity_, arity_);
  }
  iterator begin() const noexcept { return iterator(ids_, arity_); }
  iterator end() const noexcept { return iterator(ids_ + len_, arity_); }
  /* The ids of all rows, concatenated. */
  const std::uint32_t *data() const noexcept { return ids_; }
  std::size_t ids_size() const noexcept { return len_; }

 private:
  const std::uint32_t *ids_ = nullptr;
  std::size_t len_ = 0;
  std::size_t arity_ = 1;
};

/* An owned list of simplices (the answer of one query), viewed as rows. */
class Rows {
 public:
  Rows() = default;
  Rows(std::vector<std::uint32_t> ids, std::size_t arity) : ids_(std::move(ids)), arity_(arity) {}
  RowsView view() const noexcept { return RowsView(ids_.data(), ids_.size(), arity_); }
  std::size_t size() const noexcept { return view().size(); }
  bool empty() const noexcept { return ids_.empty(); }
  std::size_t arity() const noexcept { return arity_; }
  SimplexView operator[](std::size_t i) const noexcept { return view()[i]; }
  RowsView::iterator begin() const noexcept { return view().begin(); }
  RowsView::iterator end() const noexcept { return view().end(); }
  const std::vector<std::uint32_t> &ids() const noexcept { return ids_; }

 private:
  std::vector<std::uint32_t> ids_;
  std::size_t arity_ = 1;
};

/* A normalised simplicial complex (owns a TpxComplex). */
class Live;

class Complex {
 public:
  /* Simplices as lists of vertex ids in any order over the vertices 0 .. n_vertices-1. */
  static Complex from_simplices(std::uint32_t n_vertices,
                                const std::vector<std::vector<std::uint32_t>> &simplices) {
    std::vector<std::uint32_t> ids;
    std::vector<std::size_t> offsets{0};
    for (const auto &s : simplices) {
      ids.insert(ids.end(), s.begin(), s.end());
      offsets.push_back(ids.size());
    }
    return from_arrays(n_vertices, ids, offsets);
  }

  /* Simplex i is ids[offsets[i] .. offsets[i+1]]; coords empty or n_vertices * coord_dim. */
  static Complex from_arrays(std::uint32_t n_vertices, const std::vector<std::uint32_t> &ids,
                             const std::vector<std::size_t> &offsets,
                             const std::vector<double> &coords = {},
                             std::size_t coord_dim = 0) {
    TpxComplex *c = nullptr;
    const std::size_t n = offsets.empty() ? 0 : offsets.size() - 1;
    detail::check(tpx_complex_from_arrays(n_vertices, ids.data(), offsets.data(), n,
                                          coords.empty() ? nullptr : coords.data(), coord_dim,
                                          &c));
    return Complex(c);
  }

  /* Reads .off, .obj, .mesh or .simplices. */
  static Complex from_file(const std::string &path) {
    TpxComplex *c = nullptr;
    detail::check(tpx_complex_from_file(path.c_str(), &c));
    return Complex(c);
  }

  Complex(Complex &&o) noexcept : c_(std::exchange(o.c_, nullptr)) {}
  Complex &operator=(Complex &&o) noexcept {
    if (this != &o) {
      tpx_complex_free(c_);
      c_ = std::exchange(o.c_, nullptr);
    }
    return *this;
  }
  Complex(const Complex &) = delete;
  Complex &operator=(const Complex &) = delete;
  ~Complex() { tpx_complex_free(c_); }

  std::uint32_t dimension() const {
    std::uint32_t d = 0;
    detail::check(tpx_complex_dimension(c_, &d));
    return d;
  }
  std::uint32_t vertex_count() const {
    std::uint32_t n = 0;
    detail::check(tpx_complex_vertex_count(c_, &n));
    return n;
  }
  std::size_t top_count(std::uint32_t p) const {
    std::size_t n = 0;
    detail::check(tpx_complex_top_count(c_, p, &n));
    return n;
  }
  /* Coordinates per vertex; 0 when the complex has none. */
  std::size_t coord_dim() const {
    std::size_t n = 0;
    detail::check(tpx_complex_coord_dim(c_, &n));
    return n;
  }
  /* The coordinates, vertex-major (coord_dim() per vertex); empty without coordinates. */
  std::vector<double> coords() const {
    std::vector<double> buf(coord_dim() * vertex_count());
    std::size_t len = 0;
    detail::check(tpx_complex_coords(c_, buf.data(), buf.size(), &len));
    buf.resize(len);
    return buf;
  }
  /* The top p-simplices in ascending lexicographic order (throws for p > dimension()). */
  Rows top_simplices(std::uint32_t p) const {
    std::vector<std::uint32_t> buf((p + 1) * top_count(p));
    std::size_t len = 0;
    detail::check(tpx_complex_top_simplices(c_, p, buf.data(), buf.size(), &len));
    buf.resize(len);
    return Rows(std::move(buf), p + 1);
  }
  /* Writes the complex (top simplices in input order and winding, coordinates bit for bit);
   * throws TPX_STATUS_FORMAT_CANNOT_HOLD, naming the simplex, if the format cannot hold it. */
  void write(const std::string &path, Format format = Format::FromExtension) const {
    detail::check(tpx_complex_write(c_, path.c_str(), static_cast<std::uint32_t>(format)));
  }
  const TpxComplex *get() const noexcept { return c_; }

 private:
  friend class Live;
  explicit Complex(TpxComplex *c) noexcept : c_(c) {}
  TpxComplex *c_ = nullptr;
};

/* R_{p,q} of every p-simplex (owns a TpxRelationTable): row i, a RowsView of q+1 ids, belongs
   to the i-th p-simplex of Structure::simplices(p). */
class RelationTable {
 public:
  class iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = RowsView;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = RowsView;
    iterator() = default;
    iterator(const RelationTable *t, std::size_t i) : t_(t), i_(i) {}
    RowsView operator*() const noexcept { return (*t_)[i_]; }
    iterator &operator++() noexcept {
      ++i_;
      return *this;
    }
    iterator operator++(int) noexcept {
      iterator old = *this;
      ++i_;
      return old;
    }
    bool operator==(const iterator &o) const noexcept { return i_ == o.i_; }
    bool operator!=(const iterator &o) const noexcept { return i_ != o.i_; }

   private:
    const RelationTable *t_ = nullptr;
    std::size_t i_ = 0;
  };

  RelationTable(RelationTable &&o) noexcept
      : t_(std::exchange(o.t_, nullptr)),
        offsets_(o.offsets_),
        n_offsets_(o.n_offsets_),
        ids_(o.ids_),
        n_ids_(o.n_ids_),
        arity_(o.arity_) {}
  RelationTable &operator=(RelationTable &&o) noexcept {
    if (this != &o) {
      tpx_relation_table_free(t_);
      t_ = std::exchange(o.t_, nullptr);
      offsets_ = o.offsets_;
      n_offsets_ = o.n_offsets_;
      ids_ = o.ids_;
      n_ids_ = o.n_ids_;
      arity_ = o.arity_;
    }
    return *this;
  }
  RelationTable(const RelationTable &) = delete;
  RelationTable &operator=(const RelationTable &) = delete;
  ~RelationTable() { tpx_relation_table_free(t_); }

  /* Number of rows (n_p). */
  std::size_t size() const noexcept { return n_offsets_ == 0 ? 0 : n_offsets_ - 1; }
  std::size_t arity() const noexcept { return arity_; }
  RowsView operator[](std::size_t i) const noexcept {
    return RowsView(ids_ + offsets_[i], offsets_[i + 1] - offsets_[i], arity_);
  }
  iterator begin() const noexcept { return iterator(this, 0); }
  iterator end() const noexcept { return iterator(this, size()); }
  /* The CSR arrays as the C ABI gives them. */
  const std::size_t *offsets() const noexcept { return offsets_; }
  std::size_t offsets_size() const noexcept { return n_offsets_; }
  const std::uint32_t *ids() const noexcept { return ids_; }
  std::size_t ids_size() const noexcept { return n_ids_; }

 private:
  friend class Structure;
  RelationTable(TpxRelationTable *t, std::size_t arity) noexcept : t_(t), arity_(arity) {
    offsets_ = tpx_relation_table_offsets(t_, &n_offsets_);
    ids_ = tpx_relation_table_ids(t_, &n_ids_);
  }
  TpxRelationTable *t_ = nullptr;
  const std::size_t *offsets_ = nullptr;
  std::size_t n_offsets_ = 0;
  const std::uint32_t *ids_ = nullptr;
  std::size_t n_ids_ = 0;
  std::size_t arity_ = 1;
};

/* A built structure (owns a TpxStructure). Independent of the Complex once built. */
class Structure {
 public:
  Structure(const Complex &c, Kind kind) {
    detail::check(tpx_structure_build(c.get(), static_cast<std::uint32_t>(kind), &s_));
  }
  Structure(Structure &&o) noexcept : s_(std::exchange(o.s_, nullptr)) {}
  Structure &operator=(Structure &&o) noexcept {
    if (this != &o) {
      tpx_structure_free(s_);
      s_ = std::exchange(o.s_, nullptr);
    }
    return *this;
  }
  Structure(const Structure &) = delete;
  Structure &operator=(const Structure &) = delete;
  ~Structure() { tpx_structure_free(s_); }

  Kind kind() const {
    std::uint32_t k = 0;
    detail::check(tpx_structure_kind(s_, &k));
    return static_cast<Kind>(k);
  }
  std::uint32_t dimension() const {
    std::uint32_t d = 0;
    detail::check(tpx_structure_dimension(s_, &d));
    return d;
  }
  std::size_t count(std::uint32_t p) const {
    std::size_t n = 0;
    detail::check(tpx_structure_count(s_, p, &n));
    return n;
  }
  std::size_t top_count(std::uint32_t p) const {
    std::size_t n = 0;
    detail::check(tpx_structure_top_count(s_, p, &n));
    return n;
  }
  TpxStorage storage() const {
    TpxStorage st{0, 0, 0};
    detail::check(tpx_structure_storage(s_, &st));
    return st;
  }

  /* Every p-simplex in ascending lexicographic order. */
  Rows simplices(std::uint32_t p) const {
    std::vector<std::uint32_t> buf((p + 1) * count(p));
    std::size_t len = 0;
    detail::check(tpx_structure_simplices(s_, p, buf.data(), buf.size(), &len));
    buf.resize(len);
    return Rows(std::move(buf), p + 1);
  }

  /* R_{p,q}(simplex), p = simplex.size() - 1, in ascending lexicographic order. */
  Rows relation(const std::vector<std::uint32_t> &simplex, std::uint32_t q) const {
    std::vector<std::uint32_t> buf(16 * (q + 1));
    std::size_t len = 0;
    TpxStatus st = tpx_relation(s_, simplex.data(), simplex.size(), q, buf.data(), buf.size(),
                                &len);
    if (st == TPX_STATUS_BUFFER_TOO_SMALL) {
      // The structure is immutable, so the second call needs exactly `len`.
      buf.resize(len);
      st = tpx_relation(s_, simplex.data(), simplex.size(), q, buf.data(), buf.size(), &len);
    }
    detail::check(st);
    buf.resize(len);
    return Rows(std::move(buf), q + 1);
  }
  Rows relation(std::initializer_list<std::uint32_t> simplex, std::uint32_t q) const {
    return relation(std::vector<std::uint32_t>(simplex), q);
  }

  /* R_{p,q} of every p-simplex at once. */
  RelationTable relation_table(std::uint32_t p, std::uint32_t q) const {
    TpxRelationTable *t = nullptr;
    detail::check(tpx_relation_table(s_, p, q, &t));
    return RelationTable(t, q + 1);
  }

  const TpxStructure *get() const noexcept { return s_; }

 private:
  TpxStructure *s_ = nullptr;
};

/* What Live::contract may unify (values of TPX_CONTRACT_*). */
enum class ContractMode : std::uint32_t {
  PreserveTopology = TPX_CONTRACT_PRESERVE_TOPOLOGY,
  Free = TPX_CONTRACT_FREE,
  PreserveManifold = TPX_CONTRACT_PRESERVE_MANIFOLD,
};

/* The undo record of one contraction, for Live::split. Move-only owner. */
class Undo {
 public:
  Undo() = default;
  explicit Undo(TpxUndo *u) noexcept : u_(u) {}
  Undo(Undo &&o) noexcept : u_(std::exchange(o.u_, nullptr)) {}
  Undo &operator=(Undo &&o) noexcept {
    if (this != &o) {
      tpx_undo_free(u_);
      u_ = std::exchange(o.u_, nullptr);
    }
    return *this;
  }
  Undo(const Undo &) = delete;
  Undo &operator=(const Undo &) = delete;
  ~Undo() { tpx_undo_free(u_); }
  const TpxUndo *get() const noexcept { return u_; }

 private:
  TpxUndo *u_ = nullptr;
};

/* An updatable complex (any dimension, non-manifold): insert/remove top simplices, contract
 * edges (link-checked or free), split (undo), move vertices. Edits need exclusive access; a
 * refused edit throws Error (status says why: TPX_STATUS_NOT_AN_EDGE,
 * TPX_STATUS_LINK_CONDITION_FAILS, ...) and leaves the complex unchanged. */
class Live {
 public:
  explicit Live(const Complex &c) { detail::check(tpx_live_from_complex(c.get(), &l_)); }
  Live(Live &&o) noexcept : l_(std::exchange(o.l_, nullptr)) {}
  Live &operator=(Live &&o) noexcept {
    if (this != &o) {
      tpx_live_free(l_);
      l_ = std::exchange(o.l_, nullptr);
    }
    return *this;
  }
  Live(const Live &) = delete;
  Live &operator=(const Live &) = delete;
  ~Live() { tpx_live_free(l_); }

  std::uint32_t vertex_slots() const {
    std::uint32_t n = 0;
    detail::check(tpx_live_vertex_slots(l_, &n));
    return n;
  }
  std::uint32_t vertex_count() const {
    std::uint32_t n = 0;
    detail::check(tpx_live_vertex_count(l_, &n));
    return n;
  }
  bool is_vertex(std::uint32_t v) const {
    std::uint32_t b = 0;
    detail::check(tpx_live_is_vertex(l_, v, &b));
    return b != 0;
  }
  std::uint32_t dimension() const {
    std::uint32_t d = 0;
    detail::check(tpx_live_dimension(l_, &d));
    return d;
  }
  std::size_t top_count(std::uint32_t p) const {
    std::size_t n = 0;
    detail::check(tpx_live_top_count(l_, p, &n));
    return n;
  }
  /* Live top p-simplices (p >= 1), vertices in stored (winding) order. */
  Rows top_simplices(std::uint32_t p) const {
    std::size_t len = 0;
    TpxStatus st = tpx_live_top_simplices(l_, p, nullptr, 0, &len);
    std::vector<std::uint32_t> buf(len);
    if (st == TPX_STATUS_BUFFER_TOO_SMALL) {
      st = tpx_live_top_simplices(l_, p, buf.data(), buf.size(), &len);
    }
    detail::check(st);
    buf.resize(len);
    return Rows(std::move(buf), p + 1);
  }
  /* R_{p,q}(simplex), rows of q+1 ascending ids, lexicographic. */
  Rows relation(const std::vector<std::uint32_t> &simplex, std::uint32_t q) const {
    std::vector<std::uint32_t> buf(64);
    std::size_t len = 0;
    TpxStatus st = tpx_live_relation(l_, simplex.data(), simplex.size(), q, buf.data(),
                                     buf.size(), &len);
    if (st == TPX_STATUS_BUFFER_TOO_SMALL) {
      buf.resize(len);
      st = tpx_live_relation(l_, simplex.data(), simplex.size(), q, buf.data(), buf.size(), &len);
    }
    detail::check(st);
    buf.resize(len);
    return Rows(std::move(buf), q + 1);
  }
  std::vector<double> coords(std::uint32_t v) const {
    std::size_t k = 0;
    detail::check(tpx_live_coord_dim(l_, &k));
    std::vector<double> xyz(k);
    std::size_t len = 0;
    detail::check(tpx_live_coords(l_, v, xyz.data(), xyz.size(), &len));
    return xyz;
  }
  void set_coords(std::uint32_t v, const std::vector<double> &xyz) {
    detail::check(tpx_live_set_coords(l_, v, xyz.data(), xyz.size()));
  }
  std::uint32_t add_vertex(const std::vector<double> &xyz) {
    std::uint32_t v = 0;
    detail::check(tpx_live_add_vertex(l_, xyz.data(), xyz.size(), &v));
    return v;
  }
  void insert_top(const std::vector<std::uint32_t> &simplex) {
    detail::check(tpx_live_insert_top(l_, simplex.data(), simplex.size()));
  }
  void remove_top(const std::vector<std::uint32_t> &simplex) {
    detail::check(tpx_live_remove_top(l_, simplex.data(), simplex.size()));
  }
  /* Whether {a, b} is an edge satisfying the link condition (no exception). */
  bool link_condition(std::uint32_t a, std::uint32_t b) const {
    TpxStatus st = tpx_live_link_condition(l_, a, b);
    if (st == TPX_STATUS_NOT_AN_EDGE || st == TPX_STATUS_LINK_CONDITION_FAILS) {
      return false;
    }
    detail::check(st);
    return true;
  }
  /* The link condition on the complex coned over its boundary (what PreserveManifold checks). */
  bool link_condition_with_boundary(std::uint32_t a, std::uint32_t b) const {
    TpxStatus st = tpx_live_link_condition_with_boundary(l_, a, b);
    if (st == TPX_STATUS_NOT_AN_EDGE || st == TPX_STATUS_LINK_CONDITION_FAILS) {
      return false;
    }
    detail::check(st);
    return true;
  }
  /* Contracts b into a (a moves to `position` when not empty); returns the undo record. */
  Undo contract(std::uint32_t a, std::uint32_t b,
                ContractMode mode = ContractMode::PreserveTopology,
                const std::vector<double> &position = {}) {
    TpxUndo *u = nullptr;
    detail::check(tpx_live_contract(l_, a, b, static_cast<std::uint32_t>(mode),
                                    position.empty() ? nullptr : position.data(),
                                    position.size(), &u));
    return Undo(u);
  }
  /* Undoes a contraction (vertex split). */
  void split(const Undo &u) { detail::check(tpx_live_split(l_, u.get())); }
  /* Drops removed vertices and slots; returns old -> new vertex ids (UINT32_MAX: removed). */
  std::vector<std::uint32_t> compact() {
    std::vector<std::uint32_t> map(vertex_slots());
    std::size_t len = 0;
    detail::check(tpx_live_compact(l_, map.data(), map.size(), &len));
    map.resize(len);
    return map;
  }
  /* A frozen copy, to build any Structure from. */
  Complex to_complex() const {
    TpxComplex *c = nullptr;
    detail::check(tpx_live_to_complex(l_, &c));
    return Complex(c);
  }
  void validate() const { detail::check(tpx_live_validate(l_)); }

  const TpxLive *get() const noexcept { return l_; }

 private:
  TpxLive *l_ = nullptr;
};

inline std::string version() { return tpx_version(); }

}  // namespace topoplex

#endif /* TOPOPLEX_HPP */
