#include <cmath>
#include <fidus/contact/contact_error.h>
#include <fidus/lubrication/lubrication_coupling.h>
#include <string>

namespace Fidus::Contact
{
  namespace
  {
    using Local = std::array<double, 12>;

    bool
    is_wall(const LubricationBond &b)
    {
      return b.j == LubricationBond::no_particle;
    }

    /// The bond's generalised velocities (U_i, w_i, U_j, w_j) from x.
    Local
    gather(const LubricationBond &b, const std::vector<double> &x)
    {
      Local l{};
      for (unsigned int k = 0; k < 6; ++k)
        {
          l[k] = x[6 * b.i + k];
          if (!is_wall(b))
            l[6 + k] = x[6 * b.j + k];
        }
      return l;
    }
  } // namespace



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
        const Local f = correction.subgrid_loads(b, v, false);
        const Local g = correction.resolved_loads(b, v);
        for (unsigned int k = 0; k < 6; ++k)
          {
            y[6 * b.i + k] -= f[k] + g[k];
            if (!is_wall(b))
              y[6 * b.j + k] -= f[6 + k] + g[6 + k];
          }
      }
  }



  unsigned int
  LubricationCoupling::step(const std::vector<double> &r,
                            std::vector<double>       &s) const
  {
    const std::size_t   n = zeta.size();
    std::vector<double> rhs(6 * n), res(6 * n), z(6 * n), p(6 * n), ap;
    double              rhs2 = 0.;
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        {
          rhs[6 * i + d]     = zeta[i] * r[6 * i + d];
          rhs[6 * i + 3 + d] = zeta_rot[i] * r[6 * i + 3 + d];
        }
    for (const LubricationBond &b : correction.bonds())
      {
        const Local g = correction.resolved_loads(b, gather(b, r));
        for (unsigned int k = 0; k < 6; ++k)
          {
            rhs[6 * b.i + k] -= g[k];
            if (!is_wall(b))
              rhs[6 * b.j + k] -= g[6 + k];
          }
      }
    s.assign(6 * n, 0.);
    double rz = 0.;
    for (std::size_t k = 0; k < 6 * n; ++k)
      {
        res[k] = rhs[k];
        z[k]   = res[k] / diagonal[k];
        p[k]   = z[k];
        rz += res[k] * z[k];
        rhs2 += rhs[k] * rhs[k];
      }
    const LubricationSettings &settings = correction.get_settings();
    const double goal2 = settings.tolerance * settings.tolerance * rhs2;
    double       res2  = rhs2;
    unsigned int it    = 0;
    while (res2 > goal2 && it < settings.max_iterations)
      {
        apply(p, ap);
        double pap = 0.;
        for (std::size_t k = 0; k < 6 * n; ++k)
          pap += p[k] * ap[k];
        const double alpha  = rz / pap;
        double       rz_new = 0.;
        res2                = 0.;
        for (std::size_t k = 0; k < 6 * n; ++k)
          {
            s[k] += alpha * p[k];
            res[k] -= alpha * ap[k];
            z[k] = res[k] / diagonal[k];
            rz_new += res[k] * z[k];
            res2 += res[k] * res[k];
          }
        const double beta = rz_new / rz;
        rz                = rz_new;
        for (std::size_t k = 0; k < 6 * n; ++k)
          p[k] = z[k] + beta * p[k];
        ++it;
      }
    if (!(res2 <= goal2))
      throw ContactError(
        "lubrication coupling: the conjugate gradients of a step did not "
        "converge in " +
        std::to_string(it) + " iterations (relative residual " +
        std::to_string(std::sqrt(res2 / rhs2)) + ")");
    return it;
  }
} // namespace Fidus::Contact
