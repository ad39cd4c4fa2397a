// topoplex_bench_data [--quick] [--only FAMILY,...] [--list] OUTDIR
//
// Makes the benchmark datasets into OUTDIR (see docs/benchmarks.md, "Side by side with
// OpenMesh, CGAL and GUDHI"): surf-<name>-<ntri>.off, tet-<name>-<ntet>.mesh,
// alpha-<points>-<ntop>.simplices, rips-<points>-<ntop>.simplices. A dataset already made (its
// record OUTDIR/.meta/<id>.tsv and its file exist) is skipped. OUTDIR/datasets.tsv lists every
// made dataset: file, vertices, top simplices, top simplices by dimension, generation seconds
// (wall clock, then CPU), source, parameters. --quick: only the ~10^4 and ~10^5 sizes. --list: print the plan only.
// Inputs: $TOPOPLEX_CGAL_DATA (CGAL's data/ directory; default: extracted at configure time)
// and $TOPOPLEX_SHARED_DATA (../shared/data; its copies of the CGAL meshes are preferred).
#include "common.hpp"

#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <set>
#include <sstream>

using namespace bench_data;

namespace {

// The plan. Sizes are what the inputs give: Loop subdivision multiplies triangles by 4, the
// other families are tuned to their target (see each file).
const std::vector<Spec> kSpecs = {
    {"surf-fandisk-0", "surf", "fandisk", 12946, 0, true},      // 12,946 triangles (CAD part)
    {"surf-elephant-1", "surf", "elephant", 22232, 1, true},    // 22,232
    {"surf-elephant-2", "surf", "elephant", 88928, 2, true},    // 88,928
    {"surf-elephant-4", "surf", "elephant", 1422848, 4, false}, // 1,422,848
    {"surf-bunny00-2", "surf", "bunny00", 1206528, 2, false},   // 1,206,528 (scanned)
    {"tet-bunny00-1e4", "tet", "bunny00", 10000, 0, true},
    {"tet-bunny00-1e5", "tet", "bunny00", 100000, 0, true},
    {"tet-bunny00-1e6", "tet", "bunny00", 1000000, 0, false},
    {"tet-elephant-1e5", "tet", "elephant", 100000, 0, true},
    {"alpha-kitten-1e4", "alpha", "kitten.xyz", 10000, 3, true},
    {"alpha-building-1e5", "alpha", "building.ply", 100000, 3, true},
    // No CGAL point set is large enough for 10^6 maximal simplices: a dense scan-like cloud from
    // the bunny scan's mesh, refined.
    {"alpha-bunny00L2-1e6", "alpha", "bunny00", 1000000, 3, false, 2},
    {"rips-kitten-1e4", "rips", "kitten.xyz", 10000, 4, true},
    {"rips-kitten-1e5", "rips", "kitten.xyz", 100000, 4, true},
    {"rips-building-1e6", "rips", "building.ply", 1000000, 4, false},
};

std::string env_or(const char* name, const char* fallback) {
  const char* v = std::getenv(name);
  return v && *v ? v : fallback;
}

Made run(const Env& env, const Spec& s) {
  if (s.family == "surf") return make_surf(env, s);
  if (s.family == "tet") return make_tets(env, s);
  if (s.family == "alpha") return make_alpha(env, s);
  return make_rips(env, s);
}

std::string tsv(const Made& m, double cpu_seconds) {
  std::ostringstream o;
  o << m.file << '\t' << m.vertices << '\t' << m.top << '\t' << m.top_by_dim << '\t' << m.seconds
    << '\t' << cpu_seconds << '\t' << m.source << '\t' << m.params << '\n';
  return o.str();
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, list = false;
  std::set<std::string> only;
  std::string out;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--quick") {
      quick = true;
    } else if (a == "--list") {
      list = true;
    } else if (a == "--only" && i + 1 < argc) {
      std::stringstream ss(argv[++i]);
      for (std::string f; std::getline(ss, f, ',');) only.insert(f);
    } else if (!a.empty() && a[0] != '-' && out.empty()) {
      out = a;
    } else {
      std::fprintf(stderr, "usage: %s [--quick] [--only surf,tet,alpha,rips] [--list] OUTDIR\n",
                   argv[0]);
      return 2;
    }
  }
  if (out.empty() && !list) {
    std::fprintf(stderr, "usage: %s [--quick] [--only surf,tet,alpha,rips] [--list] OUTDIR\n",
                 argv[0]);
    return 2;
  }
  Env env{out, env_or("TOPOPLEX_CGAL_DATA", TOPOPLEX_CGAL_DATA_DEFAULT),
          env_or("TOPOPLEX_SHARED_DATA", TOPOPLEX_SHARED_DATA_DEFAULT)};
  std::vector<Spec> plan;
  for (const auto& s : kSpecs)
    if ((!quick || s.quick) && (only.empty() || only.count(s.family))) plan.push_back(s);
  if (list) {
    for (const auto& s : plan)
      std::printf("%s\t%s\t%s\t%ld\n", s.id.c_str(), s.family.c_str(), s.source.c_str(), s.target);
    return 0;
  }
  fs::create_directories(env.out / ".meta");

  int failed = 0;
  for (const auto& s : plan) {
    fs::path meta = env.out / ".meta" / (s.id + ".tsv");
    if (fs::exists(meta)) {
      std::ifstream in(meta);
      std::string file;
      std::getline(in, file, '\t');
      if (fs::exists(env.out / file)) {
        std::printf("%-22s cached: %s\n", s.id.c_str(), file.c_str());
        continue;
      }
    }
    std::printf("%-22s making (target %s top simplices) ...\n", s.id.c_str(),
                with_commas(static_cast<std::size_t>(s.target)).c_str());
    std::fflush(stdout);
    auto t0 = std::chrono::steady_clock::now();
    std::clock_t c0 = std::clock();  // single-threaded: CPU time tells the cost on a busy machine
    try {
      Made m = run(env, s);
      m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
      std::ofstream(meta) << tsv(m, cpu);
      std::printf("%-22s -> %s: %s vertices, %s top simplices (%s), %.1f s (CPU %.1f s)\n",
                  s.id.c_str(), m.file.c_str(), with_commas(m.vertices).c_str(),
                  with_commas(m.top).c_str(), m.top_by_dim.c_str(), m.seconds, cpu);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: FAILED: %s\n", s.id.c_str(), e.what());
      ++failed;
    }
    std::fflush(stdout);
  }

  // datasets.tsv: every dataset made so far (not only this run's plan), in plan order.
  std::ofstream all(env.out / "datasets.tsv");
  all << "file\tvertices\ttop\ttop_by_dim\tseconds\tcpu_seconds\tsource\tparams\n";
  for (const auto& s : kSpecs) {
    fs::path meta = env.out / ".meta" / (s.id + ".tsv");
    if (!fs::exists(meta)) continue;
    std::ifstream in(meta);
    std::string line;
    std::getline(in, line);
    std::string file = line.substr(0, line.find('\t'));
    if (fs::exists(env.out / file)) all << line << '\n';
  }
  return failed ? 1 : 0;
}
