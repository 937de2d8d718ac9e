// SPDX-License-Identifier: LGPL-3.0-or-later
// Umbrella header of the Blended_shape package: every area but Scanning
// (include <CGAL/Blended_shape/Scanning.h> for the scan simulator and the CAD objects).
#ifndef CGAL_BLENDED_SHAPE_H
#define CGAL_BLENDED_SHAPE_H

#include <CGAL/Blended_shape/parameters.h>
#include <CGAL/Blended_shape/Primitives.h>
#include <CGAL/Blended_shape/Blending.h>
#include <CGAL/Blended_shape/Fitting.h>
#include <CGAL/Blended_shape/Evolution.h>
#include <CGAL/Blended_shape/IO.h>

#endif // CGAL_BLENDED_SHAPE_H
