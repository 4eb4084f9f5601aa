// The stopping rules of the Uzawa loop (UzawaLoop), on a model problem
// whose residuals are known: after n multiplier updates the strain left in
// the solid is a given sequence m_n (geometric, or chosen to make a rule
// fire), and the particle's rotation changes by a given amount. Every
// count below follows from the rules by hand:
//
// - geometric contraction 0.5 from 0.1 to the tolerance 1e-3: converged
//   after 8 iterations (0.1 * 0.5^7 = 7.8e-4), 7 updates, every solve exact;
// - the per-particle measure is the one compared when asked for;
// - contraction 0.99 or growth: stopped after 2 iterations as stalled;
// - the maximum of 5 iterations: 4 updates, the last solve exact;
// - inexact solves (factor 1): the geometric prediction m_k^2 / m_(k-1)
//   makes exactly the last solve exact; a prediction that misses ends on
//   an inexact solve, which is solved again to the linear tolerance;
// - the rigid velocity tolerance stops on the change of omega, scaled by
//   the shear or by a larger forced velocity;
// - a NaN residual is an error, not a stall.

#include "../fidus_test.h"

#include <deal.II/base/mpi.h>
#include <fidus/core/input_error.h>
#include <fidus/fluid/fictitious_domain/uzawa_loop.h>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

using namespace FidusTest;
using Fidus::UzawaLoop;
using Fidus::UzawaProblem;

namespace
{
  /// One particle of radius 2 in a shear of rate 1. After n updates the
  /// strain residual is strain(n) and omega has moved by
  /// sum_{j <= n} omega_step(j).
  class ModelProblem : public UzawaProblem
  {
  public:
    std::function<double(unsigned int)> strain;
    std::function<double(unsigned int)> omega_step = [](unsigned int) {
      return 0.;
    };
    bool per_particle_only = false;

    unsigned int        updates = 0;
    unsigned int        loads   = 0;
    std::vector<double> tolerances;

    void
    load_multiplier() override
    {
      ++loads;
    }

    unsigned int
    solve_velocity(const double tolerance) override
    {
      tolerances.push_back(tolerance);
      return 10;
    }

    Residual
    rigidity_residual() const override
    {
      Residual r;
      r.shear_rate = 1.;
      r.particle   = strain(updates);
      r.held       = per_particle_only ? 0. : strain(updates);
      return r;
    }

    std::vector<Fidus::RigidMotion>
    rigid_motions() const override
    {
      Fidus::RigidMotion m;
      for (unsigned int j = 0; j <= updates; ++j)
        m.omega[2] += omega_step(j);
      return {m};
    }

    double
    particle_radius(unsigned int) const override
    {
      return 2.;
    }

    void
    update_multiplier() override
    {
      ++updates;
    }

    unsigned int
    exact_solves(const double linear_tolerance) const
    {
      unsigned int n = 0;
      for (const double t : tolerances)
        n += (t <= linear_tolerance);
      return n;
    }
  };

  UzawaLoop::Settings
  base_settings()
  {
    UzawaLoop::Settings s;
    s.rigidity_tolerance = 1e-3;
    s.max_iterations     = 50;
    s.linear_tolerance   = 1e-6;
    return s;
  }

  /// Solves inside the loop to the rigidity tolerance (factor 1), the
  /// first one too.
  UzawaLoop::Settings
  inexact_settings()
  {
    UzawaLoop::Settings s = base_settings();
    s.inexact_factor      = 1.;
    s.first_solve_exact   = false;
    return s;
  }

  std::function<double(unsigned int)>
  geometric(const double first, const double ratio)
  {
    return [=](unsigned int n) { return first * std::pow(ratio, n); };
  }

  void
  check_count(const std::string &what,
              const unsigned int value,
              const unsigned int expected)
  {
    const bool ok = value == expected;
    if (!ok)
      ++failures();
    std::cout << what << " = " << expected << ": "
              << (ok ? "OK" : "FAILED (" + std::to_string(value) + ")")
              << std::endl;
  }

  void
  check_flag(const std::string &what, const bool value, const bool expected)
  {
    check_count(what, value ? 1 : 0, expected ? 1 : 0);
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  std::cout << "a. geometric 0.5, exact solves" << std::endl;
  {
    ModelProblem p;
    p.strain     = geometric(0.1, 0.5);
    const auto r = UzawaLoop(base_settings()).run(p);
    check_count("iterations", r.iterations, 8);
    check_count("updates", p.updates, 7);
    check_count("solves", p.tolerances.size(), 8);
    check_count("exact solves", p.exact_solves(1e-6), 8);
    check_count("linear iterations", r.linear_iterations, 80);
    check_flag("converged", r.converged, true);
    check_flag("stalled", r.stalled, false);
    check_range("residual / 0.1 0.5^7",
                r.rigidity_residual / 7.8125e-4,
                1. - 1e-12,
                1. + 1e-12);
  }

  std::cout << "b. the per-particle measure" << std::endl;
  for (const bool per_particle : {false, true})
    {
      ModelProblem p;
      p.strain                = geometric(0.1, 0.5);
      p.per_particle_only     = true; // the box's residual is 0
      auto s                  = base_settings();
      s.rigidity_per_particle = per_particle;
      const auto r            = UzawaLoop(s).run(p);
      check_count(per_particle ? "per particle: iterations" : "box: iterations",
                  r.iterations,
                  per_particle ? 8 : 1);
      check_range("particle residual reported / 0.1 0.5^(iterations-1)",
                  r.particle_rigidity_residual /
                    (0.1 * std::pow(0.5, r.iterations - 1)),
                  1. - 1e-12,
                  1. + 1e-12);
    }

  std::cout << "c. no progress" << std::endl;
  for (const double ratio : {0.99, 1.5})
    {
      ModelProblem p;
      p.strain     = geometric(0.1, ratio);
      const auto r = UzawaLoop(base_settings()).run(p);
      check_count(ratio < 1. ? "ratio 0.99: iterations" :
                               "ratio 1.5: iterations",
                  r.iterations,
                  2);
      check_count("updates", p.updates, 1);
      check_flag("stalled", r.stalled, true);
      check_flag("converged", r.converged, false);
    }
  {
    // 0.97 per iteration is progress (more than 2 %).
    ModelProblem p;
    p.strain     = geometric(2e-3, 0.97);
    auto       s = base_settings();
    const auto r = UzawaLoop(s).run(p);
    // 2e-3 0.97^n < 1e-3 first at n = 23.
    check_count("ratio 0.97: iterations", r.iterations, 24);
    check_flag("converged", r.converged, true);
  }

  std::cout << "d. the maximum count, inexact solves" << std::endl;
  {
    ModelProblem p;
    p.strain         = geometric(0.1, 0.9);
    auto s           = inexact_settings();
    s.max_iterations = 5;
    const auto r     = UzawaLoop(s).run(p);
    check_count("iterations", r.iterations, 5);
    check_count("updates (the last keeps its multiplier)", p.updates, 4);
    check_count("solves", p.tolerances.size(), 5);
    check_count("exact solves", p.exact_solves(1e-6), 1);
    check_flag("last solve exact", p.tolerances.back() <= 1e-6, true);
    check_flag("converged", r.converged, false);
    check_flag("stalled", r.stalled, false);
  }

  std::cout << "e. inexact solves, prediction right" << std::endl;
  {
    ModelProblem p;
    p.strain     = geometric(0.1, 0.5);
    const auto s = inexact_settings();
    const auto r = UzawaLoop(s).run(p);
    check_count("iterations", r.iterations, 8);
    check_count("solves", p.tolerances.size(), 8);
    check_count("exact solves", p.exact_solves(1e-6), 1);
    check_flag("last solve exact", p.tolerances.back() <= 1e-6, true);
    check_range("inexact solves' tolerance / 1e-3",
                p.tolerances.front() / 1e-3,
                1. - 1e-12,
                1. + 1e-12);
    check_flag("converged", r.converged, true);
  }

  std::cout << "f. inexact solves, prediction missed" << std::endl;
  {
    // Predicted after the second iteration: 0.02^2 / 0.1 = 4e-3, so the
    // third solve is inexact; it meets the tolerance (5e-4) and is solved
    // again.
    const std::vector<double> m = {0.1, 0.02, 5e-4};
    ModelProblem              p;
    p.strain     = [&](unsigned int n) { return m[std::min(n, 2u)]; };
    const auto s = inexact_settings();
    const auto r = UzawaLoop(s).run(p);
    check_count("iterations", r.iterations, 3);
    check_count("loads", p.loads, 3);
    check_count("solves", p.tolerances.size(), 4);
    check_count("exact solves", p.exact_solves(1e-6), 1);
    check_flag("last solve exact", p.tolerances.back() <= 1e-6, true);
    check_count("linear iterations", r.linear_iterations, 40);
    check_flag("converged", r.converged, true);
  }

  std::cout << "g. rigid velocity tolerance" << std::endl;
  for (const double forced : {0., 4.})
    {
      ModelProblem p;
      p.strain     = [](unsigned int) { return 1.; }; // never rigid
      p.omega_step = geometric(0.1, 0.5);
      auto s       = base_settings();
      s.rigid_velocity_tolerance = 1e-3;
      s.forced_velocity_scale    = forced;
      const auto r               = UzawaLoop(s).run(p);
      // The change a |d omega| / max(g a, U_F) is 0.1 0.5^k without a
      // force (g a = 2 < U_F = 4 halves it): below 1e-3 first at k = 7,
      // and k = 6 with the force.
      const unsigned int k = forced > 0. ? 6 : 7;
      check_count(forced > 0. ? "forced velocity 4: iterations" :
                                "no force: iterations",
                  r.iterations,
                  k + 1);
      check_range("change reported / expected",
                  r.rigid_velocity_change /
                    (0.1 * std::pow(0.5, k) * (forced > 0. ? 0.5 : 1.)),
                  1. - 1e-12,
                  1. + 1e-12);
      check_flag("converged", r.converged, true);
    }
  {
    // Converged at once: no change to report.
    ModelProblem p;
    p.strain     = geometric(1e-4, 0.5);
    const auto r = UzawaLoop(base_settings()).run(p);
    check_count("converged at once: iterations", r.iterations, 1);
    check_flag("change is NaN", std::isnan(r.rigid_velocity_change), true);
  }

  std::cout << "h. a NaN residual" << std::endl;
  {
    ModelProblem p;
    p.strain    = [](unsigned int n) { return n < 2 ? 0.1 / (n + 1) : NAN; };
    bool thrown = false;
    try
      {
        UzawaLoop(base_settings()).run(p);
      }
    catch (const Fidus::RunError &)
      {
        thrown = true;
      }
    check_flag("RunError thrown", thrown, true);
    check_count("solves before it", p.tolerances.size(), 3);
  }

  return exit_code();
}
