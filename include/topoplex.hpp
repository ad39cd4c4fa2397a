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

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <typeinfo>
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
  /* The live complex: a Structure of this kind is an IA* nobody edits; Live edits one. */
  IASTAR = TPX_KIND_IASTAR,
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

/* Where an attribute's elements are (values of TPX_LOCATION_*): one per vertex id, or one per
 * simplex as listed, in input order (Complex::listed_index gives a simplex's listing). */
enum class Location : std::uint32_t {
  Vertices = TPX_LOCATION_VERTICES,
  Listed = TPX_LOCATION_LISTED,
};

/* The type of an attribute's numbers (values of TPX_VALUE_*). */
enum class ValueType : std::uint32_t {
  I32 = TPX_VALUE_I32,
  I64 = TPX_VALUE_I64,
  F32 = TPX_VALUE_F32,
  F64 = TPX_VALUE_F64,
};

/* What Live contractions {a, b} -> a do to a's vertex values (values of TPX_VERTEX_*). */
enum class VertexPolicy : std::uint32_t {
  Survivor = TPX_VERTEX_SURVIVOR, /* a keeps its own (the default) */
  Average = TPX_VERTEX_AVERAGE,   /* reals: the mean of a's and b's; labels stay a's */
};

/* One attribute of a Complex (Complex::attributes): the name copied, the rest as the library
 * reports it (TpxAttributeInfo). */
struct AttributeInfo {
  std::string name;
  Location location;
  ValueType type;
  std::size_t components; /* numbers per element, 1 to 9 */
  std::size_t elements;   /* vertex count, or number of listed simplices */
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

/* The ValueType of a C++ number type: int32_t, int64_t, float, double. */
template <class T>
struct value_type_of;
template <>
struct value_type_of<std::int32_t> {
  static constexpr ValueType value = ValueType::I32;
};
template <>
struct value_type_of<std::int64_t> {
  static constexpr ValueType value = ValueType::I64;
};
template <>
struct value_type_of<float> {
  static constexpr ValueType value = ValueType::F32;
};
template <>
struct value_type_of<double> {
  static constexpr ValueType value = ValueType::F64;
};

inline const char *value_type_name(ValueType t) {
  switch (t) {
    case ValueType::I32: return "int32_t";
    case ValueType::I64: return "int64_t";
    case ValueType::F32: return "float";
    case ValueType::F64: return "double";
  }
  return "?";
}

/* The value a C call writes through its last (out) parameter: fn(args..., &value), checked.
 * T is value-initialised first (0, nullptr, an all-zero struct). */
template <class T, class F, class... A>
T get(F fn, A... args) {
  T value{};
  check(fn(args..., &value));
  return value;
}

/* A C call that writes an answer into a caller's buffer: fn(args..., buf.data(), buf.size(),
 * &len), checked, then buf resized to the answer's length. When the library answers
 * BUFFER_TOO_SMALL (len then holds the length needed) buf grows to len and fn is called once
 * more: the object is immutable or exclusively borrowed between the calls, so that suffices. */
template <class V, class F, class... A>
void fill(V &buf, F fn, A... args) {
  std::size_t len = 0;
  TpxStatus st = fn(args..., buf.data(), buf.size(), &len);
  if (st == TPX_STATUS_BUFFER_TOO_SMALL) {
    buf.resize(len);
    st = fn(args..., buf.data(), buf.size(), &len);
  }
  check(st);
  buf.resize(len);
}

/* The one owner of a library object: holds a T* (possibly null), move-only, and releases it
 * with Free (a tpx_*_free, which accepts null) when destroyed or assigned over. A class
 * holding one as a member gets its move constructor, move assignment and destructor
 * implicitly, all noexcept, and no copies. */
template <class T, void (*Free)(T *)>
class Owned {
 public:
  Owned() = default;
  explicit Owned(T *p) noexcept : p_(p) {}
  Owned(Owned &&o) noexcept : p_(std::exchange(o.p_, nullptr)) {}
  Owned &operator=(Owned &&o) noexcept {
    if (this != &o) {
      Free(p_);
      p_ = std::exchange(o.p_, nullptr);
    }
    return *this;
  }
  Owned(const Owned &) = delete;
  Owned &operator=(const Owned &) = delete;
  ~Owned() { Free(p_); }
  T *get() const noexcept { return p_; }

 private:
  T *p_ = nullptr;
};

/* What every owning class below promises (checked once each, after its definition). */
template <class C>
constexpr bool move_only = std::is_nothrow_move_constructible<C>::value &&
                           std::is_nothrow_move_assignable<C>::value &&
                           std::is_nothrow_destructible<C>::value &&
                           !std::is_copy_constructible<C>::value &&
                           !std::is_copy_assignable<C>::value;
}  // namespace detail

/* The kind named `name` as the topoplex CLI's --structure takes it ("ig", "PE", "iastar"; ASCII
 * case ignored): tpx_kind_from_name, the library's one name map. Throws Error
 * (TPX_STATUS_UNKNOWN_KIND, the message listing the names) for any other name. A free function
 * because Kind is a C++ enum, which cannot have members; Kind::from_name reads as
 * kind_from_name. */
inline Kind kind_from_name(const std::string &name) {
  return static_cast<Kind>(detail::get<std::uint32_t>(tpx_kind_from_name, name.c_str()));
}
/* The CLI name of `kind` ("ig" .. "iastar"; tpx_kind_name); throws UNKNOWN_KIND otherwise. */
inline std::string kind_name(Kind kind) {
  return detail::get<const char *>(tpx_kind_name, static_cast<std::uint32_t>(kind));
}

/* A non-owning view of vertex ids: one simplex's (ascending, or in winding order where the call
 * says so), or a vertex's one-ring (MeshView::for_each_ring). */
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

/* A non-owning view of coordinates: n doubles (coord_dim per vertex, vertex after vertex). */
class CoordsView {
 public:
  CoordsView() = default;
  CoordsView(const double *xyz, std::size_t n) : xyz_(xyz), n_(n) {}
  const double *begin() const noexcept { return xyz_; }
  const double *end() const noexcept { return xyz_ + n_; }
  const double *data() const noexcept { return xyz_; }
  std::size_t size() const noexcept { return n_; }
  double operator[](std::size_t i) const noexcept { return xyz_[i]; }

 private:
  const double *xyz_ = nullptr;
  std::size_t n_ = 0;
};

/* A normalised simplicial complex (owns a TpxComplex). */
/* The numbers of one attribute, lent from its Complex without a copy (Complex::attribute<T>):
 * size() numbers of type T, components() per element, element after element. Valid while the
 * Complex lives and none of its attributes is set or removed (set_attribute,
 * remove_attribute); a view does not own anything and costs nothing to copy. */
template <class T>
class AttributeView {
 public:
  AttributeView() = default;
  AttributeView(const T *data, std::size_t size, std::size_t components)
      : data_(data), size_(size), components_(components) {}
  const T *data() const noexcept { return data_; }
  std::size_t size() const noexcept { return size_; }
  bool empty() const noexcept { return size_ == 0; }
  std::size_t components() const noexcept { return components_; }
  std::size_t elements() const noexcept { return components_ == 0 ? 0 : size_ / components_; }
  const T &operator[](std::size_t i) const noexcept { return data_[i]; }
  /* The first number of element e (components() numbers follow). */
  const T *element(std::size_t e) const noexcept { return data_ + e * components_; }
  const T *begin() const noexcept { return data_; }
  const T *end() const noexcept { return data_ + size_; }
  std::vector<T> to_vector() const { return std::vector<T>(begin(), end()); }

 private:
  const T *data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t components_ = 0;
};

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

  /* Simplex i is ids[offsets[i] .. offsets[i+1]]; coords empty or n_vertices * coord_dim.
   * max_simplices: the closure budget (0: the default, max(2^20, 64 x input size);
   * UINT64_MAX: unlimited); above it, Error with TPX_STATUS_TOO_LARGE. */
  static Complex from_arrays(std::uint32_t n_vertices, const std::vector<std::uint32_t> &ids,
                             const std::vector<std::size_t> &offsets,
                             const std::vector<double> &coords = {},
                             std::size_t coord_dim = 0, std::uint64_t max_simplices = 0) {
    const std::size_t n = offsets.empty() ? 0 : offsets.size() - 1;
    return Complex(detail::get<TpxComplex *>(tpx_complex_from_arrays_budget, n_vertices,
                                             ids.data(), offsets.data(), n,
                                             coords.empty() ? nullptr : coords.data(), coord_dim,
                                             max_simplices));
  }

  /* Reads .off, .obj, .mesh or .simplices (max_simplices: as for from_arrays). */
  static Complex from_file(const std::string &path, std::uint64_t max_simplices = 0) {
    return Complex(
        detail::get<TpxComplex *>(tpx_complex_from_file_budget, path.c_str(), max_simplices));
  }
  /* The same, fanning each convex planar polygon into triangles (the CLI's --triangulate;
   * tpx_complex_from_file_flags with TPX_READ_TRIANGULATE); other polygons are refused with
   * the reason, naming file and line. */
  static Complex from_file_triangulated(const std::string &path, std::uint64_t max_simplices = 0) {
    return Complex(detail::get<TpxComplex *>(tpx_complex_from_file_flags, path.c_str(),
                                             max_simplices, std::uint32_t(TPX_READ_TRIANGULATE)));
  }

  /* The complex saved in a .tpx file (`topoplex save`, Complex::save), rebuilt from its saved
   * listing and validated like any input: O(size of the listing). */
  static Complex open(const std::string &path) {
    return Complex(detail::get<TpxComplex *>(tpx_complex_open, path.c_str()));
  }

  std::uint32_t dimension() const {
    return detail::get<std::uint32_t>(tpx_complex_dimension, c_.get());
  }
  std::uint32_t vertex_count() const {
    return detail::get<std::uint32_t>(tpx_complex_vertex_count, c_.get());
  }
  std::size_t top_count(std::uint32_t p) const {
    return detail::get<std::size_t>(tpx_complex_top_count, c_.get(), p);
  }
  /* What normalisation absorbed: simplices as given, extra listings, faces of listed ones. */
  TpxInputStats input_stats() const {
    return detail::get<TpxInputStats>(tpx_complex_input_stats, c_.get());
  }
  /* Coordinates per vertex; 0 when the complex has none. */
  std::size_t coord_dim() const {
    return detail::get<std::size_t>(tpx_complex_coord_dim, c_.get());
  }
  /* Listed simplex i exactly as given; `top` receives its top id (as Structure::top numbers
   * them) or UINT32_MAX when it was absorbed as a face of another listed simplex. */
  std::vector<std::uint32_t> input_simplex(std::size_t i, std::uint32_t &top) const {
    std::vector<std::uint32_t> out(16);
    std::size_t len = 0;
    detail::check(tpx_complex_input_simplex(c_.get(), i, out.data(), out.size(), &len, &top));
    out.resize(len);
    return out;
  }

  /* Replaces the coordinates: `dim` numbers per vertex, vertex-major (vertex_count() * dim
   * finite numbers; a complex without coordinates gains them). Throws Error
   * (TPX_STATUS_INVALID_ARGUMENT naming the problem) and changes nothing otherwise. Structures
   * built before keep what they were built with. No allocation when dim is coord_dim(). */
  void set_coords(const std::vector<double> &xyz, std::size_t dim) {
    detail::check(tpx_complex_set_coords(c_.get(), dim, xyz.data(), xyz.size()));
  }
  /* Top p-simplex i (of top_simplices(p)) with its vertices in input winding, lent from the
   * complex (valid while it lives): no copy. */
  SimplexView top_oriented(std::uint32_t p, std::uint32_t i) const {
    const std::uint32_t *ids = nullptr;
    std::size_t n = 0;
    detail::check(tpx_complex_top_oriented(c_.get(), p, i, &ids, &n));
    return SimplexView(ids, n);
  }
  /* The coordinates, vertex-major (coord_dim() per vertex); empty without coordinates. */
  std::vector<double> coords() const {
    std::vector<double> buf(coord_dim() * vertex_count());
    detail::fill(buf, tpx_complex_coords, c_.get());
    return buf;
  }
  /* The top p-simplices in ascending lexicographic order (throws for p > dimension()). */
  Rows top_simplices(std::uint32_t p) const {
    std::vector<std::uint32_t> buf((p + 1) * top_count(p));
    detail::fill(buf, tpx_complex_top_simplices, c_.get(), p);
    return Rows(std::move(buf), p + 1);
  }
  /* Writes the complex (top simplices in input order and winding, coordinates bit for bit);
   * throws TPX_STATUS_FORMAT_CANNOT_HOLD, naming the simplex, if the format cannot hold it. */
  void write(const std::string &path, Format format = Format::FromExtension) const {
    detail::check(tpx_complex_write(c_.get(), path.c_str(), static_cast<std::uint32_t>(format)));
  }
  /* Saves the complex alone to a .tpx file (written under a temporary name, then renamed);
   * Structure::save stores a structure beside it. */
  void save(const std::string &path) const {
    detail::check(tpx_save(c_.get(), nullptr, path.c_str()));
  }
  /* ---- attributes: named labels and fields on the vertices and the listed simplices ---- */

  /* Every attribute, in order (index i of tpx_complex_attribute_info): names copied. O(count). */
  std::vector<AttributeInfo> attributes() const {
    const std::size_t n = detail::get<std::size_t>(tpx_complex_attribute_count, c_.get());
    std::vector<AttributeInfo> out;
    out.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      const TpxAttributeInfo a = detail::get<TpxAttributeInfo>(tpx_complex_attribute_info, c_.get(), i);
      out.push_back(AttributeInfo{std::string(a.name, a.name_len), static_cast<Location>(a.location),
                                  static_cast<ValueType>(a.value_type), a.components, a.elements});
    }
    return out;
  }
  /* The values of attribute `name` at `location`, lent (see AttributeView: valid while this
   * Complex lives and its attributes are not changed). T must be the stored type (int32_t,
   * int64_t, float, double): otherwise Error TPX_STATUS_INVALID_ARGUMENT naming both; no such
   * attribute: TPX_STATUS_NO_SUCH_ATTRIBUTE. O(attributes); no copy. */
  template <class T>
  AttributeView<T> attribute(const std::string &name, Location location) const {
    const std::size_t i = detail::get<std::size_t>(tpx_complex_attribute_find, c_.get(), name.c_str(),
                                                   static_cast<std::uint32_t>(location));
    const TpxAttributeInfo a = detail::get<TpxAttributeInfo>(tpx_complex_attribute_info, c_.get(), i);
    const ValueType want = detail::value_type_of<T>::value;
    if (static_cast<ValueType>(a.value_type) != want) {
      throw Error(TPX_STATUS_INVALID_ARGUMENT,
                  "attribute '" + name + "' holds " +
                      detail::value_type_name(static_cast<ValueType>(a.value_type)) + ", not " +
                      detail::value_type_name(want));
    }
    const void *p = nullptr;
    std::size_t n = 0;
    detail::check(tpx_complex_attribute_data(c_.get(), i, &p, &n));
    return AttributeView<T>(static_cast<const T *>(p), n, a.components);
  }
  /* Sets attribute `name` at `location` to a copy of data[0 .. n] (`components` numbers per
   * element: n = vertex_count() or input_stats().input_simplices, times components), replacing
   * one of the same name and location (views of it die). Writers then carry it or refuse the
   * format. Throws Error (TPX_STATUS_INVALID_ARGUMENT naming the attribute) and changes nothing
   * otherwise. O(n). */
  template <class T>
  void set_attribute(const std::string &name, Location location, std::size_t components,
                     const T *data, std::size_t n) {
    detail::check(tpx_complex_set_attribute(c_.get(), name.c_str(), static_cast<std::uint32_t>(location),
                                            static_cast<std::uint32_t>(detail::value_type_of<T>::value),
                                            components, data, n));
  }
  template <class T>
  void set_attribute(const std::string &name, Location location, std::size_t components,
                     const std::vector<T> &data) {
    set_attribute(name, location, components, data.data(), data.size());
  }
  /* Removes the attributes called `name` (both locations) and their label names (views of
   * them die); TPX_STATUS_NO_SUCH_ATTRIBUTE when there is none. O(attributes). */
  void remove_attribute(const std::string &name) {
    detail::check(tpx_complex_remove_attribute(c_.get(), name.c_str()));
  }
  /* The listing of a simplex (vertex ids in any order): its element in the Location::Listed
   * attributes, or TPX_NOT_LISTED for one never listed. O(log n) after the first call. */
  std::size_t listed_index(const std::vector<std::uint32_t> &simplex) const {
    return detail::get<std::size_t>(tpx_complex_listed_index, c_.get(), simplex.data(), simplex.size());
  }
  /* The name of `label` of integer attribute `attribute` for simplices of `dimension`
   * (Gmsh $PhysicalNames), copied; empty when it has none. */
  std::string label_name(const std::string &attribute, std::uint32_t dimension, std::int64_t label) const {
    const char *p = nullptr;
    std::size_t n = 0;
    detail::check(tpx_complex_label_name(c_.get(), attribute.c_str(), dimension, label, &p, &n));
    return p ? std::string(p, n) : std::string();
  }

  const TpxComplex *get() const noexcept { return c_.get(); }

 private:
  friend class Live;
  explicit Complex(TpxComplex *c) noexcept : c_(c) {}
  detail::Owned<TpxComplex, tpx_complex_free> c_;
};
static_assert(detail::move_only<Complex>, "Complex: a move-only owner");

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
  friend class StructureView;
  RelationTable(TpxRelationTable *t, std::size_t arity) noexcept : t_(t), arity_(arity) {
    offsets_ = tpx_relation_table_offsets(t, &n_offsets_);
    ids_ = tpx_relation_table_ids(t, &n_ids_);
  }
  detail::Owned<TpxRelationTable, tpx_relation_table_free> t_;
  const std::size_t *offsets_ = nullptr;
  std::size_t n_offsets_ = 0;
  const std::uint32_t *ids_ = nullptr;
  std::size_t n_ids_ = 0;
  std::size_t arity_ = 1;
};
static_assert(detail::move_only<RelationTable>, "RelationTable: a move-only owner");

/* Answer order of navigation calls. */
enum class Order : std::uint32_t {
  Natural = TPX_ORDER_NATURAL,             /* the structure's own order (cheapest) */
  Lexicographic = TPX_ORDER_LEXICOGRAPHIC  /* ascending index = lexicographic */
};

/* A handle to one simplex of one Structure: 12 bytes, copy freely, nothing to release; valid as
 * long as its Structure lives. index() is the simplex's dense index among the simplices of its
 * dimension (a vertex's index is its id), so per-simplex user data is an array indexed by it
 * (see SimplexData). Two handles of one structure name the same simplex exactly when equal. */
class Simplex {
 public:
  Simplex() = default;
  explicit Simplex(const TpxSimplex &h) : h_(h) {}
  std::uint32_t index() const noexcept { return h_.index; }
  std::uint32_t dim() const noexcept { return h_.meta & 0xffu; }
  const TpxSimplex &raw() const noexcept { return h_; }
  bool operator==(const Simplex &o) const noexcept {
    return h_.index == o.h_.index && h_.meta == o.h_.meta && h_.owner == o.h_.owner;
  }
  bool operator!=(const Simplex &o) const noexcept { return !(*this == o); }

 private:
  TpxSimplex h_{};
};

/* Handles of one dimension over a borrowed span of dense indices (an answer of related(),
 * triangles_around(), ...). Iterating yields Simplex values; no allocation. */
class SimplexSpan {
 public:
  class iterator {
   public:
    using iterator_category = std::random_access_iterator_tag;
    using value_type = Simplex;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = Simplex;
    iterator() = default;
    iterator(const std::uint32_t *p, std::uint32_t dim, std::uint32_t owner)
        : p_(p), dim_(dim), owner_(owner) {}
    Simplex operator*() const noexcept { return Simplex(TpxSimplex{*p_, dim_, owner_}); }
    iterator &operator++() noexcept {
      ++p_;
      return *this;
    }
    iterator operator++(int) noexcept {
      iterator t = *this;
      ++p_;
      return t;
    }
    difference_type operator-(const iterator &o) const noexcept { return p_ - o.p_; }
    bool operator==(const iterator &o) const noexcept { return p_ == o.p_; }
    bool operator!=(const iterator &o) const noexcept { return p_ != o.p_; }

   private:
    const std::uint32_t *p_ = nullptr;
    std::uint32_t dim_ = 0, owner_ = 0;
  };
  SimplexSpan(const std::uint32_t *ids, std::size_t n, std::uint32_t dim, std::uint32_t owner)
      : ids_(ids), n_(n), dim_(dim), owner_(owner) {}
  iterator begin() const noexcept { return iterator(ids_, dim_, owner_); }
  iterator end() const noexcept { return iterator(ids_ + n_, dim_, owner_); }
  std::size_t size() const noexcept { return n_; }
  bool empty() const noexcept { return n_ == 0; }
  Simplex operator[](std::size_t i) const noexcept {
    return Simplex(TpxSimplex{ids_[i], dim_, owner_});
  }
  /* The dense indices themselves. */
  const std::uint32_t *indices() const noexcept { return ids_; }

 private:
  const std::uint32_t *ids_;
  std::size_t n_;
  std::uint32_t dim_, owner_;
};

/* An answer that owns its indices (returned by value); iterate it like a SimplexSpan. */
class SimplexList {
 public:
  SimplexList() = default;
  SimplexList(std::vector<std::uint32_t> ids, std::uint32_t dim, std::uint32_t owner)
      : ids_(std::move(ids)), dim_(dim), owner_(owner) {}
  SimplexSpan::iterator begin() const noexcept { return span().begin(); }
  SimplexSpan::iterator end() const noexcept { return span().end(); }
  std::size_t size() const noexcept { return ids_.size(); }
  bool empty() const noexcept { return ids_.empty(); }
  Simplex operator[](std::size_t i) const noexcept { return span()[i]; }
  SimplexSpan span() const noexcept { return SimplexSpan(ids_.data(), ids_.size(), dim_, owner_); }
  const std::vector<std::uint32_t> &indices() const noexcept { return ids_; }

 private:
  std::vector<std::uint32_t> ids_;
  std::uint32_t dim_ = 0, owner_ = 0;
};

/* R_{p,q} of every p-simplex as one CSR lent by its Structure (Structure::view, over
 * tpx_relation_view): view[i] is the answer of the p-simplex of dense index i as a SimplexSpan,
 * read inline (two loads, no library call), so `for (auto f : vf[v])` costs what a circulator
 * costs. Answers in natural order, the same as related(). Copy freely; valid as long as its
 * Structure lives. Where the structure stores the relation in CSR form (the IG's co-boundaries
 * R_{p,p+1}) the arrays are its own (built() false, no memory); otherwise the first view(p, q)
 * of a structure builds an index once, kept with the structure (bytes() of memory). */
class RelationView {
 public:
  RelationView() = default;
  RelationView(const TpxRelationView &v, std::uint32_t q, std::uint32_t owner) noexcept
      : v_(v), q_(q), owner_(owner) {}
  /* Number of p-simplices. */
  std::size_t size() const noexcept { return v_.count; }
  /* The answer of the p-simplex of dense index i (i < size(), unchecked). O(1). */
  SimplexSpan operator[](std::uint32_t i) const noexcept {
    const std::uint32_t a = v_.offsets[i], b = v_.offsets[i + 1];
    return SimplexSpan(v_.ids + a, b - a, q_, owner_);
  }
  /* By a handle that is its index (the nine structures, handles made from indices). A live
   * complex's lasting handle is not: use view[live.index(h)]. */
  SimplexSpan operator[](Simplex h) const noexcept { return (*this)[h.index()]; }
  /* |R_{p,q}| of the p-simplex of dense index i. O(1). */
  std::uint32_t degree(std::uint32_t i) const noexcept { return v_.offsets[i + 1] - v_.offsets[i]; }
  /* Whether the arrays are an index built for the view (else the structure's own). */
  bool built() const noexcept { return v_.built != 0; }
  /* Bytes of the two arrays (extra memory when built()). */
  std::uint64_t bytes() const noexcept { return v_.bytes; }
  const TpxRelationView &raw() const noexcept { return v_; }

 private:
  TpxRelationView v_{};
  std::uint32_t q_ = 0, owner_ = 0;
};

/* Cyclically ordered groups (fans around a vertex, radial groups around an edge). Reuse one
 * object across calls (Structure::fans_around(v, fans)) to avoid allocation. */
class Fans {
 public:
  std::size_t size() const noexcept { return groups_; }
  /* Group k, in cyclic order. */
  SimplexSpan operator[](std::size_t k) const noexcept {
    return SimplexSpan(items_.data() + offsets_[k], offsets_[k + 1] - offsets_[k], dim_, owner_);
  }
  bool closed(std::size_t k) const noexcept { return (flags_[k] & TPX_GROUP_CLOSED) != 0; }
  /* Consistently oriented and counter-clockwise by the input winding. */
  bool oriented(std::size_t k) const noexcept { return (flags_[k] & TPX_GROUP_ORIENTED) != 0; }
  /* Every group's simplices, group after group. */
  SimplexSpan all() const noexcept {
    return SimplexSpan(items_.data(), items_n_, dim_, owner_);
  }

 private:
  friend class StructureView;
  std::vector<std::uint32_t> items_, offsets_, flags_;
  std::size_t items_n_ = 0, groups_ = 0;
  std::uint32_t dim_ = 2, owner_ = 0;
};

/* The navigation of one structure, without owning it: every const query of a built Structure
 * (which is one) and of a Live complex (Live::as_structure(), over tpx_live_structure), so that
 * code written against it runs on any kind, the editable one included. Copy it freely; it is
 * valid while its structure lives. On a live complex, indices above vertices (handle(p, i),
 * related ids, view(p, q), degrees, index(h)) are its numbering until the next edit, which
 * drops lent views; handles from locate() and the Live handle calls last across edits; after
 * Live::compact() take a new StructureView (the owner stamp changes). */
class StructureView {
 public:
  explicit StructureView(const TpxStructure *s)
      : s_(s), stamp_(detail::get<std::uint32_t>(tpx_structure_stamp, s)) {}

  Kind kind() const {
    return static_cast<Kind>(detail::get<std::uint32_t>(tpx_structure_kind, s_));
  }
  std::uint32_t dimension() const {
    return detail::get<std::uint32_t>(tpx_structure_dimension, s_);
  }
  std::size_t count(std::uint32_t p) const {
    return detail::get<std::size_t>(tpx_structure_count, s_, p);
  }
  std::size_t top_count(std::uint32_t p) const {
    return detail::get<std::size_t>(tpx_structure_top_count, s_, p);
  }
  TpxStorage storage() const { return detail::get<TpxStorage>(tpx_structure_storage, s_); }

  /* Every p-simplex in ascending lexicographic order. */
  Rows simplices(std::uint32_t p) const {
    std::vector<std::uint32_t> buf((p + 1) * count(p));
    detail::fill(buf, tpx_structure_simplices, s_, p);
    return Rows(std::move(buf), p + 1);
  }

  /* R_{p,q}(simplex), p = simplex.size() - 1, in ascending lexicographic order. */
  Rows relation(const std::vector<std::uint32_t> &simplex, std::uint32_t q) const {
    std::vector<std::uint32_t> buf(16 * (q + 1));
    detail::fill(buf, tpx_relation, s_, simplex.data(), simplex.size(), q);
    return Rows(std::move(buf), q + 1);
  }
  Rows relation(std::initializer_list<std::uint32_t> simplex, std::uint32_t q) const {
    return relation(std::vector<std::uint32_t>(simplex), q);
  }

  /* R_{p,q} of every p-simplex at once. */
  RelationTable relation_table(std::uint32_t p, std::uint32_t q) const {
    return RelationTable(detail::get<TpxRelationTable *>(tpx_relation_table, s_, p, q),
                         q + 1);
  }


  /* ---- handles: locate once, then navigate (see the Rust `handle` module for costs) ---- */

  /* The handle of the simplex with these vertex ids (any order); throws NOT_IN_COMPLEX. */
  Simplex locate(const std::uint32_t *ids, std::size_t n) const {
    return Simplex(detail::get<TpxSimplex>(tpx_locate, s_, ids, n));
  }
  Simplex locate(const std::vector<std::uint32_t> &ids) const {
    return locate(ids.data(), ids.size());
  }
  Simplex locate(std::initializer_list<std::uint32_t> ids) const {
    return locate(ids.begin(), ids.size());
  }
  /* The p-simplex of dense index i (checked). vertex(v) = handle(0, v). */
  Simplex handle(std::uint32_t p, std::uint32_t i) const {
    return Simplex(detail::get<TpxSimplex>(tpx_handle, s_, p, i));
  }
  Simplex vertex(std::uint32_t v) const { return handle(0, v); }
  /* The owner stamp every handle of this structure carries. */
  std::uint32_t stamp() const { return stamp_; }

  /* Vertex ids of h, ascending, into `out` (reused). */
  void vertices(Simplex h, std::vector<std::uint32_t> &out) const {
    out.resize(16);
    detail::fill(out, tpx_simplex_vertices, s_, &h.raw());
  }
  std::vector<std::uint32_t> vertices(Simplex h) const {
    std::vector<std::uint32_t> out;
    vertices(h, out);
    return out;
  }

  /* R_{p,q}(h) as dense indices of q-simplices into `out`, reusing its capacity: after the first
   * calls, no allocation. */
  void related(Simplex h, std::uint32_t q, std::vector<std::uint32_t> &out,
               Order order = Order::Natural) const {
    if (out.capacity() < 16) out.reserve(16);
    out.resize(out.capacity());
    detail::fill(out, tpx_related, s_, &h.raw(), q, static_cast<std::uint32_t>(order));
  }
  /* R_{p,q}(h) as a range of handles. */
  SimplexList related(Simplex h, std::uint32_t q, Order order = Order::Natural) const {
    std::vector<std::uint32_t> ids;
    related(h, q, ids, order);
    return SimplexList(std::move(ids), q, stamp_);
  }
  /* Faces, cofaces and neighbours by name. */
  SimplexList boundary(Simplex h, std::uint32_t q, Order o = Order::Natural) const {
    return related(h, q, o);
  }
  SimplexList coboundary(Simplex h, std::uint32_t q, Order o = Order::Natural) const {
    return related(h, q, o);
  }
  SimplexList adjacent(Simplex h, Order o = Order::Natural) const {
    return related(h, h.dim(), o);
  }
  /* R_{p,q} of the p-simplices of dense indices `indices`, in CSR form: answer i is
   * ids[offsets[i] .. offsets[i+1]]. Buffers are reused. */
  void related_batch(std::uint32_t p, const std::vector<std::uint32_t> &indices, std::uint32_t q,
                     std::vector<std::uint32_t> &offsets, std::vector<std::uint32_t> &ids,
                     Order order = Order::Natural) const {
    offsets.resize(indices.size() + 1);
    if (ids.empty()) ids.resize(indices.size() * 8 + 16);
    const auto o = static_cast<std::uint32_t>(order);
    detail::fill(ids, tpx_related_batch, s_, p, indices.data(), indices.size(), q, o,
                 offsets.data());
  }
  /* R_{p,q} of every p-simplex, lent as a RelationView iterated inline (see RelationView for
   * its cost: the first call for a relation the structure does not store builds an index). */
  RelationView view(std::uint32_t p, std::uint32_t q) const {
    return RelationView(detail::get<TpxRelationView>(tpx_relation_view, s_, p, q), q, stamp_);
  }
  /* |R_{p,q}| of the p-simplices of dense indices `indices` into `out` (resized), counts only
   * (tpx_degree_batch: O(1) each for relations the IG stores). */
  void degrees(std::uint32_t p, const std::vector<std::uint32_t> &indices, std::uint32_t q,
               std::vector<std::uint32_t> &out) const {
    out.resize(indices.size());
    detail::check(tpx_degree_batch(s_, p, indices.data(), indices.size(), q, out.data()));
  }
  /* |R_{p,q}(h)| without writing the answer. */
  std::size_t degree(Simplex h, std::uint32_t q) const {
    return detail::get<std::size_t>(tpx_degree, s_, &h.raw(), q);
  }
  bool is_boundary(Simplex h) const { return test(h, 0); }
  bool is_manifold(Simplex h) const { return test(h, 1); }
  /* Star (every simplex having h as a proper face) or link of h, dimension ascending. */
  std::vector<Simplex> star(Simplex h, Order o = Order::Natural) const { return star_or_link(h, 0, o); }
  std::vector<Simplex> link(Simplex h, Order o = Order::Natural) const { return star_or_link(h, 1, o); }

  /* Top simplices: ids 0..top_total()-1 (dimension ascending, lexicographic within; the same
   * for every structure of one complex). */
  std::uint32_t top_total() const { return detail::get<std::uint32_t>(tpx_top_total, s_); }
  Simplex top(std::uint32_t t) const {
    return Simplex(detail::get<TpxSimplex>(tpx_top, s_, t));
  }
  /* The top id of h, or UINT32_MAX when h is not a top simplex. */
  std::uint32_t top_id(Simplex h) const {
    return detail::get<std::uint32_t>(tpx_top_id, s_, &h.raw());
  }
  /* Top simplex t with its vertices as given in the input (its winding). */
  std::vector<std::uint32_t> top_as_given(std::uint32_t t) const {
    std::vector<std::uint32_t> out;
    top_as_given(t, out);
    return out;
  }
  /* The same into `out`, reusing its capacity: no allocation once it holds 16 ids (a pass
   * over every top simplex; Complex::top_oriented and Live::top_vertices lend without copy). */
  void top_as_given(std::uint32_t t, std::vector<std::uint32_t> &out) const {
    if (out.capacity() < 16) out.reserve(16);
    out.resize(out.capacity());
    detail::fill(out, tpx_top_as_given, s_, t);
  }

  /* Cyclic order. The manifold fans of triangles around vertex v (a complex of dimension <= 2),
   * each counter-clockwise by the input winding where oriented; `fans` is reused. */
  void fans_around(Simplex v, Fans &fans) const { cyclic(v, 0, 2, fans); }
  Fans fans_around(Simplex v) const {
    Fans f;
    fans_around(v, f);
    return f;
  }
  /* Circulator-style: for (auto t : mesh.triangles_around(v)) — every fan's triangles in order,
   * fan after fan. */
  SimplexList triangles_around(Simplex v) const {
    Fans f;
    fans_around(v, f);
    auto all = f.all();
    return SimplexList(std::vector<std::uint32_t>(all.indices(), all.indices() + all.size()), 2,
                       stamp_);
  }
  /* The triangles (q = 2) or tetrahedra (q = 3) around edge e in radial order, grouped. */
  void around_edge(Simplex e, std::uint32_t q, Fans &fans) const { cyclic(e, q, q, fans); }
  Fans around_edge(Simplex e, std::uint32_t q) const {
    Fans f;
    around_edge(e, q, f);
    return f;
  }

  /* Saves this structure with `c`, the complex it was built from (the file pairs them), to a
   * .tpx file: one pass over the listing and the structure's arrays. */
  void save(const Complex &c, const std::string &path) const {
    detail::check(tpx_save(c.get(), s_, path.c_str()));
  }

  /* The dense index of h: its lexicographic rank among the simplices of its dimension (a
   * vertex: its id). h.index() for the nine structures; on a live complex, whose handles above
   * vertices last across edits and are not indices, its index until the next edit. */
  std::uint32_t index(Simplex h) const {
    return detail::get<std::uint32_t>(tpx_simplex_index, s_, &h.raw());
  }

  const TpxStructure *get() const noexcept { return s_; }

 protected:
  bool test(Simplex h, std::uint32_t what) const {
    return detail::get<std::uint32_t>(tpx_simplex_test, s_, &h.raw(), what) != 0;
  }
  std::vector<Simplex> star_or_link(Simplex h, std::uint32_t link, Order o) const {
    std::vector<TpxSimplex> buf(64);
    detail::fill(buf, tpx_star, s_, &h.raw(), link, static_cast<std::uint32_t>(o));
    return std::vector<Simplex>(buf.begin(), buf.end());
  }
  void cyclic(Simplex h, std::uint32_t q, std::uint32_t dim, Fans &f) const {
    if (f.items_.size() < 16) f.items_.resize(16);
    if (f.flags_.size() < 4) f.flags_.resize(4);
    f.offsets_.resize(f.flags_.size() + 1);
    std::size_t ni = 0, ng = 0;
    TpxStatus st = tpx_cyclic(s_, &h.raw(), q, f.items_.data(), f.items_.size(),
                              f.offsets_.data(), f.flags_.data(), f.flags_.size(), &ni, &ng);
    if (st == TPX_STATUS_BUFFER_TOO_SMALL) {
      if (f.items_.size() < ni) f.items_.resize(ni);
      if (f.flags_.size() < ng) f.flags_.resize(ng);
      f.offsets_.resize(f.flags_.size() + 1);
      st = tpx_cyclic(s_, &h.raw(), q, f.items_.data(), f.items_.size(), f.offsets_.data(),
                      f.flags_.data(), f.flags_.size(), &ni, &ng);
    }
    detail::check(st);
    f.items_n_ = ni;
    f.groups_ = ng;
    f.dim_ = dim;
    f.owner_ = stamp_;
  }

  const TpxStructure *s_ = nullptr;
  std::uint32_t stamp_ = 0;
};

namespace detail {
/* The owner a Structure holds, as its first base so that it owns the pointer before the
 * StructureView base reads the stamp (a failure there frees it). */
struct StructureOwner {
  Owned<TpxStructure, tpx_structure_free> owned;
};
}  // namespace detail

/* A built structure (owns a TpxStructure). Independent of the Complex once built. Every kind,
 * Kind::IASTAR included (an IA* live complex nobody edits: for editing, use Live). */
class Structure : private detail::StructureOwner, public StructureView {
 public:
  Structure(const Complex &c, Kind kind)
      : Structure(detail::get<TpxStructure *>(tpx_structure_build, c.get(),
                                              static_cast<std::uint32_t>(kind))) {}
  /* The structure of `kind` saved in a .tpx file, memory-mapped: opening costs O(sections)
   * (O(file) with verify: every checksum and invariant checked first); arrays are paged in as
   * queries touch them and the mapping lives as long as the Structure. A file holding another
   * kind or only a complex gets the structure built from its saved complex instead. */
  static Structure open(const std::string &path, Kind kind, bool verify = false) {
    return Structure(detail::get<TpxStructure *>(tpx_structure_open, path.c_str(),
                                                 static_cast<std::uint32_t>(kind),
                                                 verify ? TPX_OPEN_VERIFY : 0u));
  }

 private:
  /* Takes ownership of s first, so that s is freed when reading its stamp fails. */
  explicit Structure(TpxStructure *s) : detail::StructureOwner{detail::Owned<TpxStructure, tpx_structure_free>(s)}, StructureView(s) {}
};
static_assert(detail::move_only<Structure>, "Structure: a move-only owner");

/* Per-simplex user data for the p-simplices of one structure, indexed by handle (dense index),
 * as pmp and geometry-central do: a std::vector<T> of count(p) entries. A handle that is its
 * index (the nine structures, the ranges over indices) costs nothing to look up; a live
 * complex's lasting handle (from locate(), handle(p, i) with p > 0) is converted by one call
 * (tpx_simplex_index: its index until the next edit). On a Live from which vertices were
 * removed, vertex indices are slots: size vertex data with Live::vertex_slots(). */
template <class T>
class SimplexData {
 public:
  SimplexData(const StructureView &s, std::uint32_t p, const T &init = T())
      : s_(s.get()), dim_(p), data_(s.count(p), init) {}
  T &operator[](Simplex h) { return data_.at(check(h)); }
  const T &operator[](Simplex h) const { return data_.at(check(h)); }
  T &operator[](std::uint32_t i) { return data_[i]; }
  const T &operator[](std::uint32_t i) const { return data_[i]; }
  std::size_t size() const noexcept { return data_.size(); }
  std::vector<T> &data() noexcept { return data_; }

 private:
  std::size_t check(Simplex h) const {
    if (h.dim() != dim_) throw Error(TPX_STATUS_WRONG_HANDLE_KIND, "handle of another dimension");
    if ((h.raw().meta >> 8) != 0) {
      return detail::get<std::uint32_t>(tpx_simplex_index, s_, &h.raw());
    }
    return h.index();
  }
  const TpxStructure *s_;
  std::uint32_t dim_;
  std::vector<T> data_;
};

/* The standard decomposition into initial quasi-manifold components (owns a TpxDecomposition). */
class Decomposition {
 public:
  /* One component: its dimension, its top simplices over local vertex ids, and the original
   * vertex of each local vertex. Views into the Decomposition (valid while it lives). */
  struct Component {
    std::uint32_t dimension;
    RowsView tops;
    const std::uint32_t *original_ids;
    std::size_t local_vertex_count;
  };
  explicit Decomposition(const Complex &c)
      : d_(detail::get<TpxDecomposition *>(tpx_decomposition_build, c.get())) {}

  std::size_t size() const {
    return detail::get<std::size_t>(tpx_decomposition_component_count, d_.get());
  }
  Component operator[](std::size_t i) const {
    std::uint32_t dim = 0;
    const std::uint32_t *tops = nullptr, *orig = nullptr;
    std::size_t tops_len = 0, orig_len = 0;
    detail::check(
        tpx_decomposition_component(d_.get(), i, &dim, &tops, &tops_len, &orig, &orig_len));
    return Component{dim, RowsView(tops, tops_len, dim + 1), orig, orig_len};
  }
  const TpxDecomposition *get() const noexcept { return d_.get(); }

 private:
  detail::Owned<TpxDecomposition, tpx_decomposition_free> d_;
};
static_assert(detail::move_only<Decomposition>, "Decomposition: a move-only owner");

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
  const TpxUndo *get() const noexcept { return u_.get(); }

 private:
  detail::Owned<TpxUndo, tpx_undo_free> u_;
};
static_assert(detail::move_only<Undo>, "Undo: a move-only owner");

/* Handles over a borrowed array of TpxSimplex (answers of the live complex that last across
 * edits, unlike its indices). Iterating yields Simplex values; no allocation. */
class HandleSpan {
 public:
  class iterator {
   public:
    using iterator_category = std::random_access_iterator_tag;
    using value_type = Simplex;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = Simplex;
    iterator() = default;
    explicit iterator(const TpxSimplex *p) : p_(p) {}
    Simplex operator*() const noexcept { return Simplex(*p_); }
    iterator &operator++() noexcept {
      ++p_;
      return *this;
    }
    iterator operator++(int) noexcept {
      iterator t = *this;
      ++p_;
      return t;
    }
    difference_type operator-(const iterator &o) const noexcept { return p_ - o.p_; }
    bool operator==(const iterator &o) const noexcept { return p_ == o.p_; }
    bool operator!=(const iterator &o) const noexcept { return p_ != o.p_; }

   private:
    const TpxSimplex *p_ = nullptr;
  };
  HandleSpan(const TpxSimplex *h, std::size_t n) : h_(h), n_(n) {}
  iterator begin() const noexcept { return iterator(h_); }
  iterator end() const noexcept { return iterator(h_ + n_); }
  std::size_t size() const noexcept { return n_; }
  bool empty() const noexcept { return n_ == 0; }
  Simplex operator[](std::size_t i) const noexcept { return Simplex(h_[i]); }

 private:
  const TpxSimplex *h_;
  std::size_t n_;
};

/* An answer that owns its handles (returned by value); iterate it like a HandleSpan. */
class HandleList {
 public:
  HandleList() = default;
  explicit HandleList(std::vector<TpxSimplex> h) : h_(std::move(h)) {}
  HandleSpan::iterator begin() const noexcept { return span().begin(); }
  HandleSpan::iterator end() const noexcept { return span().end(); }
  std::size_t size() const noexcept { return h_.size(); }
  bool empty() const noexcept { return h_.empty(); }
  Simplex operator[](std::size_t i) const noexcept { return Simplex(h_[i]); }
  HandleSpan span() const noexcept { return HandleSpan(h_.data(), h_.size()); }

 private:
  std::vector<TpxSimplex> h_;
};

/* Cyclically ordered groups of handles (Live::fans_around, Live::around_edge); reuse one object
 * across calls to avoid allocation. */
class HandleFans {
 public:
  std::size_t size() const noexcept { return groups_; }
  /* Group k, in cyclic order. */
  HandleSpan operator[](std::size_t k) const noexcept {
    return HandleSpan(items_.data() + offsets_[k], offsets_[k + 1] - offsets_[k]);
  }
  bool closed(std::size_t k) const noexcept { return (flags_[k] & TPX_GROUP_CLOSED) != 0; }
  /* Consistently oriented and counter-clockwise by the input winding. */
  bool oriented(std::size_t k) const noexcept { return (flags_[k] & TPX_GROUP_ORIENTED) != 0; }
  /* Every group's simplices, group after group. */
  HandleSpan all() const noexcept { return HandleSpan(items_.data(), items_n_); }

 private:
  friend class Live;
  std::vector<TpxSimplex> items_;
  std::vector<std::uint32_t> offsets_, flags_;
  std::size_t items_n_ = 0, groups_ = 0;
};

/* Answers of many handles at once (Live::related_batch), in CSR form: batch[k] is the answer of
 * the k-th handle asked. Reuse one object across calls to avoid allocation. */
class HandleBatch {
 public:
  std::size_t size() const noexcept { return asked_; }
  bool empty() const noexcept { return asked_ == 0; }
  /* The answer of the k-th handle asked. */
  HandleSpan operator[](std::size_t k) const noexcept {
    return HandleSpan(items_.data() + offsets_[k], offsets_[k + 1] - offsets_[k]);
  }
  /* Every answer, one after the other. */
  HandleSpan all() const noexcept { return HandleSpan(items_.data(), items_n_); }

 private:
  friend class Live;
  std::vector<TpxSimplex> asked_raw_, items_;
  std::vector<std::uint32_t> offsets_;
  std::size_t asked_ = 0, items_n_ = 0;
};

/* A top simplex of a live complex named by its packed id, as its stars hold it: dimension
 * (>= 1) in the top 4 bits, slot below (the top ids of Live::top_id / tpx_live_top_vertices). */
class TopRef {
 public:
  constexpr TopRef() = default;
  constexpr explicit TopRef(std::uint32_t raw) noexcept : raw_(raw) {}
  constexpr TopRef(std::uint32_t p, std::uint32_t slot) noexcept : raw_(p << 28 | slot) {}
  constexpr std::uint32_t raw() const noexcept { return raw_; }
  constexpr std::uint32_t dim() const noexcept { return raw_ >> 28; }
  constexpr std::uint32_t slot() const noexcept { return raw_ & 0x0FFFFFFFu; }
  constexpr bool operator==(TopRef o) const noexcept { return raw_ == o.raw_; }
  constexpr bool operator!=(TopRef o) const noexcept { return raw_ != o.raw_; }
  constexpr bool operator<(TopRef o) const noexcept { return raw_ < o.raw_; }

 private:
  std::uint32_t raw_ = UINT32_MAX;
};

/* The tops through one vertex, lent from the star arena (in no particular order). */
class TopSpan {
 public:
  class iterator {
   public:
    using iterator_category = std::random_access_iterator_tag;
    using value_type = TopRef;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = TopRef;
    iterator() = default;
    explicit iterator(const std::uint32_t *p) : p_(p) {}
    TopRef operator*() const noexcept { return TopRef(*p_); }
    iterator &operator++() noexcept { ++p_; return *this; }
    iterator operator++(int) noexcept { iterator t = *this; ++p_; return t; }
    difference_type operator-(iterator o) const noexcept { return p_ - o.p_; }
    bool operator==(iterator o) const noexcept { return p_ == o.p_; }
    bool operator!=(iterator o) const noexcept { return p_ != o.p_; }

   private:
    const std::uint32_t *p_ = nullptr;
  };
  TopSpan() = default;
  TopSpan(const std::uint32_t *raw, std::size_t n) : raw_(raw), n_(n) {}
  iterator begin() const noexcept { return iterator(raw_); }
  iterator end() const noexcept { return iterator(raw_ + n_); }
  std::size_t size() const noexcept { return n_; }
  bool empty() const noexcept { return n_ == 0; }
  TopRef operator[](std::size_t i) const noexcept { return TopRef(raw_[i]); }

 private:
  const std::uint32_t *raw_ = nullptr;
  std::size_t n_ = 0;
};

/* Groups of tops in cyclic order, written by MeshView::fans_around and MeshView::around_edge
 * (the inline forms of tpx_cyclic on the mesh); reuse one per thread to avoid allocation. */
class TopFans {
 public:
  std::size_t size() const noexcept { return closed_.size(); }
  /* Group k's tops in cyclic order. */
  TopSpan operator[](std::size_t k) const noexcept {
    return TopSpan(items_.data() + offsets_[k], offsets_[k + 1] - offsets_[k]);
  }
  /* The group closes (its last top is joined to its first). */
  bool closed(std::size_t k) const noexcept { return closed_[k] != 0; }
  /* The group is consistently oriented and listed counter-clockwise by the input winding. */
  bool oriented(std::size_t k) const noexcept { return oriented_[k] != 0; }

 private:
  friend class MeshView;
  /* One top around the vertex or edge with its two sides: the link vertices through which it
   * can join its neighbours in the group (prev before next in the winding for a triangle). */
  struct Piece {
    std::uint32_t top, prev, next;
  };
  void clear() {
    items_.clear();
    offsets_.assign(1, 0);
    closed_.clear();
    oriented_.clear();
    pieces_.clear();
  }
  std::vector<std::uint32_t> items_, offsets_{0};
  std::vector<std::uint8_t> closed_, oriented_, seen_;
  std::vector<Piece> pieces_;
  std::vector<std::uint64_t> sides_;  // side vertex << 32 | piece
  std::vector<std::uint32_t> chain_;
};

/* Scratch of MeshView's one-ring passes (for_each_neighbour, the for_each_edge taking it): one
 * stamp per vertex slot (4 bytes each, grown on first use to the mesh's vertex_slots()), so a
 * candidate is tested for "seen" in O(1) instead of sorting the candidates; for_each_edge adds a
 * count per slot (4 bytes more). Keep one per thread and reuse it across queries and across
 * edits (it grows when the mesh does); a NeighbourMarks is not shared between threads. */
class NeighbourMarks {
 public:
  NeighbourMarks() = default;
  /* The bytes held. */
  std::size_t bytes() const noexcept {
    return (stamp_.capacity() + count_.capacity() + order_.capacity()) * sizeof(std::uint32_t);
  }

 private:
  friend class MeshView;
  /* Starts a query over n vertex slots: a fresh round, so every stamp reads "unseen". */
  std::uint32_t *begin(std::uint32_t n) {
    if (stamp_.size() < n) stamp_.resize(n, 0);
    if (++round_ == 0) {  // the counter wrapped: old stamps could read "seen"
      std::fill(stamp_.begin(), stamp_.end(), 0u);
      round_ = 1;
    }
    return stamp_.data();
  }
  std::vector<std::uint32_t> stamp_, count_, order_;
  std::uint32_t round_ = 0;
};

/* The live complex's own arrays (tpx_live_arrays), navigated inline: no library call per
 * query, no index beyond what the live complex stores, no allocation except the caller's
 * reused output vectors. Take one with Live::mesh(); it is valid until the next edit of the
 * topology (insert, remove, contract, split, add_vertex, compact) — setting coordinates writes
 * in place and keeps it valid — so take a new one after each edit (O(1)).
 *
 * What is stored: the top simplices per dimension in winding order (a removed slot is a
 * tombstone), and per vertex its star St*(v), the tops of dimension >= 1 through v. Every other
 * simplex is a vertex subset of a top. Costs below: k_v = |St*(v)|, d the dimension; "the
 * smallest star" is that of the simplex's vertex with the fewest tops.
 *
 * With the facet adjacency (Live::mesh_with_adjacency(), tpx_live_adjacency: an index of 4 bytes
 * per vertex of every top, built on request and dropped by the next edit), the tops across a
 * top's facets (FF, TT) are read rather than found by star scans. With the rings
 * (Live::mesh_with_rings(), tpx_live_rings: every vertex's one-ring and the tops at each of its
 * edges, 4 bytes per vertex slot and 8 per ring entry, built on request and dropped by the next
 * edit), for_each_neighbour, for_each_ring and for_each_edge read a row per vertex instead of
 * deduplicating its star's vertices: the same answers in the same order, no marks touched.
 *
 * Many threads may read one MeshView at once (it is a set of const pointers). */
class MeshView {
 public:
  MeshView() = default;
  explicit MeshView(const TpxLiveArrays &a) noexcept : a_(a) {}
  /* With the facet adjacency of the same state of the same live complex. */
  MeshView(const TpxLiveArrays &a, const TpxLiveAdjacency &adj) noexcept : a_(a), adj_(adj), has_adj_(true) {}
  /* With either index or both (NULL: without it), each of the same state of the same live
   * complex as `a`. */
  MeshView(const TpxLiveArrays &a, const TpxLiveAdjacency *adj, const TpxLiveRings *rings) noexcept
      : a_(a), has_adj_(adj != nullptr), has_rings_(rings != nullptr) {
    if (adj) adj_ = *adj;
    if (rings) rings_ = *rings;
  }
  bool has_adjacency() const noexcept { return has_adj_; }
  bool has_rings() const noexcept { return has_rings_; }
  /* With has_rings(): R_{0,0}(v), v's neighbours in for_each_neighbour's order, as stored
   * (empty for a removed or isolated vertex). O(1), no copy. */
  SimplexView ring(std::uint32_t v) const noexcept {
    const std::uint32_t b = rings_.offsets[v];
    return SimplexView(rings_.neighbours + b, rings_.offsets[v + 1] - b);
  }
  /* With has_rings(): for each entry of ring(v), the live tops (any dimension >= 1) holding
   * that edge. O(1), no copy. */
  SimplexView ring_tops(std::uint32_t v) const noexcept {
    const std::uint32_t b = rings_.offsets[v];
    return SimplexView(rings_.held + b, rings_.offsets[v + 1] - b);
  }
  /* What lies across the facet of live top t opposite its i-th vertex (i <= t.dim()), among the
   * live tops of t's dimension: TPX_ACROSS_NONE, the one other top's packed id, or
   * TPX_ACROSS_MANY (a non-manifold facet). Needs has_adjacency(). O(1). */
  std::uint32_t across(TopRef t, std::uint32_t i) const noexcept {
    return adj_.across[t.dim()][std::size_t(t.slot()) * (t.dim() + 1) + i];
  }

  std::uint32_t vertex_slots() const noexcept { return a_.vertex_slots; }
  /* Slot v holds a live vertex. O(1). */
  bool is_vertex(std::uint32_t v) const noexcept { return v < a_.vertex_slots && a_.alive[v]; }
  std::size_t coord_dim() const noexcept { return a_.coord_dim; }
  /* Vertex v's coord_dim() numbers. O(1). */
  const double *coords(std::uint32_t v) const noexcept { return a_.coords + v * a_.coord_dim; }
  std::uint32_t generation() const noexcept { return a_.generation; }

  /* Slots of dimension p's top table (live or tombstoned): iterate s < slots(p) and skip
   * !is_top(TopRef(p, s)). O(1). */
  std::uint32_t slots(std::uint32_t p) const noexcept {
    return p == 0 || p > 15 ? 0 : static_cast<std::uint32_t>(a_.top_lens[p] / (p + 1));
  }
  /* t names a live top (its slot exists and is not a tombstone). O(1). */
  bool is_top(TopRef t) const noexcept {
    const std::uint32_t p = t.dim();
    return p >= 1 && t.slot() < slots(p) && (a_.tops[p][t.slot() * (p + 1)] >> 31) == 0;
  }
  /* The vertices of live top t in stored order: the input winding (b replaced by a in place
   * after a contraction). O(1), no copy. */
  SimplexView vertices(TopRef t) const noexcept {
    const std::uint32_t p = t.dim();
    return SimplexView(a_.tops[p] + std::size_t(t.slot()) * (p + 1), p + 1);
  }
  /* St*(v): the live tops of dimension >= 1 through vertex slot v < vertex_slots(), in no
   * particular order (empty for an isolated vertex and for a removed slot). O(1), no copy. */
  TopSpan star(std::uint32_t v) const noexcept {
    const std::uint32_t *b = a_.star_blocks + 3 * std::size_t(v);
    return TopSpan(a_.star_words + b[0], b[1]);
  }
  /* Whether top t holds vertex v. O(d). */
  bool holds(TopRef t, std::uint32_t v) const noexcept {
    for (std::uint32_t w : vertices(t))
      if (w == v) return true;
    return false;
  }
  /* Calls f(TopRef) for every live top holding every vertex of s[0..n) (n >= 1, live distinct
   * vertices; any order): the tops of the simplex's star. O(d·n·k) over the smallest star. */
  template <class F>
  void for_each_top_holding(const std::uint32_t *s, std::size_t n, F &&f) const {
    std::uint32_t best = s[0];
    for (std::size_t i = 1; i < n; ++i)
      if (star(s[i]).size() < star(best).size()) best = s[i];
    for (TopRef t : star(best)) {
      bool all = true;
      for (std::size_t i = 0; i < n && all; ++i) all = s[i] == best || holds(t, s[i]);
      if (all) f(t);
    }
  }
  /* The number of live tops of dimension p holding all of s[0..n) (p = 0: every dimension).
   * For a pure triangle mesh, with s an edge and p = 2: 1 on the boundary, 2 inside, more at a
   * non-manifold edge. Cost as for_each_top_holding, no allocation. */
  std::size_t tops_holding(const std::uint32_t *s, std::size_t n, std::uint32_t p = 0) const {
    std::size_t k = 0;
    for_each_top_holding(s, n, [&](TopRef t) { k += p == 0 || t.dim() == p; });
    return k;
  }
  /* Whether s[0..n) (live distinct vertices) is a simplex of the complex. O(d·n·k). */
  bool is_simplex(const std::uint32_t *s, std::size_t n) const {
    if (n == 1) return is_vertex(s[0]);
    bool found = false;
    for_each_top_holding(s, n, [&](TopRef) { found = true; });
    return found;
  }
  /* Whether the simplex s[0..n) (live distinct vertices of a simplex of the mesh) lies on the
   * boundary, as tpx_simplex_test's 0 says: s, or a simplex of its star, is not a top and has
   * exactly one coface one dimension up (a surface's boundary edges, their vertices and
   * triangles; a dangling end of a wire). `scratch` is reused. O(Σ_τ k·d) over the simplices τ
   * of the star, each τ's cofaces from its smallest star. */
  bool is_boundary(const std::uint32_t *s, std::size_t n, std::vector<std::uint32_t> &scratch) const {
    // The simplices of the star: s with every subset of a top's other vertices.
    bool found = false;
    for_each_top_holding(s, n, [&](TopRef t) {
      if (found) return;
      std::uint32_t rest[16];
      std::size_t r = 0;
      for (std::uint32_t w : vertices(t))
        if (std::find(s, s + n, w) == s + n) rest[r++] = w;
      for (std::uint32_t mask = 0; mask < (1u << r) && !found; ++mask) {
        scratch.assign(s, s + n);
        for (std::size_t i = 0; i < r; ++i)
          if (mask >> i & 1) scratch.push_back(rest[i]);
        found = one_coface_up(scratch);
      }
    });
    return found;
  }
  /* Whether the simplex s[0..n) is manifold, as tpx_simplex_test's 1 says: its star is pure
   * (every top through s has the same dimension) and its link (those tops without s) is a
   * connected pseudo-manifold: for a link of points, one or two; else every facet of the link
   * in one or two of its simplices, and the link connected through them. A top is manifold.
   * `scratch` is reused (plus a union-find of k entries). O(k²·d³) over the tops through s (k
   * of them): for the small stars of meshes. */
  bool is_manifold(const std::uint32_t *s, std::size_t n, std::vector<std::uint32_t> &scratch) const {
    scratch.clear();
    std::size_t arity = 0;
    bool pure = true;
    for_each_top_holding(s, n, [&](TopRef t) {
      const std::size_t k = t.dim() + 1 - n;
      if (scratch.empty() && arity == 0) arity = k;
      pure = pure && k == arity;
      for (std::uint32_t w : vertices(t))
        if (std::find(s, s + n, w) == s + n) scratch.push_back(w);
    });
    if (!pure) return false;
    if (arity == 0 || scratch.empty()) return true;
    const std::size_t m = scratch.size() / arity;
    if (arity == 1) return m <= 2;
    // Rows i, j share a facet when they have arity - 1 vertices in common; a facet of row i in
    // more than one other row is in three rows or more.
    const auto common = [&](std::size_t i, std::size_t j) {
      std::size_t c = 0;
      for (std::size_t a = 0; a < arity; ++a)
        for (std::size_t b = 0; b < arity; ++b) c += scratch[i * arity + a] == scratch[j * arity + b];
      return c;
    };
    std::vector<std::uint32_t> root(m);
    for (std::size_t i = 0; i < m; ++i) root[i] = static_cast<std::uint32_t>(i);
    const auto find = [&](std::uint32_t x) {
      while (root[x] != x) x = root[x] = root[root[x]];
      return x;
    };
    for (std::size_t i = 0; i < m; ++i) {
      // For each facet of row i (without its entry a), how many other rows hold it.
      for (std::size_t a = 0; a < arity; ++a) {
        std::size_t holders = 0;
        for (std::size_t j = 0; j < m; ++j) {
          if (j == i || common(i, j) != arity - 1) continue;
          bool has = true;
          for (std::size_t b = 0; b < arity && has; ++b)
            if (b != a) has = std::find(&scratch[j * arity], &scratch[j * arity] + arity, scratch[i * arity + b]) !=
                              &scratch[j * arity] + arity;
          if (!has) continue;
          if (++holders > 1) return false;
          root[find(static_cast<std::uint32_t>(i))] = find(static_cast<std::uint32_t>(j));
        }
      }
    }
    for (std::size_t i = 1; i < m; ++i)
      if (find(static_cast<std::uint32_t>(i)) != find(0)) return false;
    return true;
  }
  /* R_{0,0}(v): calls f(w) once for every vertex w sharing an edge with v (any top through v
   * holds it), in the order the star's tops first name them (no sorting; see neighbours() for
   * ascending order). `marks` is this thread's scratch (see NeighbourMarks). O(d·k_v), no
   * allocation once `marks` has grown to vertex_slots(). The one-ring for smoothing, valences
   * and tetrahedral vertex stars. With has_rings(): the stored ring, O(|ring|), `marks`
   * untouched. */
  template <class F>
  void for_each_neighbour(std::uint32_t v, NeighbourMarks &marks, F &&f) const {
    if (has_rings_) {
      for (std::uint32_t w : ring(v)) f(w);
      return;
    }
    std::uint32_t *seen = marks.begin(a_.vertex_slots);
    const std::uint32_t r = marks.round_;
    seen[v] = r;
    const auto visit = [&](std::uint32_t w) {
      if (seen[w] != r) {
        seen[w] = r;
        f(w);
      }
    };
    for (TopRef t : star(v)) {
      const std::uint32_t p = t.dim();
      const std::uint32_t *q = a_.tops[p] + std::size_t(t.slot()) * (p + 1);
      if (p == 2) {  // a surface's case, unrolled
        visit(q[0]);
        visit(q[1]);
        visit(q[2]);
      } else {
        for (std::uint32_t i = 0; i <= p; ++i) visit(q[i]);
      }
    }
  }
  /* Whole-mesh pass: calls f(v, ring) for every live vertex v, ascending, with ring its
   * neighbours R_{0,0}(v) in for_each_neighbour's order, lent from `marks` until f returns
   * (a SimplexView of ids; empty for an isolated vertex). The batch form of for_each_neighbour
   * for passes over every vertex (smoothing, valences, vertex normals): it reads ahead of the
   * vertex it is at (the rows of later vertices' tops, then their vertices' stamps and
   * coordinates) on meshes larger than the caches (from 2^17 vertex slots), where it runs
   * 1.4-2x faster than a loop calling for_each_neighbour per vertex; on smaller meshes, whose
   * arrays the caches hold, it costs what that loop costs to a tenth (writing out each ring;
   * docs/benchmarks.md, "The mesh"). f may read the mesh and write coordinates through
   * Live::set_coords (in place: the view stays valid), not edit the topology. O(Σ_v d·k_v),
   * no allocation once `marks` has grown to vertex_slots() and the largest ring. With
   * has_rings(): each stored ring in turn, O(Σ_v |ring(v)|), `marks` untouched (10 smoothing
   * rounds 1.5-2.3x faster than over the stars, once the rings are built; docs/benchmarks.md,
   * "The mesh"). */
  template <class F>
  void for_each_ring(NeighbourMarks &marks, F &&f) const {
    if (has_rings_) {
      for (std::uint32_t v = 0; v < a_.vertex_slots; ++v)
        if (a_.alive[v]) f(v, ring(v));
      return;
    }
    std::vector<std::uint32_t> &ring = marks.order_;
    std::uint32_t *seen = marks.begin(a_.vertex_slots);  // grown once: the pointer holds
    const double *coords = a_.coord_dim ? a_.coords : nullptr;
    const bool ahead = a_.vertex_slots >= kReadAheadFrom;
    for (std::uint32_t v = 0; v < a_.vertex_slots; ++v) {
      if (ahead) read_ahead(v, [&](std::uint32_t w) {
        prefetch(seen + w);
        if (coords) prefetch(coords + std::size_t(w) * a_.coord_dim);
      });
      if (!a_.alive[v]) continue;
      // Room for every candidate first, so that the ring is written without a check per id: a
      // top names at most 15 others, so only a star of more than size/15 tops is counted.
      const TopSpan st = star(v);
      if (ring.size() < 15 * st.size()) {
        std::size_t room = 0;
        for (TopRef t : st) room += t.dim();
        if (ring.size() < room) ring.resize(std::max<std::size_t>(room, 1024));
      }
      std::uint32_t *out = ring.data();
      std::uint32_t n = 0;
      for_each_neighbour(v, marks, [&](std::uint32_t w) { out[n++] = w; });
      f(v, SimplexView(out, n));
    }
  }
  /* R_{0,0}(v): the vertices sharing an edge with v, ascending, into `out` (reused). O(d·k_v +
   * m log m), m the candidates. */
  void neighbours(std::uint32_t v, std::vector<std::uint32_t> &out) const {
    out.clear();
    const TopSpan st = star(v);
    if (st.size() > 16) {  // a hub: sort once
      for (TopRef t : st)
        for (std::uint32_t w : vertices(t))
          if (w != v) out.push_back(w);
      std::sort(out.begin(), out.end());
      out.erase(std::unique(out.begin(), out.end()), out.end());
      return;
    }
    // A typical star (a handful of tops): insert each candidate in place, ascending, once.
    for (TopRef t : st)
      for (std::uint32_t w : vertices(t)) {
        if (w == v) continue;
        std::size_t i = out.size();
        while (i > 0 && out[i - 1] > w) --i;
        if (i > 0 && out[i - 1] == w) continue;
        out.insert(out.begin() + static_cast<std::ptrdiff_t>(i), w);
      }
  }
  /* Calls f(TopRef u) for every live top u of t's dimension sharing a facet (all but one
   * vertex) with live top t: for a pure triangle mesh the faces across t's edges (FF), for a
   * tetrahedral mesh the tetrahedra across its triangles (TT); across a non-manifold facet
   * every other top through it. Each u once (two distinct p-simplices share at most one facet),
   * in no particular order. Two star scans: the tops through x (t's vertex of smallest star)
   * sharing p vertices with t, then those through y (the next smallest) that miss x — the
   * ones across the facet opposite x. O(d²·(k_x + k_y)), no allocation; for edges and
   * triangles whose vertices' stars hold at most 16 tops, whether a top holds a vertex is read
   * from that vertex's star (O(d·k²), the stars' cache lines only). With the facet adjacency
   * (has_adjacency()): O(d), plus the smallest star's scan at each non-manifold facet. */
  template <class F>
  void for_each_adjacent_top(TopRef t, F &&f) const {
    const SimplexView vt = vertices(t);
    const std::uint32_t p = t.dim();
    if (has_adj_) {
      for (std::uint32_t i = 0; i <= p; ++i) {
        const std::uint32_t e = across(t, i);
        if (e == TPX_ACROSS_NONE) continue;
        if (e != TPX_ACROSS_MANY) {
          f(TopRef(e));
          continue;
        }
        // A non-manifold facet: every other top of dimension p through it.
        std::uint32_t facet[16];
        std::size_t n = 0;
        for (std::uint32_t j = 0; j <= p; ++j)
          if (j != i) facet[n++] = vt[j];
        for_each_top_holding(facet, n, [&](TopRef u) {
          if (u.dim() == p && u != t) f(u);
        });
      }
      return;
    }
    std::uint32_t x = vt[0], y = vt[1];
    if (star(y).size() < star(x).size()) std::swap(x, y);
    for (std::uint32_t i = 2; i <= p; ++i) {
      const std::size_t k = star(vt[i]).size();
      if (k < star(x).size()) {
        y = x;
        x = vt[i];
      } else if (k < star(y).size()) {
        y = vt[i];
      }
    }
    bool small = p <= 2;
    for (std::uint32_t w : vt) small = small && star(w).size() <= 16;
    if (small) {
      // Edges and triangles whose stars are small (a surface's usual vertices): whether u holds
      // w is a scan of w's star, in cache lines already read, rather than a load of u's
      // vertices from elsewhere in the table.
      const auto in_star = [&](std::uint32_t w, TopRef u) {
        for (TopRef s : star(w))
          if (s == u) return true;
        return false;
      };
      const auto one_miss = [&](TopRef u) {
        std::uint32_t missed = 0;
        for (std::uint32_t w : vt)
          if (!in_star(w, u) && ++missed > 1) return false;
        return missed == 1;
      };
      for (TopRef u : star(x))
        if (u.dim() == p && u != t && one_miss(u)) f(u);
      for (TopRef u : star(y))
        if (u.dim() == p && !in_star(x, u) && one_miss(u)) f(u);
      return;
    }
    const auto shares_a_facet = [&](TopRef u) {
      std::uint32_t common = 0;
      for (std::uint32_t w : vertices(u)) common += holds(t, w);
      return common == p;
    };
    for (TopRef u : star(x))
      if (u.dim() == p && u != t && shares_a_facet(u)) f(u);
    for (TopRef u : star(y))
      if (u.dim() == p && !holds(u, x) && shares_a_facet(u)) f(u);
  }
  /* The same into `out` (reused). */
  void adjacent_tops(TopRef t, std::vector<TopRef> &out) const {
    out.clear();
    for_each_adjacent_top(t, [&](TopRef u) { out.push_back(u); });
  }
  /* The manifold fans of top triangles around vertex v into `out` (reused), as tpx_cyclic with
   * q = 0 gives them on a complex of dimension <= 2: the triangles joined through the edges vx
   * that exactly two of them hold, each group from one end (or, closed, from its lowest top),
   * counter-clockwise by the input winding where the group is oriented; groups by ascending
   * lowest top. In a mixed complex only the top triangles at v take part (a tetrahedron's
   * triangles are not tops). O(k_v log k_v), no allocation once `out` is warm. */
  void fans_around(std::uint32_t v, TopFans &out) const {
    out.clear();
    for (TopRef t : star(v)) {
      if (t.dim() != 2) continue;
      const SimplexView w = vertices(t);
      const std::uint32_t at = w[0] == v ? 0 : w[1] == v ? 1 : 2;
      out.pieces_.push_back({t.raw(), w[(at + 1) % 3], w[(at + 2) % 3]});
    }
    chains(out, true);
  }
  /* The tops of dimension q (2 or 3) through the edge {a, b} into `out` (reused), as tpx_cyclic
   * with q gives them on a complex of dimension q: tetrahedra (q = 3) joined through the
   * triangles abx that exactly two of them hold, in radial order, unoriented; triangles
   * (q = 2) as one group ascending, closed when there are two or more (a 2-complex has no
   * radial order without geometry; empty when none holds the edge). Only tops take part.
   * O(k log k) over the smaller star. */
  void around_edge(std::uint32_t a, std::uint32_t b, std::uint32_t q, TopFans &out) const {
    out.clear();
    const std::uint32_t e[2] = {a, b};
    for_each_top_holding(e, 2, [&](TopRef t) {
      if (t.dim() != q) return;
      std::uint32_t side[2] = {0, 0}, k = 0;
      for (std::uint32_t w : vertices(t))
        if (w != a && w != b && k < 2) side[k++] = w;
      out.pieces_.push_back({t.raw(), side[0], side[1]});
    });
    if (q == 3) {
      chains(out, false);
      return;
    }
    // One group, as tpx_cyclic gives it (empty for an edge no top triangle holds).
    std::sort(out.pieces_.begin(), out.pieces_.end(),
              [](const TopFans::Piece &x, const TopFans::Piece &y) { return x.top < y.top; });
    for (const TopFans::Piece &p : out.pieces_) out.items_.push_back(p.top);
    out.offsets_.push_back(static_cast<std::uint32_t>(out.items_.size()));
    out.closed_.push_back(out.pieces_.size() >= 2);
    out.oriented_.push_back(0);
  }
  /* Whole-mesh pass: calls f(a, b, m) once for every edge {a, b} (a < b) with m the number of
   * live top p-simplices holding it (p >= 1; edges held only by tops of other dimensions get
   * m = 0). With p = 2 on a triangle mesh: m == 1 on the boundary, m > 2 at a non-manifold
   * edge. `scratch` is reused. O(Σ_v d·k_v log). */
  template <class F>
  void for_each_edge(std::uint32_t p, std::vector<std::uint64_t> &scratch, F &&f) const {
    for (std::uint32_t a = 0; a < a_.vertex_slots; ++a) {
      if (!a_.alive[a]) continue;
      scratch.clear();
      for (TopRef t : star(a))
        for (std::uint32_t w : vertices(t))
          if (w > a) scratch.push_back(std::uint64_t(w) << 1 | (t.dim() == p));
      std::sort(scratch.begin(), scratch.end());
      for (std::size_t i = 0; i < scratch.size();) {
        const std::uint32_t b = static_cast<std::uint32_t>(scratch[i] >> 1);
        std::size_t m = 0;
        for (; i < scratch.size() && (scratch[i] >> 1) == b; ++i) m += scratch[i] & 1;
        f(a, b, m);
      }
    }
  }
  /* The same pass with a NeighbourMarks instead of sorting: f(a, b, m) once for every edge
   * {a, b} (a < b), a ascending, the b of one a in the order a's star first names them.
   * O(Σ_v d·k_v), no allocation once `marks` has grown to vertex_slots(); it reads ahead of
   * the vertex it is at, as for_each_ring does. With has_rings() on a complex whose tops all
   * have dimension p (the rings' top_dims is 1 << p, so an edge's top count is its p-count):
   * the stored rings and counts, O(Σ_v |ring(v)|), `marks` untouched; otherwise the pass
   * above. */
  template <class F>
  void for_each_edge(std::uint32_t p, NeighbourMarks &marks, F &&f) const {
    if (has_rings_ && p < 32 && rings_.top_dims == (1u << p)) {
      for (std::uint32_t a = 0; a < a_.vertex_slots; ++a) {
        const SimplexView ring = this->ring(a), tops = ring_tops(a);
        for (std::size_t i = 0; i < ring.size(); ++i)
          if (ring[i] > a) f(a, ring[i], std::size_t(tops[i]));
      }
      return;
    }
    if (marks.count_.size() < a_.vertex_slots) marks.count_.resize(a_.vertex_slots);
    std::uint32_t *count = marks.count_.data();
    std::vector<std::uint32_t> &order = marks.order_;
    std::uint32_t *seen = marks.begin(a_.vertex_slots);  // grown once: the pointer holds
    const bool ahead = a_.vertex_slots >= kReadAheadFrom;
    for (std::uint32_t a = 0; a < a_.vertex_slots; ++a) {
      if (ahead) read_ahead(a, [&](std::uint32_t w) {
        prefetch(seen + w);
        prefetch(count + w);
      });
      if (!a_.alive[a]) continue;
      marks.begin(a_.vertex_slots);
      const std::uint32_t r = marks.round_;
      order.clear();
      const auto visit = [&](std::uint32_t w, std::uint32_t of_p) {
        if (w <= a) return;
        if (seen[w] != r) {
          seen[w] = r;
          count[w] = 0;
          order.push_back(w);
        }
        count[w] += of_p;
      };
      for (TopRef t : star(a)) {
        const std::uint32_t q = t.dim(), of_p = q == p;
        const std::uint32_t *s = a_.tops[q] + std::size_t(t.slot()) * (q + 1);
        if (q == 2) {  // a surface's case, unrolled
          visit(s[0], of_p);
          visit(s[1], of_p);
          visit(s[2], of_p);
        } else {
          for (std::uint32_t i = 0; i <= q; ++i) visit(s[i], of_p);
        }
      }
      for (std::uint32_t b : order) f(a, b, std::size_t(count[b]));
    }
  }
  /* Whole-mesh pass: calls f(t, u) for every ordered pair of live top triangles sharing an
   * edge (each unordered pair twice: (t, u) and (u, t)) — every face's neighbour faces as one
   * batch, found per vertex rather than per face. `scratch` is reused. O(Σ_v k_v log k_v +
   * pairs). */
  template <class F>
  void for_each_adjacent_triangle_pair(std::vector<std::uint64_t> &scratch, F &&f) const {
    for (std::uint32_t a = 0; a < a_.vertex_slots; ++a) {
      if (!a_.alive[a]) continue;
      scratch.clear();
      for (TopRef t : star(a)) {
        if (t.dim() != 2) continue;
        for (std::uint32_t w : vertices(t))
          if (w > a) scratch.push_back(std::uint64_t(w) << 32 | t.raw());
      }
      std::sort(scratch.begin(), scratch.end());
      for (std::size_t i = 0; i < scratch.size();) {
        std::size_t j = i;
        while (j < scratch.size() && (scratch[j] >> 32) == (scratch[i] >> 32)) ++j;
        for (std::size_t x = i; x < j; ++x)
          for (std::size_t y = i; y < j; ++y)
            if (x != y)
              f(TopRef(static_cast<std::uint32_t>(scratch[x])),
                TopRef(static_cast<std::uint32_t>(scratch[y])));
        i = j;
      }
    }
  }
  const TpxLiveArrays &arrays() const noexcept { return a_; }

 private:
  /* Groups out.pieces_ into chains joined through sides held by exactly two pieces (pieces
   * sorted by top first), each walked from an end, a cycle rotated to its lowest top; with
   * `wound`, a chain whose pieces follow the winding (each next side the following prev side)
   * is listed that way and marked oriented. The inline form of the library's cyclic walk. */
  static void chains(TopFans &out, bool wound) {
    using Piece = TopFans::Piece;
    std::vector<Piece> &pc = out.pieces_;
    std::sort(pc.begin(), pc.end(), [](const Piece &x, const Piece &y) { return x.top < y.top; });
    const std::size_t n = pc.size();
    out.sides_.clear();
    for (std::size_t i = 0; i < n; ++i) {
      out.sides_.push_back(std::uint64_t(pc[i].prev) << 32 | i);
      out.sides_.push_back(std::uint64_t(pc[i].next) << 32 | i);
    }
    std::sort(out.sides_.begin(), out.sides_.end());
    const std::vector<std::uint64_t> &sides = out.sides_;
    constexpr std::size_t none = static_cast<std::size_t>(-1);
    // The other piece holding side x when exactly two do, else none.
    const auto joined = [&](std::size_t i, std::uint32_t x) -> std::size_t {
      const auto lo = std::lower_bound(sides.begin(), sides.end(), std::uint64_t(x) << 32);
      const auto hi = std::lower_bound(lo, sides.end(), (std::uint64_t(x) + 1) << 32);
      if (hi - lo != 2) return none;
      const std::size_t p = static_cast<std::uint32_t>(*lo), r = static_cast<std::uint32_t>(*(lo + 1));
      return p == i ? r : p;
    };
    // From `cur`, entered through side `came`, the side it leaves by and the piece there.
    const auto step = [&](std::size_t cur, std::uint32_t came, std::uint32_t &side) {
      side = pc[cur].prev == came ? pc[cur].next : pc[cur].prev;
      return joined(cur, side);
    };
    out.seen_.assign(n, 0);
    std::vector<std::uint32_t> &chain = out.chain_;
    for (std::size_t start = 0; start < n; ++start) {
      if (out.seen_[start]) continue;
      // Back to an end of the chain (or around a cycle to `start`).
      std::size_t first = start;
      std::uint32_t came = pc[start].next, side = 0;
      for (std::size_t j; (j = step(first, came, side)) != none && j != start;) {
        came = side;
        first = j;
      }
      chain.assign(1, static_cast<std::uint32_t>(first));
      out.seen_[first] = 1;
      std::size_t cur = first;
      came = joined(first, pc[first].prev) == none ? pc[first].prev : pc[first].next;
      for (std::size_t j; (j = step(cur, came, side)) != none && !out.seen_[j];) {
        out.seen_[j] = 1;
        chain.push_back(static_cast<std::uint32_t>(j));
        cur = j;
        came = side;
      }
      const bool closed = chain.size() >= 3 && joined(chain[0], pc[chain[0]].prev) != none &&
                          joined(chain[0], pc[chain[0]].next) != none;
      if (closed) std::rotate(chain.begin(), std::min_element(chain.begin(), chain.end()), chain.end());
      bool oriented = false;
      if (wound) {
        const auto forward = [&] {
          const std::size_t m = chain.size(), steps = closed ? m : m - 1;
          for (std::size_t i = 0; i < steps; ++i)
            if (pc[chain[i]].next != pc[chain[(i + 1) % m]].prev) return false;
          return true;
        };
        const auto reverse = [&] { std::reverse(chain.begin() + (closed ? 1 : 0), chain.end()); };
        oriented = forward();
        if (!oriented) {
          reverse();
          oriented = forward();
          if (!oriented) reverse();
        }
      }
      for (std::uint32_t i : chain) out.items_.push_back(pc[i].top);
      out.offsets_.push_back(static_cast<std::uint32_t>(out.items_.size()));
      out.closed_.push_back(closed);
      out.oriented_.push_back(oriented);
    }
  }
  /* Whether the simplex tau (distinct vertices) is not a top and has exactly one coface one
   * dimension up: the tops through it add exactly one distinct vertex among them. */
  bool one_coface_up(const std::vector<std::uint32_t> &tau) const {
    bool top = false, two = false;
    std::uint32_t first = 0xffffffffu;
    for_each_top_holding(tau.data(), tau.size(), [&](TopRef t) {
      if (t.dim() + 1 == tau.size()) top = true;
      for (std::uint32_t w : vertices(t)) {
        if (std::find(tau.begin(), tau.end(), w) != tau.end()) continue;
        if (first == 0xffffffffu) first = w;
        else if (w != first) two = true;
      }
    });
    return !top && !two && first != 0xffffffffu;
  }

  /* Read-ahead of the whole-mesh passes (for_each_ring, for_each_edge), which visit vertex
   * slots in order: the rows of the tops through slot v + kRowsAhead are asked from memory,
   * then, once those rows have arrived, what the rows of slot v + kRingAhead name (stamps,
   * counts, coordinates). A star's rows and its vertices' data are scattered reads; without
   * the hints the loop waits for them one vertex at a time (on a 1.2M-triangle mesh these
   * passes ran 1.4–2x faster with them; docs/benchmarks.md, "The mesh"). Only from
   * kReadAheadFrom vertex slots (a mesh's arrays then outgrow the caches, about 90 bytes a
   * vertex for a triangle mesh): below it every read hits the cache and reading the stars a
   * second time only costs (up to 2x on 6.5k vertices). */
  static constexpr std::uint32_t kRowsAhead = 8, kRingAhead = 4, kReadAheadFrom = 1u << 17;
  static void prefetch(const void *p) noexcept {
    // An asm statement where it can be one: GCC 12's mod/ref analysis counts __builtin_prefetch
    // as no effect at all, takes read_ahead for a pure call and deletes it whole. A prefetch
    // never faults, whatever the address.
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
    __asm__ volatile("prefetcht0 %0" : : "m"(*static_cast<const char *>(p)));
#elif (defined(__GNUC__) || defined(__clang__)) && defined(__aarch64__)
    __asm__ volatile("prfm pldl1keep, %0" : : "Q"(*static_cast<const char *>(p)));
#elif defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p);
#else
    (void)p;
#endif
  }
  /* Before visiting slot v of an in-order pass: asks for the rows of the tops of later slots,
   * and calls ahead(w) for every vertex w of the tops through slot v + kRingAhead. */
  template <class G>
  void read_ahead(std::uint32_t v, G &&ahead) const noexcept {
    if (v + kRowsAhead < a_.vertex_slots)
      for (TopRef t : star(v + kRowsAhead)) prefetch(vertices(t).data());
    if (v + kRingAhead < a_.vertex_slots)
      for (TopRef t : star(v + kRingAhead))
        for (std::uint32_t w : vertices(t)) ahead(w);
  }

  TpxLiveArrays a_{};
  TpxLiveAdjacency adj_{};
  TpxLiveRings rings_{};
  bool has_adj_ = false, has_rings_ = false;
};

/* An updatable complex (any dimension, non-manifold): insert/remove top simplices, contract
 * edges (link-checked or free), split (undo), move vertices. Edits need exclusive access; a
 * refused edit throws Error (status says why: TPX_STATUS_NOT_AN_EDGE,
 * TPX_STATUS_LINK_CONDITION_FAILS, ...) and leaves the complex unchanged. */
class Live {
 public:
  explicit Live(const Complex &c)
      : l_(detail::get<TpxLive *>(tpx_live_from_complex, c.get())) {}
  /* The mesh of any input file (tpx_live_from_file): a plain mesh file (the usual case) read
   * straight into the live complex with no frozen complex built; a .tpx as open(); anything
   * else normalised first. The same live complex as Live(Complex::from_file(path)). With
   * `triangulate`, convex planar polygons are fanned into triangles (others refused). */
  static Live from_file(const std::string &path, bool verify = false, bool triangulate = false) {
    return Live(detail::get<TpxLive *>(tpx_live_from_file, path.c_str(),
                                       (verify ? TPX_OPEN_VERIFY : 0u) |
                                           (triangulate ? TPX_OPEN_TRIANGULATE : 0u)));
  }
  /* An editable live complex from a .tpx file: the saved live complex if it holds one, else one
   * built from its saved complex. Arrays are copied out (editable): O(size). */
  static Live open(const std::string &path, bool verify = false) {
    return Live(
        detail::get<TpxLive *>(tpx_live_open, path.c_str(), verify ? TPX_OPEN_VERIFY : 0u));
  }
  /* Saves a compacted copy (this live complex is unchanged, its handles stay valid): O(size). */
  void save(const std::string &path) const { detail::check(tpx_live_save(l_.get(), path.c_str())); }
  std::uint32_t vertex_slots() const {
    return detail::get<std::uint32_t>(tpx_live_vertex_slots, l_.get());
  }
  std::uint32_t vertex_count() const {
    return detail::get<std::uint32_t>(tpx_live_vertex_count, l_.get());
  }
  bool is_vertex(std::uint32_t v) const {
    return detail::get<std::uint32_t>(tpx_live_is_vertex, l_.get(), v) != 0;
  }
  std::uint32_t dimension() const {
    return detail::get<std::uint32_t>(tpx_live_dimension, l_.get());
  }
  std::size_t top_count(std::uint32_t p) const {
    return detail::get<std::size_t>(tpx_live_top_count, l_.get(), p);
  }
  /* Live top p-simplices (p >= 1), vertices in stored (winding) order. */
  Rows top_simplices(std::uint32_t p) const {
    std::vector<std::uint32_t> buf;  // empty: the first call asks for the length
    detail::fill(buf, tpx_live_top_simplices, l_.get(), p);
    return Rows(std::move(buf), p + 1);
  }
  /* R_{p,q}(simplex), rows of q+1 ascending ids, lexicographic. */
  Rows relation(const std::vector<std::uint32_t> &simplex, std::uint32_t q) const {
    std::vector<std::uint32_t> buf(64);
    detail::fill(buf, tpx_live_relation, l_.get(), simplex.data(), simplex.size(), q);
    return Rows(std::move(buf), q + 1);
  }
  std::vector<double> coords(std::uint32_t v) const {
    std::vector<double> xyz(detail::get<std::size_t>(tpx_live_coord_dim, l_.get()));
    std::size_t len = 0;
    detail::check(tpx_live_coords(l_.get(), v, xyz.data(), xyz.size(), &len));
    return xyz;
  }
  std::size_t coord_dim() const { return detail::get<std::size_t>(tpx_live_coord_dim, l_.get()); }
  /* Moves live vertex v (coord_dim() finite numbers). Not an edit of the topology: handles,
   * indices and views stay valid. */
  void set_coords(std::uint32_t v, const std::vector<double> &xyz) {
    detail::check(tpx_live_set_coords(l_.get(), v, xyz.data(), xyz.size()));
  }
  /* Moves every vertex at once: vertex_slots() * coord_dim() finite numbers, slot after slot
   * (a removed vertex's are stored and never read). No allocation. */
  void set_all_coords(const double *xyz, std::size_t n) {
    detail::check(tpx_live_set_all_coords(l_.get(), xyz, n));
  }
  void set_all_coords(const std::vector<double> &xyz) { set_all_coords(xyz.data(), xyz.size()); }
  /* Every slot's coordinates, lent (coord_dim() per slot; valid until add_vertex, compact or
   * the Live's end; set_coords writes through it): a whole-mesh pass reads them with no call. */
  CoordsView all_coords() const {
    const double *xyz = nullptr;
    std::size_t n = 0;
    detail::check(tpx_live_all_coords(l_.get(), &xyz, &n));
    return CoordsView(xyz, n);
  }
  std::uint32_t add_vertex(const std::vector<double> &xyz) {
    return detail::get<std::uint32_t>(tpx_live_add_vertex, l_.get(), xyz.data(), xyz.size());
  }
  void insert_top(const std::vector<std::uint32_t> &simplex) {
    detail::check(tpx_live_insert_top(l_.get(), simplex.data(), simplex.size()));
  }
  void remove_top(const std::vector<std::uint32_t> &simplex) {
    detail::check(tpx_live_remove_top(l_.get(), simplex.data(), simplex.size()));
  }
  /* Whether {a, b} is an edge satisfying the link condition (no exception). */
  bool link_condition(std::uint32_t a, std::uint32_t b) const {
    TpxStatus st = tpx_live_link_condition(l_.get(), a, b);
    if (st == TPX_STATUS_NOT_AN_EDGE || st == TPX_STATUS_LINK_CONDITION_FAILS) {
      return false;
    }
    detail::check(st);
    return true;
  }
  /* The link condition on the complex coned over its boundary (what PreserveManifold checks). */
  bool link_condition_with_boundary(std::uint32_t a, std::uint32_t b) const {
    TpxStatus st = tpx_live_link_condition_with_boundary(l_.get(), a, b);
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
    return Undo(detail::get<TpxUndo *>(tpx_live_contract, l_.get(), a, b,
                                       static_cast<std::uint32_t>(mode),
                                       position.empty() ? nullptr : position.data(),
                                       position.size()));
  }
  /* Undoes a contraction (vertex split). */
  void split(const Undo &u) { detail::check(tpx_live_split(l_.get(), u.get())); }
  /* Drops removed vertices and slots; returns old -> new vertex ids (UINT32_MAX: removed).
   * User properties (add_vertex_property) follow their slots. */
  std::vector<std::uint32_t> compact() {
    std::vector<std::vector<std::uint32_t>> tops;
    if (!props_.empty()) tops = top_slot_maps();
    std::vector<std::uint32_t> map(vertex_slots());
    detail::fill(map, tpx_live_compact, l_.get());
    for (auto &q : props_) {
      if (q) q->remap(map, tops);
    }
    return map;
  }
  /* Writes the live complex as to_complex().write(path, format) would (the same bytes),
   * without building that complex (tpx_live_write): the memory above the live complex is its
   * listing and the file's bytes. */
  void write(const std::string &path, Format format = Format::FromExtension) const {
    detail::check(tpx_live_write(l_.get(), path.c_str(), static_cast<std::uint32_t>(format)));
  }
  /* A frozen copy, to build any Structure from. */
  Complex to_complex() const {
    return Complex(detail::get<TpxComplex *>(tpx_live_to_complex, l_.get()));
  }
  void validate() const { detail::check(tpx_live_validate(l_.get())); }

  /* ---- attributes by handle (the Complex's attributes carried along edits) ---- */

  /* The values of listed attribute `name` on live top t (a top id of dimension >= 1: top_id),
   * copied as doubles (labels exact up to 2^53). A top made by an edit has labels 0 and reals
   * NaN. O(star of its first vertex). */
  std::vector<double> top_values(const std::string &name, std::uint32_t t) const {
    std::vector<double> out(9);
    detail::fill(out, tpx_live_top_values, l_.get(), name.c_str(), t);
    return out;
  }
  /* Sets them (as many numbers as the attribute's components; rounded to its type). Throws
   * TPX_STATUS_NO_SUCH_ATTRIBUTE, TPX_STATUS_INVALID_ARGUMENT (wrong length), a handle status;
   * nothing changes then. */
  void set_top_values(const std::string &name, std::uint32_t t, const std::vector<double> &values) {
    detail::check(tpx_live_set_top_values(l_.get(), name.c_str(), t, values.data(), values.size()));
  }
  /* The values of vertex attribute `name` on live vertex v, copied as doubles. */
  std::vector<double> vertex_values(const std::string &name, std::uint32_t v) const {
    std::vector<double> out(9);
    detail::fill(out, tpx_live_vertex_values, l_.get(), name.c_str(), v);
    return out;
  }
  /* What later contractions do to the survivor's vertex values (replaces a merge). */
  void set_vertex_policy(VertexPolicy policy) {
    detail::check(tpx_live_set_vertex_policy(l_.get(), static_cast<std::uint32_t>(policy)));
    merge_.reset();
  }
  /* Sets the values of vertex attribute `name` on live vertex v (as many numbers as its
   * components; rounded to its type, labels exact integers). Throws TPX_STATUS_NO_SUCH_ATTRIBUTE,
   * TPX_STATUS_INVALID_ARGUMENT, TPX_STATUS_DEAD_VERTEX; nothing changes then. */
  void set_vertex_values(const std::string &name, std::uint32_t v,
                         const std::vector<double> &values) {
    detail::check(
        tpx_live_set_vertex_values(l_.get(), name.c_str(), v, values.data(), values.size()));
  }
  /* The caller's merge at a contraction {a, b} -> a: merge(name, a, b, row_a, row_b, components)
   * once per vertex attribute before the contraction, changing a's row in place (rounded to the
   * attribute's type); the split restores it. Held by this Live (moves with it) until
   * set_vertex_policy or another merge. It must not throw: an exception cannot cross the C ABI,
   * so one escaping it ends the program (std::terminate). */
  using VertexMerge = std::function<void(const std::string &name, std::uint32_t a,
                                         std::uint32_t b, double *row_a, const double *row_b,
                                         std::size_t components)>;
  void set_vertex_merge(VertexMerge merge) {
    auto held = std::make_unique<VertexMerge>(std::move(merge));
    detail::check(tpx_live_set_vertex_merge(l_.get(), &Live::call_merge, held.get()));
    merge_ = std::move(held);
  }

  /* ---- user properties per element (OpenMesh's add_property), kept by this Live ----
   * A property holds one T per vertex slot (add_vertex_property) or per top slot of each
   * dimension >= 1 (add_top_property, a top named by its packed id p << 28 | slot, as
   * top_id() gives it), in C++ only: the C ABI, to_complex(), writers and save() do not see
   * them (use attributes for data that travels with files). Storage: one std::vector<T> per
   * property (one per dimension for tops), grown to a slot on first write; access O(1) (a
   * slot never written reads the initial value). Across edits a value belongs to its slot:
   * - a contraction {a, b} -> a leaves a's value as it is (set it yourself for another rule)
   *   and b's in b's removed slot; a top the contraction rewrites in place keeps its slot and
   *   value; a top it makes one dimension lower is a new top (the initial value); the split
   *   writes nothing, so every value is as it was;
   * - a removed vertex or top keeps its value in its tombstoned slot (a split or nothing may
   *   need it); a new vertex or top gets a new slot, with the initial value;
   * - compact() moves each live slot's value to the slot's new number and drops the removed
   *   ones, with the same renumbering the live complex makes (O(slots) per property).
   * T is any copyable type but bool (std::vector<bool> has no T&: use std::uint8_t). */
  template <class T>
  class VertexProperty {
    friend class Live;
    std::size_t index_ = SIZE_MAX;
    explicit VertexProperty(std::size_t i) noexcept : index_(i) {}

   public:
    VertexProperty() = default;
  };
  template <class T>
  class TopProperty {
    friend class Live;
    std::size_t index_ = SIZE_MAX;
    explicit TopProperty(std::size_t i) noexcept : index_(i) {}

   public:
    TopProperty() = default;
  };
  /* A new property `name` (unique among this Live's vertex properties; std::invalid_argument
   * otherwise), every slot reading `init`. */
  template <class T>
  VertexProperty<T> add_vertex_property(const std::string &name, const T &init = T()) {
    return VertexProperty<T>(add_property<T>(name, true, init));
  }
  template <class T>
  TopProperty<T> add_top_property(const std::string &name, const T &init = T()) {
    return TopProperty<T>(add_property<T>(name, false, init));
  }
  /* The existing property `name` of type T (std::invalid_argument when absent or of another
   * type). */
  template <class T>
  VertexProperty<T> vertex_property(const std::string &name) const {
    return VertexProperty<T>(find_property<T>(name, true));
  }
  template <class T>
  TopProperty<T> top_property(const std::string &name) const {
    return TopProperty<T>(find_property<T>(name, false));
  }
  /* Vertex v's value (the slot grown to on write). */
  template <class T>
  T &property(VertexProperty<T> h, std::uint32_t v) {
    return grow(store<T>(h.index_).vertices, v, store<T>(h.index_).init);
  }
  template <class T>
  const T &property(VertexProperty<T> h, std::uint32_t v) const {
    const auto &s = store<T>(h.index_);
    return v < s.vertices.size() ? s.vertices[v] : s.init;
  }
  /* Top `top`'s value (packed id p << 28 | slot, p >= 1). */
  template <class T>
  T &property(TopProperty<T> h, std::uint32_t top) {
    auto &s = store<T>(h.index_);
    return grow(s.tops[top >> 28], top & ((1u << 28) - 1), s.init);
  }
  template <class T>
  const T &property(TopProperty<T> h, std::uint32_t top) const {
    const auto &s = store<T>(h.index_);
    const auto &rows = s.tops[top >> 28];
    const std::uint32_t slot = top & ((1u << 28) - 1);
    return slot < rows.size() ? rows[slot] : s.init;
  }
  /* Removes property `name` (vertex or top); false when there is none. */
  bool remove_property(const std::string &name) {
    for (auto it = props_.begin(); it != props_.end(); ++it) {
      if (*it && (*it)->name == name) {
        it->reset();  // handles of the others keep their index
        return true;
      }
    }
    return false;
  }

  /* ---- handles: the same navigation as Structure (see tpx_live_structure) ----
   * A vertex's handle index is its id; other simplices are named through a top simplex.
   * A handle keeps naming its simplex across edits while that simplex exists (when its top
   * simplex was removed, the simplex is located again on each use), across a contraction of b
   * into a it names the image (b replaced by a); it is refused once the simplex is gone
   * (STALE_HANDLE) and after compact() (STALE_GENERATION). Answers come lexicographic (both
   * orders cost the same). */

  /* The live complex's arrays for inline navigation (MeshView): O(1), nothing copied; valid
   * until the next edit of the topology. The fast path for every pass over the mesh. */
  MeshView mesh() const { return MeshView(detail::get<TpxLiveArrays>(tpx_live_arrays, l_.get())); }
  /* Keeps the facet adjacency across edits (tpx_live_keep_adjacency): built now, then repaired
   * by every edit around what it changed (each edit costs O(Σ_t d²·k) more over the tops at the
   * vertices it touches) and rebuilt by compact(), so mesh_with_adjacency() is O(1) after any
   * edit; keep = false goes back to building it on request. */
  void keep_adjacency(bool keep = true) {
    detail::check(tpx_live_keep_adjacency(l_.get(), keep ? 1u : 0u));
  }
  /* The mesh with its facet adjacency (tpx_live_adjacency: built on the first call after an
   * edit, O(Σ_t d²·k), 4 bytes per vertex of every top; then O(1)): FF and TT become
   * reads. Valid as mesh() is, until the next edit of the topology. */
  MeshView mesh_with_adjacency() const { return mesh_with(true, false); }
  /* The mesh with every vertex's one-ring stored (tpx_live_rings: built on the first call
   * after an edit, O(Σ_v d·k_v) on one thread, 4 bytes per vertex slot and 8 per ring entry,
   * about 52 bytes a vertex of a closed triangle mesh; then O(1)): for passes repeated over the
   * rings (smoothing rounds, valences, edge counts), which then read a row per vertex. Setting
   * coordinates keeps it; valid as mesh() is, until the next edit of the topology. */
  MeshView mesh_with_rings() const { return mesh_with(false, true); }
  /* The mesh with the indices asked for (each built on request as above). */
  MeshView mesh_with(bool adjacency, bool rings) const {
    const TpxLiveArrays a = detail::get<TpxLiveArrays>(tpx_live_arrays, l_.get());
    TpxLiveAdjacency adj{};
    TpxLiveRings r{};
    if (adjacency) adj = detail::get<TpxLiveAdjacency>(tpx_live_adjacency, l_.get());
    if (rings) r = detail::get<TpxLiveRings>(tpx_live_rings, l_.get());
    return MeshView(a, adjacency ? &adj : nullptr, rings ? &r : nullptr);
  }

  /* The live complex seen as a borrowed structure (never free it), for the tpx_* handle calls. */
  const TpxStructure *structure() const {
    return detail::get<const TpxStructure *>(tpx_live_structure, l_.get());
  }
  Simplex locate(std::initializer_list<std::uint32_t> ids) const {
    return locate(std::vector<std::uint32_t>(ids));
  }
  Simplex locate(const std::vector<std::uint32_t> &ids) const {
    return Simplex(detail::get<TpxSimplex>(tpx_locate, structure(), ids.data(), ids.size()));
  }
  Simplex vertex(std::uint32_t v) const {
    return Simplex(detail::get<TpxSimplex>(tpx_handle, structure(), 0, v));
  }
  /* Vertex ids of h, ascending. */
  std::vector<std::uint32_t> vertices(Simplex h) const {
    std::vector<std::uint32_t> out(16);
    detail::fill(out, tpx_simplex_vertices, structure(), &h.raw());
    return out;
  }
  /* R_{p,q}(h) as handles into `out` (reused: no allocation once it has grown). */
  void related(Simplex h, std::uint32_t q, std::vector<TpxSimplex> &out,
               Order order = Order::Natural) const {
    if (out.capacity() < 16) out.reserve(16);
    out.resize(out.capacity());
    detail::fill(out, tpx_related_handles, structure(), &h.raw(), q,
                 static_cast<std::uint32_t>(order));
  }
  HandleList related(Simplex h, std::uint32_t q, Order order = Order::Natural) const {
    std::vector<TpxSimplex> out;
    related(h, q, out, order);
    return HandleList(std::move(out));
  }
  HandleList boundary(Simplex h, std::uint32_t q, Order o = Order::Natural) const {
    return related(h, q, o);
  }
  HandleList coboundary(Simplex h, std::uint32_t q, Order o = Order::Natural) const {
    return related(h, q, o);
  }
  HandleList adjacent(Simplex h, Order o = Order::Natural) const { return related(h, h.dim(), o); }
  /* R_{p,q} of many handles at once (any dimensions, mixed; tpx_related_handles_batch): out[k]
   * is the q-simplices related to hs[k]. `out` is reused: no allocation once it has grown. */
  void related_batch(const std::vector<Simplex> &hs, std::uint32_t q, HandleBatch &out,
                     Order order = Order::Natural) const {
    out.asked_raw_.clear();
    for (const Simplex &h : hs) out.asked_raw_.push_back(h.raw());
    out.offsets_.resize(hs.size() + 1);
    if (out.items_.size() < 4 * hs.size() + 16) out.items_.resize(4 * hs.size() + 16);
    std::size_t len = 0;
    const TpxStructure *s = structure();
    const auto o = static_cast<std::uint32_t>(order);
    TpxStatus st = tpx_related_handles_batch(s, out.asked_raw_.data(), hs.size(), q, o,
                                             out.offsets_.data(), out.items_.data(),
                                             out.items_.size(), &len);
    if (st == TPX_STATUS_BUFFER_TOO_SMALL) {
      out.items_.resize(len);
      st = tpx_related_handles_batch(s, out.asked_raw_.data(), hs.size(), q, o,
                                     out.offsets_.data(), out.items_.data(), out.items_.size(),
                                     &len);
    }
    out.asked_ = 0;
    out.items_n_ = 0;
    detail::check(st);
    out.asked_ = hs.size();
    out.items_n_ = len;
  }
  HandleBatch related_batch(const std::vector<Simplex> &hs, std::uint32_t q,
                            Order order = Order::Natural) const {
    HandleBatch b;
    related_batch(hs, q, b, order);
    return b;
  }
  std::size_t degree(Simplex h, std::uint32_t q) const {
    return detail::get<std::size_t>(tpx_degree, structure(), &h.raw(), q);
  }
  bool is_boundary(Simplex h) const { return test(h, 0); }
  bool is_manifold(Simplex h) const { return test(h, 1); }
  HandleList star(Simplex h, Order o = Order::Natural) const { return star_or_link(h, 0, o); }
  HandleList link(Simplex h, Order o = Order::Natural) const { return star_or_link(h, 1, o); }
  /* The top id of h (dimension in the top 4 bits, slot below; not dense), or UINT32_MAX. */
  std::uint32_t top_id(Simplex h) const {
    return detail::get<std::uint32_t>(tpx_top_id, structure(), &h.raw());
  }
  /* Top simplex t with its vertices in stored (winding) order. */
  std::vector<std::uint32_t> top_as_given(std::uint32_t t) const {
    std::vector<std::uint32_t> out(16);
    detail::fill(out, tpx_top_as_given, structure(), t);
    return out;
  }
  /* The same ids lent from the live complex's top table, no copy (tpx_live_top_vertices):
   * valid until the next edit. t: a top id of dimension >= 1 (top_id, Structure::top). */
  SimplexView top_vertices(std::uint32_t t) const {
    const std::uint32_t *ids = nullptr;
    std::size_t n = 0;
    detail::check(tpx_live_top_vertices(l_.get(), t, &ids, &n));
    return SimplexView(ids, n);
  }

  /* ---- the navigation every structure shares (StructureView over tpx_live_structure) ----
   * Everything a built Structure answers — count, simplices, handle(p, i), related ids and
   * batches, view(p, q), degrees, index(h), cyclic order — answered by this live complex.
   * Its indices above vertices are lexicographic ranks of the moment: use them, views and the
   * handles SimplexList makes from them only until the next edit (vertex indices are slots,
   * stable until compact()). Take a new one after compact(). */
  StructureView as_structure() const { return StructureView(structure()); }
  std::size_t count(std::uint32_t p) const { return as_structure().count(p); }
  /* The p-simplex of index i (for p > 0, named so that the handle lasts across edits). */
  Simplex handle(std::uint32_t p, std::uint32_t i) const { return as_structure().handle(p, i); }
  std::uint32_t index(Simplex h) const { return as_structure().index(h); }
  /* R_{p,q} of every p-simplex lent as a RelationView (valid until the next edit). Vertex rows
   * are slots (vertex_slots() of them, a removed vertex's empty). */
  RelationView view(std::uint32_t p, std::uint32_t q) const { return as_structure().view(p, q); }
  void degrees(std::uint32_t p, const std::vector<std::uint32_t> &indices, std::uint32_t q,
               std::vector<std::uint32_t> &out) const {
    as_structure().degrees(p, indices, q, out);
  }
  /* Manifold fans of triangles around vertex v (a complex of dimension <= 2), each
   * counter-clockwise by the winding where oriented; `fans` is reused. */
  void fans_around(Simplex v, HandleFans &fans) const { cyclic(v, 0, fans); }
  HandleFans fans_around(Simplex v) const {
    HandleFans f;
    fans_around(v, f);
    return f;
  }
  /* Circulator-style: every fan's triangles in order, fan after fan. */
  HandleList triangles_around(Simplex v) const {
    HandleFans f;
    fans_around(v, f);
    auto all = f.all();
    return HandleList(std::vector<TpxSimplex>(f.items_.begin(), f.items_.begin() + all.size()));
  }
  /* The triangles (q = 2) or tetrahedra (q = 3) around edge e in radial order, grouped. */
  void around_edge(Simplex e, std::uint32_t q, HandleFans &fans) const { cyclic(e, q, fans); }
  HandleFans around_edge(Simplex e, std::uint32_t q) const {
    HandleFans f;
    around_edge(e, q, f);
    return f;
  }

  const TpxLive *get() const noexcept { return l_.get(); }

 private:
  bool test(Simplex h, std::uint32_t what) const {
    return detail::get<std::uint32_t>(tpx_simplex_test, structure(), &h.raw(), what) != 0;
  }
  HandleList star_or_link(Simplex h, std::uint32_t link, Order o) const {
    std::vector<TpxSimplex> buf(64);
    detail::fill(buf, tpx_star, structure(), &h.raw(), link, static_cast<std::uint32_t>(o));
    return HandleList(std::move(buf));
  }
  void cyclic(Simplex h, std::uint32_t q, HandleFans &f) const {
    if (f.items_.size() < 16) f.items_.resize(16);
    if (f.flags_.size() < 4) f.flags_.resize(4);
    f.offsets_.resize(f.flags_.size() + 1);
    std::size_t ni = 0, ng = 0;
    const TpxStructure *s = structure();
    TpxStatus st = tpx_cyclic_handles(s, &h.raw(), q, f.items_.data(), f.items_.size(),
                                      f.offsets_.data(), f.flags_.data(), f.flags_.size(), &ni,
                                      &ng);
    if (st == TPX_STATUS_BUFFER_TOO_SMALL) {
      if (f.items_.size() < ni) f.items_.resize(ni);
      if (f.flags_.size() < ng) f.flags_.resize(ng);
      f.offsets_.resize(f.flags_.size() + 1);
      st = tpx_cyclic_handles(s, &h.raw(), q, f.items_.data(), f.items_.size(),
                              f.offsets_.data(), f.flags_.data(), f.flags_.size(), &ni, &ng);
    }
    detail::check(st);
    f.items_n_ = ni;
    f.groups_ = ng;
  }

  explicit Live(TpxLive *l) noexcept : l_(l) {}
  /* A user property's values (see add_vertex_property). */
  struct PropertyBase {
    std::string name;
    bool on_vertices = true;
    virtual ~PropertyBase() = default;
    virtual const std::type_info &type() const noexcept = 0;
    /* Moves each kept slot's value to its new number: map[old] = new or UINT32_MAX. */
    virtual void remap(const std::vector<std::uint32_t> &vertex_map,
                       const std::vector<std::vector<std::uint32_t>> &top_maps) = 0;
  };
  template <class T>
  struct PropertyStore final : PropertyBase {
    static_assert(!std::is_same<T, bool>::value, "a bool property: use std::uint8_t");
    T init;
    std::vector<T> vertices;
    std::vector<std::vector<T>> tops = std::vector<std::vector<T>>(16);
    explicit PropertyStore(const T &i) : init(i) {}
    const std::type_info &type() const noexcept override { return typeid(T); }
    void remap(const std::vector<std::uint32_t> &vertex_map,
               const std::vector<std::vector<std::uint32_t>> &top_maps) override {
      auto apply = [this](std::vector<T> &rows, const std::vector<std::uint32_t> &map) {
        std::size_t kept = 0;
        for (std::uint32_t m : map) kept += m != UINT32_MAX;
        std::vector<T> out(kept, init);
        for (std::size_t i = 0; i < rows.size() && i < map.size(); ++i) {
          if (map[i] != UINT32_MAX) out[map[i]] = std::move(rows[i]);
        }
        rows = std::move(out);
      };
      if (on_vertices) {
        apply(vertices, vertex_map);
      } else {
        for (std::size_t p = 1; p < tops.size(); ++p) apply(tops[p], top_maps[p]);
      }
    }
  };
  template <class T>
  std::size_t add_property(const std::string &name, bool on_vertices, const T &init) {
    for (const auto &q : props_) {
      if (q && q->name == name && q->on_vertices == on_vertices) {
        throw std::invalid_argument("a " + std::string(on_vertices ? "vertex" : "top") +
                                    " property '" + name + "' exists");
      }
    }
    auto s = std::make_unique<PropertyStore<T>>(init);
    s->name = name;
    s->on_vertices = on_vertices;
    props_.push_back(std::move(s));
    return props_.size() - 1;
  }
  template <class T>
  std::size_t find_property(const std::string &name, bool on_vertices) const {
    for (std::size_t i = 0; i < props_.size(); ++i) {
      const auto &q = props_[i];
      if (q && q->name == name && q->on_vertices == on_vertices) {
        if (q->type() != typeid(T)) {
          throw std::invalid_argument("property '" + name + "' holds another type");
        }
        return i;
      }
    }
    throw std::invalid_argument("no " + std::string(on_vertices ? "vertex" : "top") +
                                " property '" + name + "'");
  }
  template <class T>
  PropertyStore<T> &store(std::size_t i) const {
    if (i >= props_.size() || !props_[i]) throw std::invalid_argument("a removed property");
    return static_cast<PropertyStore<T> &>(*props_[i]);
  }
  template <class T>
  static T &grow(std::vector<T> &rows, std::uint32_t slot, const T &init) {
    if (slot >= rows.size()) rows.resize(std::size_t(slot) + 1, init);
    return rows[slot];
  }
  /* Before compact(): per dimension, old top slot -> new slot (UINT32_MAX: removed), as the
   * live complex renumbers them (live slots densely, in ascending order). */
  std::vector<std::vector<std::uint32_t>> top_slot_maps() const {
    const TpxLiveArrays a = detail::get<TpxLiveArrays>(tpx_live_arrays, l_.get());
    std::vector<std::vector<std::uint32_t>> maps(16);
    for (std::size_t p = 1; p < 16; ++p) {
      const std::size_t slots = a.top_lens[p] / (p + 1);
      std::uint32_t next = 0;
      maps[p].resize(slots, UINT32_MAX);
      for (std::size_t s = 0; s < slots; ++s) {
        if ((a.tops[p][s * (p + 1)] & 0x80000000u) == 0) maps[p][s] = next++;
      }
    }
    return maps;
  }
  std::vector<std::unique_ptr<PropertyBase>> props_;
  static void call_merge(void *user, const char *name, std::uint32_t a, std::uint32_t b,
                         double *row_a, const double *row_b, std::size_t components) noexcept {
    (*static_cast<VertexMerge *>(user))(name, a, b, row_a, row_b, components);
  }
  detail::Owned<TpxLive, tpx_live_free> l_;
  /* The merge set_vertex_merge handed to the C ABI (its address stays put when Live moves). */
  std::unique_ptr<VertexMerge> merge_;
};
static_assert(detail::move_only<Live>, "Live: a move-only owner");

inline std::string version() { return tpx_version(); }

}  // namespace topoplex

#endif /* TOPOPLEX_HPP */
