// SPDX-License-Identifier: LGPL-3.0-or-later
// The command-line conventions shared by the blended_* tools: `--help` prints
// the usage and exits 0; a command-line mistake prints "TOOL: what" and exits
// 2; any other failure prints "TOOL: what" and exits 1. Values are parsed
// strictly: "12x", "nan" or "1,2" where three numbers are expected are errors.
#ifndef BLENDED_SHAPE_TOOLS_INTERNAL_COMMAND_LINE_H
#define BLENDED_SHAPE_TOOLS_INTERNAL_COMMAND_LINE_H

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

namespace blended_shape_tools {

/// A mistake on the command line (exit code 2).
struct Usage_error : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// The arguments after the program name, consumed left to right.
class Arguments
{
public:
  Arguments(int argc, char** argv) : m_args(argv + (argc > 0 ? 1 : 0), argv + (argc > 0 ? argc : 0)) {}

  bool empty() const { return m_position >= m_args.size(); }
  const std::string& next() { return m_args[m_position++]; }

  /// The value following `flag`; a missing value (or another flag) is a usage error.
  std::string value_of(const std::string& flag)
  {
    if(empty() || m_args[m_position].rfind("--", 0) == 0)
      throw Usage_error("missing value after " + flag);
    return next();
  }

  bool wants_help() const
  {
    return std::any_of(m_args.begin(), m_args.end(),
                       [](const std::string& a) { return a == "--help" || a == "-h"; });
  }

private:
  std::vector<std::string> m_args;
  std::size_t m_position = 0;
};

/// A flag is anything starting with '-' except a lone "-".
inline bool is_flag(const std::string& a) { return a.size() > 1 && a[0] == '-'; }

/// A finite number, the whole text.
inline double parse_number(const std::string& flag, const std::string& text)
{
  if(text.empty() || std::isspace(static_cast<unsigned char>(text[0])))
    throw Usage_error(flag + ": '" + text + "' is not a number");
  errno = 0;
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if(end != text.c_str() + text.size())
    throw Usage_error(flag + ": '" + text + "' is not a number");
  if(errno == ERANGE || !std::isfinite(x))
    throw Usage_error(flag + ": '" + text + "' is not a finite number");
  return x;
}

/// A non-negative integer, digits only.
inline std::uint64_t parse_integer(const std::string& flag, const std::string& text)
{
  std::uint64_t n = 0;
  const char* last = text.data() + text.size();
  const auto r = std::from_chars(text.data(), last, n);
  if(text.empty() || r.ptr != last || r.ec == std::errc::invalid_argument)
    throw Usage_error(flag + ": '" + text + "' is not a non-negative integer");
  if(r.ec == std::errc::result_out_of_range)
    throw Usage_error(flag + ": '" + text + "' is too large");
  return n;
}

/// Exactly `n` comma-separated finite numbers.
inline std::vector<double> parse_numbers(const std::string& flag, const std::string& text, std::size_t n)
{
  std::vector<double> values;
  std::size_t start = 0;
  while(true)
  {
    const std::size_t comma = text.find(',', start);
    values.push_back(parse_number(flag, text.substr(start, comma == std::string::npos ? std::string::npos
                                                                                        : comma - start)));
    if(comma == std::string::npos)
      break;
    start = comma + 1;
  }
  if(values.size() != n)
    throw Usage_error(flag + ": '" + text + "' has " + std::to_string(values.size()) + " values; give " +
                      std::to_string(n) + " comma-separated numbers");
  return values;
}

inline std::array<double, 3> parse_triple(const std::string& flag, const std::string& text)
{
  const std::vector<double> v = parse_numbers(flag, text, 3);
  return {{v[0], v[1], v[2]}};
}

/// The lower-case extension of a file name, without the dot ("" if none).
inline std::string extension_of(const std::string& filename)
{
  const std::size_t slash = filename.find_last_of("/\\");
  const std::size_t dot = filename.find_last_of('.');
  if(dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return std::string();
  std::string ext = filename.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

/// Runs `body(arguments)` with the conventions above; returns the exit code.
template <class Body>
int run_tool(const char* tool, const std::string& usage, int argc, char** argv, Body&& body)
{
  Arguments arguments(argc, argv);
  if(arguments.wants_help())
  {
    std::cout << usage;
    return 0;
  }
  try
  {
    body(arguments);
    return 0;
  }
  catch(const Usage_error& e)
  {
    std::cerr << tool << ": " << e.what() << "\nRun '" << tool << " --help' for the usage." << std::endl;
    return 2;
  }
  catch(const std::bad_alloc&)
  {
    std::cerr << tool << ": out of memory; use a smaller input or resolution" << std::endl;
    return 1;
  }
  catch(const std::exception& e)
  {
    std::cerr << tool << ": " << e.what() << std::endl;
    return 1;
  }
}

} // namespace blended_shape_tools

#endif // BLENDED_SHAPE_TOOLS_INTERNAL_COMMAND_LINE_H
