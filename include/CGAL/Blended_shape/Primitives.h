// SPDX-License-Identifier: LGPL-3.0-or-later
// Primitives: the BlendedShapePrimitive models (superquadric ellipsoid and toroid, hole component), their singularity-free charts and chart meshes, the type-erased component and the primitive checker.
#ifndef CGAL_BLENDED_SHAPE_PRIMITIVES_H
#define CGAL_BLENDED_SHAPE_PRIMITIVES_H

#include <CGAL/Blended_shape/Primitives/Chart_domain.h>
#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_ellipsoid.h>
#include <CGAL/Blended_shape/Primitives/Superquadric_toroid.h>
#include <CGAL/Blended_shape/Primitives/Hole_component.h>
#include <CGAL/Blended_shape/Primitives/Component_shape.h>
#include <CGAL/Blended_shape/Primitives/check_primitive.h>

#endif // CGAL_BLENDED_SHAPE_PRIMITIVES_H
