// SPDX-License-Identifier: LGPL-3.0-or-later
// For the tests that run the command-line tools: a temporary directory that
// removes itself, and running a command with its output captured.
#ifndef CGAL_BLENDED_SHAPE_TOOL_TEST_UTIL_H
#define CGAL_BLENDED_SHAPE_TOOL_TEST_UTIL_H

#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

struct Temp_dir
{
  std::filesystem::path path;
  explicit Temp_dir(const std::string& prefix = "blended_test")
  {
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    path = std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(stamp));
    std::filesystem::create_directories(path);
  }
  ~Temp_dir()
  {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
  std::size_t number_of_files() const
  {
    return std::size_t(std::distance(std::filesystem::directory_iterator(path), std::filesystem::directory_iterator()));
  }
};

// Runs a command with stdout and stderr captured; returns the exit code
// (-1 if it did not exit normally).
inline int run(const std::string& command, const Temp_dir& dir, std::string* err = nullptr,
               std::string* out = nullptr)
{
  const std::string out_file = dir / "cmd_stdout.txt", err_file = dir / "cmd_stderr.txt";
  const int status = std::system((command + " >\"" + out_file + "\" 2>\"" + err_file + "\"").c_str());
  auto slurp = [](const std::string& file) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  };
  if(err) *err = slurp(err_file);
  if(out) *out = slurp(out_file);
  std::error_code ignored;
  std::filesystem::remove(out_file, ignored);
  std::filesystem::remove(err_file, ignored);
  if(status == -1 || !WIFEXITED(status))
    return -1;
  return WEXITSTATUS(status);
}

inline std::string quote(const std::string& s) { return "\"" + s + "\""; }

#endif
