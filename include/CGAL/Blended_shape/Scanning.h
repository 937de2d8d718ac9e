// SPDX-License-Identifier: LGPL-3.0-or-later
// Scanning: the range scan simulator and the CAD test objects (sec. 6). Not included by <CGAL/Blended_shape.h>: it pulls CGAL's Boolean operations with an exact kernel into the translation unit.
#ifndef CGAL_BLENDED_SHAPE_SCANNING_H
#define CGAL_BLENDED_SHAPE_SCANNING_H

#include <CGAL/Blended_shape/Scanning/Range_scan_simulator.h>
#include <CGAL/Blended_shape/Scanning/CAD_objects.h>

#endif // CGAL_BLENDED_SHAPE_SCANNING_H
