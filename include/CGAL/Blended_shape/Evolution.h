// SPDX-License-Identifier: LGPL-3.0-or-later
// Evolution (sec. 4, 5.4): the decisions that change a model's structure while it fits
// (part splitting from force regions, hole blends from self-proximity) and the
// evolving fit that applies them. Its headers live in Evolution/.
#ifndef CGAL_BLENDED_SHAPE_EVOLUTION_H
#define CGAL_BLENDED_SHAPE_EVOLUTION_H

#include <CGAL/Blended_shape/Evolution/Branch_segments.h>
#include <CGAL/Blended_shape/Evolution/Crease_segments.h>
#include <CGAL/Blended_shape/Evolution/Evolution_settings.h>
#include <CGAL/Blended_shape/Evolution/Force_regions.h>
#include <CGAL/Blended_shape/Evolution/Part_evolution.h>
#include <CGAL/Blended_shape/Evolution/Split_proposal.h>
#include <CGAL/Blended_shape/Evolution/fit_blended_shape.h>

#endif // CGAL_BLENDED_SHAPE_EVOLUTION_H
