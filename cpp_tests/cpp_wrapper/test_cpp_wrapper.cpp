// topoplex.hpp on the drawn fixture (same as test_c_api.c):
//
//          3 ------ 4 ------ 5        tetrahedron 0 1 2 3
//         /|\      /                  dangling triangle 2 3 4 on edge 2-3
//        / | \    /                   wire edge 4-5
//       0--|--2--/
//        \ | /
//         \|/
//          1
#include "topoplex.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace {

using Ids = std::vector<std::uint32_t>;
using topoplex::Complex;
using topoplex::Error;
using topoplex::Kind;
using topoplex::Structure;

Complex fixture() { return Complex::from_simplices(6, {{3, 2, 1, 0}, {4, 2, 3}, {5, 4}}); }

std::vector<Ids> rows_of(const topoplex::RowsView &v) {
  std::vector<Ids> out;
  for (auto s : v) out.push_back(s.to_vector());
  return out;
}

template <class F>
TpxStatus status_of(F &&f) {
  try {
    f();
  } catch (const Error &e) {
    return e.status();
  }
  return TPX_STATUS_OK;
}

static_assert(!std::is_copy_constructible<Complex>::value, "handles are move-only");
static_assert(std::is_nothrow_move_constructible<Structure>::value, "handles move cheaply");

TEST(Wrapper, ComplexAndStructureQueries) {
  Complex c = fixture();
  EXPECT_EQ(c.dimension(), 3u);
  EXPECT_EQ(c.vertex_count(), 6u);
  EXPECT_EQ(c.top_count(1), 1u);
  Structure s(c, Kind::IG);
  {
    // The structure outlives the complex it was built from.
    Complex gone = std::move(c);
  }
  EXPECT_EQ(s.kind(), Kind::IG);
  EXPECT_EQ(s.dimension(), 3u);
  EXPECT_EQ(s.count(1), 9u);
  EXPECT_EQ(s.top_count(3), 1u);
  EXPECT_GT(s.storage().bytes, 0u);

  topoplex::Rows tris = s.relation({3, 2}, 2);
  ASSERT_EQ(tris.size(), 3u);
  EXPECT_EQ(tris.arity(), 3u);
  EXPECT_EQ(rows_of(tris.view()), (std::vector<Ids>{{0, 2, 3}, {1, 2, 3}, {2, 3, 4}}));
  EXPECT_EQ(tris[2][2], 4u);
  EXPECT_TRUE(s.relation({5}, 2).empty());
  EXPECT_EQ(s.simplices(1).size(), 9u);
  EXPECT_EQ(rows_of(s.simplices(3).view()), (std::vector<Ids>{{0, 1, 2, 3}}));
}

TEST(Wrapper, LargeAnswerGrowsTheBuffer) {
  // A fan of 40 triangles on edge 0-1: more rows than the first guess of 16.
  std::vector<Ids> fan;
  for (std::uint32_t v = 2; v < 42; ++v) fan.push_back({0, 1, v});
  Structure s(Complex::from_simplices(42, fan), Kind::IG);
  topoplex::Rows r = s.relation({1, 0}, 2);
  ASSERT_EQ(r.size(), 40u);
  for (std::size_t i = 0; i < r.size(); ++i) {
    EXPECT_EQ(r[i].to_vector(), (Ids{0, 1, static_cast<std::uint32_t>(i + 2)}));
  }
}

TEST(Wrapper, RelationTableRowsAreViews) {
  Structure s(fixture(), Kind::IG);
  topoplex::RelationTable t = s.relation_table(0, 1);
  ASSERT_EQ(t.size(), 6u);
  EXPECT_EQ(t.offsets_size(), 7u);
  EXPECT_EQ(t.ids_size(), 36u);
  EXPECT_EQ(rows_of(t[4]), (std::vector<Ids>{{2, 4}, {3, 4}, {4, 5}}));
  EXPECT_EQ(rows_of(t[5]), (std::vector<Ids>{{4, 5}}));
  std::vector<std::size_t> degrees;
  for (auto row : t) degrees.push_back(row.size());
  EXPECT_EQ(degrees, (std::vector<std::size_t>{3, 3, 4, 4, 3, 1}));
  topoplex::RelationTable moved = std::move(t);
  EXPECT_EQ(moved.size(), 6u);
}

TEST(Wrapper, ErrorsCarryStatusAndMessage) {
  Structure s(fixture(), Kind::IG);
  try {
    s.relation({0, 4}, 0);
    FAIL() << "expected topoplex::Error";
  } catch (const Error &e) {
    EXPECT_EQ(e.status(), TPX_STATUS_NOT_IN_COMPLEX);
    EXPECT_NE(std::string(e.what()).find("[0 4]"), std::string::npos) << e.what();
  }
  EXPECT_EQ(status_of([&] { s.relation({1, 1}, 0); }), TPX_STATUS_INVALID_SIMPLEX);
  EXPECT_EQ(status_of([&] { s.relation({}, 0); }), TPX_STATUS_INVALID_SIMPLEX);
  EXPECT_EQ(status_of([&] { s.relation({0}, 9); }), TPX_STATUS_DIMENSION_OUT_OF_RANGE);
  EXPECT_EQ(status_of([&] { s.relation_table(0, 9); }), TPX_STATUS_DIMENSION_OUT_OF_RANGE);
  EXPECT_EQ(status_of([&] { Structure(fixture(), static_cast<Kind>(42)); }),
            TPX_STATUS_UNKNOWN_KIND);
  EXPECT_EQ(status_of([] { Complex::from_simplices(2, {{0, 2}}); }), TPX_STATUS_INVALID_COMPLEX);
  EXPECT_EQ(status_of([] { Complex::from_file(TPX_TEST_DATA_DIR "/does_not_exist.obj"); }),
            TPX_STATUS_IO_ERROR);
  EXPECT_EQ(status_of([] { Complex::from_file(TPX_TEST_DATA_DIR "/garbage.off"); }),
            TPX_STATUS_PARSE_ERROR);
}

// Issue 16: absorbed counts are visible, and the closure budget is an argument (one 4-simplex
// has 31 simplices by the bound).
TEST(Wrapper, InputStatsAndClosureBudget) {
  auto c = Complex::from_simplices(5, {{0, 1, 2}, {2, 1, 0}, {1, 2}, {3, 4}});
  TpxInputStats st = c.input_stats();
  EXPECT_EQ(st.input_simplices, 4u);
  EXPECT_EQ(st.absorbed_duplicates, 1u);
  EXPECT_EQ(st.absorbed_faces, 1u);
  const Ids four{0, 1, 2, 3, 4};
  const std::vector<std::size_t> one{0, 5};
  EXPECT_EQ(status_of([&] { Complex::from_arrays(5, four, one, {}, 0, 30); }),
            TPX_STATUS_TOO_LARGE);
  EXPECT_EQ(Complex::from_arrays(5, four, one, {}, 0, 31).dimension(), 4u);
  EXPECT_EQ(status_of([] { Complex::from_arrays(UINT32_MAX, {}, {}); }), TPX_STATUS_TOO_LARGE);
}

TEST(Wrapper, FileComplexMatchesArrays) {
  Structure a(Complex::from_file(TPX_TEST_DATA_DIR "/tet_triangle_wire.simplices"), Kind::IG);
  Structure b(fixture(), Kind::IG);
  for (std::uint32_t p = 0; p <= 3; ++p) {
    EXPECT_EQ(a.simplices(p).ids(), b.simplices(p).ids()) << "p = " << p;
  }
}

TEST(Wrapper, ComplexGivesBackTopsAndCoordinates) {
  const Complex c = Complex::from_arrays(6, {3, 2, 1, 0, 4, 2, 3, 5, 4}, {0, 4, 7, 9},
                                         {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2}, 3);
  EXPECT_EQ(rows_of(c.top_simplices(3).view()), (std::vector<Ids>{{0, 1, 2, 3}}));
  EXPECT_EQ(rows_of(c.top_simplices(2).view()), (std::vector<Ids>{{2, 3, 4}}));
  EXPECT_EQ(rows_of(c.top_simplices(1).view()), (std::vector<Ids>{{4, 5}}));
  EXPECT_TRUE(c.top_simplices(0).empty());
  EXPECT_EQ(status_of([&] { c.top_simplices(4); }), TPX_STATUS_DIMENSION_OUT_OF_RANGE);
  EXPECT_EQ(c.coord_dim(), 3u);
  EXPECT_EQ(c.coords(), (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2}));
  EXPECT_EQ(fixture().coord_dim(), 0u);
  EXPECT_TRUE(fixture().coords().empty());
}

TEST(Wrapper, WriteRoundTripsAndRefuses) {
  // The fixture with coordinates, written as .simplices (format from the extension) and read back.
  const std::vector<double> xyz{0, 0, 0, 0.1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1, 2, 2, 1e-300};
  const Complex c = Complex::from_arrays(6, {3, 2, 1, 0, 4, 2, 3, 5, 4}, {0, 4, 7, 9}, xyz, 3);
  const std::string path = testing::TempDir() + "topoplex_wrapper_write.simplices";
  c.write(path);
  const Complex back = Complex::from_file(path);
  EXPECT_EQ(back.coords(), xyz);
  EXPECT_EQ(rows_of(back.top_simplices(3).view()), (std::vector<Ids>{{0, 1, 2, 3}}));
  // OFF cannot hold the tetrahedron; an explicit format overrides the extension.
  EXPECT_EQ(status_of([&] { c.write(testing::TempDir() + "t.off"); }),
            TPX_STATUS_FORMAT_CANNOT_HOLD);
  EXPECT_EQ(status_of([&] { c.write(testing::TempDir() + "t.xyz"); }), TPX_STATUS_UNKNOWN_FORMAT);
  c.write(testing::TempDir() + "t.xyz", topoplex::Format::MEDIT);
  std::ifstream f(testing::TempDir() + "t.xyz");
  std::string first;
  std::getline(f, first);
  EXPECT_EQ(first, "MeshVersionFormatted 2");
}

// Saved and opened back: every relation of every kind on the reopened (memory-mapped)
// structure equals the fresh one; the complex and a live complex come back too; a cut file is
// refused with a status, not read past its end.
TEST(Wrapper, SavedStructuresOpenBackEqual) {
  const Complex c = fixture();
  const std::string path = testing::TempDir() + "topoplex_wrapper_save.tpx";
  int saved = 0;
  for (Kind k : {Kind::IG, Kind::SIG, Kind::IA, Kind::IQM, Kind::NMIA, Kind::TS, Kind::PE,
                 Kind::LE, Kind::DE}) {
    // IA and the manifold-only kinds refuse this mixed-dimensional fixture at build.
    if (status_of([&] { Structure(c, k); }) == TPX_STATUS_UNSUPPORTED_COMPLEX) continue;
    ++saved;
    const Structure fresh(c, k);
    fresh.save(c, path);
    const Structure back = Structure::open(path, k, /*verify=*/true);
    EXPECT_EQ(back.kind(), k);
    for (std::uint32_t p = 0; p <= 3; ++p) {
      const std::vector<Ids> all = rows_of(fresh.simplices(p).view());
      EXPECT_EQ(rows_of(back.simplices(p).view()), all);
      for (const Ids &s : all) {
        for (std::uint32_t q = 0; q <= 3; ++q) {
          EXPECT_EQ(rows_of(back.relation(s, q).view()), rows_of(fresh.relation(s, q).view()));
        }
      }
    }
  }
  EXPECT_GE(saved, 4);  // IG, SIG, IQM, NMIA at least
  EXPECT_EQ(rows_of(Complex::open(path).top_simplices(2).view()), (std::vector<Ids>{{2, 3, 4}}));

  topoplex::Live live(c);
  live.remove_top({2, 3, 4});
  live.save(path);
  const topoplex::Live reopened = topoplex::Live::open(path);
  EXPECT_EQ(reopened.top_count(2), 0u);
  EXPECT_EQ(reopened.top_count(3), 1u);

  Structure(c, Kind::SIG).save(c, path);
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
  }
  const TpxStatus cut = status_of([&] { Structure::open(path, Kind::SIG); });
  EXPECT_TRUE(cut == TPX_STATUS_SAVED_FILE_TRUNCATED || cut == TPX_STATUS_SAVED_FILE_CORRUPT)
      << cut;
}

TEST(Wrapper, ConstStructureFromTwoThreads) {
  const Structure s(fixture(), Kind::IG);
  std::vector<Ids> got(2);
  std::thread t0([&] { got[0] = s.relation({2}, 0).ids(); });
  std::thread t1([&] { got[1] = s.relation({3}, 0).ids(); });
  t0.join();
  t1.join();
  EXPECT_EQ(got[0], (Ids{0, 1, 3, 4}));
  EXPECT_EQ(got[1], (Ids{0, 1, 2, 4}));
}


// Handles: locate once, ranges of handles, buffer-reusing overloads, per-simplex data, tops as
// given, and bad handles as exceptions with the right status.
TEST(Wrapper, HandlesNavigateTheFixture) {
  const Complex c = fixture();
  const Structure s(c, Kind::NMIA);
  const topoplex::Simplex e = s.locate({3, 2});
  EXPECT_EQ(e.dim(), 1u);
  EXPECT_EQ(s.vertices(e), (Ids{2, 3}));
  std::vector<Ids> tris;
  for (auto t : s.related(e, 2, topoplex::Order::Lexicographic)) tris.push_back(s.vertices(t));
  EXPECT_EQ(tris, (std::vector<Ids>{{0, 2, 3}, {1, 2, 3}, {2, 3, 4}}));
  EXPECT_EQ(s.degree(e, 3), 1u);
  EXPECT_FALSE(s.is_manifold(e));
  Ids buf;
  s.related(s.vertex(4), 0, buf, topoplex::Order::Lexicographic);
  EXPECT_EQ(buf, (Ids{2, 3, 5}));
  Ids offsets, ids;
  s.related_batch(0, {4, 5}, 0, offsets, ids, topoplex::Order::Lexicographic);
  EXPECT_EQ(offsets, (Ids{0, 3, 4}));
  EXPECT_EQ(ids, (Ids{2, 3, 5, 4}));
  // Tops: 4-5, 2 3 4 (given as 4 2 3), 0 1 2 3 (given as 3 2 1 0).
  ASSERT_EQ(s.top_total(), 3u);
  EXPECT_EQ(s.top_as_given(1), (Ids{4, 2, 3}));
  EXPECT_EQ(s.top_as_given(2), (Ids{3, 2, 1, 0}));
  EXPECT_EQ(s.top_id(s.top(2)), 2u);
  topoplex::SimplexData<int> mark(s, 1, 0);
  mark[e] = 7;
  EXPECT_EQ(mark[e.index()], 7);
  EXPECT_EQ(status_of([&] { mark[s.vertex(0)] = 1; }), TPX_STATUS_WRONG_HANDLE_KIND);
  const Structure other(c, Kind::IG);
  EXPECT_EQ(status_of([&] { s.degree(other.locate({2, 3}), 2); }), TPX_STATUS_FOREIGN_HANDLE);
  EXPECT_EQ(status_of([&] { s.handle(1, 999); }), TPX_STATUS_INVALID_HANDLE);
  // Radial groups around edge 2-3: one tetrahedron, so a sweep 0 2 3 -> 1 2 3, then 2 3 4.
  const topoplex::Fans f = s.around_edge(e, 2);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[0].size(), 2u);
  EXPECT_EQ(s.vertices(f[1][0]), (Ids{2, 3, 4}));
}

// Lent relations on the fixture, for every kind that holds it: each view's answers equal
// related() handle by handle; the IG lends its stored edge -> triangle lists (not built), an
// index otherwise (built, kept: the same arrays on the second view); degrees() counts alone.
TEST(Wrapper, RelationViewsIterateInlineAndMatchRelated) {
  const Complex c = fixture();
  for (Kind k : {Kind::IG, Kind::SIG, Kind::IQM, Kind::NMIA}) {
    const Structure s(c, k);
    for (std::uint32_t p = 0; p <= 3; ++p)
      for (std::uint32_t q = 0; q <= 3; ++q) {
        const topoplex::RelationView v = s.view(p, q);
        ASSERT_EQ(v.size(), s.count(p));
        Ids all;
        for (std::uint32_t i = 0; i < v.size(); ++i) {
          Ids got, want;
          for (auto x : v[i]) got.push_back(x.index());
          s.related(s.handle(p, i), q, want);
          EXPECT_EQ(got, want) << "kind " << int(k) << " R_" << p << q << " of " << i;
          EXPECT_EQ(v.degree(i), want.size());
          all.push_back(i);
        }
        Ids deg;
        s.degrees(p, all, q, deg);
        for (std::uint32_t i = 0; i < v.size(); ++i) EXPECT_EQ(deg[i], v.degree(i));
        EXPECT_EQ(s.view(p, q).raw().ids, v.raw().ids);
        if (k == Kind::IG) {
          EXPECT_EQ(v.built(), q != p + 1);
        }
      }
    EXPECT_EQ(status_of([&] { s.view(0, 4); }), TPX_STATUS_DIMENSION_OUT_OF_RANGE);
  }
}

// Circulator over a wound fan: triangles around vertex 0, counter-clockwise by the winding.
//
//        3
//       / \          A = 0 1 2, B given as 2 3 0, C given as 4 1 0: one open fan C, A, B.
//      0---2
//      |\ /
//      4-1
TEST(Wrapper, TrianglesAroundAVertexComeCounterClockwise) {
  const Complex c = Complex::from_simplices(5, {{0, 1, 2}, {2, 3, 0}, {4, 1, 0}});
  for (Kind k : {Kind::TS, Kind::PE, Kind::LE, Kind::DE, Kind::IA, Kind::IG}) {
    const Structure s(c, k);
    std::vector<Ids> order;
    for (auto t : s.triangles_around(s.vertex(0))) order.push_back(s.vertices(t));
    EXPECT_EQ(order, (std::vector<Ids>{{0, 1, 4}, {0, 1, 2}, {0, 2, 3}}));
    const topoplex::Fans f = s.fans_around(s.vertex(0));
    ASSERT_EQ(f.size(), 1u);
    EXPECT_TRUE(f.oriented(0));
    EXPECT_FALSE(f.closed(0));
  }
}

// The live complex navigates by handles like a Structure, across edits, until compact().
TEST(Wrapper, LiveNavigatesByHandlesAcrossEdits) {
  topoplex::Live live(fixture());
  topoplex::Simplex e = live.locate({3, 2});
  std::vector<Ids> tris;
  for (auto t : live.coboundary(e, 2)) tris.push_back(live.vertices(t));
  EXPECT_EQ(tris, (std::vector<Ids>{{0, 2, 3}, {1, 2, 3}, {2, 3, 4}}));
  EXPECT_EQ(live.degree(e, 3), 1u);
  EXPECT_FALSE(live.is_manifold(e));
  EXPECT_EQ(live.star(e).size(), 4u);
  EXPECT_EQ(live.link(live.vertex(5)).size(), 1u);
  const topoplex::HandleFans f = live.around_edge(e, 2);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(live.vertices(f[1][0]), (Ids{2, 3, 4}));
  const topoplex::Simplex t = live.locate({2, 3, 4});
  EXPECT_EQ(live.top_as_given(live.top_id(t)), (Ids{4, 2, 3}));
  live.remove_top({2, 3, 4});
  EXPECT_EQ(status_of([&] { live.degree(t, 0); }), TPX_STATUS_STALE_HANDLE);
  // Edge 2-3 was named through the triangle (the lowest top slot holding it); it lives on in the
  // tetrahedron, and its handle keeps naming it (located again on each use).
  EXPECT_EQ(live.degree(e, 2), 2u);
  EXPECT_EQ(live.vertices(e), (Ids{2, 3}));
  // Many handles at once, dimensions mixed: each answer as the handle alone gives it.
  const std::vector<topoplex::Simplex> asked{e, live.vertex(5), live.locate({0, 2, 3}), live.vertex(4)};
  topoplex::HandleBatch batch;
  for (std::uint32_t q = 0; q <= live.dimension(); ++q) {
    live.related_batch(asked, q, batch);
    ASSERT_EQ(batch.size(), asked.size());
    std::size_t total = 0;
    for (std::size_t k = 0; k < asked.size(); ++k) {
      std::vector<Ids> got, want;
      for (auto x : batch[k]) got.push_back(live.vertices(x));
      for (auto x : live.related(asked[k], q)) want.push_back(live.vertices(x));
      EXPECT_EQ(got, want) << "q " << q << " handle " << k;
      total += batch[k].size();
    }
    EXPECT_EQ(batch.all().size(), total);
  }
  live.related_batch(asked, 1, batch);
  EXPECT_EQ(batch[1].size(), 1u);  // 5's only neighbour edge: the wire 4-5
  EXPECT_EQ(status_of([&] { live.related_batch({e, live.vertex(4)}, 9, batch); }),
            TPX_STATUS_DIMENSION_OUT_OF_RANGE);
  EXPECT_TRUE(batch.empty());
  e = live.locate({2, 3});
  EXPECT_EQ(live.degree(e, 2), 2u);
  live.compact();
  EXPECT_EQ(status_of([&] { live.degree(e, 2); }), TPX_STATUS_STALE_GENERATION);
  // A triangle fan after compaction: around 4 only the wire 4-5 remains.
  EXPECT_EQ(live.related(live.vertex(4), 0).size(), 1u);
}

// Names map to kinds in any ASCII case; an unknown name throws UNKNOWN_KIND.
TEST(Wrapper, KindFromNameKnowsEveryCliName) {
  EXPECT_EQ(topoplex::kind_from_name("pe"), Kind::PE);
  EXPECT_EQ(topoplex::kind_from_name("IaStar"), Kind::IASTAR);
  EXPECT_EQ(topoplex::kind_from_name("NMIA"), Kind::NMIA);
  EXPECT_EQ(status_of([] { topoplex::kind_from_name("halfedge"); }), TPX_STATUS_UNKNOWN_KIND);
  for (Kind k : {Kind::IG, Kind::SIG, Kind::IA, Kind::IQM, Kind::NMIA, Kind::TS, Kind::PE,
                 Kind::LE, Kind::DE, Kind::IASTAR})
    EXPECT_EQ(topoplex::kind_from_name(topoplex::kind_name(k)), k);
  EXPECT_EQ(topoplex::kind_name(Kind::IASTAR), "iastar");
}

// The live complex answers the shared navigation (StructureView) as a built IG does: the same
// counts, handle(p, i) simplices, index(h), views (as sets: natural orders differ) and degrees;
// before and after an edit, which renumbers; Kind::IASTAR builds a Structure that does too.
TEST(Wrapper, LiveSharesTheStructureNavigationAcrossEdits) {
  const auto same_as_ig = [](const topoplex::StructureView &s, const Complex &c) {
    const Structure ig(c, Kind::IG);
    for (std::uint32_t p = 0; p <= ig.dimension(); ++p) {
      ASSERT_EQ(s.count(p), ig.count(p));
      Ids all;
      for (std::uint32_t i = 0; i < ig.count(p); ++i) {
        EXPECT_EQ(s.vertices(s.handle(p, i)), ig.vertices(ig.handle(p, i)));
        EXPECT_EQ(s.index(s.handle(p, i)), i);
        all.push_back(i);
      }
      for (std::uint32_t q = 0; q <= ig.dimension(); ++q) {
        const topoplex::RelationView a = s.view(p, q), b = ig.view(p, q);
        ASSERT_EQ(a.size(), b.size());
        for (std::uint32_t i = 0; i < a.size(); ++i) {
          Ids x, y;
          for (auto h : a[i]) x.push_back(h.index());
          for (auto h : b[i]) y.push_back(h.index());
          std::sort(y.begin(), y.end());
          EXPECT_EQ(x, y) << "R_" << p << q << " of " << i;
        }
        Ids da, db;
        s.degrees(p, all, q, da);
        ig.degrees(p, all, q, db);
        EXPECT_EQ(da, db);
      }
    }
  };
  const Complex c = fixture();
  same_as_ig(Structure(c, Kind::IASTAR), c);
  topoplex::Live live(c);
  same_as_ig(live.as_structure(), c);
  // Per-face data through a lasting handle of the live complex: converted to its index.
  topoplex::SimplexData<int> mark(live.as_structure(), 2);
  mark[live.locate({2, 3, 4})] = 7;
  EXPECT_EQ(mark[4u], 7);  // triangles 012 013 023 123 234
  live.contract(0, 1, topoplex::ContractMode::Free);
  live.compact();
  same_as_ig(live.as_structure(), live.to_complex());
}

// Coordinates set on a Complex and on a Live (one vertex, all at once; lent), refused when not
// finite or of the wrong length; windings lent as views.
TEST(Wrapper, CoordinatesAreSettableAndWindingsLent) {
  Complex c = fixture();
  std::vector<double> xyz(12);
  for (std::size_t i = 0; i < xyz.size(); ++i) xyz[i] = 0.25 * double(i);
  c.set_coords(xyz, 2);
  EXPECT_EQ(c.coord_dim(), 2u);
  EXPECT_EQ(c.coords(), xyz);
  std::vector<double> bad = xyz;
  bad[3] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(status_of([&] { c.set_coords(bad, 2); }), TPX_STATUS_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { c.set_coords(xyz, 3); }), TPX_STATUS_INVALID_ARGUMENT);
  EXPECT_EQ(c.coords(), xyz);
  EXPECT_EQ(c.top_oriented(2, 0).to_vector(), (Ids{4, 2, 3}));

  topoplex::Live live(c);
  const topoplex::CoordsView all = live.all_coords();
  EXPECT_EQ(std::vector<double>(all.begin(), all.end()), xyz);
  std::vector<double> moved(xyz.size(), 1.5);
  live.set_all_coords(moved);
  EXPECT_EQ(std::vector<double>(all.begin(), all.end()), moved);  // written through
  live.set_coords(5, {9.0, 8.0});
  EXPECT_EQ(live.coords(5), (std::vector<double>{9.0, 8.0}));
  EXPECT_EQ(all[10], 9.0);
  EXPECT_EQ(status_of([&] { live.set_coords(5, {std::nan(""), 0.0}); }),
            TPX_STATUS_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { live.set_all_coords(xyz.data(), 11); }), TPX_STATUS_INVALID_ARGUMENT);
  EXPECT_EQ(live.coords(5), (std::vector<double>{9.0, 8.0}));
  const std::uint32_t t = live.top_id(live.locate({2, 3, 4}));
  EXPECT_EQ(live.top_vertices(t).to_vector(), (Ids{4, 2, 3}));
  EXPECT_EQ(live.top_vertices(t).to_vector(), live.top_as_given(t));
  Ids reused;
  live.as_structure().top_as_given(t, reused);
  EXPECT_EQ(reused, (Ids{4, 2, 3}));
  const Structure ig(c, Kind::IG);
  for (std::uint32_t k = 0; k < ig.top_total(); ++k) {
    ig.top_as_given(k, reused);
    EXPECT_EQ(reused, ig.top_as_given(k));
  }
}

// The decomposition class: the bowtie splits into two components at its pinch vertex.
TEST(Wrapper, DecompositionOfTheBowtie) {
  const Complex c = Complex::from_simplices(5, {{0, 1, 2}, {0, 3, 4}});
  const topoplex::Decomposition d(c);
  ASSERT_EQ(d.size(), 2u);
  for (std::size_t i = 0; i < d.size(); ++i) {
    const auto comp = d[i];
    EXPECT_EQ(comp.dimension, 2u);
    EXPECT_EQ(comp.tops.size(), 1u);
    EXPECT_EQ(comp.local_vertex_count, 3u);
  }
}

}  // namespace

namespace {

/* The fixture with data: per vertex a double 2-vector, per listing (tetrahedron, triangle, edge)
 * an int32 label. Typed views lend the numbers set; the wrong type throws; written to VTK and
 * read back, the views hold the same numbers; the live complex reads and writes a top's label by
 * handle and carries it into the complex it gives back. */
TEST(Wrapper, AttributesAreTypedSpansAndSurviveWriteAndLive) {
  Complex c = fixture();
  std::vector<double> velocity;
  for (int i = 0; i < 12; ++i) velocity.push_back(0.5 * i - 1.0);
  const std::vector<std::int32_t> ref{11, 22, 33};
  c.set_attribute("velocity", topoplex::Location::Vertices, 2, velocity);
  c.set_attribute("ref", topoplex::Location::Listed, 1, ref);
  const auto all = c.attributes();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].name, "velocity");
  EXPECT_EQ(all[0].type, topoplex::ValueType::F64);
  EXPECT_EQ(all[0].components, 2u);
  EXPECT_EQ(all[0].elements, 6u);
  EXPECT_EQ(all[1].location, topoplex::Location::Listed);
  auto v = c.attribute<double>("velocity", topoplex::Location::Vertices);
  EXPECT_EQ(v.to_vector(), velocity);
  EXPECT_EQ(v.elements(), 6u);
  EXPECT_EQ(v.element(5)[1], velocity[11]);
  auto r = c.attribute<std::int32_t>("ref", topoplex::Location::Listed);
  EXPECT_EQ(r.to_vector(), ref);
  EXPECT_EQ(status_of([&] { c.attribute<float>("ref", topoplex::Location::Listed); }),
            TPX_STATUS_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { c.attribute<std::int32_t>("ref", topoplex::Location::Vertices); }),
            TPX_STATUS_NO_SUCH_ATTRIBUTE);
  EXPECT_EQ(status_of([&] { c.set_attribute("ref", topoplex::Location::Listed, 1, std::vector<std::int32_t>{1}); }),
            TPX_STATUS_INVALID_ARGUMENT);
  EXPECT_EQ(c.listed_index({2, 3, 4}), 1u);
  EXPECT_EQ(c.listed_index({2, 3}), TPX_NOT_LISTED);
  EXPECT_EQ(c.label_name("ref", 2, 22), "");

  c.write("tpx_cpp_attributes.vtk", topoplex::Format::VTKBinary);
  Complex back = Complex::from_file("tpx_cpp_attributes.vtk");
  std::remove("tpx_cpp_attributes.vtk");
  EXPECT_EQ(back.attribute<double>("velocity", topoplex::Location::Vertices).to_vector(), velocity);
  auto rb = back.attribute<std::int32_t>("ref", topoplex::Location::Listed);
  for (const Ids &s : {Ids{0, 1, 2, 3}, Ids{2, 3, 4}, Ids{4, 5}}) {
    EXPECT_EQ(rb[back.listed_index(s)], r[c.listed_index(s)]);
  }

  topoplex::Live live(c);
  const std::uint32_t tri = live.top_id(live.locate({2, 3, 4}));
  EXPECT_EQ(live.top_values("ref", tri), std::vector<double>{22.0});
  live.set_top_values("ref", tri, {-7.0});
  EXPECT_EQ(live.top_values("ref", tri), std::vector<double>{-7.0});
  EXPECT_EQ(live.vertex_values("velocity", 5), (std::vector<double>{velocity[10], velocity[11]}));
  EXPECT_EQ(status_of([&] { live.set_top_values("ref", tri, {1.0, 2.0}); }), TPX_STATUS_INVALID_ARGUMENT);
  live.set_vertex_policy(topoplex::VertexPolicy::Average);
  Complex frozen = live.to_complex();
  EXPECT_EQ(frozen.attribute<std::int32_t>("ref", topoplex::Location::Listed)[frozen.listed_index({2, 3, 4})], -7);
  c.remove_attribute("ref");
  EXPECT_EQ(c.attributes().size(), 1u);
}

/* A std::function merge at contractions: called per vertex attribute with a, b and both rows,
 * a's row left as it makes it (checked against the rows before), the split restores it; it
 * moves with the Live; set_vertex_values sets one vertex's row; the policy replaces the merge. */
TEST(Wrapper, LiveVertexMergeIsACallersFunctionAndSplitRestores) {
  Complex c = fixture();
  std::vector<double> velocity;
  for (int i = 0; i < 12; ++i) velocity.push_back(0.5 * i - 1.0);
  c.set_attribute("velocity", topoplex::Location::Vertices, 2, velocity);
  c.set_attribute("material", topoplex::Location::Vertices, 1,
                  std::vector<std::int32_t>{10, 11, 12, 13, 14, 15});
  std::vector<std::string> seen;
  topoplex::Live first(c);
  first.set_vertex_merge([&seen](const std::string &name, std::uint32_t a, std::uint32_t b,
                                 double *row_a, const double *row_b, std::size_t k) {
    seen.push_back(name + " " + std::to_string(a) + "<-" + std::to_string(b));
    for (std::size_t i = 0; i < k; ++i) {
      row_a[i] = name == "material" ? std::max(row_a[i], row_b[i]) : row_a[i] - row_b[i];
    }
  });
  topoplex::Live live = std::move(first);  // the merge moves with it
  {
    const topoplex::Undo u = live.contract(4, 5, topoplex::ContractMode::Free);
    EXPECT_EQ(seen, (std::vector<std::string>{"velocity 4<-5", "material 4<-5"}));
    EXPECT_EQ(live.vertex_values("velocity", 4),
              (std::vector<double>{velocity[8] - velocity[10], velocity[9] - velocity[11]}));
    EXPECT_EQ(live.vertex_values("material", 4), std::vector<double>{15.0});
    live.split(u);
  }
  EXPECT_EQ(live.vertex_values("velocity", 4), (std::vector<double>{velocity[8], velocity[9]}));
  live.set_vertex_values("velocity", 1, {3.0, 4.0});
  EXPECT_EQ(live.vertex_values("velocity", 1), (std::vector<double>{3.0, 4.0}));
  EXPECT_EQ(status_of([&] { live.set_vertex_values("velocity", 1, {3.0}); }),
            TPX_STATUS_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { live.set_vertex_values("material", 1, {0.5}); }),
            TPX_STATUS_INVALID_ARGUMENT);
  live.set_vertex_policy(topoplex::VertexPolicy::Survivor);
  live.contract(4, 5, topoplex::ContractMode::Free);
  EXPECT_EQ(seen.size(), 2u);
  EXPECT_EQ(live.vertex_values("velocity", 4), (std::vector<double>{velocity[8], velocity[9]}));
}

/* The live tops of every dimension as (sorted vertices, packed id). */
std::vector<std::pair<Ids, std::uint32_t>> live_tops(const topoplex::Live &live) {
  std::vector<std::pair<Ids, std::uint32_t>> out;
  for (std::uint32_t p = 1; p <= 3; ++p) {
    const auto rows = live.top_simplices(p);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      Ids s(rows[i].begin(), rows[i].end());
      const std::uint32_t id = live.top_id(live.locate(s));
      std::sort(s.begin(), s.end());
      out.emplace_back(s, id);
    }
  }
  return out;
}

/* User properties per vertex and per top, against a brute force keyed by the original vertex
 * ids: values follow their slots through a contraction, its split, a removal and an
 * insertion, and compact() moves them with the renumbering it returns; a new top reads the
 * initial value; names and types are checked. */
TEST(Wrapper, UserPropertiesFollowTheirSlotsThroughEditsAndCompact) {
  topoplex::Live live(fixture());
  auto name = live.add_vertex_property<std::string>("name", "none");
  auto weight = live.add_top_property<double>("weight", -1.0);
  std::map<Ids, double> want;  // by original vertex ids
  for (std::uint32_t v = 0; v < 6; ++v) live.property(name, v) = "v" + std::to_string(v);
  for (const auto &t : live_tops(live)) {
    double w = 0.5;
    for (std::uint32_t v : t.first) w += 1.5 * v;
    live.property(weight, t.second) = w;
    want[t.first] = w;
  }
  EXPECT_THROW(live.add_vertex_property<int>("name"), std::invalid_argument);
  EXPECT_THROW(live.vertex_property<int>("name"), std::invalid_argument);
  EXPECT_THROW(live.top_property<double>("absent"), std::invalid_argument);
  EXPECT_EQ(live.property(live.vertex_property<std::string>("name"), 3), "v3");
  {
    const topoplex::Undo u = live.contract(2, 3, topoplex::ContractMode::Free);
    EXPECT_EQ(live.property(name, 2), "v2");  // the survivor's, untouched
    live.split(u);
  }
  for (const auto &t : live_tops(live)) EXPECT_EQ(live.property(weight, t.second), want.at(t.first));
  // 4 into 5: the triangle [2 3 4] becomes [2 3 5] in its slot, the edge goes, vertex 4 dies.
  live.contract(5, 4, topoplex::ContractMode::Free);
  want[Ids{2, 3, 5}] = want.at(Ids{2, 3, 4});
  want.erase(Ids{2, 3, 4});
  want.erase(Ids{4, 5});
  for (const auto &t : live_tops(live)) EXPECT_EQ(live.property(weight, t.second), want.at(t.first));
  // A new triangle after a removed one: compact() moves it down a slot.
  live.insert_top({0, 1, 5});
  live.remove_top({2, 3, 5});
  want.erase(Ids{2, 3, 5});
  const std::vector<std::uint32_t> map = live.compact();
  EXPECT_EQ(map[4], UINT32_MAX);
  EXPECT_EQ(map[5], 4u);
  std::vector<std::uint32_t> old(live.vertex_slots(), UINT32_MAX);
  for (std::uint32_t v = 0; v < map.size(); ++v) {
    if (map[v] != UINT32_MAX) old[map[v]] = v;
  }
  for (std::uint32_t w = 0; w < live.vertex_slots(); ++w) {
    EXPECT_EQ(live.property(name, w), "v" + std::to_string(old[w])) << w;
  }
  std::size_t inserted = 0;
  for (const auto &t : live_tops(live)) {
    Ids orig;
    for (std::uint32_t v : t.first) orig.push_back(old[v]);
    std::sort(orig.begin(), orig.end());
    const auto it = want.find(orig);
    if (it == want.end()) {
      EXPECT_EQ(orig, (Ids{0, 1, 5}));
      EXPECT_EQ(live.property(weight, t.second), -1.0);
      ++inserted;
    } else {
      EXPECT_EQ(live.property(weight, t.second), it->second);
    }
  }
  EXPECT_EQ(inserted, 1u);
  EXPECT_TRUE(live.remove_property("weight"));
  EXPECT_FALSE(live.remove_property("weight"));
  EXPECT_THROW(live.property(weight, 1u << 28), std::invalid_argument);
}

}  // namespace

// A square written as one quadrilateral: refused as read, naming the polygon; fanned from its
// first vertex when asked, by the complex and by the mesh alike (winding kept).
TEST(Wrapper, QuadIsRefusedOrFannedOnRequest) {
  const std::string path = testing::TempDir() + "topoplex_quad.off";
  {
    std::ofstream f(path);
    f << "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  }
  try {
    Complex::from_file(path);
    ADD_FAILURE() << "a quadrilateral was read as it is";
  } catch (const topoplex::Error &e) {
    EXPECT_NE(std::string(e.what()).find("polygon with 4 vertices"), std::string::npos) << e.what();
  }
  const Complex c = Complex::from_file_triangulated(path);
  EXPECT_EQ(c.top_count(2), 2u);
  topoplex::Live mesh = topoplex::Live::from_file(path, false, true);
  std::vector<std::vector<std::uint32_t>> tops;
  for (auto t : mesh.top_simplices(2)) tops.push_back(t.to_vector());
  EXPECT_EQ(tops, (std::vector<std::vector<std::uint32_t>>{{0, 1, 2}, {0, 2, 3}}));
  std::remove(path.c_str());
}
