// The PETSc DMPlex bridge (include/topoplex_dmplex.hpp): one rank's DMPlex part <-> a Topoplex
// complex over the C ABI's C++ wrapper. Conventions and costs are in the header and docs/dmplex.md.
#include "topoplex_dmplex.hpp"

#include <algorithm>
#include <map>
#include <sstream>

namespace topoplex {
namespace dmplex {

namespace {

void petsc_check(PetscErrorCode ierr, const char *call) {
  if (ierr != 0) {
    std::ostringstream m;
    m << "PETSc call " << call << " failed with error " << static_cast<int>(ierr);
    throw Error(Code::Petsc, m.str());
  }
}
#define TPX_PETSC(call) petsc_check((call), #call)

// Tetrahedra: PETSc's cone order is Topoplex's winding with vertices 0 and 1 swapped.
void petsc_winding(std::vector<std::uint32_t> &vs) {
  if (vs.size() == 4) std::swap(vs[0], vs[1]);
}

bool skipped_label(const char *name) {
  const std::string n(name);
  return n == "depth" || n == "celltype";
}

std::vector<std::uint32_t> sorted(std::vector<std::uint32_t> v) {
  std::sort(v.begin(), v.end());
  return v;
}

// Appends to `vs` the vertex ids (point - vStart) of point p: p itself when a vertex, else the
// vertices of its transitive closure in closure order.
void append_vertices(DM dm, PetscInt p, PetscInt vStart, PetscInt vEnd,
                     std::vector<std::uint32_t> &vs) {
  if (p >= vStart && p < vEnd) {
    vs.push_back(static_cast<std::uint32_t>(p - vStart));
    return;
  }
  PetscInt n = 0;
  PetscInt *closure = nullptr;
  TPX_PETSC(DMPlexGetTransitiveClosure(dm, p, PETSC_TRUE, &n, &closure));
  for (PetscInt k = 0; k < n; ++k) {
    const PetscInt q = closure[2 * k];
    if (q >= vStart && q < vEnd) vs.push_back(static_cast<std::uint32_t>(q - vStart));
  }
  TPX_PETSC(DMPlexRestoreTransitiveClosure(dm, p, PETSC_TRUE, &n, &closure));
}

}  // namespace

PetscInt overlap_needed(std::uint32_t p, std::uint32_t q) { return q < p ? 0 : 1; }

namespace {

std::uint64_t key_hash(const std::uint32_t *k, std::size_t n) noexcept {
  std::uint64_t h = 0x9e3779b97f4a7c15ull ^ n;
  for (std::size_t i = 0; i < n; ++i) {
    h ^= k[i] + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
  }
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  return h;
}

// Up to 4 vertex ids (a simplex of the bridge), sorted into `out`; false for more.
bool sorted_key(const std::uint32_t *vs, std::size_t n, std::uint32_t *out) noexcept {
  if (n > 4) return false;
  std::copy(vs, vs + n, out);
  std::sort(out, out + n);
  return true;
}

}  // namespace

std::size_t RankMesh::slot_of(const std::vector<PetscInt> &slots, const std::uint32_t *key, std::size_t n) const noexcept {
  const std::size_t mask = slots.size() - 1;
  std::size_t i = static_cast<std::size_t>(key_hash(key, n)) & mask;
  std::uint32_t other[4] = {0, 0, 0, 0};
  while (slots[i] >= 0) {
    const std::size_t ip = static_cast<std::size_t>(slots[i]);
    const auto [a, b] = layout_.range(ip, p_start_);
    if (b - a == n) {
      sorted_key(&simplex_ids_[a], n, other);
      if (std::equal(key, key + n, other)) return i;
    }
    i = (i + 1) & mask;
  }
  return i;
}

RankMesh RankMesh::from_dm(DM dm, const ImportOptions &options) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(dm));
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);

  PetscInt pStart, pEnd, vStart, vEnd, depth;
  TPX_PETSC(DMPlexGetChart(dm, &pStart, &pEnd));
  TPX_PETSC(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  TPX_PETSC(DMPlexGetDepth(dm, &depth));
  DMPlexInterpolatedFlag interp;
  TPX_PETSC(DMPlexIsInterpolated(dm, &interp));
  PetscInt overlap = 0;
  TPX_PETSC(DMPlexGetOverlap(dm, &overlap));
  // The adjacency the overlap was grown with (DMPlexDistribute copies it to the parallel DM).
  PetscBool use_cone = PETSC_FALSE, use_closure = PETSC_TRUE;
  TPX_PETSC(DMGetBasicAdjacency(dm, &use_cone, &use_closure));
  const std::size_t npoints = static_cast<std::size_t>(pEnd - pStart);

  // Every point's simplex (closure vertices in closure order; tops in Topoplex winding) in one
  // flat array. A point's depth comes from the strata (contiguous in a stratified DM); a depth-1
  // point's closure vertices are its cone, deeper points walk their transitive closure.
  std::vector<PetscInt> stratum_start(static_cast<std::size_t>(depth) + 1), stratum_end(stratum_start.size());
  for (PetscInt d = 0; d <= depth; ++d) {
    TPX_PETSC(DMPlexGetDepthStratum(dm, d, &stratum_start[static_cast<std::size_t>(d)],
                                    &stratum_end[static_cast<std::size_t>(d)]));
  }
  auto depth_of = [&](PetscInt p) -> PetscInt {
    for (std::size_t d = 0; d < stratum_start.size(); ++d) {
      if (p >= stratum_start[d] && p < stratum_end[d]) return static_cast<PetscInt>(d);
    }
    PetscInt pd = 0;  // not stratified by ranges: ask PETSc
    TPX_PETSC(DMPlexGetPointDepth(dm, p, &pd));
    return pd;
  };
  // The closure's vertices of an interpolated simplex point from cones and cone orientations, in
  // the order DMPlexGetTransitiveClosure lists them (a breadth-first walk, each cone arranged by
  // the orientation its point is reached with), without PETSc's per-point cell-type lookups.
  // False when a cone on the way has not the size or depth of a simplex's (the caller then walks
  // PETSc's closure and judges the cell).
  const DMPolytopeType simplex_type[4] = {DM_POLYTOPE_POINT, DM_POLYTOPE_SEGMENT, DM_POLYTOPE_TRIANGLE,
                                          DM_POLYTOPE_TETRAHEDRON};
  auto simplex_closure = [&](PetscInt p, PetscInt pdepth, std::vector<std::uint32_t> &out) -> bool {
    if (pdepth > 3) return false;
    PetscInt pts[15], oris[15], deps[15];
    int n = 1, head = 0;
    pts[0] = p;
    oris[0] = 0;
    deps[0] = pdepth;
    while (head < n) {
      const PetscInt q = pts[head], o = oris[head], dq = deps[head];
      ++head;
      if (dq == 0) continue;
      PetscInt nc = 0;
      const PetscInt *cone = nullptr, *ornt = nullptr;
      TPX_PETSC(DMPlexGetConeSize(dm, q, &nc));
      if (nc != dq + 1) return false;
      TPX_PETSC(DMPlexGetCone(dm, q, &cone));
      TPX_PETSC(DMPlexGetConeOrientation(dm, q, &ornt));
      const PetscInt *arr = DMPolytopeTypeGetArrangment(simplex_type[dq], o);
      const std::size_t lower = static_cast<std::size_t>(dq - 1);
      for (PetscInt t = 0; t < nc; ++t) {
        const PetscInt i = arr[2 * t];
        const PetscInt cp = cone[i];
        if (cp < stratum_start[lower] || cp >= stratum_end[lower]) return false;
        if (std::find(pts, pts + n, cp) != pts + n) continue;
        if (n == 15) return false;
        pts[n] = cp;
        oris[n] = dq > 1 ? DMPolytopeTypeComposeOrientation(simplex_type[dq - 1], arr[2 * t + 1], ornt[i]) : 0;
        deps[n] = dq - 1;
        ++n;
      }
    }
    for (int k = 0; k < n; ++k) {
      if (deps[k] == 0) out.push_back(static_cast<std::uint32_t>(pts[k] - vStart));
    }
    return true;
  };
  const bool fast_closure = interp == DMPLEX_INTERPOLATED_FULL && depth <= 3;
  std::vector<std::uint32_t> vs;
  Layout layout;
  std::vector<std::uint32_t> simplex_ids;
  simplex_ids.reserve(3 * npoints);
  std::vector<PetscInt> tops;
  std::vector<std::uint32_t> ids;
  std::vector<std::size_t> offsets{0};
  // Fast path for a fully interpolated simplicial DM (every point of depth d has d + 1 cone
  // points, all of depth d - 1): the points are filled stratum by stratum, each from its cone and
  // the vertices already found for its faces, in PETSc's closure order (a breadth-first walk with
  // each cone arranged by the orientation it is reached with): an edge is its cone; a triangle
  // reached with orientation o lists its first arranged edge's vertices (swapped when that edge's
  // composed orientation is not 0), then the vertex its second arranged edge adds; a tetrahedron
  // lists its first face's vertices as that triangle reached with its cone orientation, then the
  // vertex of its second face that is missing. False (nothing filled) when the DM is not such a DM.
  auto fast_fill = [&]() -> bool {
    if (!fast_closure) return false;
    // The strata in chart order, each a contiguous range of points with d + 1 vertices.
    std::vector<Layout::Stratum> strata;
    for (PetscInt d = 0; d <= depth; ++d) {
      const std::size_t k = static_cast<std::size_t>(d);
      if (stratum_end[k] > stratum_start[k]) {
        strata.push_back({stratum_start[k], stratum_end[k], 0, static_cast<std::uint64_t>(d + 1)});
      }
    }
    std::sort(strata.begin(), strata.end(),
              [](const Layout::Stratum &a, const Layout::Stratum &b) { return a.start < b.start; });
    std::uint64_t total = 0;
    PetscInt next = pStart;
    for (Layout::Stratum &st : strata) {
      if (st.start != next) return false;
      st.base = total;
      total += static_cast<std::uint64_t>(st.end - st.start) * st.width;
      next = st.end;
    }
    if (next != pEnd) return false;
    // Every point's cone size must be a simplex's (vertices none); tops have no support.
    std::vector<char> is_top(npoints);
    for (const Layout::Stratum &st : strata) {
      const PetscInt want = static_cast<PetscInt>(st.width) == 1 ? 0 : static_cast<PetscInt>(st.width);
      for (PetscInt p = st.start; p < st.end; ++p) {
        PetscInt support = 0, nc = 0;
        TPX_PETSC(DMPlexGetSupportSize(dm, p, &support));
        TPX_PETSC(DMPlexGetConeSize(dm, p, &nc));
        if (nc != want) return false;
        is_top[static_cast<std::size_t>(p - pStart)] = support == 0;
      }
    }
    std::vector<std::uint64_t> base_of(static_cast<std::size_t>(depth) + 1, 0);
    for (const Layout::Stratum &st : strata) base_of[st.width - 1] = st.base;
    simplex_ids.assign(total, 0);
    // Point q of depth dq's vertices.
    auto stored_at = [&](PetscInt q, PetscInt dq) {
      const std::size_t k = static_cast<std::size_t>(dq);
      return &simplex_ids[base_of[k] + static_cast<std::uint64_t>(q - stratum_start[k]) * static_cast<std::uint64_t>(dq + 1)];
    };
    auto in_stratum = [&](PetscInt q, PetscInt d) {
      return q >= stratum_start[static_cast<std::size_t>(d)] && q < stratum_end[static_cast<std::size_t>(d)];
    };
    // Triangle q reached with orientation o: its three vertices into out; false if malformed.
    auto triangle = [&](PetscInt q, PetscInt o, std::uint32_t *out) -> bool {
      const PetscInt *cone = nullptr, *ornt = nullptr;
      TPX_PETSC(DMPlexGetCone(dm, q, &cone));
      TPX_PETSC(DMPlexGetConeOrientation(dm, q, &ornt));
      const PetscInt *arr = DMPolytopeTypeGetArrangment(DM_POLYTOPE_TRIANGLE, o);
      const PetscInt e0 = cone[arr[0]], e1 = cone[arr[2]];
      if (!in_stratum(e0, 1) || !in_stratum(e1, 1)) return false;
      const PetscInt co = DMPolytopeTypeComposeOrientation(DM_POLYTOPE_SEGMENT, arr[1], ornt[arr[0]]);
      const std::uint32_t *a = stored_at(e0, 1), *b = stored_at(e1, 1);
      out[0] = co == 0 ? a[0] : a[1];
      out[1] = co == 0 ? a[1] : a[0];
      out[2] = b[0] == a[0] || b[0] == a[1] ? b[1] : b[0];
      return true;
    };
    for (PetscInt d = 0; d <= depth; ++d) {
      for (PetscInt p = stratum_start[static_cast<std::size_t>(d)]; p < stratum_end[static_cast<std::size_t>(d)]; ++p) {
        std::uint32_t *out = stored_at(p, d);
        if (d == 0) {
          out[0] = static_cast<std::uint32_t>(p - vStart);
          continue;
        }
        const PetscInt *cone = nullptr, *ornt = nullptr;
        TPX_PETSC(DMPlexGetCone(dm, p, &cone));
        for (PetscInt k = 0; k <= d; ++k) {
          if (!in_stratum(cone[k], d - 1)) return false;
        }
        if (d == 1) {
          out[0] = static_cast<std::uint32_t>(cone[0] - vStart);
          out[1] = static_cast<std::uint32_t>(cone[1] - vStart);
        } else if (d == 2) {
          if (!triangle(p, 0, out)) return false;
        } else {
          TPX_PETSC(DMPlexGetConeOrientation(dm, p, &ornt));
          if (!triangle(cone[0], ornt[0], out)) return false;
          const std::uint32_t *g = stored_at(cone[1], 2);
          for (int k = 0; k < 3; ++k) {
            if (g[k] != out[0] && g[k] != out[1] && g[k] != out[2]) out[3] = g[k];
          }
        }
      }
    }
    // The tops, in ascending points (the strata are sorted by their first point).
    for (const Layout::Stratum &st : strata) {
      for (PetscInt p = st.start; p < st.end; ++p) {
        if (!is_top[static_cast<std::size_t>(p - pStart)]) continue;
        std::uint32_t *v = &simplex_ids[st.base + static_cast<std::uint64_t>(p - st.start) * st.width];
        if (st.width == 4) std::swap(v[0], v[1]);  // petsc_winding
        tops.push_back(p);
        ids.insert(ids.end(), v, v + st.width);
        offsets.push_back(ids.size());
      }
    }
    layout.strata = std::move(strata);
    return true;
  };
  if (!fast_fill()) {
  simplex_ids.clear();
  layout.strata.clear();
  layout.offsets.assign(npoints + 1, 0);
  std::vector<std::uint64_t> &simplex_offsets = layout.offsets;
  for (PetscInt p = pStart; p < pEnd; ++p) {
    const std::size_t ip = static_cast<std::size_t>(p - pStart);
    PetscInt support = 0;
    TPX_PETSC(DMPlexGetSupportSize(dm, p, &support));
    const bool top = support == 0;
    const bool vertex = p >= vStart && p < vEnd;
    // Vertices of a non-interpolated DM's non-top points do not exist: only tops and vertices
    // have closures worth walking, except when interpolated (every point is a simplex).
    if (top || vertex || interp != DMPLEX_INTERPOLATED_NONE) {
      const std::size_t first = simplex_ids.size();
      if (vertex) {
        simplex_ids.push_back(static_cast<std::uint32_t>(p - vStart));
      } else {
        const PetscInt pdepth = depth_of(p);
        if (pdepth == 1) {
          PetscInt nc = 0;
          const PetscInt *cone = nullptr;
          TPX_PETSC(DMPlexGetConeSize(dm, p, &nc));
          TPX_PETSC(DMPlexGetCone(dm, p, &cone));
          for (PetscInt k = 0; k < nc; ++k) {
            if (cone[k] >= vStart && cone[k] < vEnd) simplex_ids.push_back(static_cast<std::uint32_t>(cone[k] - vStart));
          }
        } else {
          vs.clear();
          if (!fast_closure || !simplex_closure(p, pdepth, vs)) {
            vs.clear();
            append_vertices(dm, p, vStart, vEnd, vs);
          }
          simplex_ids.insert(simplex_ids.end(), vs.begin(), vs.end());
        }
        const std::size_t nv = simplex_ids.size() - first;
        // Interpolated points: a simplex has depth + 1 vertices. Depth-1 points of a
        // non-interpolated DM: the cell type tells a tetrahedron from a quadrilateral.
        bool simplex = false;
        DMPolytopeType ct = DM_POLYTOPE_UNKNOWN;
        if (pdepth >= 2 || (pdepth == 1 && nv == 2 && interp != DMPLEX_INTERPOLATED_NONE)) {
          simplex = nv == static_cast<std::size_t>(pdepth) + 1;
        } else {
          TPX_PETSC(DMPlexGetCellType(dm, p, &ct));
          simplex = (ct == DM_POLYTOPE_SEGMENT && nv == 2) || (ct == DM_POLYTOPE_TRIANGLE && nv == 3) ||
                    (ct == DM_POLYTOPE_TETRAHEDRON && nv == 4);
        }
        if (!simplex) {
          if (ct == DM_POLYTOPE_UNKNOWN) TPX_PETSC(DMPlexGetCellType(dm, p, &ct));
          std::ostringstream m;
          m << "DMPlex point " << p << " (rank " << rank << ") is a " << DMPolytopeTypes[ct] << " with " << nv
            << " vertices at depth " << pdepth
            << ": Topoplex holds simplicial complexes only (points, segments, triangles, tetrahedra)";
          throw Error(Code::NotSimplicial, m.str());
        }
        if (top && nv == 4) std::swap(simplex_ids[first], simplex_ids[first + 1]);  // petsc_winding
      }
      if (top) {
        tops.push_back(p);
        ids.insert(ids.end(), simplex_ids.begin() + static_cast<std::ptrdiff_t>(first), simplex_ids.end());
        offsets.push_back(ids.size());
      }
    }
    simplex_offsets[ip + 1] = simplex_ids.size();
  }
  }  // general walk

  // Labels: integer values per point; points with a value that are not listed yet (faces of an
  // interpolated DM) are listed after the tops.
  struct LabelValues {
    std::string name;
    std::vector<std::pair<PetscInt, PetscInt>> point_value;
  };
  std::vector<LabelValues> labels;
  if (options.labels) {
    PetscInt nlabels = 0;
    TPX_PETSC(DMGetNumLabels(dm, &nlabels));
    for (PetscInt l = 0; l < nlabels; ++l) {
      const char *name = nullptr;
      TPX_PETSC(DMGetLabelName(dm, l, &name));
      if (skipped_label(name)) continue;
      DMLabel label;
      TPX_PETSC(DMGetLabelByNum(dm, l, &label));
      LabelValues lv{name, {}};
      IS valueIS;
      TPX_PETSC(DMLabelGetValueIS(label, &valueIS));
      PetscInt nvalues = 0;
      const PetscInt *values = nullptr;
      TPX_PETSC(ISGetLocalSize(valueIS, &nvalues));
      TPX_PETSC(ISGetIndices(valueIS, &values));
      for (PetscInt i = 0; i < nvalues; ++i) {
        IS pointIS;
        TPX_PETSC(DMLabelGetStratumIS(label, values[i], &pointIS));
        if (!pointIS) continue;
        PetscInt n = 0;
        const PetscInt *pts = nullptr;
        TPX_PETSC(ISGetLocalSize(pointIS, &n));
        TPX_PETSC(ISGetIndices(pointIS, &pts));
        for (PetscInt k = 0; k < n; ++k) {
          if (pts[k] >= pStart && pts[k] < pEnd) lv.point_value.emplace_back(pts[k], values[i]);
        }
        TPX_PETSC(ISRestoreIndices(pointIS, &pts));
        TPX_PETSC(ISDestroy(&pointIS));
      }
      TPX_PETSC(ISRestoreIndices(valueIS, &values));
      TPX_PETSC(ISDestroy(&valueIS));
      std::sort(lv.point_value.begin(), lv.point_value.end());
      for (std::size_t k = 1; k < lv.point_value.size(); ++k) {
        if (lv.point_value[k].first == lv.point_value[k - 1].first) {
          std::ostringstream m;
          m << "DMLabel '" << name << "' gives point " << lv.point_value[k].first << " two values ("
            << lv.point_value[k - 1].second << " and " << lv.point_value[k].second
            << "): a Topoplex attribute holds one value per simplex";
          throw Error(Code::Refused, m.str());
        }
      }
      if (!lv.point_value.empty()) labels.push_back(std::move(lv));
    }
  }
  std::vector<std::uint32_t> point_listing(npoints, UINT32_MAX);
  std::vector<PetscInt> listed_point = tops;
  for (std::size_t i = 0; i < tops.size(); ++i) point_listing[static_cast<std::size_t>(tops[i] - pStart)] = static_cast<std::uint32_t>(i);
  for (const LabelValues &lv : labels) {
    for (const auto &pv : lv.point_value) {
      const PetscInt p = pv.first;
      const std::size_t ip = static_cast<std::size_t>(p - pStart);
      if ((p >= vStart && p < vEnd) || point_listing[ip] != UINT32_MAX) continue;
      const auto [a, b] = layout.range(ip, pStart);
      if (a == b) continue;  // not a simplex here (non-interpolated face)
      point_listing[ip] = static_cast<std::uint32_t>(listed_point.size());
      listed_point.push_back(p);
      ids.insert(ids.end(), simplex_ids.begin() + static_cast<std::ptrdiff_t>(a), simplex_ids.begin() + static_cast<std::ptrdiff_t>(b));
      offsets.push_back(ids.size());
    }
  }

  // Coordinates of the vertices (none when the DM has none).
  std::vector<double> coords;
  std::size_t cdim = 0;
  if (options.coordinates) {
    Vec local = nullptr;
    TPX_PETSC(DMGetCoordinatesLocal(dm, &local));
    if (local) {
      PetscInt d = 0;
      TPX_PETSC(DMGetCoordinateDim(dm, &d));
      PetscSection section;
      TPX_PETSC(DMGetCoordinateSection(dm, &section));
      const PetscScalar *a = nullptr;
      TPX_PETSC(VecGetArrayRead(local, &a));
      cdim = static_cast<std::size_t>(d);
      coords.resize(cdim * static_cast<std::size_t>(vEnd - vStart));
      for (PetscInt v = vStart; v < vEnd; ++v) {
        PetscInt off = 0, dof = 0;
        TPX_PETSC(PetscSectionGetDof(section, v, &dof));
        TPX_PETSC(PetscSectionGetOffset(section, v, &off));
        if (dof != d) {
          VecRestoreArrayRead(local, &a);
          std::ostringstream m;
          m << "DMPlex vertex point " << v << " has " << dof << " coordinates, not " << d;
          throw Error(Code::Refused, m.str());
        }
        for (PetscInt k = 0; k < d; ++k) {
          coords[static_cast<std::size_t>(v - vStart) * cdim + static_cast<std::size_t>(k)] =
              static_cast<double>(PetscRealPart(a[off + k]));
        }
      }
      TPX_PETSC(VecRestoreArrayRead(local, &a));
    }
  }

  RankMesh out;
  if (vEnd > vStart) {
    out.complex_.emplace(Complex::from_arrays(static_cast<std::uint32_t>(vEnd - vStart), ids, offsets, coords, cdim));
  }
  out.rank_ = rank;
  out.size_ = size;
  out.overlap_ = overlap;
  out.vertex_adjacency_ = !use_cone && use_closure;
  out.interpolated_ = interp == DMPLEX_INTERPOLATED_FULL;
  out.p_start_ = pStart;
  out.p_end_ = pEnd;
  out.v_start_ = vStart;
  out.v_end_ = vEnd;
  out.vertex_point_.resize(static_cast<std::size_t>(vEnd - vStart));
  for (PetscInt v = vStart; v < vEnd; ++v) out.vertex_point_[static_cast<std::size_t>(v - vStart)] = v;
  out.listed_point_ = std::move(listed_point);
  out.top_listings_ = tops.size();
  // The listings after the tops (labelled faces), by point, for listing_of_point.
  for (std::size_t i = out.top_listings_; i < out.listed_point_.size(); ++i) {
    out.extra_listing_.emplace_back(out.listed_point_[i], static_cast<std::uint32_t>(i));
  }
  std::sort(out.extra_listing_.begin(), out.extra_listing_.end());

  // Attributes from the labels.
  const std::size_t nlisted = out.listed_point_.size();
  for (const LabelValues &lv : labels) {
    std::vector<std::int32_t> at_vertices(out.vertex_point_.size(), -1), at_listed(nlisted, -1);
    bool any_vertex = false, any_listed = false;
    for (const auto &pv : lv.point_value) {
      const PetscInt p = pv.first;
      const std::int32_t value = static_cast<std::int32_t>(pv.second);
      if (p >= vStart && p < vEnd) {
        at_vertices[static_cast<std::size_t>(p - vStart)] = value;
        any_vertex = true;
      }
      const std::uint32_t i = point_listing[static_cast<std::size_t>(p - pStart)];
      if (i != UINT32_MAX) {
        at_listed[i] = value;
        any_listed = true;
      }
    }
    if (any_vertex) out.complex_->set_attribute(lv.name, Location::Vertices, 1, at_vertices);
    if (any_listed) out.complex_->set_attribute(lv.name, Location::Listed, 1, at_listed);
  }

  // Owners from the point SF: leaves are ghosts owned by their root's rank; every other point is
  // this rank's. Only the ghosts are kept, sorted by point.
  std::vector<std::pair<PetscInt, int>> ghosts;
  PetscSF sf;
  TPX_PETSC(DMGetPointSF(dm, &sf));
  PetscInt nroots = -1, nleaves = 0;
  const PetscInt *ilocal = nullptr;
  const PetscSFNode *iremote = nullptr;
  TPX_PETSC(PetscSFGetGraph(sf, &nroots, &nleaves, &ilocal, &iremote));
  if (nroots >= 0) {
    for (PetscInt i = 0; i < nleaves; ++i) {
      const PetscInt p = ilocal ? ilocal[i] : i;
      if (p >= pStart && p < pEnd) ghosts.emplace_back(p, static_cast<int>(iremote[i].rank));
    }
  }
  std::sort(ghosts.begin(), ghosts.end());
  out.ghost_point_.reserve(ghosts.size());
  out.ghost_owner_.reserve(ghosts.size());
  for (const auto &g : ghosts) {
    if (!out.ghost_point_.empty() && out.ghost_point_.back() == g.first) continue;
    out.ghost_point_.push_back(g.first);
    out.ghost_owner_.push_back(g.second);
  }

  // Global vertex numbers (collective).
  IS numbering;
  TPX_PETSC(DMPlexGetVertexNumbering(dm, &numbering));
  const PetscInt *gn = nullptr;
  PetscInt ngn = 0;
  TPX_PETSC(ISGetLocalSize(numbering, &ngn));
  TPX_PETSC(ISGetIndices(numbering, &gn));
  out.global_vertex_.resize(out.vertex_point_.size());
  for (std::size_t v = 0; v < out.global_vertex_.size() && static_cast<PetscInt>(v) < ngn; ++v) {
    out.global_vertex_[v] = gn[v] < 0 ? -(gn[v] + 1) : gn[v];
  }
  TPX_PETSC(ISRestoreIndices(numbering, &gn));

  out.layout_ = std::move(layout);
  out.simplex_ids_ = std::move(simplex_ids);
  return out;
}

const std::vector<PetscInt> &RankMesh::point_slots() const {
  PointTable &t = *table_;
  std::call_once(t.once, [&] {
    // The first point of a vertex set wins.
    const std::size_t npoints = static_cast<std::size_t>(p_end_ - p_start_);
    std::size_t entries = 0;
    for (std::size_t ip = 0; ip < npoints; ++ip) {
      const auto [a, b] = layout_.range(ip, p_start_);
      entries += a != b;
    }
    std::size_t cap = 16;
    while (cap < 2 * entries) cap *= 2;
    t.slots.assign(cap, -1);
    std::uint32_t key[4] = {0, 0, 0, 0};
    for (std::size_t ip = 0; ip < npoints; ++ip) {
      const auto [a, b] = layout_.range(ip, p_start_);
      const std::uint64_t n = b - a;
      if (n == 0 || !sorted_key(&simplex_ids_[a], n, key)) continue;
      const std::size_t slot = slot_of(t.slots, key, n);
      if (t.slots[slot] < 0) t.slots[slot] = static_cast<PetscInt>(ip);
    }
    t.built.store(true, std::memory_order_release);
  });
  return t.slots;
}

std::size_t RankMesh::bytes() const noexcept {
  return vertex_point_.capacity() * sizeof(PetscInt) + listed_point_.capacity() * sizeof(PetscInt) +
         extra_listing_.capacity() * sizeof(std::pair<PetscInt, std::uint32_t>) + ghost_point_.capacity() * sizeof(PetscInt) + ghost_owner_.capacity() * sizeof(int) +
         global_vertex_.capacity() * sizeof(PetscInt) + layout_.offsets.capacity() * sizeof(std::uint64_t) +
         layout_.strata.capacity() * sizeof(Layout::Stratum) +
         simplex_ids_.capacity() * sizeof(std::uint32_t) +
         (table_ && table_->built.load(std::memory_order_acquire) ? table_->slots.capacity() * sizeof(PetscInt) : 0);
}

const Complex &RankMesh::complex() const {
  if (!complex_) throw Error(Code::Refused, "rank " + std::to_string(rank_) + " holds no point: no complex");
  return *complex_;
}

Complex &RankMesh::complex() {
  return const_cast<Complex &>(static_cast<const RankMesh &>(*this).complex());
}

namespace {

// points[i], or InvalidArgument naming `what` i and the `count` there are ("listing 9 out of
// range (4 listed)").
PetscInt point_at(const std::vector<PetscInt> &points, std::size_t i, const char *what,
                  const char *count) {
  if (i >= points.size()) {
    throw Error(Code::InvalidArgument, std::string(what) + " " + std::to_string(i) +
                                           " out of range (" + std::to_string(points.size()) +
                                           " " + count + ")");
  }
  return points[i];
}

}  // namespace

PetscInt RankMesh::point_of_vertex(std::uint32_t v) const {
  return point_at(vertex_point_, v, "vertex", "vertices");
}

std::uint32_t RankMesh::vertex_of_point(PetscInt p) const {
  return p >= v_start_ && p < v_end_ ? static_cast<std::uint32_t>(p - v_start_) : NO_VERTEX;
}

PetscInt RankMesh::point_of_listing(std::size_t i) const {
  return point_at(listed_point_, i, "listing", "listed");
}

std::size_t RankMesh::listing_of_point(PetscInt p) const {
  if (p < p_start_ || p >= p_end_) return NO_LISTING;
  // Tops: the first top_listings_ listings, in ascending point order.
  const auto tops_end = listed_point_.begin() + static_cast<std::ptrdiff_t>(top_listings_);
  const auto it = std::lower_bound(listed_point_.begin(), tops_end, p);
  if (it != tops_end && *it == p) return static_cast<std::size_t>(it - listed_point_.begin());
  const auto e = std::lower_bound(extra_listing_.begin(), extra_listing_.end(), std::make_pair(p, std::uint32_t(0)));
  return e != extra_listing_.end() && e->first == p ? e->second : NO_LISTING;
}

PetscInt RankMesh::point_of(std::vector<std::uint32_t> simplex) const {
  std::uint32_t key[4] = {0, 0, 0, 0};
  if (simplex.empty() || !sorted_key(simplex.data(), simplex.size(), key)) return NO_POINT;
  const std::vector<PetscInt> &slots = point_slots();
  const PetscInt ip = slots[slot_of(slots, key, simplex.size())];
  return ip < 0 ? NO_POINT : p_start_ + ip;
}

std::vector<std::uint32_t> RankMesh::simplex_of_point(PetscInt p) const {
  if (p < p_start_ || p >= p_end_) {
    throw Error(Code::InvalidArgument, "point " + std::to_string(p) + " outside the chart [" +
                                           std::to_string(p_start_) + ", " + std::to_string(p_end_) + ")");
  }
  const std::size_t ip = static_cast<std::size_t>(p - p_start_);
  const auto [a, b] = layout_.range(ip, p_start_);
  if (a == b) {
    throw Error(Code::InvalidArgument, "point " + std::to_string(p) +
                                           " is a face of a non-interpolated DM: no vertices kept");
  }
  return std::vector<std::uint32_t>(simplex_ids_.begin() + static_cast<std::ptrdiff_t>(a),
                                    simplex_ids_.begin() + static_cast<std::ptrdiff_t>(b));
}

int RankMesh::point_owner(PetscInt p) const {
  if (p < p_start_ || p >= p_end_) {
    throw Error(Code::InvalidArgument, "point " + std::to_string(p) + " outside the chart [" +
                                           std::to_string(p_start_) + ", " + std::to_string(p_end_) + ")");
  }
  const auto it = std::lower_bound(ghost_point_.begin(), ghost_point_.end(), p);
  return it != ghost_point_.end() && *it == p ? ghost_owner_[static_cast<std::size_t>(it - ghost_point_.begin())] : rank_;
}

int RankMesh::owner(const StructureView &s, const std::vector<std::uint32_t> &simplex) const {
  const PetscInt p = point_of(simplex);
  if (p != NO_POINT) return point_owner(p);
  if (simplex.empty()) throw Error(Code::InvalidArgument, "owner of an empty simplex");
  // No point: the smallest rank owning a cell (a top) that contains the simplex.
  int best = -1;
  const std::uint32_t d = s.dimension();
  for (std::uint32_t q = static_cast<std::uint32_t>(simplex.size()); q <= d; ++q) {
    for (auto row : s.relation(simplex, q)) {
      const std::vector<std::uint32_t> cell(row.begin(), row.end());
      const PetscInt c = point_of(cell);
      if (c == NO_POINT || listing_of_point(c) == NO_LISTING) continue;
      const int o = point_owner(c);
      if (best < 0 || o < best) best = o;
    }
  }
  if (best < 0) throw Error(Code::InvalidArgument, "simplex is in no cell of this rank");
  // A rank that owns no cell around the simplex may see part of its star only: the smallest
  // owner it sees (not this rank: it owns none of them), a ghost here either way.
  return best;
}

PetscInt RankMesh::global_vertex(std::uint32_t v) const {
  if (v >= global_vertex_.size()) throw Error(Code::InvalidArgument, "vertex " + std::to_string(v) + " out of range");
  return global_vertex_[v];
}

Rows RankMesh::owned_relation(const StructureView &s, const std::vector<std::uint32_t> &simplex,
                              std::uint32_t q) const {
  const std::uint32_t p = static_cast<std::uint32_t>(simplex.size()) - 1;
  if (size_ > 1 && q >= p && overlap_ > 0 && !vertex_adjacency_) {
    std::ostringstream m;
    m << "R(" << p << "," << q << ") on rank " << rank_
      << ": the overlap was grown with an adjacency other than PETSc's default (useCone = false, "
         "useClosure = true), so layers need not hold whole vertex stars";
    throw Error(Code::OverlapTooSmall, m.str());
  }
  if (size_ > 1 && overlap_ < overlap_needed(p, q)) {
    std::ostringstream m;
    m << "R(" << p << "," << q << ") needs overlap " << overlap_needed(p, q) << " to be exact on rank "
      << rank_ << ", the DM has overlap " << overlap_;
    throw Error(Code::OverlapTooSmall, m.str());
  }
  if (!owned(s, simplex)) {
    std::ostringstream m;
    m << "simplex {";
    for (std::size_t i = 0; i < simplex.size(); ++i) m << (i ? "," : "") << simplex[i];
    m << "} is a ghost on rank " << rank_ << ": its relations may be cut by the overlap";
    throw Error(Code::Ghost, m.str());
  }
  if (q > s.dimension()) return Rows({}, q + 1);
  return s.relation(simplex, q);
}

DM to_dm(MPI_Comm comm, const Complex *complex, const ExportOptions &options, int root) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  // Root decides; the others learn the dimensions and whether to refuse (collective either way).
  std::vector<std::vector<std::uint32_t>> cells;  // vertex ids, PETSc winding
  std::vector<std::size_t> cell_listing;
  long header[5] = {0, 0, 0, 0, 0};  // dim, nverts, cdim, refused, top-dimension count
  std::string refusal;
  if (rank == root) {
    if (!complex) throw Error(Code::InvalidArgument, "to_dm: no complex on the root rank");
    const TpxInputStats st = complex->input_stats();
    std::vector<bool> dims(complex->dimension() + 1, false);
    for (std::size_t i = 0; i < st.input_simplices; ++i) {
      std::uint32_t top = 0;
      std::vector<std::uint32_t> vs = complex->input_simplex(i, top);
      if (top == UINT32_MAX || vs.size() < 2) continue;
      dims[vs.size() - 1] = true;
      petsc_winding(vs);
      cells.push_back(std::move(vs));
      cell_listing.push_back(i);
    }
    header[0] = static_cast<long>(complex->dimension());
    header[1] = static_cast<long>(complex->vertex_count());
    header[2] = static_cast<long>(complex->coord_dim());
    header[4] = static_cast<long>(std::count(dims.begin(), dims.end(), true));
    if (options.interpolate && header[4] > 1) {
      header[3] = 1;
    }
  }
  MPI_Bcast(header, 5, MPI_LONG, root, comm);
  if (header[3]) {
    throw Error(Code::Refused,
                "to_dm: the complex has top simplices of " + std::to_string(header[4]) +
                    " dimensions; DMPlexInterpolate needs one cell dimension (export it with "
                    "interpolate = false: a cell-vertex DM holds mixed dimensions)");
  }
  const PetscInt dim = static_cast<PetscInt>(header[0]);
  const PetscInt nverts = rank == root ? static_cast<PetscInt>(header[1]) : 0;
  const PetscInt ncells = static_cast<PetscInt>(cells.size());

  DM dm;
  TPX_PETSC(DMCreate(comm, &dm));
  TPX_PETSC(DMSetType(dm, DMPLEX));
  TPX_PETSC(DMSetDimension(dm, dim));
  TPX_PETSC(DMPlexSetChart(dm, 0, ncells + nverts));
  for (PetscInt c = 0; c < ncells; ++c) TPX_PETSC(DMPlexSetConeSize(dm, c, static_cast<PetscInt>(cells[static_cast<std::size_t>(c)].size())));
  TPX_PETSC(DMSetUp(dm));
  std::vector<PetscInt> cone;
  for (PetscInt c = 0; c < ncells; ++c) {
    cone.clear();
    for (std::uint32_t v : cells[static_cast<std::size_t>(c)]) cone.push_back(ncells + static_cast<PetscInt>(v));
    TPX_PETSC(DMPlexSetCone(dm, c, cone.data()));
  }
  TPX_PETSC(DMPlexSymmetrize(dm));
  TPX_PETSC(DMPlexStratify(dm));
  if (header[2] > 0) {
    std::vector<PetscReal> xyz;
    if (rank == root) {
      const std::vector<double> c = complex->coords();
      xyz.assign(c.begin(), c.end());
    }
    TPX_PETSC(DMPlexBuildCoordinatesFromCellList(dm, static_cast<PetscInt>(header[2]), xyz.data()));
  }
  if (options.interpolate) {
    DM idm;
    TPX_PETSC(DMPlexInterpolate(dm, &idm));
    TPX_PETSC(DMPlexCopyCoordinates(dm, idm));
    TPX_PETSC(DMDestroy(&dm));
    dm = idm;
  }

  // Labels from integer one-component attributes (root only; DMPlexDistribute sends them on).
  if (options.labels && rank == root) {
    PetscInt pStart, pEnd, vStart, vEnd;
    TPX_PETSC(DMPlexGetChart(dm, &pStart, &pEnd));
    TPX_PETSC(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
    // Simplex (sorted vertex ids) -> point, for every point.
    std::map<std::vector<std::uint32_t>, PetscInt> point_of;
    for (PetscInt p = pStart; p < pEnd; ++p) {
      std::vector<std::uint32_t> vs;
      append_vertices(dm, p, vStart, vEnd, vs);
      point_of.emplace(sorted(vs), p);
    }
    const TpxInputStats st = complex->input_stats();
    for (const AttributeInfo &a : complex->attributes()) {
      if (a.components != 1 || (a.type != ValueType::I32 && a.type != ValueType::I64)) continue;
      DMLabel label;
      TPX_PETSC(DMCreateLabel(dm, a.name.c_str()));
      TPX_PETSC(DMGetLabel(dm, a.name.c_str(), &label));
      auto set = [&](PetscInt p, std::int64_t value, const std::string &what) {
        if (value == -1) return;
        PetscInt old = -1;
        TPX_PETSC(DMLabelGetValue(label, p, &old));
        if (old == value) return;
        if (old != -1) {
          throw Error(Code::Refused, "to_dm: attribute '" + a.name + "' gives point " + std::to_string(p) + " (" +
                                         what + ") the values " + std::to_string(old) + " and " +
                                         std::to_string(value));
        }
        TPX_PETSC(DMLabelSetValue(label, p, static_cast<PetscInt>(value)));
      };
      auto value_at = [&](std::size_t i) -> std::int64_t {
        if (a.type == ValueType::I32) return complex->attribute<std::int32_t>(a.name, a.location)[i];
        return complex->attribute<std::int64_t>(a.name, a.location)[i];
      };
      if (a.location == Location::Vertices) {
        for (std::uint32_t v = 0; v < complex->vertex_count(); ++v) set(vStart + static_cast<PetscInt>(v), value_at(v), "vertex " + std::to_string(v));
      } else {
        for (std::size_t i = 0; i < st.input_simplices; ++i) {
          const std::int64_t value = value_at(i);
          if (value == -1) continue;
          std::uint32_t top = 0;
          const std::vector<std::uint32_t> vs = complex->input_simplex(i, top);
          const auto it = point_of.find(sorted(vs));
          if (it == point_of.end()) {
            throw Error(Code::Refused, "to_dm: attribute '" + a.name + "' labels listed simplex " + std::to_string(i) +
                                           ", a face with no DMPlex point in a non-interpolated DM (export with "
                                           "interpolate = true)");
          }
          set(it->second, value, "listed simplex " + std::to_string(i));
        }
      }
    }
  }
  return dm;
}

DM distribute(DM serial, PetscInt overlap, PetscSF *migration) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(serial));
  // What PETSc 3.18's DMPlexDistribute cannot carry (checked on every rank, refused on all):
  //  - a point with no support that is not a cell (height 0): an isolated vertex, or a dangling
  //    lower-dimensional simplex of an interpolated DM: only cells and their closures migrate;
  //  - cells of several dimensions: DMPlexStratifyMigrationSF orders the received points by the
  //    cell types of the DM's dimension only, and fails ("ilocal has duplicate entries").
  PetscInt pStart, pEnd, cStart, cEnd;
  TPX_PETSC(DMPlexGetChart(serial, &pStart, &pEnd));
  TPX_PETSC(DMPlexGetHeightStratum(serial, 0, &cStart, &cEnd));
  long bad[2] = {-1, -1};  // a lost point, a cell of another dimension
  PetscInt cdim = -1;
  for (PetscInt p = pStart; p < pEnd; ++p) {
    PetscInt support = 0;
    TPX_PETSC(DMPlexGetSupportSize(serial, p, &support));
    const bool cell = p >= cStart && p < cEnd;
    if (support == 0 && !cell && bad[0] < 0) bad[0] = p;
    if (cell) {
      DMPolytopeType ct;
      TPX_PETSC(DMPlexGetCellType(serial, p, &ct));
      const PetscInt d = DMPolytopeTypeGetDim(ct);
      if (cdim < 0) cdim = d;
      if (d != cdim && bad[1] < 0) bad[1] = p;
    }
  }
  long any[2];
  MPI_Allreduce(bad, any, 2, MPI_LONG, MPI_MAX, comm);
  if (any[0] >= 0) {
    throw Error(Code::Refused, "distribute: point " + std::to_string(any[0]) +
                                   " has no support and is not a cell; DMPlexDistribute moves cells and their "
                                   "closures only, so it would be lost");
  }
  if (any[1] >= 0) {
    throw Error(Code::Refused, "distribute: cell " + std::to_string(any[1]) +
                                   " has another dimension than the first cell; PETSc 3.18's DMPlexDistribute "
                                   "cannot migrate cells of several dimensions");
  }
  DM parallel = nullptr;
  PetscSF sf = nullptr;
  TPX_PETSC(DMPlexDistribute(serial, overlap, migration ? &sf : nullptr, &parallel));
  if (!parallel) {  // one rank: PETSc leaves the DM where it is
    TPX_PETSC(DMClone(serial, &parallel));
    if (migration) {
      TPX_PETSC(PetscSFCreate(comm, &sf));
      std::vector<PetscSFNode> remote(static_cast<std::size_t>(pEnd - pStart));
      for (PetscInt p = pStart; p < pEnd; ++p) {
        remote[static_cast<std::size_t>(p - pStart)].rank = 0;
        remote[static_cast<std::size_t>(p - pStart)].index = p;
      }
      TPX_PETSC(PetscSFSetGraph(sf, pEnd - pStart, pEnd - pStart, nullptr, PETSC_COPY_VALUES, remote.data(), PETSC_COPY_VALUES));
    }
  }
  if (migration) *migration = sf;
  return parallel;
}

std::vector<PetscInt> serial_points(DM local, PetscSF migration) {
  PetscInt pStart, pEnd;
  TPX_PETSC(DMPlexGetChart(local, &pStart, &pEnd));
  std::vector<PetscInt> out(static_cast<std::size_t>(pEnd - pStart), -1);
  PetscInt nroots = 0, nleaves = 0;
  const PetscInt *ilocal = nullptr;
  const PetscSFNode *iremote = nullptr;
  TPX_PETSC(PetscSFGetGraph(migration, &nroots, &nleaves, &ilocal, &iremote));
  for (PetscInt i = 0; i < nleaves; ++i) {
    const PetscInt p = ilocal ? ilocal[i] : i;
    if (p >= pStart && p < pEnd) out[static_cast<std::size_t>(p - pStart)] = iremote[i].index;
  }
  return out;
}

}  // namespace dmplex
}  // namespace topoplex
