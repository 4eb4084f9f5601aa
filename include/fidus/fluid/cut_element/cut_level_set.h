#ifndef fidus_fluid_cut_level_set_h
#define fidus_fluid_cut_level_set_h

#include <deal.II/base/function.h>
#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

namespace Fidus
{
  using namespace dealii;

  /**
   * The level set psi(xi) = |lower + H xi - X| - a of a ball on the
   * reference cell of an axis-parallel cell of sides H = diag(h_0, ...)
   * (negative in the ball; in the reference cell of a cell that is not a
   * cube the ball is an ellipsoid, which the quadrature generator takes as
   * any other smooth level set). The cut quadratures of CutStokesInclusion are
   * generated in reference coordinates, where FEValues wants them, from this
   * exact sphere: its value, gradient and Hessian, which
   * NonMatching::QuadratureGenerator needs.
   */
  template <int dim>
  class CutLevelSet : public Function<dim>
  {
  public:
    /// The cell's lower and upper corners; the ball.
    CutLevelSet(const Point<dim> &lower,
                const Point<dim> &upper,
                const Point<dim> &center,
                const double      radius)
      : lower(lower)
      , h(upper - lower)
      , center(center)
      , radius(radius)
    {}

    /// psi at the reference point @p xi.
    double
    value(const Point<dim> &xi, const unsigned int = 0) const override
    {
      return (real(xi) - center).norm() - radius;
    }

    /// Its gradient with respect to @p xi.
    Tensor<1, dim>
    gradient(const Point<dim> &xi, const unsigned int = 0) const override
    {
      const Tensor<1, dim> r = real(xi) - center;
      // Times the inverse of |r|, as deal.II divides a tensor by a number
      // (a cubic cell's quadratures are then those of a single size h).
      const double   inverse = 1. / r.norm();
      Tensor<1, dim> g;
      for (unsigned int d = 0; d < dim; ++d)
        g[d] = h[d] * r[d] * inverse;
      return g;
    }

    /// Its Hessian with respect to @p xi.
    SymmetricTensor<2, dim>
    hessian(const Point<dim> &xi, const unsigned int = 0) const override
    {
      const Tensor<1, dim>    r = real(xi) - center;
      const double            d = r.norm();
      SymmetricTensor<2, dim> H;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          H[i][j] =
            h[i] * h[j] * ((i == j ? 1. : 0.) - r[i] * r[j] / (d * d)) / d;
      return H;
    }

  private:
    Point<dim>
    real(const Point<dim> &xi) const
    {
      Point<dim> x = lower;
      for (unsigned int d = 0; d < dim; ++d)
        x[d] += h[d] * xi[d];
      return x;
    }

    const Point<dim>     lower;
    const Tensor<1, dim> h;
    const Point<dim>     center;
    const double         radius;
  };
} // namespace Fidus

#endif
