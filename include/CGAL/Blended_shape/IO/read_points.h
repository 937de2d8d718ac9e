// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_IO_READ_POINTS_H
#define CGAL_BLENDED_SHAPE_IO_READ_POINTS_H

#include <CGAL/Blended_shape/IO/Input_error.h>
#include <CGAL/Blended_shape/IO/check_points.h>
#include <CGAL/Blended_shape/IO/internal/ply_layout.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/IO/read_ply_points.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapeIO

What `read_points()` did with a file.
*/
struct Read_report
{
  /// Points stored in the output (after dropping and welding).
  std::size_t points_read = 0;
  /// Points dropped because a coordinate was NaN or infinite.
  std::size_t non_finite_dropped = 0;
  /// The format used, from the extension: "xyz", "pts", "pwn", "txt", "ply", "off", "obj" or "stl".
  std::string format;
};

namespace internal {

// ---------------------------------------------------------------------------
// File access, shared by read_points() and read_triangle_mesh().

inline std::string quoted(const std::string& filename) { return "'" + filename + "'"; }

// The extension of the file name (not of a directory in the path), lower case, without the dot.
inline std::string lower_case_extension(const std::string& filename)
{
  std::string ext = std::filesystem::path(filename).extension().string();
  if(!ext.empty())
    ext.erase(0, 1);
  for(char& c : ext)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

inline std::string upper_case(std::string s)
{
  for(char& c : s)
    c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

// Throws File_not_found or Unreadable_file unless `filename` is a regular
// file that can be opened for reading; returns its size in bytes.
// `function` starts the messages.
inline std::uintmax_t check_readable_file(const std::string& filename, const std::string& function)
{
  namespace fs = std::filesystem;
  if(filename.empty())
    throw Input_error(Input_error::File_not_found,
                      function + ": the file name is empty; pass the path of the file to read");

  std::error_code ec;
  const fs::file_status status = fs::status(filename, ec);
  if(status.type() == fs::file_type::not_found)
  {
    std::string where;
    const fs::path absolute = fs::absolute(filename, ec);
    if(!ec && absolute != fs::path(filename))
      where = " (looked for " + quoted(absolute.string()) + ")";
    throw Input_error(Input_error::File_not_found,
                      function + ": cannot find the file " + quoted(filename) + where +
                      "; check the spelling and the working directory");
  }
  if(status.type() == fs::file_type::directory)
    throw Input_error(Input_error::Unreadable_file,
                      function + ": " + quoted(filename) +
                      " is a directory, not a file; pass the path of a file inside it");
  if(ec || status.type() == fs::file_type::unknown || status.type() == fs::file_type::none)
    throw Input_error(Input_error::Unreadable_file,
                      function + ": cannot access " + quoted(filename) + " (" + ec.message() +
                      "); check the permissions of the file and of its directories");

  errno = 0;
  std::ifstream probe(filename, std::ios::binary);
  if(!probe)
  {
    const std::string reason = errno != 0 ? std::strerror(errno) : "unknown reason";
    throw Input_error(Input_error::Unreadable_file,
                      function + ": cannot open " + quoted(filename) + " for reading (" + reason +
                      "); check the permissions of the file");
  }
  const std::uintmax_t size = fs::file_size(filename, ec);
  return ec ? std::uintmax_t(1) : size; // unknown size (e.g. a pipe): let the reader decide
}

// Checks a PLY file before CGAL's readers see it (read_ply_layout(),
// check_ply_data()): a vertex whose x, y or z is missing or is an integer
// property would make them fill zeros or fail an assertion, a file that is
// not PLY at all makes them print to std::cerr, and a corrupt list length
// makes them allocate it.
inline void check_ply_file(const std::string& filename, const std::string& function)
{
  const std::string where = function + ": " + quoted(filename);
  std::ifstream in(filename, std::ios::binary);
  const Ply_layout layout = read_ply_layout(in, where);
  bool has_vertex_element = false;
  int coordinates_found = 0;
  std::string bad_property;
  for(const Ply_element& e : layout.elements)
  {
    if(e.name != "vertex" && e.name != "vertices")
      continue;
    has_vertex_element = true;
    for(const Ply_property& p : e.properties)
      if(p.name == "x" || p.name == "y" || p.name == "z")
      {
        if(!p.is_list() && is_ply_floating_type(p.type))
          ++coordinates_found;
        else if(bad_property.empty())
          bad_property = p.name + " of type " + (p.is_list() ? "list" : p.type);
      }
  }
  if(has_vertex_element && (!bad_property.empty() || coordinates_found != 3))
    throw Input_error(Input_error::Malformed_content,
                      function + ": the vertices of the PLY file " + quoted(filename) +
                      (bad_property.empty() ? std::string(" lack an x, y or z property")
                                            : " have coordinate " + bad_property) +
                      "; the vertex element needs float or double properties x, y and z");
  // (no vertices: reported later as an empty file)
  const std::streampos data = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streampos end = in.tellg();
  if(data == std::streampos(-1) || end == std::streampos(-1) || end < data)
    return; // not seekable (a pipe): CGAL's reader decides
  in.seekg(data);
  check_ply_data(in, std::uintmax_t(end - data), layout, where);
}

// Reads an off, obj, ply or stl file as a polygon soup. A reader failure, or a
// face index past the vertices (so that later steps never read out of
// bounds, whatever the reader checked), is Malformed_content.
template <class Point_3>
void read_soup_or_throw(const std::string& filename, const std::string& format,
                        std::vector<Point_3>& points,
                        std::vector<std::vector<std::size_t> >& polygons,
                        const std::string& function)
{
  if(format == "ply")
    check_ply_file(filename, function);
  if(!CGAL::IO::read_polygon_soup(filename, points, polygons))
    throw Input_error(Input_error::Malformed_content,
                      function + ": " + quoted(filename) + " is not a valid " + upper_case(format) +
                      " file (CGAL's reader failed: bad header, non-numeric value or truncated "
                      "data); check that the file is complete and really is in this format");
  for(const std::vector<std::size_t>& polygon : polygons)
    for(std::size_t v : polygon)
      if(v >= points.size())
        throw Input_error(Input_error::Malformed_content,
                          function + ": a face of " + quoted(filename) + " uses vertex index " +
                          std::to_string(v) + " but the file has only " +
                          std::to_string(points.size()) +
                          " vertices; the file is corrupt or truncated");
}

// Merges points with exactly equal coordinates; each keeps the position of
// its first occurrence, so the output order is deterministic and follows the
// file. Returns, for each input index, the index of its point after welding.
// \pre all points are finite (NaN does not compare).
template <class Point_3>
std::vector<std::size_t> weld_exact_duplicates(std::vector<Point_3>& points)
{
  const std::size_t n = points.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  // Stable: within a group of equal points, the first occurrence comes first.
  std::stable_sort(order.begin(), order.end(),
                   [&points](std::size_t a, std::size_t b) { return points[a] < points[b]; });

  std::vector<std::size_t> first_occurrence(n);
  for(std::size_t k = 0; k < n; ++k)
  {
    const bool same_as_previous = k > 0 && points[order[k]] == points[order[k - 1]];
    first_occurrence[order[k]] = same_as_previous ? first_occurrence[order[k - 1]] : order[k];
  }

  std::vector<std::size_t> new_index(n);
  std::vector<Point_3> welded;
  for(std::size_t i = 0; i < n; ++i)
  {
    if(first_occurrence[i] == i)
    {
      new_index[i] = welded.size();
      welded.push_back(points[i]);
    }
    else
      new_index[i] = new_index[first_occurrence[i]]; // first_occurrence[i] < i
  }
  points.swap(welded);
  return new_index;
}

// ---------------------------------------------------------------------------
// Text point formats.

inline bool is_blank(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

inline const char* skip_blanks(const char* c)
{
  while(*c != '\0' && is_blank(*c))
    ++c;
  return c;
}

// True if the rest of the line is one non-negative integer: a .pts point count.
inline bool is_single_count(const char* c)
{
  if(!std::isdigit(static_cast<unsigned char>(*c)))
    return false;
  while(std::isdigit(static_cast<unsigned char>(*c)))
    ++c;
  return *skip_blanks(c) == '\0';
}

// One point per line: the first three numbers are x y z, anything after them
// (normals, colours, intensity) is ignored. std::strtod so that "nan" and
// "inf" parse: such points are dropped later, with a count, instead of
// making the whole file fail.
template <class Point_3>
void read_text_points(const std::string& filename, bool skip_count_line,
                      std::vector<Point_3>& points, const std::string& function)
{
  std::ifstream in(filename, std::ios::binary); // binary: we strip '\r' ourselves
  const std::string syntax =
    "; each data line must start with three numbers x y z separated by spaces or tabs "
    "(blank lines and lines starting with '#' are skipped)";
  std::string line;
  std::size_t line_number = 0;
  bool first_data_line = true;
  while(std::getline(in, line))
  {
    ++line_number;
    if(line_number == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0)
      line.erase(0, 3); // UTF-8 byte-order mark written by some Windows tools
    const char* c = skip_blanks(line.c_str());
    if(*c == '\0' || *c == '#')
      continue;
    const bool is_first = first_data_line;
    first_data_line = false;
    if(is_first && skip_count_line && is_single_count(c))
      continue;

    const std::string where = function + ": line " + std::to_string(line_number) + " of " +
                              quoted(filename);
    double xyz[3];
    for(int k = 0; k < 3; ++k)
    {
      c = skip_blanks(c);
      if(*c == '\0')
        throw Input_error(Input_error::Malformed_content,
                          where + " has only " + plural(std::size_t(k), "number") + syntax);
      char* end = nullptr;
      xyz[k] = std::strtod(c, &end);
      if(end == c || (*end != '\0' && !is_blank(*end)))
      {
        const char* token_end = c;
        while(*token_end != '\0' && !is_blank(*token_end))
          ++token_end;
        // (bytes that are not printable ASCII shown as \xNN: a binary file's
        // bytes would otherwise go to the terminal as they are)
        std::string token;
        for(const char* t = c; t != token_end && t != c + 40; ++t)
        {
          const unsigned char b = static_cast<unsigned char>(*t);
          if(b >= 0x20 && b < 0x7f)
            token += *t;
          else
          {
            const char* hex = "0123456789abcdef";
            token += std::string("\\x") + hex[b >> 4] + hex[b & 15];
          }
        }
        throw Input_error(Input_error::Malformed_content,
                          where + ": '" + token + "' is not a number" + syntax);
      }
      c = end;
    }
    points.push_back(Point_3(xyz[0], xyz[1], xyz[2]));
  }
  if(in.bad())
    throw Input_error(Input_error::Unreadable_file,
                      function + ": an I/O error occurred while reading line " +
                      std::to_string(line_number + 1) + " of " + quoted(filename) +
                      "; check the disk or copy the file elsewhere");
}

inline const char* supported_point_extensions()
{
  return ".xyz, .pts, .pwn, .txt (text: x y z per line), .ply, .off, .obj, .stl";
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeIO

Reads a point cloud from a file, chosen by the file name extension (letter
case does not matter):

- `.xyz`, `.pts`, `.pwn`, `.txt`: text, one point per line; the first three
  numbers of a line are x y z and further columns (normals, colours,
  intensity) are ignored; blank lines and lines starting with `#` are
  skipped; in a `.pts` file, a first line holding a single integer (the
  point count) is skipped;
- `.ply`, ascii or binary: the vertices (faces, if any, are ignored);
- `.off`, `.obj`, `.stl`: the vertices of the mesh. STL repeats each vertex
  for every triangle, so exactly equal points are merged (the first
  occurrence keeps its place).

Points with a NaN or infinite coordinate are **dropped** (scanners write
them for pixels without a return) and counted in
`Read_report::non_finite_dropped`. The remaining points are then checked like
`check_points()` does.

`points` is cleared first and, on error, left empty.

\tparam Point_3 a point type of a CGAL kernel, constructible from three `double`.

\throws Input_error with code
 - `File_not_found`: no file at `filename`;
 - `Unreadable_file`: a directory, no read permission, or an I/O error;
 - `Unsupported_format`: another extension (the message lists the supported ones);
 - `Malformed_content`: the content does not parse; for text formats the
   message gives the line number; a PLY file is checked whole before it is
   read: its header (the vertices need float or double x, y, z), that its
   data holds every element the header declares, and that no list (a
   face's vertices) is longer than the rest of the file could hold, which
   would otherwise make CGAL's reader allocate it;
 - `No_points`, `Too_few_points` (fewer than `minimum_number_of_points`),
   `All_points_identical`: counted after dropping non-finite points.

Collinear or coplanar clouds are not rejected here: the initialization reports them.
*/
template <class Point_3>
Read_report read_points(const std::string& filename, std::vector<Point_3>& points)
{
  const std::string function = "read_points";
  points.clear();

  const std::uintmax_t size = internal::check_readable_file(filename, function);
  Read_report report;
  report.format = internal::lower_case_extension(filename);
  const std::string& format = report.format;
  const bool is_text = format == "xyz" || format == "pts" || format == "pwn" || format == "txt";
  const bool is_mesh = format == "off" || format == "obj" || format == "stl";
  if(!is_text && !is_mesh && format != "ply")
    throw Input_error(Input_error::Unsupported_format,
                      function + ": cannot read " + internal::quoted(filename) + ": " +
                      (format.empty() ? std::string("it has no extension")
                                      : "the extension '." + format + "' is not supported") +
                      "; supported extensions are " + internal::supported_point_extensions() +
                      "; convert the file or rename it if its content is in one of these formats");

  const std::string where = function + ": " + internal::quoted(filename);
  if(size == 0)
    throw Input_error(Input_error::No_points,
                      where + " is empty; provide a file with at least " +
                      std::to_string(minimum_number_of_points) + " points");

  std::vector<Point_3> read;
  if(is_text)
    internal::read_text_points(filename, format == "pts", read, function);
  else if(format == "ply")
  {
    internal::check_ply_file(filename, function);
    std::ifstream in(filename, std::ios::binary); // binary: ascii PLY reads fine this way too
    if(!CGAL::IO::read_PLY(in, std::back_inserter(read)))
      throw Input_error(Input_error::Malformed_content,
                        where + " is not a valid PLY file (CGAL::IO::read_PLY failed: bad "
                        "header or truncated data); check that the file is complete");
  }
  else
  {
    std::vector<std::vector<std::size_t> > faces_unused;
    internal::read_soup_or_throw(filename, format, read, faces_unused, function);
  }

  const auto finite_end = std::remove_if(read.begin(), read.end(),
                                         [](const Point_3& p) { return !internal::is_finite_point(p); });
  report.non_finite_dropped = std::size_t(read.end() - finite_end);
  read.erase(finite_end, read.end());

  if(format == "stl")
    internal::weld_exact_duplicates(read);

  const std::string note = report.non_finite_dropped == 0
    ? std::string()
    : " after dropping " + internal::plural(report.non_finite_dropped, "point") +
      " with NaN or infinite coordinates";
  internal::check_count_and_spread(read, CGAL::Identity_property_map<Point_3>(), where, note);

  report.points_read = read.size();
  points.swap(read);
  return report;
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_IO_READ_POINTS_H
