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

#include <CGAL/Blended_shape/internal/write_file_atomically.h>

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
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <new>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
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
  // (decimal only: strtod() would also read hexadecimal, "0x10")
  if(text.empty() || std::isspace(static_cast<unsigned char>(text[0])) ||
     text.find_first_of("xX") != std::string::npos)
    throw Usage_error(flag + ": '" + text + "' is not a number");
  errno = 0;
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if(end != text.c_str() + text.size())
    throw Usage_error(flag + ": '" + text + "' is not a number");
  // (ERANGE also flags a tiny value rounded to a subnormal or to 0: a number all the same)
  if((errno == ERANGE && std::abs(x) == HUGE_VAL) || !std::isfinite(x))
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

/// A file a tool reads or writes, and the flag that named it ("input" for
/// the operand). An empty path is an output not asked for.
struct Named_file
{
  std::string flag, path;
};

namespace internal {

// Whether `a` and `b` name the same file: the same file on disk, or, where
// either is yet to be made, the same path once the links are followed.
inline bool same_file(const std::filesystem::path& a, const std::filesystem::path& b)
{
  namespace fs = std::filesystem;
  std::error_code ec, ec2;
  if(fs::exists(a, ec) && fs::exists(b, ec2))
    return fs::equivalent(a, b, ec);
  const fs::path ca = fs::weakly_canonical(a, ec), cb = fs::weakly_canonical(b, ec2);
  return !ec && !ec2 && ca == cb;
}

} // namespace internal

/// Before any work, so that a long run does not end in an error it could
/// have given at once: no output is the same file as an input or another
/// output (a Usage_error: the run would overwrite it), and each output can be
/// made: it is not a directory, and its directory exists and takes a new
/// file (std::runtime_error otherwise). Devices and pipes (`/dev/null`)
/// are taken as they are.
inline void check_files(const std::vector<Named_file>& inputs, const std::vector<Named_file>& outputs)
{
  namespace fs = std::filesystem;
  std::vector<std::pair<Named_file, fs::path>> seen; // regular files or files to make, links followed
  for(const std::vector<Named_file>* group : {&inputs, &outputs})
    for(const Named_file& f : *group)
    {
      if(f.path.empty())
        continue;
      std::error_code ec;
      const fs::file_status status = fs::status(f.path, ec); // (through the links)
      const bool output = group == &outputs;
      if(output && fs::is_directory(status))
        throw Usage_error(f.flag + ": '" + f.path + "' is a directory; give the name of a file to write");
      if(fs::exists(status) && !fs::is_regular_file(status))
        continue;
      const fs::path target = CGAL::Blended_shapes::internal::final_target_of(f.path);
      if(output) // (two inputs may be one file: a mesh fitted with itself as the reference)
        for(const auto& earlier : seen)
          if(internal::same_file(earlier.second, target))
            throw Usage_error(f.flag + " '" + f.path + "' is the same file as " + earlier.first.flag + " '" +
                              earlier.first.path + "', which it would overwrite; give another file name");
      seen.emplace_back(f, target);
      if(!output)
        continue;
      const fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
      if(!fs::is_directory(directory, ec))
        throw std::runtime_error(f.flag + ": the directory '" + directory.string() + "' of '" + f.path +
                                 "' does not exist; create it first");
      const std::string probe = CGAL::Blended_shapes::internal::temporary_name_for(target.string());
      const bool created = bool(std::ofstream(probe));
      fs::remove(probe, ec);
      if(!created)
        throw std::runtime_error(f.flag + ": cannot create a file in '" + directory.string() +
                                 "'; check its permissions, or write '" + target.filename().string() + "' elsewhere");
    }
}

/// Writes the outputs in turn (each pair: its path, "" if not asked for, and
/// the call that writes it). If one fails, the files written before it are
/// removed, so that a failed run leaves none of its outputs, and the error
/// is rethrown.
inline void write_all_or_none(const std::vector<std::pair<std::string, std::function<void()>>>& outputs)
{
  namespace fs = std::filesystem;
  std::vector<fs::path> written;
  try
  {
    for(const auto& o : outputs)
      if(!o.first.empty())
      {
        o.second();
        written.push_back(CGAL::Blended_shapes::internal::final_target_of(o.first));
      }
  }
  catch(...)
  {
    for(const fs::path& p : written)
    {
      std::error_code ec;
      if(fs::is_regular_file(fs::symlink_status(p, ec)))
        fs::remove(p, ec);
    }
    throw;
  }
}

/// Runs `body(command_line)` with the conventions above, the command line
/// split by `options` (see known_options()); returns the exit code. Ended by
/// Ctrl-C or `kill`, a tool leaves no half-written temporary file behind.
template <class Body>
int run_tool(const char* tool, const std::string& usage, int argc, char** argv,
             const boost::program_options::options_description& options, Body&& body)
{
  CGAL::Blended_shapes::internal::remove_partial_files_on_termination_signals();
  // What went to standard output (the usage, a summary) must have arrived.
  const auto stdout_written = [tool] {
    if(std::cout.flush())
      return 0;
    std::cerr << tool << ": writing to standard output failed (closed, or the disk is full)" << std::endl;
    return 1;
  };
  for(int i = 1; i < argc; ++i)
    if(std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h")
    {
      std::cout << usage;
      return stdout_written();
    }
  try
  {
    body(parse_command_line(argc, argv, options));
    return stdout_written();
  }
  catch(const Usage_error& e)
  {
    std::cerr << tool << ": " << e.what() << "\nRun '" << tool << " --help' for the usage." << std::endl;
    return 2;
  }
  catch(const std::bad_alloc&)
  {
    std::cerr << tool << ": out of memory; use a smaller input or resolution, or check that the input file is "
                         "intact (a corrupt header or face list can claim more elements than the file holds)"
              << std::endl;
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
