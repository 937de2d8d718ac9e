// SPDX-License-Identifier: LGPL-3.0-or-later
// Blending (sec. 3): blending function and regions, blends, the blended shape, its quotient domain, hierarchy, pieces and unified mesh.
#ifndef CGAL_BLENDED_SHAPE_BLENDING_H
#define CGAL_BLENDED_SHAPE_BLENDING_H

#include <CGAL/Blended_shape/Blending/Blending_function.h>
#include <CGAL/Blended_shape/Blending/Blending_region.h>
#include <CGAL/Blended_shape/Blending/Ellipse_blending_region.h>
#include <CGAL/Blended_shape/Blending/Blend.h>
#include <CGAL/Blended_shape/Blending/Shape_point.h>
#include <CGAL/Blended_shape/Blending/Blended_shape.h>
#include <CGAL/Blended_shape/Blending/Blended_shape_mesh.h>
#include <CGAL/Blended_shape/Blending/Quotient_domain.h>
#include <CGAL/Blended_shape/Blending/Blending_hierarchy.h>

#endif // CGAL_BLENDED_SHAPE_BLENDING_H
