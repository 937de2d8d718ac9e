// SPDX-License-Identifier: LGPL-3.0-or-later
// Shared by the benchmark programs: the machine they ran on, and running a
// job in a child process to measure its own peak memory.
#ifndef BLENDED_SHAPE_BENCHMARK_UTIL_H
#define BLENDED_SHAPE_BENCHMARK_UTIL_H

#include <CGAL/version.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

namespace blended_shape_benchmark {

// A command-line count: 1 to 9 decimal digits only (no sign, no trailing
// text; any count these programs take), into `value`; false otherwise,
// `value` unchanged.
inline bool parse_count(const char* text, std::size_t& value)
{
  if(text == nullptr || *text == '\0' || std::strspn(text, "0123456789") != std::strlen(text) || std::strlen(text) > 9)
    return false;
  value = std::size_t(std::strtoul(text, nullptr, 10));
  return true;
}

// A command-line number: a whole finite decimal number (strtod, no trailing
// text), into `value`; false otherwise, `value` unchanged.
inline bool parse_number(const char* text, double& value)
{
  if(text == nullptr || *text == '\0')
    return false;
  char* end = nullptr;
  const double x = std::strtod(text, &end);
  if(end == text || *end != '\0' || !std::isfinite(x))
    return false;
  value = x;
  return true;
}

/// One line on the machine and build: CPU model, cores, compiler, CGAL.
inline std::string machine_description()
{
  std::ifstream cpu("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while(std::getline(cpu, line))
    if(line.rfind("model name", 0) == 0)
    {
      model = line.substr(line.find(':') + 2);
      break;
    }
  std::ostringstream s;
  s << model << ", " << std::thread::hardware_concurrency() << " cores visible, g++ " << __VERSION__
    << ", CGAL " << CGAL_VERSION_STR
#ifdef NDEBUG
    << ", Release";
#else
    << ", NOT a Release build (numbers are meaningless)";
#endif
  return s.str();
}

/// Runs `job()` (which returns a trivially copyable result) in a forked child
/// and returns its result and the child's peak resident memory in MiB.
template <class Result, class Job>
Result run_in_child(Job&& job, double& peak_mib)
{
  int fd[2];
  if(pipe(fd) != 0)
    throw std::runtime_error("pipe() failed");
  const pid_t pid = fork();
  if(pid < 0)
    throw std::runtime_error("fork() failed");
  if(pid == 0)
  {
    close(fd[0]);
    const Result r = job();
    const char* p = reinterpret_cast<const char*>(&r);
    std::size_t left = sizeof(Result);
    while(left > 0)
    {
      const ssize_t n = write(fd[1], p, left);
      if(n <= 0) _exit(1);
      p += n;
      left -= std::size_t(n);
    }
    close(fd[1]);
    _exit(0);
  }
  close(fd[1]);
  Result r;
  char* p = reinterpret_cast<char*>(&r);
  std::size_t got = 0;
  while(got < sizeof(Result))
  {
    const ssize_t n = read(fd[0], p + got, sizeof(Result) - got);
    if(n <= 0) break;
    got += std::size_t(n);
  }
  close(fd[0]);
  int status = 0;
  struct rusage usage;
  std::memset(&usage, 0, sizeof usage);
  wait4(pid, &status, 0, &usage);
  if(got != sizeof(Result) || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("a benchmark job failed in its child process");
  peak_mib = double(usage.ru_maxrss) / 1024.; // kilobytes on Linux
  return r;
}

} // namespace blended_shape_benchmark

#endif
