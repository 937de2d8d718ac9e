// SPDX-License-Identifier: LGPL-3.0-or-later
// Input and output: point and mesh readers with their checks and errors, model files (JSON), mesh writers.
#ifndef CGAL_BLENDED_SHAPE_IO_H
#define CGAL_BLENDED_SHAPE_IO_H

#include <CGAL/Blended_shape/IO/Input_error.h>
#include <CGAL/Blended_shape/IO/check_points.h>
#include <CGAL/Blended_shape/IO/read_points.h>
#include <CGAL/Blended_shape/IO/read_triangle_mesh.h>
#include <CGAL/Blended_shape/IO/Blended_shape_io.h>
#include <CGAL/Blended_shape/IO/Blended_shape_mesh_io.h>

#endif // CGAL_BLENDED_SHAPE_IO_H
