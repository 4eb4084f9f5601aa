#include "bond_algebra.h"

#include <cmath>
#include <fidus/contact/contact_error.h>
#include <fidus/lubrication/lubrication_coupling.h>
#include <string>

namespace Fidus::Contact
{
  using BondAlgebra::gather;
  using BondAlgebra::is_wall;
  using BondAlgebra::Local;
  using BondAlgebra::scatter_add;



  LubricationCoupling::LubricationCoupling(
    const LubricationCorrection &correction,
    const std::vector<double>   &radii)
    : correction(correction)
    , zeta(radii.size())
    , zeta_rot(radii.size())
    , diagonal(6 * radii.size())
  {
    for (std::size_t i = 0; i < radii.size(); ++i)
      {
        zeta[i]     = correction.drag(radii[i]);
        zeta_rot[i] = correction.rotational_drag(radii[i]);
        for (unsigned int d = 0; d < 3; ++d)
          {
            diagonal[6 * i + d]     = zeta[i];
            diagonal[6 * i + 3 + d] = zeta_rot[i];
          }
      }
    // D's diagonal, one local unit velocity at a time: the load a bond
    // puts on the unknown it moves, with the sign of a resistance.
    for (const LubricationBond &b : correction.bonds())
      for (unsigned int k = 0; k < (is_wall(b) ? 6u : 12u); ++k)
        {
          Local e{};
          e[k]          = 1.;
          const Local f = correction.subgrid_loads(b, e, false);
          const Local g = correction.resolved_loads(b, e);
          diagonal[6 * (k < 6 ? b.i : b.j) + k % 6] -= f[k] + g[k];
        }
  }



  void
  LubricationCoupling::loads(const std::vector<double> &x,
                             std::vector<Vec3>         &force,
                             std::vector<Vec3>         &torque) const
  {
    const std::size_t n = zeta.size();
    force.assign(n, Vec3{{0., 0., 0.}});
    torque.assign(n, Vec3{{0., 0., 0.}});
    for (const LubricationBond &b : correction.bonds())
      {
        const Local f = correction.subgrid_loads(b, gather(b, x), true);
        for (unsigned int d = 0; d < 3; ++d)
          {
            force[b.i][d] += f[d];
            torque[b.i][d] += f[3 + d];
            if (!is_wall(b))
              {
                force[b.j][d] += f[6 + d];
                torque[b.j][d] += f[9 + d];
              }
          }
      }
  }



  void
  LubricationCoupling::apply(const std::vector<double> &x,
                             std::vector<double>       &y) const
  {
    const std::size_t n = zeta.size();
    y.assign(6 * n, 0.);
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        {
          y[6 * i + d]     = zeta[i] * x[6 * i + d];
          y[6 * i + 3 + d] = zeta_rot[i] * x[6 * i + 3 + d];
        }
    // The loads resist the motion: (Z + D) x = zeta x - the loads of the
    // resolved and the sub-grid resistances at x, walls at rest.
    for (const LubricationBond &b : correction.bonds())
      {
        const Local v = gather(b, x);
        scatter_add(b, correction.subgrid_loads(b, v, false), -1., y);
        scatter_add(b, correction.resolved_loads(b, v), -1., y);
      }
  }



  unsigned int
  LubricationCoupling::step(const std::vector<double> &r,
                            std::vector<double>       &s) const
  {
    const std::size_t   n = zeta.size();
    std::vector<double> rhs(6 * n);
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        {
          rhs[6 * i + d]     = zeta[i] * r[6 * i + d];
          rhs[6 * i + 3 + d] = zeta_rot[i] * r[6 * i + 3 + d];
        }
    for (const LubricationBond &b : correction.bonds())
      scatter_add(b, correction.resolved_loads(b, gather(b, r)), -1., rhs);
    s.assign(6 * n, 0.);
    const LubricationSettings  &settings = correction.get_settings();
    const BondAlgebra::CgResult cg =
      BondAlgebra::jacobi_cg([this](const std::vector<double> &v,
                                    std::vector<double> &y) { apply(v, y); },
                             diagonal,
                             rhs,
                             settings.tolerance,
                             settings.max_iterations,
                             s);
    if (!(cg.residual2 <= settings.tolerance * settings.tolerance * cg.rhs2))
      throw ContactError(
        "lubrication coupling: the conjugate gradients of a step did not "
        "converge in " +
        std::to_string(cg.iterations) + " iterations (relative residual " +
        std::to_string(std::sqrt(cg.residual2 / cg.rhs2)) + ")");
    return cg.iterations;
  }
} // namespace Fidus::Contact
