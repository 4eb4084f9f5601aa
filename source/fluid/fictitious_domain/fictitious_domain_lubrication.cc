#include <algorithm>
#include <cmath>
#include <deque>
#include <fidus/fluid/fictitious_domain/anderson_mixing.h>
#include <fidus/fluid/fictitious_domain/fictitious_domain_model.h>
#include <fidus/lubrication/lubrication_coupling.h>
#include <iostream>
#include <sstream>

// The fictitious domain with the sub-grid lubrication solved with its flow
// (Fluid/Lubrication coupling = with the flow): the bonds' loads act on the
// particles as body forces, and the rigid velocities and the loads are
// iterated to agree (Contact::LubricationCoupling).

namespace Fidus
{
  using namespace dealii;

  namespace
  {
    /// At most this many solves with the bonds' loads per solve of a step.
    constexpr unsigned int max_coupling_solves = 30;
    /// The linear tolerance of a solve with new loads over the last
    /// change of the rigid velocities (relative to the largest speed): on
    /// the dense 3D scene a solve to a relative residual t moved them by
    /// about 4 t, so this keeps that error near a tenth of the change.
    constexpr double coupling_forcing = 0.02;
    /// Earlier iterates that the Anderson mixing combines with the newest.
    constexpr unsigned int coupling_mixing_depth = 5;

    using Vec3 = std::array<double, 3>;

    /// U and W as one vector, six values per particle.
    std::vector<double>
    pack(const std::vector<Vec3> &U, const std::vector<Vec3> &W)
    {
      std::vector<double> x(6 * U.size());
      for (std::size_t i = 0; i < U.size(); ++i)
        for (unsigned int d = 0; d < 3; ++d)
          {
            x[6 * i + d]     = U[i][d];
            x[6 * i + 3 + d] = W[i][d];
          }
      return x;
    }

    /// The inverse of pack().
    void
    unpack(const std::vector<double> &x,
           std::vector<Vec3>         &U,
           std::vector<Vec3>         &W)
    {
      for (std::size_t i = 0; i < U.size(); ++i)
        for (unsigned int d = 0; d < 3; ++d)
          {
            U[i][d] = x[6 * i + d];
            W[i][d] = x[6 * i + 3 + d];
          }
    }

    /// The largest speed of a particle in @p x: |U| or a |omega|.
    double
    largest_speed(const std::vector<double> &x,
                  const std::vector<double> &radii)
    {
      double s = 0.;
      for (std::size_t i = 0; i < radii.size(); ++i)
        {
          double u2 = 0., w2 = 0.;
          for (unsigned int d = 0; d < 3; ++d)
            {
              u2 += x[6 * i + d] * x[6 * i + d];
              w2 += x[6 * i + 3 + d] * x[6 * i + 3 + d];
            }
          s = std::max({s, std::sqrt(u2), radii[i] * std::sqrt(w2)});
        }
      return s;
    }

    /// The loosest linear tolerance of a solve with new loads: the Uzawa
    /// loop's inexact one ('Inexact Uzawa factor' times the loop's
    /// tolerance), never below the linear tolerance, which is also what
    /// an exact (direct) solver gets.
    double
    loosest_tolerance(const FictitiousDomainParameters &fd,
                      const bool                        exact_solver)
    {
      if (exact_solver)
        return fd.linear_tolerance;
      const double loop_tolerance = fd.rigid_velocity_tolerance > 0. ?
                                      fd.rigid_velocity_tolerance :
                                      fd.rigidity_tolerance;
      return std::max(fd.linear_tolerance,
                      fd.inexact_uzawa_factor * loop_tolerance);
    }

    double
    dot(const std::vector<double> &a, const std::vector<double> &b)
    {
      double s = 0.;
      for (std::size_t k = 0; k < a.size(); ++k)
        s += a[k] * b[k];
      return s;
    }
  } // namespace



  template <int dim>
  typename FictitiousDomainModel<dim>::Statistics
  FictitiousDomainModel<dim>::solve_with_subgrid_lubrication(
    const std::vector<Vec3> &X,
    const double             shear_rate,
    const SolveLabel        &label,
    std::vector<Vec3>       &U,
    std::vector<Vec3>       &W)
  {
    const std::vector<double> &radii = prm.particles.radii;

    // The solve without the bonds: the whole step if no pair is close.
    // With bonds the solve only starts the iteration, whose last solve
    // meets the linear tolerance: it stops at the loosest one (the first
    // solve of a step was a sixth of the iteration's FGMRES in the dense
    // 3D scene).
    const FictitiousDomainParameters &fd = prm.fictitious_domain;
    const double                      inexact_tolerance =
      loosest_tolerance(fd, solver->solves_exactly());
    const std::vector<Contact::LubricationBond> &bonds =
      subgrid->find_bonds(X, radii);
    Statistics stats = solve_stokes(shear_rate,
                                    label,
                                    external_force.get(),
                                    nullptr,
                                    bonds.empty() ? 0. : inexact_tolerance);
    extract_rigid_motion(U, W);
    if (bonds.empty())
      return stats;

    // Iterate x <- x + P (u(L(x)) - x) with Anderson mixing.
    // Start from the correction after the solve: a third fewer solves
    // than from P y0 on a dense 2D configuration (22 -> 15 per solve),
    // since it carries the walls' forcing and the calibrated ranges. It
    // collects the same bonds again.
    std::vector<Vec3> u_corrected, w_corrected;
    subgrid->correct(X, radii, U, W, u_corrected, w_corrected);
    const Contact::LubricationCoupling coupling(*subgrid, radii);
    const std::vector<double>          y0    = pack(U, W);
    const double                       scale = largest_speed(y0, radii);
    const double        goal = prm.lubrication.coupling_tolerance * scale;
    std::vector<double> x    = pack(u_corrected, w_corrected), f, loaded;
    AndersonMixing      mixing(coupling_mixing_depth);
    std::deque<std::vector<double>> g_history, f_history;
    double                          change = 0.;

    // Inexact solves: an iterate far from the fixed point needs its
    // velocity only to a fraction of its distance from it. Each solve with
    // new loads stops at a linear tolerance proportional to the last
    // change (coupling_forcing times it, relative to the largest speed),
    // between the linear tolerance and the Uzawa loop's inexact one
    // ('Inexact Uzawa factor' times its tolerance), so that the last
    // iterates, whose change is near the goal, are solved to the linear
    // tolerance and the velocities handed on meet it. An iterate within
    // the goal on a looser solve is solved again with the same loads.
    double tolerance = inexact_tolerance;
    for (unsigned int solves = 1; solves <= max_coupling_solves; ++solves)
      {
        coupling.loads(x, load_force, load_torque);
        loaded                = x;
        const bool this_exact = tolerance <= fd.linear_tolerance;
        stats                 = stats.followed_by(solve_stokes(shear_rate,
                                               label,
                                               nullptr,
                                               load_density.get(),
                                               tolerance));
        extract_rigid_motion(U, W);
        std::vector<double> r = pack(U, W);
        for (std::size_t k = 0; k < r.size(); ++k)
          r[k] -= x[k];
        coupling.step(r, f);
        change = largest_speed(f, radii);
        if (prm.output.verbosity == Verbosity::verbose &&
            Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
          std::cout << "    lubrication coupling: solve " << solves
                    << " (linear tolerance " << tolerance << ")"
                    << ", rigid velocity change " << change / scale
                    << std::endl;
        if (change <= goal && !this_exact && solves < max_coupling_solves)
          {
            tolerance = fd.linear_tolerance;
            continue;
          }
        // The particles move with the velocities whose loads the flow
        // carries, so that the bonds' forces (measured on them) and the
        // flow's stress belong to one solution: with those of the solve,
        // a velocity difference within the tolerance came back times the
        // bonds' resistance, and N1 and the particle pressure of a dense
        // suspension still moved by 0.1-0.2 between tolerances 1e-3 and
        // 1e-4.
        if (change <= goal)
          {
            unpack(loaded, U, W);
            return stats;
          }
        tolerance = std::clamp(coupling_forcing * change / scale,
                               fd.linear_tolerance,
                               inexact_tolerance);

        if (mixing.size() == coupling_mixing_depth + 1)
          {
            mixing.drop_oldest();
            g_history.pop_front();
            f_history.pop_front();
          }
        std::vector<double> products;
        for (const std::vector<double> &fi : f_history)
          products.push_back(dot(f, fi));
        products.push_back(dot(f, f));
        mixing.push(products);
        for (std::size_t k = 0; k < f.size(); ++k)
          x[k] += f[k];
        g_history.push_back(x);
        f_history.push_back(f);
        const std::vector<double> alpha = mixing.weights();
        std::fill(x.begin(), x.end(), 0.);
        for (std::size_t h = 0; h < alpha.size(); ++h)
          for (std::size_t k = 0; k < x.size(); ++k)
            x[k] += alpha[h] * g_history[h][k];
      }
    std::ostringstream m;
    m << label.where << ": the sub-grid lubrication solved with the flow "
      << "still changed a rigid velocity by " << change / scale
      << " of the largest after " << max_coupling_solves
      << " solves, above 'Fluid/Lubrication coupling tolerance' = "
      << prm.lubrication.coupling_tolerance;
    unpack(loaded, U, W);
    warnings.warn("lubrication coupling not converged",
                  m.str(),
                  label.step,
                  change / scale);
    return stats;
  }



  // The class is instantiated in fictitious_domain_model.cc; here only
  // the member defined in this file.
  template typename FictitiousDomainModel<2>::Statistics
  FictitiousDomainModel<2>::solve_with_subgrid_lubrication(
    const std::vector<Vec3> &,
    double,
    const SolveLabel &,
    std::vector<Vec3> &,
    std::vector<Vec3> &);
  template typename FictitiousDomainModel<3>::Statistics
  FictitiousDomainModel<3>::solve_with_subgrid_lubrication(
    const std::vector<Vec3> &,
    double,
    const SolveLabel &,
    std::vector<Vec3> &,
    std::vector<Vec3> &);
} // namespace Fidus
