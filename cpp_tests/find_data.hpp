// Where an optional data file of the C++ tests is: in the directory the environment variable
// names (the user's override), else in the one the build configured. Shared by peers/ and
// decompose/ (header-only: each is its own executable).
#pragma once

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace topoplex_tests {

// `relative` under $env_var, else under `fallback` (an empty directory is skipped); empty when
// neither holds a readable file.
inline std::string find_data_file(const char* env_var, const char* fallback, const std::string& relative) {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv(env_var)) dirs.emplace_back(env);
  dirs.emplace_back(fallback);
  for (const auto& d : dirs) {
    if (d.empty()) continue;
    const std::string path = d + "/" + relative;
    if (std::ifstream(path).good()) return path;
  }
  return {};
}

}  // namespace topoplex_tests

// Declares `var` as the path of data file `relative` (find_data_file's search), or skips the
// current test, naming the file and the variable that points elsewhere.
#define TOPOPLEX_REQUIRE_DATA_FILE(var, env_var, fallback, relative)                         \
  const std::string var = ::topoplex_tests::find_data_file(env_var, fallback, relative); \
  if (var.empty())                                                                        \
  GTEST_SKIP() << "data file " << (relative) << " not found (set " env_var ")"
