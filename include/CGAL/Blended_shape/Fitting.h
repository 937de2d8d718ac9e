// SPDX-License-Identifier: LGPL-3.0-or-later
// Fitting (sec. 5.1-5.3): deformable models, initialization, closest points, the fitter and its visitor, metrics, sampling, the multi-start search and the one-call fit of a superquadric.
#ifndef CGAL_BLENDED_SHAPE_FITTING_H
#define CGAL_BLENDED_SHAPE_FITTING_H

#include <CGAL/Blended_shape/Fitting/Deformable_model.h>
#include <CGAL/Blended_shape/Fitting/Deformable_blended_model.h>
#include <CGAL/Blended_shape/Fitting/initialize_from_moments.h>
#include <CGAL/Blended_shape/Fitting/Closest_point_locator.h>
#include <CGAL/Blended_shape/Fitting/Fitting_visitor.h>
#include <CGAL/Blended_shape/Fitting/Fitting_settings.h>
#include <CGAL/Blended_shape/Fitting/Deformable_model_fitter.h>
#include <CGAL/Blended_shape/Fitting/Fit_metrics.h>
#include <CGAL/Blended_shape/Fitting/Blended_model_metrics.h>
#include <CGAL/Blended_shape/Fitting/sample_model.h>
#include <CGAL/Blended_shape/Fitting/Superquadric_multistart_search.h>
#include <CGAL/Blended_shape/Fitting/fit_superquadric.h>

#endif // CGAL_BLENDED_SHAPE_FITTING_H
