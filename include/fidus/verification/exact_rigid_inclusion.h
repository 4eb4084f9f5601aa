#ifndef fidus_fluid_exact_rigid_inclusion_h
#define fidus_fluid_exact_rigid_inclusion_h

#include <deal.II/base/function.h>

namespace Fidus
{
  using namespace dealii;

  /**
   * Exact Stokes solution around one torque-free rigid particle of radius a
   * centred at x_c in the linear flow u_inf = g (y - y_c) e_x (validation.md
   * case 3b): the particle rotates at -g/2 and does not translate.
   * Components 0..dim-1 are the velocity, component dim the pressure.
   *
   * 2D: the strain part in polar coordinates about x_c, with e = g/2,
   *   u_r = e sin 2t (r - 2a^2/r + a^4/r^3), u_t = e cos 2t (r - a^4/r^3),
   *   p = -4 eta e a^2 sin 2t / r^2, plus the rigid rotation e (y, -x).
   * 3D: the classical rigid sphere in a linear flow,
   *   u = w x r + E r - (a^5/|r|^5) E r - 5/2 (a^3/|r|^5 - a^5/|r|^7)(r.E.r) r,
   *   p = -5 eta a^3 (r.E.r) / |r|^5.
   * Inside the particle the velocity is the rigid rotation and p = 0.
   */
  template <int dim>
  class ExactRigidInclusion : public Function<dim>
  {
  public:
    /// Particle centre @p center, radius @p radius, shear rate @p g and
    /// fluid viscosity @p eta.
    ExactRigidInclusion(const Point<dim> &center,
                        const double      radius,
                        const double      g,
                        const double      eta);

    void
    vector_value(const Point<dim> &p, Vector<double> &values) const override;

    double
    value(const Point<dim> &p, const unsigned int component) const override;

    /// Gradient by central differences (step 1e-6 a): used for H1 error
    /// norms only, where its O(1e-12) error is far below the discretisation
    /// error.
    Tensor<1, dim>
    gradient(const Point<dim> &p, const unsigned int component) const override;

  private:
    const Point<dim> center;
    const double     a, g, eta;
  };
} // namespace Fidus

#endif
