// SPDX-License-Identifier: LGPL-3.0-or-later
// Umbrella header of the Blended_shape package.
#ifndef CGAL_BLENDED_SHAPE_H
#define CGAL_BLENDED_SHAPE_H

#include <CGAL/Blended_shape/Chart_domain.h>
#include <CGAL/Blended_shape/Chart_mesh.h>
#include <CGAL/Blended_shape/Superquadric_ellipsoid.h>
#include <CGAL/Blended_shape/Superquadric_toroid.h>
#include <CGAL/Blended_shape/Hole_component.h>
#include <CGAL/Blended_shape/Blending_function.h>
#include <CGAL/Blended_shape/Blending_region.h>
#include <CGAL/Blended_shape/Component_shape.h>
#include <CGAL/Blended_shape/Blend.h>
#include <CGAL/Blended_shape/Blended_shape.h>
#include <CGAL/Blended_shape/Blended_shape_mesh.h>
#include <CGAL/Blended_shape/Blended_shape_io.h>
#include <CGAL/Blended_shape/check_primitive.h>
#include <CGAL/Blended_shape/Input_error.h>
#include <CGAL/Blended_shape/check_points.h>
#include <CGAL/Blended_shape/read_points.h>
#include <CGAL/Blended_shape/read_triangle_mesh.h>
#include <CGAL/Blended_shape/initialize_from_moments.h>
#include <CGAL/Blended_shape/Deformable_model.h>
#include <CGAL/Blended_shape/Deformable_blended_model.h>
#include <CGAL/Blended_shape/Closest_point_locator.h>
#include <CGAL/Blended_shape/Blended_shape_fitter.h>
#include <CGAL/Blended_shape/Fit_metrics.h>
#include <CGAL/Blended_shape/fit_blended_shape.h>
#include <CGAL/Blended_shape/sample_model.h>
#include <CGAL/Blended_shape/Range_scan_simulator.h>
#include <CGAL/Blended_shape/CAD_objects.h>
#include <CGAL/Blended_shape/Blended_shape_mesh_io.h>
#include <CGAL/Blended_shape/Quotient_domain.h>
#include <CGAL/Blended_shape/Blending_hierarchy.h>

#endif // CGAL_BLENDED_SHAPE_H
