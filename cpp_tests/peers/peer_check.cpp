#include "peer_check.hpp"

#include "../find_data.hpp"

#include <gtest/gtest.h>
#include <topoplex.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <numeric>
#include <sstream>

#ifndef TOPOPLEX_PEERS_DATA_DIR
#define TOPOPLEX_PEERS_DATA_DIR ""
#endif
#ifndef TOPOPLEX_PEERS_SHARED_DATA_DIR
#define TOPOPLEX_PEERS_SHARED_DATA_DIR ""
#endif

namespace peers {
namespace {

const char* const kKindNames[9] = {"IG", "SIG", "IA", "IQM", "NMIA", "TS", "PE", "LE", "DE"};
constexpr uint32_t kKindIg = 0;
constexpr uint32_t kKindCount = 9;
// Mismatches printed per (kind, relation); the rest are only counted.
constexpr size_t kShownMismatches = 5;

std::string status_name(uint32_t s) {
  static const char* const names[] = {
      "OK",           "NULL_ARGUMENT",         "INVALID_ARGUMENT", "IO_ERROR",
      "PARSE_ERROR",  "INVALID_COMPLEX",       "UNKNOWN_KIND",     "NOT_IMPLEMENTED",
      "UNSUPPORTED_COMPLEX", "NOT_IN_COMPLEX", "INVALID_SIMPLEX",  "DIMENSION_OUT_OF_RANGE",
      "BUFFER_TOO_SMALL", "TOO_LARGE",         "PANIC"};
  if (s < sizeof(names) / sizeof(names[0])) return names[s];
  return "status " + std::to_string(s);
}

std::string last_error() {
  const char* m = tpx_last_error_message();
  return m ? m : "";
}

std::string show(const uint32_t* ids, size_t n) {
  std::string s = "[";
  for (size_t i = 0; i < n; ++i) s += (i ? " " : "") + std::to_string(ids[i]);
  return s + "]";
}

std::string show_rows(const std::vector<uint32_t>& rows, size_t arity) {
  std::string s = "{";
  for (size_t i = 0; i < rows.size(); i += arity) s += (i ? " " : "") + show(&rows[i], arity);
  return s + "}";
}

// Sorts flat rows of `arity` ids lexicographically; returns false if two rows are equal.
bool sort_flat_rows(std::vector<uint32_t>& rows, size_t arity) {
  const size_t n = rows.size() / arity;
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t{0});
  auto row_less = [&](size_t a, size_t b) {
    return std::lexicographical_compare(rows.begin() + a * arity, rows.begin() + (a + 1) * arity,
                                        rows.begin() + b * arity, rows.begin() + (b + 1) * arity);
  };
  std::sort(order.begin(), order.end(), row_less);
  std::vector<uint32_t> sorted;
  sorted.reserve(rows.size());
  for (size_t i : order) sorted.insert(sorted.end(), rows.begin() + i * arity, rows.begin() + (i + 1) * arity);
  rows.swap(sorted);
  for (size_t i = 1; i < n; ++i)
    if (std::equal(rows.begin() + (i - 1) * arity, rows.begin() + i * arity, rows.begin() + i * arity))
      return false;
  return true;
}

struct ComplexHandle {
  TpxComplex* p = nullptr;
  ~ComplexHandle() { tpx_complex_free(p); }
};
struct StructureHandle {
  TpxStructure* p = nullptr;
  ~StructureHandle() { tpx_structure_free(p); }
};
struct TableHandle {
  TpxRelationTable* p = nullptr;
  ~TableHandle() { tpx_relation_table_free(p); }
};

// All p-simplices of the structure as flat rows (ascending lexicographic by the ABI).
bool structure_simplices(const TpxStructure* s, uint32_t p, std::vector<uint32_t>* out) {
  size_t needed = 0;
  uint32_t st = tpx_structure_simplices(s, p, nullptr, 0, &needed);
  if (st != TPX_STATUS_OK && st != TPX_STATUS_BUFFER_TOO_SMALL) {
    ADD_FAILURE() << "tpx_structure_simplices(p=" << p << "): " << status_name(st) << ": " << last_error();
    return false;
  }
  out->assign(needed, 0);
  size_t written = 0;
  st = tpx_structure_simplices(s, p, out->data(), out->size(), &written);
  if (st != TPX_STATUS_OK) {
    ADD_FAILURE() << "tpx_structure_simplices(p=" << p << ") with " << needed
                  << " ids of room: " << status_name(st) << ": " << last_error();
    return false;
  }
  EXPECT_EQ(written, needed) << "tpx_structure_simplices(p=" << p << ") wrote a different length than it asked for";
  out->resize(written);
  return true;
}

// Compares one relation for one built structure; returns the number of mismatching simplices.
size_t compare_relation(const TpxStructure* s, const std::string& where, Relation& rel,
                        const std::vector<uint32_t>& simplices) {
  const uint32_t p = rel.p(), q = rel.q();
  const size_t pa = p + 1, qa = q + 1;
  const auto& entries = rel.entries();
  const std::string label = where + " R_{" + std::to_string(p) + "," + std::to_string(q) + "} (" + rel.name() + ")";

  // The p-simplices themselves: the peer answered exactly the complex's p-simplices.
  const size_t n_p = simplices.size() / pa;
  if (n_p != entries.size()) {
    ADD_FAILURE() << label << ": Topoplex has " << n_p << " " << p << "-simplices, the peer answered for "
                  << entries.size();
    return 1;
  }
  for (size_t i = 0; i < n_p; ++i) {
    if (!std::equal(entries[i].sigma.begin(), entries[i].sigma.end(), simplices.begin() + i * pa)) {
      ADD_FAILURE() << label << ": " << i << "-th " << p << "-simplex is " << show(&simplices[i * pa], pa)
                    << " in Topoplex but " << show(entries[i].sigma.data(), pa) << " in the peer";
      return 1;
    }
  }

  TableHandle table;
  uint32_t st = tpx_relation_table(s, p, q, &table.p);
  if (st != TPX_STATUS_OK) {
    ADD_FAILURE() << label << ": tpx_relation_table: " << status_name(st) << ": " << last_error();
    return 1;
  }
  size_t n_offsets = 0, n_ids = 0;
  const size_t* offsets = tpx_relation_table_offsets(table.p, &n_offsets);
  const uint32_t* ids = tpx_relation_table_ids(table.p, &n_ids);
  if (n_offsets != n_p + 1 || offsets == nullptr || (n_ids > 0 && ids == nullptr) || offsets[0] != 0 ||
      offsets[n_p] != n_ids) {
    ADD_FAILURE() << label << ": relation table shape: " << n_offsets << " offsets for " << n_p
                  << " simplices, " << n_ids << " ids, last offset " << (n_offsets ? offsets[n_offsets - 1] : 0);
    return 1;
  }

  size_t mismatches = 0;
  std::vector<uint32_t> got;
  for (size_t i = 0; i < n_p; ++i) {
    const size_t b = offsets[i], e = offsets[i + 1];
    std::string problem;
    if (e < b || (e - b) % qa != 0) {
      problem = "row block of " + std::to_string(e - b) + " ids is not whole rows";
    } else {
      got.assign(ids + b, ids + e);
      for (size_t r = 0; r < got.size() && problem.empty(); r += qa)
        for (size_t k = 1; k < qa; ++k)
          if (got[r + k - 1] >= got[r + k]) problem = "row " + show(&got[r], qa) + " is not ascending";
      if (problem.empty() && !sort_flat_rows(got, qa)) problem = "a row is listed twice: " + show_rows(got, qa);
      if (problem.empty() && got != entries[i].rows) problem = "answers differ";
    }
    if (!problem.empty()) {
      if (mismatches < kShownMismatches)
        ADD_FAILURE() << label << " of " << show(entries[i].sigma.data(), pa) << ": " << problem
                      << "\n  Topoplex: " << show_rows(std::vector<uint32_t>(ids + b, ids + std::max(b, e)), qa)
                      << "\n  peer:     " << show_rows(entries[i].rows, qa);
      ++mismatches;
    }
  }
  if (mismatches > kShownMismatches)
    ADD_FAILURE() << label << ": " << mismatches << " of " << n_p << " simplices differ in all";
  return mismatches;
}

}  // namespace

void Relation::add(Ids sigma, std::vector<Ids> rows) {
  std::sort(sigma.begin(), sigma.end());
  EXPECT_EQ(sigma.size(), p_ + 1) << name_ << ": peer gave a simplex of the wrong size";
  std::vector<uint32_t> flat;
  flat.reserve(rows.size() * (q_ + 1));
  for (auto& r : rows) {
    std::sort(r.begin(), r.end());
    EXPECT_EQ(r.size(), q_ + 1) << name_ << ": peer gave a row of the wrong size for " << show(sigma.data(), sigma.size());
    if (r.size() != q_ + 1) return;
    flat.insert(flat.end(), r.begin(), r.end());
  }
  if (!sort_flat_rows(flat, q_ + 1))
    ADD_FAILURE() << name_ << ": peer listed a row twice for " << show(sigma.data(), sigma.size()) << ": "
                  << show_rows(flat, q_ + 1);
  entries_.push_back(Entry{std::move(sigma), std::move(flat)});
  sorted_ = false;
}

const std::vector<Relation::Entry>& Relation::entries() {
  if (!sorted_) {
    std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) { return a.sigma < b.sigma; });
    for (size_t i = 1; i < entries_.size(); ++i)
      if (entries_[i - 1].sigma == entries_[i].sigma)
        ADD_FAILURE() << name_ << ": peer answered " << show(entries_[i].sigma.data(), entries_[i].sigma.size())
                      << " twice";
    sorted_ = true;
  }
  return entries_;
}

RelationGrid add_relations(std::vector<Relation>& rels, const std::string& peer, uint32_t dim,
                           const std::vector<std::string>& names) {
  const RelationGrid grid{rels, rels.size(), dim};
  for (uint32_t p = 0; p <= dim; ++p)
    for (uint32_t q = 0; q <= dim; ++q) {
      const size_t i = size_t(p) * (dim + 1) + q;
      rels.emplace_back(p, q, peer + " " + (names.empty() ? std::to_string(p) + "->" + std::to_string(q) : names.at(i)));
    }
  return grid;
}

KindsReport check_all_kinds(const PeerComplex& cx, std::vector<Relation>& relations) {
  KindsReport report;
  ComplexHandle complex;
  const double* coords = cx.coords.empty() ? nullptr : cx.coords.data();
  uint32_t st = tpx_complex_from_arrays(cx.n_vertices, cx.ids.data(), cx.offsets.data(), cx.simplex_count(), coords,
                                        cx.coord_dim, &complex.p);
  if (st != TPX_STATUS_OK) {
    ADD_FAILURE() << cx.name << ": tpx_complex_from_arrays: " << status_name(st) << ": " << last_error();
    return report;
  }
  uint32_t n = 0, dim = 0;
  EXPECT_EQ(tpx_complex_vertex_count(complex.p, &n), TPX_STATUS_OK);
  EXPECT_EQ(n, cx.n_vertices) << cx.name << ": vertex count";
  EXPECT_EQ(tpx_complex_dimension(complex.p, &dim), TPX_STATUS_OK);
  if (!cx.expected_tops.empty()) {
    EXPECT_EQ(dim + 1, cx.expected_tops.size()) << cx.name << ": dimension";
    for (uint32_t p = 0; p < cx.expected_tops.size(); ++p) {
      size_t tops = 0;
      EXPECT_EQ(tpx_complex_top_count(complex.p, p, &tops), TPX_STATUS_OK);
      EXPECT_EQ(tops, cx.expected_tops[p]) << cx.name << ": top " << p << "-simplices (peer's count)";
    }
  }

  // Sort once, outside the per-kind loop; also the number of p-simplices per p.
  std::map<uint32_t, size_t> peer_counts;
  for (auto& rel : relations) peer_counts[rel.p()] = rel.entries().size();

  for (uint32_t kind = 0; kind < kKindCount; ++kind) {
    const std::string kname = kKindNames[kind];
    const auto start = std::chrono::steady_clock::now();
    StructureHandle s;
    st = tpx_structure_build(complex.p, kind, &s.p);
    if (st == TPX_STATUS_NOT_IMPLEMENTED || st == TPX_STATUS_UNSUPPORTED_COMPLEX) {
      std::string msg = last_error();
      if (kind == kKindIg) ADD_FAILURE() << cx.name << ": the IG must encode every complex, got " << status_name(st) << ": " << msg;
      report.skipped.push_back(kname + ": " + status_name(st) + (msg.empty() ? "" : ": " + msg));
      continue;
    }
    if (st != TPX_STATUS_OK) {
      ADD_FAILURE() << cx.name << ": tpx_structure_build(" << kname << "): " << status_name(st) << ": " << last_error();
      continue;
    }
    const std::string where = cx.name + " [" + kname + "]";
    uint32_t got_kind = 99, sdim = 99;
    EXPECT_EQ(tpx_structure_kind(s.p, &got_kind), TPX_STATUS_OK);
    EXPECT_EQ(got_kind, kind) << where;
    EXPECT_EQ(tpx_structure_dimension(s.p, &sdim), TPX_STATUS_OK);
    EXPECT_EQ(sdim, dim) << where;
    for (const auto& [p, count] : peer_counts) {
      size_t n_p = 0;
      EXPECT_EQ(tpx_structure_count(s.p, p, &n_p), TPX_STATUS_OK);
      EXPECT_EQ(n_p, count) << where << ": number of " << p << "-simplices";
    }
    std::map<uint32_t, std::vector<uint32_t>> simplices;
    size_t bad = 0;
    for (auto& rel : relations) {
      auto it = simplices.find(rel.p());
      if (it == simplices.end()) {
        std::vector<uint32_t> list;
        if (!structure_simplices(s.p, rel.p(), &list)) {
          ++bad;
          continue;
        }
        it = simplices.emplace(rel.p(), std::move(list)).first;
      }
      bad += compare_relation(s.p, where, rel, it->second);
    }
    // Wall time of build + comparison, for the log only (speed belongs in benches).
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    char took[32];
    std::snprintf(took, sizeof took, " %.2fs", secs);
    report.checked.push_back(kname + (bad ? " (MISMATCHES)" : "") + took);
  }

  std::ostringstream line;
  line << "[peers] " << cx.name << ": " << cx.n_vertices << " vertices, dimension " << dim << ", "
       << relations.size() << " relations; kinds checked:";
  for (auto& k : report.checked) line << " " << k;
  if (report.checked.empty()) line << " none";
  for (auto& k : report.skipped) line << "\n[peers]   skipped " << k;
  std::cout << line.str() << std::endl;
  std::string checked;
  for (auto& k : report.checked) checked += (checked.empty() ? "" : " ") + k;
  ::testing::Test::RecordProperty("kinds_checked", checked);
  return report;
}

std::string data_file(const std::string& relative) {
  return topoplex_tests::find_data_file("TOPOPLEX_CGAL_DATA", TOPOPLEX_PEERS_DATA_DIR, relative);
}

std::string shared_data_file(const std::string& relative) {
  return topoplex_tests::find_data_file("TOPOPLEX_SHARED_DATA", TOPOPLEX_PEERS_SHARED_DATA_DIR, relative);
}

std::vector<double> read_xyz(const std::string& path) {
  std::vector<double> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    double x, y, z;
    if (line.empty() || line[0] == '#') continue;
    if (ls >> x >> y >> z) out.insert(out.end(), {x, y, z});
  }
  return out;
}

bool off_counts(const std::string& path, size_t* vertices, size_t* faces) {
  std::ifstream in(path);
  std::string line, tokens;
  // Header keyword, then three counts; '#' comments may sit anywhere.
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    tokens += " " + line;
    std::istringstream ts(tokens);
    std::string head;
    size_t nv, nf, ne;
    if (!(ts >> head)) continue;
    if (head.size() < 3 || head.compare(head.size() - 3, 3, "OFF") != 0) return false;
    if (ts >> nv >> nf >> ne) {
      *vertices = nv;
      *faces = nf;
      return true;
    }
  }
  return false;
}

std::vector<Ids> faces_of(const Ids& sigma, uint32_t q) {
  std::vector<Ids> out;
  const size_t n = sigma.size(), k = q + 1;
  if (k > n) return out;
  std::vector<bool> pick(n, false);
  std::fill(pick.begin(), pick.begin() + k, true);
  do {
    Ids f;
    for (size_t i = 0; i < n; ++i)
      if (pick[i]) f.push_back(sigma[i]);
    out.push_back(std::move(f));
  } while (std::prev_permutation(pick.begin(), pick.end()));
  return out;
}

std::string test_name_of(const std::string& path) {
  std::string s = path.substr(path.find('/') + 1);
  s = s.substr(0, s.find('.'));
  for (auto& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

}  // namespace peers
