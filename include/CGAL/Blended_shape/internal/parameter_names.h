// SPDX-License-Identifier: LGPL-3.0-or-later
// The package-specific named parameters (X-macro list; no include guard on purpose).
// CGAL_BLENDED_SHAPE_FITTING_SETTING(NAME): a named parameter that sets the
// member NAME of Fitting_settings (see settings_from_named_parameters()).
// CGAL_BLENDED_SHAPE_EVOLUTION_SETTING(NAME): likewise for Evolution_settings
// (see evolution_settings_from_named_parameters()).
// Initialization (initialize_from_moments)
CGAL_BLENDED_SHAPE_PARAMETER(refine_axes)
CGAL_BLENDED_SHAPE_PARAMETER(minimum_axis_ratio)
// Fitting_settings, under the names of its members
CGAL_BLENDED_SHAPE_FITTING_SETTING(integrator)
CGAL_BLENDED_SHAPE_FITTING_SETTING(energy_tolerance)
CGAL_BLENDED_SHAPE_FITTING_SETTING(force_tolerance)
CGAL_BLENDED_SHAPE_FITTING_SETTING(rest_tolerance)
CGAL_BLENDED_SHAPE_FITTING_SETTING(steady_iterations)
CGAL_BLENDED_SHAPE_FITTING_SETTING(mesh_resolution)
CGAL_BLENDED_SHAPE_FITTING_SETTING(projection_iterations)
CGAL_BLENDED_SHAPE_FITTING_SETTING(subset_size)
CGAL_BLENDED_SHAPE_FITTING_SETTING(rigid_first)
CGAL_BLENDED_SHAPE_FITTING_SETTING(rigid_iterations)
CGAL_BLENDED_SHAPE_FITTING_SETTING(robust_weighting)
CGAL_BLENDED_SHAPE_FITTING_SETTING(maximum_size_factor)
CGAL_BLENDED_SHAPE_FITTING_SETTING(placement_stiffness)
CGAL_BLENDED_SHAPE_FITTING_SETTING(number_of_threads)
// Evolution_settings, under the names of its members
CGAL_BLENDED_SHAPE_EVOLUTION_SETTING(maximum_number_of_parts)
CGAL_BLENDED_SHAPE_EVOLUTION_SETTING(target_accuracy)
CGAL_BLENDED_SHAPE_EVOLUTION_SETTING(maximum_split_tries)
CGAL_BLENDED_SHAPE_EVOLUTION_SETTING(threshold_factor)
CGAL_BLENDED_SHAPE_EVOLUTION_SETTING(analysis_resolution)
CGAL_BLENDED_SHAPE_EVOLUTION_SETTING(maximum_evolution_points)
// fit_superquadric() alone
CGAL_BLENDED_SHAPE_PARAMETER(reference_mesh)
CGAL_BLENDED_SHAPE_PARAMETER(try_all_axes)
