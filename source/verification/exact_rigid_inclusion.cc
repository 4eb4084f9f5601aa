#include <cmath>
#include <deal.II/lac/vector.h>
#include <fidus/verification/exact_rigid_inclusion.h>

namespace Fidus
{
  template <int dim>
  ExactRigidInclusion<dim>::ExactRigidInclusion(const Point<dim> &center,
                                                const double      radius,
                                                const double      g,
                                                const double      eta)
    : Function<dim>(dim + 1)
    , center(center)
    , a(radius)
    , g(g)
    , eta(eta)
  {}



  template <int dim>
  void
  ExactRigidInclusion<dim>::vector_value(const Point<dim> &p,
                                         Vector<double>   &values) const
  {
    const Tensor<1, dim> r  = p - center;
    const double         rr = r.norm();
    const double         e  = 0.5 * g;
    values                  = 0.;
    // Rigid rotation at -g/2 about z: e (y, -x).
    values[0] = e * r[1];
    values[1] = -e * r[0];
    if (rr <= a)
      return;

    if (dim == 2)
      {
        const double t = std::atan2(r[1], r[0]);
        const double ur =
          e * std::sin(2 * t) *
          (rr - 2 * a * a / rr + std::pow(a, 4) / std::pow(rr, 3));
        const double ut =
          e * std::cos(2 * t) * (rr - std::pow(a, 4) / std::pow(rr, 3));
        values[0] += ur * std::cos(t) - ut * std::sin(t);
        values[1] += ur * std::sin(t) + ut * std::cos(t);
        values[dim] = -4 * eta * e * a * a * std::sin(2 * t) / (rr * rr);
      }
    else
      {
        // E r = e (y, x, 0), r.E.r = 2 e x y.
        const double Er[3] = {e * r[1], e * r[0], 0.};
        const double rEr   = 2 * e * r[0] * r[1];
        const double a3r5  = std::pow(a, 3) / std::pow(rr, 5);
        const double a5r5  = std::pow(a, 5) / std::pow(rr, 5);
        const double a5r7  = std::pow(a, 5) / std::pow(rr, 7);
        for (unsigned int d = 0; d < dim; ++d)
          values[d] += Er[d] - a5r5 * Er[d] - 2.5 * (a3r5 - a5r7) * rEr * r[d];
        values[dim] = -5 * eta * a3r5 * rEr;
      }
  }



  template <int dim>
  double
  ExactRigidInclusion<dim>::value(const Point<dim>  &p,
                                  const unsigned int component) const
  {
    Vector<double> v(dim + 1);
    vector_value(p, v);
    return v[component];
  }

  template <int dim>
  Tensor<1, dim>
  ExactRigidInclusion<dim>::gradient(const Point<dim>  &p,
                                     const unsigned int component) const
  {
    const double   h = 1e-6 * a;
    Tensor<1, dim> g;
    for (unsigned int d = 0; d < dim; ++d)
      {
        Point<dim> xp = p, xm = p;
        xp[d] += h;
        xm[d] -= h;
        g[d] = (value(xp, component) - value(xm, component)) / (2 * h);
      }
    return g;
  }

  template class ExactRigidInclusion<2>;
  template class ExactRigidInclusion<3>;
} // namespace Fidus
