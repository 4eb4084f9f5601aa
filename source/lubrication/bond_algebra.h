#ifndef fidus_lubrication_bond_algebra_h
#define fidus_lubrication_bond_algebra_h

// Internal to the lubrication library: the generalised vectors of bonds
// (six values per particle, U then omega) and the Jacobi-preconditioned
// conjugate gradients that LubricationCorrection and LubricationCoupling
// solve their small symmetric positive definite systems with.

#include <array>
#include <cstddef>
#include <fidus/lubrication/lubrication_correction.h>
#include <vector>

namespace Fidus::Contact::BondAlgebra
{
  /// Per bond, the generalised velocities or loads of its two particles:
  /// U_i, w_i, U_j, w_j (the last six unused for a wall).
  using Local = std::array<double, 12>;

  inline bool
  is_wall(const LubricationBond &b)
  {
    return b.j == LubricationBond::no_particle;
  }

  /// The bond's generalised velocities from the global vector x.
  inline Local
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

  /// y += s l on the bond's two particles.
  inline void
  scatter_add(const LubricationBond &b,
              const Local           &l,
              const double           s,
              std::vector<double>   &y)
  {
    for (unsigned int k = 0; k < 6; ++k)
      {
        y[6 * b.i + k] += s * l[k];
        if (!is_wall(b))
          y[6 * b.j + k] += s * l[6 + k];
      }
  }

  /// What jacobi_cg() did: its iterations and the squared norms of the last
  /// residual and of the right-hand side.
  struct CgResult
  {
    unsigned int iterations = 0;
    double       residual2 = 0., rhs2 = 0.;
  };

  /**
   * Solve A x = @p rhs by conjugate gradients preconditioned with the
   * diagonal @p diagonal of A, from the initial @p x, until the residual is
   * below @p tolerance times the right-hand side or after
   * @p max_iterations. @p apply(v, y) sets y = A v.
   */
  template <typename Apply>
  CgResult
  jacobi_cg(const Apply               &apply,
            const std::vector<double> &diagonal,
            const std::vector<double> &rhs,
            const double               tolerance,
            const unsigned int         max_iterations,
            std::vector<double>       &x)
  {
    const std::size_t   m = rhs.size();
    std::vector<double> ax, r(m), z(m), p(m);
    apply(x, ax);
    CgResult result;
    double   rz = 0.;
    for (std::size_t k = 0; k < m; ++k)
      {
        r[k] = rhs[k] - ax[k];
        z[k] = r[k] / diagonal[k];
        p[k] = z[k];
        result.rhs2 += rhs[k] * rhs[k];
        rz += r[k] * z[k];
        result.residual2 += r[k] * r[k];
      }
    const double goal2 = tolerance * tolerance * result.rhs2;
    while (result.residual2 > goal2 && result.iterations < max_iterations)
      {
        apply(p, ax);
        double pap = 0.;
        for (std::size_t k = 0; k < m; ++k)
          pap += p[k] * ax[k];
        const double alpha  = rz / pap;
        double       rz_new = 0.;
        result.residual2    = 0.;
        for (std::size_t k = 0; k < m; ++k)
          {
            x[k] += alpha * p[k];
            r[k] -= alpha * ax[k];
            z[k] = r[k] / diagonal[k];
            rz_new += r[k] * z[k];
            result.residual2 += r[k] * r[k];
          }
        const double beta = rz_new / rz;
        rz                = rz_new;
        for (std::size_t k = 0; k < m; ++k)
          p[k] = z[k] + beta * p[k];
        ++result.iterations;
      }
    return result;
  }
} // namespace Fidus::Contact::BondAlgebra

#endif
