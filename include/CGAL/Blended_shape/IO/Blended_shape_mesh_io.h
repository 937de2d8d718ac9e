// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_IO_BLENDED_SHAPE_MESH_IO_H
#define CGAL_BLENDED_SHAPE_IO_BLENDED_SHAPE_MESH_IO_H

#include <CGAL/Blended_shape/Blending/Blended_shape.h>
#include <CGAL/Blended_shape/Blending/Blended_shape_mesh.h>
#include <CGAL/Blended_shape/internal/write_file_atomically.h>

#include <CGAL/IO/io.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh/IO/OFF.h>
#include <CGAL/Surface_mesh/IO/PLY.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

namespace CGAL {
namespace Blended_shapes {

namespace internal {

// A vertex with a NaN or infinite coordinate would make a file that no reader
// accepts (ASCII "nan") or that silently holds garbage (binary): refuse it
// before anything is written.
template <class Point>
void check_finite_mesh(const CGAL::Surface_mesh<Point>& mesh, const char* where)
{
  for(auto v : mesh.vertices())
  {
    const Point& p = mesh.point(v);
    if(!(std::isfinite(CGAL::to_double(p.x())) && std::isfinite(CGAL::to_double(p.y())) &&
         std::isfinite(CGAL::to_double(p.z()))))
      throw std::invalid_argument(std::string(where) + ": vertex " + std::to_string(std::size_t(v)) +
                                  " has a non-finite coordinate; the mesh was not written");
  }
}

// The `stream_precision` named parameter: 17 digits by default, which read
// back the same doubles.
template <class NamedParameters>
int stream_precision(const NamedParameters& np)
{
  return CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::stream_precision),
                                            17);
}

// write_file_atomically() with the name of the public function in front of
// its messages (they already name the file and say what to do).
template <class Writer>
void write_mesh_file(const std::string& path, const char* where, Writer&& write)
{
  if(path.empty())
    throw std::invalid_argument(std::string(where) + ": empty output file name; give a path");
  std::error_code ec;
  if(std::filesystem::is_directory(path, ec))
    throw std::runtime_error(std::string(where) + ": '" + path +
                             "' is a directory; give the path of a file to write");
  // write_file_atomically() opens the file without std::ios::binary: on
  // POSIX systems text and binary streams are the same, so binary PLY is
  // written byte for byte (on Windows it would need the binary flag).
  try
  {
    internal::write_file_atomically(path, write);
  }
  catch(const std::invalid_argument&)
  {
    throw;
  }
  catch(const std::runtime_error& e)
  {
    throw std::runtime_error(std::string(where) + ": " + e.what());
  }
}

// A mesh with finite coordinates only, written atomically.
template <class Point, class Writer>
void write_finite_mesh_file(const std::string& path, const char* where, const CGAL::Surface_mesh<Point>& mesh,
                            Writer&& write)
{
  check_finite_mesh(mesh, where);
  write_mesh_file(path, where, std::forward<Writer>(write));
}

} // namespace internal

/*!
\ingroup PkgBlendedShapeIO

Writes the overlapping per-component pieces of a blended shape (sec. 3.3,
Blended_shape_pieces::merged_mesh()) to the PLY file `path`, colored by
component: one vertex element (`x`, `y`, `z` as `double`), one face element
with the vertex indices, the face color (`red`, `green`, `blue`, `alpha`,
`uchar`: Blended_shape_pieces::component_color() of the face's component)
and the face's component index (`int component`). A comment line of the
header gives the numbers of pieces and components. Faces in strips and chart
margins appear once per side, so the pieces overlap in space: the file is for
viewing the structure, not a closed surface (write_unified_mesh_off() writes
that).

`CGAL::IO::read_PLY()` reads the file back into a `CGAL::Surface_mesh` with
the face properties `"f:color"` and `"f:component"`.

The file is written through a temporary file renamed at the end: a failure
leaves no file, and an existing file is replaced only by a complete one.

\tparam GeomTraits the kernel of the shape, as for Blended_shape
\tparam NamedParameters a sequence of named parameters

\param path the output file (by convention with the extension `.ply`)
\param pieces the pieces, as positioned by their last `update()`
\param np optional named parameters among:
  - `CGAL::parameters::use_binary_mode(bool)`: binary little-endian PLY if
    `true` (the default, smaller and exact), ASCII otherwise;
  - `CGAL::parameters::stream_precision(int)`: digits of ASCII coordinates
    (default 17, which reads back exactly).

\throws std::invalid_argument on an empty path or if a vertex has a
        non-finite coordinate (nothing is written)
\throws std::runtime_error if the file cannot be created (a missing or
        read-only directory, `path` is a directory), written or renamed (the
        message names the file and says what to check); no file is left
*/
template <class GeomTraits, class NamedParameters = CGAL::parameters::Default_named_parameters>
void write_blended_shape_pieces_ply(const std::string& path, const Blended_shape_pieces<GeomTraits>& pieces,
                                    const NamedParameters& np = CGAL::parameters::default_values())
{
  const char* where = "write_blended_shape_pieces_ply";
  const bool binary = CGAL::parameters::choose_parameter(
    CGAL::parameters::get_parameter(np, CGAL::internal_np::use_binary_mode), true);
  const int precision = internal::stream_precision(np);

  const auto mesh = pieces.merged_mesh();
  std::size_t components = 0;
  for(const auto& p : pieces.pieces())
    components = std::max(components, p.component + 1);
  const std::string comment = "Blended_shape pieces: " + std::to_string(pieces.pieces().size()) +
                              " chart pieces of " + std::to_string(components) +
                              " components; faces colored by component, property component = its index";
  internal::write_finite_mesh_file(path, where, mesh, [&](std::ostream& out) {
    CGAL::IO::set_mode(out, binary ? CGAL::IO::BINARY : CGAL::IO::ASCII);
    if(!CGAL::IO::write_PLY(out, mesh, comment, CGAL::parameters::stream_precision(precision)))
      throw std::runtime_error("CGAL::IO::write_PLY failed to write '" + path + "'; nothing was written");
  });
}

/*!
\ingroup PkgBlendedShapeIO

Writes the triangle mesh `mesh` (typically the unified mesh of a blended
shape, make_unified_mesh()) to the OFF file `path`: vertex coordinates with
`stream_precision` digits (default 17, so that `CGAL::IO::read_OFF()` reads
back the same coordinates), then the faces. The file is written through a
temporary file renamed at the end: a failure leaves no file, and an existing
file is replaced only by a complete one.

\tparam Point the point type of the mesh
\tparam NamedParameters a sequence of named parameters

\param path the output file (by convention with the extension `.off`)
\param mesh the mesh
\param np optional named parameters among
  `CGAL::parameters::stream_precision(int)` (default 17).

\throws std::invalid_argument or std::runtime_error in the cases of
        write_blended_shape_pieces_ply(): an empty path or a non-finite
        vertex coordinate, or a file that cannot be created, written or
        renamed; no file is left
*/
template <class Point, class NamedParameters = CGAL::parameters::Default_named_parameters>
void write_unified_mesh_off(const std::string& path, const CGAL::Surface_mesh<Point>& mesh,
                            const NamedParameters& np = CGAL::parameters::default_values())
{
  const int precision = internal::stream_precision(np);
  internal::write_finite_mesh_file(path, "write_unified_mesh_off", mesh, [&](std::ostream& out) {
    CGAL::IO::set_mode(out, CGAL::IO::ASCII);
    if(!CGAL::IO::write_OFF(out, mesh, CGAL::parameters::stream_precision(precision)))
      throw std::runtime_error("CGAL::IO::write_OFF failed to write '" + path + "'; nothing was written");
  });
}

/*!
\ingroup PkgBlendedShapeIO

Builds the unified closed mesh of `shape` with
`make_unified_mesh(shape, resolution, strip_rows)` and writes it to the OFF
file `path` with write_unified_mesh_off(). The mesh is built before the file
is opened: if it cannot be built, no file is touched.

\tparam GeomTraits the kernel of the shape, as for Blended_shape

\throws std::invalid_argument as make_unified_mesh() (nothing is written),
        or on an empty path
\throws std::runtime_error as write_unified_mesh_off()
*/
template <class GeomTraits>
void write_unified_mesh_off(const std::string& path, const Blended_shape<GeomTraits>& shape, int resolution = 24,
                            int strip_rows = 4)
{
  if(path.empty())
    throw std::invalid_argument("write_unified_mesh_off: empty output file name; give a path");
  write_unified_mesh_off(path, make_unified_mesh(shape, resolution, strip_rows));
}

} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_IO_BLENDED_SHAPE_MESH_IO_H
