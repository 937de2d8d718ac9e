// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_IO_INPUT_ERROR_H
#define CGAL_BLENDED_SHAPE_IO_INPUT_ERROR_H

#include <CGAL/number_utils.h>

#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>

namespace CGAL {
namespace Blended_shapes {

/*!
\ingroup PkgBlendedShapeIO

The exception thrown by the input functions of the package
(`read_points()`, `read_triangle_mesh()`, `check_points()`,
`read_blended_shape()`, `read_blended_shape_json()`) when the data
cannot be used.

`what()` is a complete sentence for the end user: it names the function,
the file (and, for text formats, the line), says what was wrong and what to
do about it. `code()` lets a program react to the kind of failure without
parsing the message.
*/
class Input_error : public std::runtime_error
{
public:
  /// The kinds of bad input.
  enum Code
  {
    File_not_found,       ///< no file at the given path
    Unreadable_file,      ///< the path exists but cannot be read (a directory, no permission, I/O error)
    Unsupported_format,   ///< the file name extension, or a model file's `"format"` or `"version"`, is not one the package reads
    Malformed_content,    ///< the content does not parse in the format of its extension
    No_points,            ///< no points (or, for a mesh, no faces)
    Too_few_points,       ///< fewer than `minimum_number_of_points` points
    Non_finite_point,     ///< a NaN or infinite coordinate where it cannot be dropped
    All_points_identical, ///< every point has exactly the same coordinates
    /// A coordinate beyond `maximum_coordinate_magnitude`, or a point set whose
    /// extent is under `minimum_point_set_extent`: squared distances would overflow or underflow
    Scale_out_of_range
  };

  /// An error of kind `c` with the message `message` (returned by `what()`).
  Input_error(Code c, const std::string& message)
    : std::runtime_error(message), m_code(c)
  {}

  /// The kind of bad input.
  Code code() const { return m_code; }

  /// A stable lower-case identifier of `c`, e.g. `"file_not_found"`, for logs and scripts.
  static const char* code_name(Code c)
  {
    switch(c)
    {
    case File_not_found: return "file_not_found";
    case Unreadable_file: return "unreadable_file";
    case Unsupported_format: return "unsupported_format";
    case Malformed_content: return "malformed_content";
    case No_points: return "no_points";
    case Too_few_points: return "too_few_points";
    case Non_finite_point: return "non_finite_point";
    case All_points_identical: return "all_points_identical";
    case Scale_out_of_range: return "scale_out_of_range";
    }
    return "unknown";
  }

private:
  Code m_code;
};

/*!
\ingroup PkgBlendedShapeIO

The smallest point set the package accepts: below this, neither the
initialization nor the fit of a primitive is meaningful.
*/
constexpr std::size_t minimum_number_of_points = 10;

/*!
\ingroup PkgBlendedShapeIO

The largest coordinate magnitude the package accepts: the initialization and
the fit sum squared coordinates and distances, which must stay finite in
double precision (the square of `1e150` is `1e300`, with room for the sums).
*/
constexpr double maximum_coordinate_magnitude = 1e150;

namespace internal {

// Whether the coordinates are finite and at most maximum_coordinate_magnitude
// in absolute value (the one test of the limit: the points, the reference
// meshes, the scanned meshes and the camera; a NaN fails every comparison).
inline bool are_coordinates_in_range(double x, double y, double z)
{
  return std::abs(x) <= maximum_coordinate_magnitude && std::abs(y) <= maximum_coordinate_magnitude &&
         std::abs(z) <= maximum_coordinate_magnitude;
}

// The same for a point (to_double: it must also compile for kernels whose FT is not double).
template <class Point>
bool has_coordinates_in_range(const Point& p)
{
  return are_coordinates_in_range(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}

// The words of every refusal of such a coordinate: "not finite or beyond
// 1e+150 in absolute value, where squared distances overflow".
inline std::string out_of_range_coordinate_words()
{
  std::ostringstream s;
  s << "not finite or beyond " << maximum_coordinate_magnitude
    << " in absolute value, where squared distances overflow";
  return s.str();
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeIO

The smallest extent (the largest side of the bounding box) of a point set
the package accepts: under it, squared distances underflow in double precision.
*/
constexpr double minimum_point_set_extent = 1e-150;

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_IO_INPUT_ERROR_H
