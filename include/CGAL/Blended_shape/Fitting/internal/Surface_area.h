// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_BLENDED_SHAPE_FITTING_INTERNAL_SURFACE_AREA_H
#define CGAL_BLENDED_SHAPE_FITTING_INTERNAL_SURFACE_AREA_H

#include <CGAL/Blended_shape/Primitives/Chart_mesh.h>

#include <Eigen/Dense>

#include <array>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Blended_shapes {
namespace internal {

// The area of a model's surface (a DeformableModel), measured on fixed
// tessellations of its charts, with its parameter gradient: the area term
// of Deformable_model_fitter (Fitting_settings::area_weight). A face counts
// if its centroid is on the surface and its canonical point lies in the
// face's own chart, so that where charts overlap (the two halves of a
// superquadric past its equator, the strips of a blend) each piece of
// surface counts once; its area is that of the triangle of its corners'
// positions.
template <class Model>
class Surface_area
{
public:
  typedef typename Model::Geom_traits Geom_traits;

  // No tessellation: empty().
  Surface_area() = default;

  // The tessellations of `model`'s charts at `resolution` (Chart_mesh).
  Surface_area(const Model& model, int resolution)
  {
    for(std::size_t c = 0; c < model.number_of_charts(); ++c)
    {
      const Chart_mesh<Geom_traits> mesh(c, model.chart_domain(c), resolution);
      Chart chart;
      for(auto v : mesh.mesh().vertices())
        chart.vertices.push_back(mesh.chart_point(v));
      for(auto f : mesh.mesh().faces())
      {
        const auto corners = mesh.face_vertices(f);
        chart.faces.push_back({std::size_t(corners[0]), std::size_t(corners[1]), std::size_t(corners[2])});
        chart.centroids.push_back(mesh.chart_point(f, {1. / 3., 1. / 3., 1. / 3.}));
      }
      m_charts.push_back(std::move(chart));
    }
  }

  bool empty() const { return m_charts.empty(); }

  // The area of `model`'s surface.
  double area(const Model& model) const
  {
    double a = 0.;
    for_each_face(model, [&](const Chart_point& u, Eigen::Vector3d& x, Eigen::MatrixXd&) {
      const auto p = model.point(u);
      x = Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
    }, [&](const std::array<const Eigen::Vector3d*, 3>& x, const std::array<const Eigen::MatrixXd*, 3>&) {
      a += 0.5 * (*x[1] - *x[0]).cross(*x[2] - *x[0]).norm();
    });
    return a;
  }

  // The area of `model`'s surface, returned, its gradient with respect to
  // the parameters, written to `gradient`, and the Gauss-Newton matrix of
  // the face areas taken as squares (A_f = (sqrt A_f)^2),
  // sum_f grad A_f grad A_f^T / (4 A_f), added to `H` (n x n, n the number
  // of parameters): positive semi-definite, it gives the step a curvature
  // along the directions that change the area.
  double area_and_gradient(const Model& model, Eigen::VectorXd& gradient, Eigen::MatrixXd& H) const
  {
    const Eigen::Index n = Eigen::Index(model.number_of_parameters());
    gradient = Eigen::VectorXd::Zero(n);
    double a = 0.;
    typename Model::Jacobian L;
    Eigen::VectorXd face_gradient(n);
    for_each_face(model, [&](const Chart_point& u, Eigen::Vector3d& x, Eigen::MatrixXd& J) {
      const auto p = model.point_and_jacobian(u, L);
      x = Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
      J = L;
    }, [&](const std::array<const Eigen::Vector3d*, 3>& x, const std::array<const Eigen::MatrixXd*, 3>& J) {
      const Eigen::Vector3d normal = (*x[1] - *x[0]).cross(*x[2] - *x[0]); // twice the area, along the normal
      const double twice_area = normal.norm();
      if(!(twice_area > 0.))
        return;
      const Eigen::Vector3d unit = normal / twice_area;
      a += 0.5 * twice_area;
      // dA/dx_a = (x_b - x_c) x n / 2 at the corners a, b, c in order
      face_gradient.setZero();
      for(std::size_t k = 0; k < 3; ++k)
        face_gradient.noalias() += J[k]->transpose() * (0.5 * (*x[(k + 1) % 3] - *x[(k + 2) % 3]).cross(unit));
      gradient += face_gradient;
      H.noalias() += face_gradient * face_gradient.transpose() / (2. * twice_area);
    });
    return a;
  }

private:
  struct Chart
  {
    std::vector<Chart_point> vertices;             // the chart points of the tessellation's vertices
    std::vector<std::array<std::size_t, 3>> faces; // their corners, counterclockwise
    std::vector<Chart_point> centroids;            // of the faces, in the chart
  };

  // Calls `face(x, J)` for each face that counts, with its corners'
  // positions and Jacobians, which `evaluate(u, x, J)` sets at each corner
  // once (corners shared by faces are evaluated once a chart).
  template <class Evaluate, class Face>
  void for_each_face(const Model& model, const Evaluate& evaluate, const Face& face) const
  {
    for(const Chart& chart : m_charts)
    {
      std::vector<Eigen::Vector3d> x(chart.vertices.size());
      std::vector<Eigen::MatrixXd> J(chart.vertices.size());
      std::vector<bool> evaluated(chart.vertices.size(), false);
      for(std::size_t f = 0; f < chart.faces.size(); ++f)
      {
        if(!counts(model, chart, f))
          continue;
        const auto& t = chart.faces[f];
        for(std::size_t v : t)
          if(!evaluated[v])
          {
            evaluate(chart.vertices[v], x[v], J[v]);
            evaluated[v] = true;
          }
        face(std::array<const Eigen::Vector3d*, 3>{&x[t[0]], &x[t[1]], &x[t[2]]},
             std::array<const Eigen::MatrixXd*, 3>{&J[t[0]], &J[t[1]], &J[t[2]]});
      }
    }
  }

  static bool counts(const Model& model, const Chart& chart, std::size_t f)
  {
    Chart_point c;
    return model.canonical_surface_point(chart.centroids[f], c) && c.chart == chart.centroids[f].chart;
  }

  std::vector<Chart> m_charts;
};

} // namespace internal
} // namespace Blended_shapes
} // namespace CGAL

#endif // CGAL_BLENDED_SHAPE_FITTING_INTERNAL_SURFACE_AREA_H
