// SPDX-License-Identifier: LGPL-3.0-or-later
// The command-line conventions shared by the blended_* tools: `--help` prints
// the usage and exits 0; a command-line mistake prints "TOOL: what" and exits
// 2; any other failure prints "TOOL: what" and exits 1. Boost.Program_options
// splits the command line (unknown options, missing values); the values are
// parsed here, strictly: "12x", "nan" or "1,2" where three numbers are
// expected are errors (Program_options' own conversions accept "nan" and
// "inf" as doubles and wrap "-3" round to a large unsigned number).
#ifndef BLENDED_SHAPE_TOOLS_INTERNAL_COMMAND_LINE_H
#define BLENDED_SHAPE_TOOLS_INTERNAL_COMMAND_LINE_H

#include <boost/program_options.hpp>

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

/// An option as given: its flag ("--seed", "-o") and its value ("" for a switch).
struct Option
{
  std::string flag, value;
};

/// The command line: the options in their order (a repeated one counts
/// where it stands, so the last wins), then the other arguments.
struct Command_line
{
  std::vector<Option> options;
  std::vector<std::string> operands;
};

/// The options a tool knows: the flags that take a value, and the switches.
/// Flags are written as typed: "--seed", or "-o" for a one-letter one.
inline boost::program_options::options_description
known_options(const std::vector<std::string>& with_value, const std::vector<std::string>& switches = {})
{
  namespace po = boost::program_options;
  po::options_description d;
  const auto name = [](const std::string& flag) { return flag.size() == 2 ? "," + flag.substr(1) : flag.substr(2); };
  for(const std::string& f : with_value)
    d.add_options()(name(f).c_str(), po::value<std::string>(), "");
  for(const std::string& f : switches)
    d.add_options()(name(f).c_str(), "");
  return d;
}

/// Splits the arguments after the program name by `options`; an unknown
/// option or a missing value is a Usage_error with Program_options' message.
inline Command_line parse_command_line(int argc, char** argv, const boost::program_options::options_description& options)
{
  namespace po = boost::program_options;
  namespace style = po::command_line_style;
  po::options_description all(options);
  all.add_options()("operand", po::value<std::vector<std::string>>(), "");
  po::positional_options_description operands;
  operands.add("operand", -1);
  Command_line line;
  try
  {
    // Whole names only: no "--max" for "--max-iterations".
    const po::parsed_options parsed = po::command_line_parser(argc, argv)
                                        .options(all)
                                        .positional(operands)
                                        .style(style::default_style & ~style::allow_guessing)
                                        .run();
    for(const po::option& o : parsed.options)
    {
      if(o.string_key == "operand")
        line.operands.insert(line.operands.end(), o.value.begin(), o.value.end());
      else
        line.options.push_back({o.string_key[0] == '-' ? o.string_key : "--" + o.string_key,
                                o.value.empty() ? std::string() : o.value.front()});
    }
  }
  catch(const po::error& e)
  {
    // Program_options calls the one-letter option -o "--o" in some messages.
    std::string m = e.what();
    for(std::size_t p = m.find("'--"); p != std::string::npos; p = m.find("'--", p + 1))
      if(p + 4 < m.size() && m[p + 4] == '\'')
        m.erase(p + 1, 1);
    throw Usage_error(m);
  }
  return line;
}

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

/// A non-negative integer in [low, high]; the error names the range (and
/// `note`, if given, what a value in it means, e.g. "0: all cores").
inline std::uint64_t parse_integer_in(const std::string& flag, const std::string& text, std::uint64_t low,
                                      std::uint64_t high, const std::string& note = std::string())
{
  const std::uint64_t n = parse_integer(flag, text);
  if(n < low || n > high)
    throw Usage_error(flag + " must be in [" + std::to_string(low) + ", " + std::to_string(high) + "]" +
                      (note.empty() ? std::string() : " (" + note + ")") + ", not " + text);
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

/// Runs `body(command_line)` with the conventions above, the command line
/// split by `options` (see known_options()); returns the exit code.
template <class Body>
int run_tool(const char* tool, const std::string& usage, int argc, char** argv,
             const boost::program_options::options_description& options, Body&& body)
{
  for(int i = 1; i < argc; ++i)
    if(std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h")
    {
      std::cout << usage;
      return 0;
    }
  try
  {
    body(parse_command_line(argc, argv, options));
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
