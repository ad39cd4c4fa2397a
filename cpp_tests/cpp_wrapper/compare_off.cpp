// compare_off GOT.off WANT.off: the two OFF files hold the same mesh — the same counts and face
// lines exactly, every coordinate within 1e-12 of the larger magnitude (mesh_app sums a one-ring
// in the order its star names the neighbours; the expected file was written by another path,
// which summed them ascending, so the last bits may differ). Exit 0 when they match, else 1 with
// the first difference.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

bool tokens(const char *path, std::vector<std::string> &out) {
  std::ifstream in(path);
  if (!in) return false;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    for (std::string w; words >> w;) out.push_back(w);
  }
  return true;
}

}  // namespace

int main(int argc, char **argv) {
  std::vector<std::string> got, want;
  if (argc != 3 || !tokens(argv[1], got) || !tokens(argv[2], want)) {
    std::fprintf(stderr, "usage: compare_off GOT.off WANT.off (both readable)\n");
    return 1;
  }
  if (got.size() != want.size() || want.size() < 4) {
    std::fprintf(stderr, "%zu tokens, want %zu\n", got.size(), want.size());
    return 1;
  }
  const std::size_t coords = 3 * std::stoul(want[1]);
  for (std::size_t i = 0; i < want.size(); ++i) {
    const bool coordinate = i >= 4 && i < 4 + coords;
    bool same = got[i] == want[i];
    if (!same && coordinate) {
      const double g = std::stod(got[i]), w = std::stod(want[i]);
      same = std::fabs(g - w) <= 1e-12 * std::fmax(1.0, std::fmax(std::fabs(g), std::fabs(w)));
    }
    if (!same) {
      std::fprintf(stderr, "token %zu: '%s', want '%s'\n", i, got[i].c_str(), want[i].c_str());
      return 1;
    }
  }
  return 0;
}
