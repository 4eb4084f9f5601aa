// Validation case 6: the KKT conditions of every projection, on random
// polydisperse configurations with random weights, moving walls and random
// predicted velocities, for both contact models and all three dual solvers,
// in 2D and 3D. The glue state builds up over the steps, so that glued
// (equality) and unglued (inequality) rows are both exercised. Checked per
// projection: u = u* + W^{-1} G^T lambda, lambda >= 0 and complementarity on
// unglued rows, equality on glued rows, a row is glued iff gamma < 0, the
// glue update gamma <- min(0, gamma - dt lambda), every pair (also those the
// pair search left out, by brute force) feasible after the step, and the
// corrected velocities of the three solvers agree.

#include "kkt_check.h"
#include "test_tools.h"

#include <cstdio>
#include <fidus/contact/contact_projector.h>
#include <iomanip>
#include <iostream>
#include <map>

using namespace Fidus::Contact;

namespace
{
  const char *
  name(const DualSolver s)
  {
    switch (s)
      {
        case DualSolver::projected_gradient:
          return "projected gradient";
        case DualSolver::accelerated_projected_gradient:
          return "accelerated projected gradient";
        case DualSolver::projected_gauss_seidel_subspace:
          return "projected Gauss-Seidel + subspace";
        default:
          return "projected Gauss-Seidel";
      }
  }

  /// Smallest linearised and true gap over all pairs and walls (O(N^2)).
  void
  brute_force_gaps(const unsigned             dim,
                   const std::vector<Vec3>   &x,
                   const std::vector<double> &a,
                   const std::vector<Vec3>   &u,
                   const std::vector<Wall>   &walls,
                   const double               dt,
                   double                    &min_linear,
                   double                    &min_true)
  {
    min_linear = min_true = 1e300;
    for (std::size_t i = 0; i < x.size(); ++i)
      {
        for (std::size_t j = i + 1; j < x.size(); ++j)
          {
            double r2 = 0., r2_new = 0., ru = 0.;
            for (unsigned d = 0; d < dim; ++d)
              {
                const double dx = x[j][d] - x[i][d];
                const double du = u[j][d] - u[i][d];
                r2 += dx * dx;
                ru += dx * du;
                r2_new += (dx + dt * du) * (dx + dt * du);
              }
            const double r = std::sqrt(r2);
            min_linear = std::min(min_linear, r - a[i] - a[j] + dt * ru / r);
            min_true   = std::min(min_true, std::sqrt(r2_new) - a[i] - a[j]);
          }
        for (const auto &w : walls)
          {
            const double g = w.side * (x[i][w.axis] - w.position) - a[i] +
                             dt * w.side * u[i][w.axis];
            min_linear = std::min(min_linear, g);
            min_true   = std::min(min_true, g);
          }
      }
  }
} // namespace

int
main()
{
  const double tolerance = 1e-11;
  const double dt        = 0.01;
  const int    n_steps   = 15;

  for (const unsigned dim : {2u, 3u})
    {
      TestTools::Random   random(dim);
      std::vector<Vec3>   x0;
      std::vector<double> a;
      const std::size_t   n = dim == 2 ? 150 : 200;
      TestTools::random_packing(random,
                                dim,
                                n,
                                dim == 2 ? 0.025 : 0.05,
                                dim == 2 ? 0.035 : 0.07,
                                0.,
                                1.,
                                0.002,
                                x0,
                                a);
      std::vector<double> weights(n);
      for (auto &w : weights)
        w = random.uniform(0.5, 2.);
      // Lower and upper walls in y move tangentially; the x walls are fixed.
      std::vector<Wall> walls(4);
      walls[0] = Wall{1, 0., 1, Vec3{{0.5, 0., 0.}}};
      walls[1] = Wall{1, 1., -1, Vec3{{-0.5, 0., 0.}}};
      walls[2] = Wall{0, 0., 1, Vec3{{0., 0., 0.}}};
      walls[3] = Wall{0, 1., -1, Vec3{{0., 0., 0.}}};
      // The same predicted velocities for every model and solver.
      std::vector<std::vector<Vec3>> u_star(n_steps, std::vector<Vec3>(n));
      for (auto &step : u_star)
        for (std::size_t i = 0; i < n; ++i)
          for (unsigned d = 0; d < dim; ++d)
            step[i][d] = random.uniform(-1., 1.) - 0.5 * (x0[i][d] - 0.5);

      for (const Model model : {Model::inelastic, Model::gluey})
        {
          // Reference: the Gauss-Seidel velocities of each step.
          std::vector<std::vector<Vec3>> reference;
          for (const DualSolver solver :
               {DualSolver::projected_gauss_seidel,
                DualSolver::projected_gauss_seidel_subspace,
                DualSolver::accelerated_projected_gradient,
                DualSolver::projected_gradient})
            {
              Settings settings;
              settings.dimension = dim;
              settings.model     = model;
              settings.solver    = solver;
              settings.tolerance = tolerance;
              ContactProjector projector(settings);
              projector.set_walls(walls);
              projector.set_weights(weights);

              std::vector<Vec3> x = x0, u;
              KKT::Errors       errors;
              bool              converged = true, glue_ok = true;
              double            worst_linear = 1e300, worst_true = 1e300;
              double            max_difference = 0.;
              unsigned int      max_iterations = 0;
              for (int s = 0; s < n_steps; ++s)
                {
                  const auto statistics =
                    projector.project(x, a, u_star[s], dt, u);
                  converged = converged && statistics.converged;
                  max_iterations =
                    std::max(max_iterations, statistics.iterations);
                  errors.merge(
                    KKT::check(projector, walls, weights, u_star[s], u, dt));

                  // Glue update of every row.
                  const auto &rows = projector.constraints();
                  for (std::size_t k = 0; k < rows.size(); ++k)
                    {
                      std::uint32_t first  = rows.first(k),
                                    second = rows.second(k);
                      if (first >= n)
                        {
                          second = GlueState::wall_key(first - n);
                          first  = rows.second(k);
                        }
                      double expected =
                        model == Model::gluey ?
                          std::min(0., rows.gamma(k) - dt * rows.lambda(k)) :
                          0.;
                      if (expected > -settings.glue_snap)
                        expected = 0.;
                      const long e = projector.glue_state().find(first, second);
                      const double g =
                        e < 0 ? 0. : projector.glue_state().entries()[e].gamma;
                      if (std::abs(g - expected) > 1e-15)
                        glue_ok = false;
                    }

                  double lin, tru;
                  brute_force_gaps(dim, x, a, u, walls, dt, lin, tru);
                  worst_linear = std::min(worst_linear, lin);
                  worst_true   = std::min(worst_true, tru);

                  if (solver == DualSolver::projected_gauss_seidel)
                    reference.push_back(u);
                  else
                    for (std::size_t i = 0; i < n; ++i)
                      for (unsigned d = 0; d < dim; ++d)
                        max_difference =
                          std::max(max_difference,
                                   dt * std::abs(u[i][d] - reference[s][i][d]));
                  // All solvers move with the reference velocities, so that
                  // they see the same configurations.
                  for (std::size_t i = 0; i < n; ++i)
                    for (unsigned d = 0; d < dim; ++d)
                      x[i][d] += dt * reference[s][i][d];
                }

              const std::string head =
                std::to_string(dim) + "D " +
                (model == Model::gluey ? "gluey" : "inelastic") + ", " +
                name(solver);
              const double tol             = 1.001 * tolerance;
              const int    failures_before = TestTools::failures();
              TestTools::check(head + ", all projections converged", converged);
              TestTools::check(head + ", glued and unglued rows present",
                               errors.n_unglued_rows > 0 &&
                                 (model == Model::inelastic ||
                                  errors.n_glued_rows > 0));
              TestTools::check(head + ", u = u* + W^-1 G^T lambda",
                               errors.stationarity <= 1e-14);
              TestTools::check(head + ", lambda >= 0 on unglued rows",
                               errors.sign <= 0.);
              TestTools::check(head + ", feasibility <= tol",
                               errors.feasibility <= tol);
              TestTools::check(head + ", complementarity <= tol",
                               errors.complementarity <= tol);
              TestTools::check(head + ", equality on glued rows <= tol",
                               errors.equality <= tol);
              TestTools::check(head + ", glued iff gamma < 0",
                               errors.glue_flag == 0.);
              TestTools::check(head + ", glue update", glue_ok);
              TestTools::check(head +
                                 ", all pairs (brute force) feasible after "
                                 "the step",
                               worst_linear >= -tol && worst_true >= -tol);
              if (solver != DualSolver::projected_gauss_seidel)
                TestTools::check(head + ", same displacements as Gauss-Seidel "
                                        "(1e-8)",
                                 max_difference <= 1e-8);
              // Numbers that would make the output unstable are printed
              // only to explain a failure.
              if (TestTools::failures() > failures_before)
                std::printf("%s: stat %.2e sign %.2e feas %.2e compl %.2e eq "
                            "%.2e lin %.2e true %.2e diff %.2e glued %u "
                            "unglued %u iterations %u\n",
                            head.c_str(),
                            errors.stationarity,
                            errors.sign,
                            errors.feasibility,
                            errors.complementarity,
                            errors.equality,
                            worst_linear,
                            worst_true,
                            max_difference,
                            errors.n_glued_rows,
                            errors.n_unglued_rows,
                            max_iterations);
            }
        }
    }
  return TestTools::failures() == 0 ? 0 : 1;
}
