// The time loop driven through the FluidModel interface by a fake model
// whose rigid velocities are known in closed form: U(X) = -k (X - c) (a
// contraction towards c, with k = shear rate), W = (0, 0, -g/2). The
// particles then follow X(t) = c + (X0 - c) exp(-k t) exactly, so the loop's
// time schemes must converge at order 2 (AB2, and the trapezoidal
// predictor-corrector) towards that answer. The test also checks what the
// loop asks of the model: one solve per step plus the start's with AB2,
// 'Trapezoidal iterations' per step with the trapezoidal scheme, the
// model's cells and iterations in statistics.csv, its angular velocity in
// particles.csv and its stress in the summary.

#include "../fidus_test.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <memory>
#include <sstream>

using namespace FidusTest;

namespace
{
  constexpr double            k      = 1.;
  const std::array<double, 3> centre = {{0.5, 0.45, 0.}};

  /// Counts its calls; its velocities and stress are closed-form.
  class ContractionModel : public Fidus::FluidModel<2>
  {
  public:
    explicit ContractionModel(unsigned int &calls)
      : calls(calls)
    {}

    Statistics
    rigid_velocities(const std::vector<Vec3> &X,
                     const double             g,
                     const SolveLabel        &label,
                     std::vector<Vec3>       &U,
                     std::vector<Vec3>       &W) override
    {
      (void)label;
      ++calls;
      for (unsigned int i = 0; i < X.size(); ++i)
        {
          U[i] = {{-k * g * (X[i][0] - centre[0]),
                   -k * g * (X[i][1] - centre[1]),
                   0.}};
          W[i] = {{0., 0., -0.5 * g}};
        }
      Statistics s;
      s.n_cells           = 1234;
      s.n_dofs            = 5678;
      s.linear_iterations = 7;
      return s;
    }

    Stress
    hydrodynamic_stress(const double g) override
    {
      Stress s;
      s.volume      = 1.;
      s.total[0][1] = 3. * g;
      s.stresslets.assign(2, dealii::SymmetricTensor<2, 3>());
      return s;
    }

    double
    cfl_length() const override
    {
      return 0.01;
    }

    bool
    resolves_gap_flow() const override
    {
      return false;
    }

  private:
    unsigned int &calls;
  };



  struct Outcome
  {
    double       error = 0.;
    unsigned int calls = 0, steps = 0;
    double       shear_stress = 0.;
  };



  Outcome
  run(const std::string &scheme, const double dt, const unsigned int passes)
  {
    std::ostringstream prm;
    prm << "set Dimension = 2\n"
        << "set Output directory = out_" << scheme << "_" << dt << "\n"
        << "subsection Fluid\n  set Model = undisturbed shear\nend\n"
        << "subsection Particles\n  set Radius = 0.05\n"
        << "  set Positions = 0.2, 0.3; 0.8, 0.7\nend\n"
        << "subsection Contact\n  set Model = none\nend\n"
        << "subsection Time stepping\n  set End time = 1\n"
        << "  set Time step = " << dt << "\n  set Scheme = " << scheme
        << "\n  set Trapezoidal iterations = " << passes << "\nend\n"
        << "subsection Output\n  set Verbosity = quiet\nend\n";
    const Fidus::Parameters p = Fidus::read_parameters_from_string(prm.str());
    Outcome                 o;
    Fidus::Simulation<2>    sim(p,
                             nullptr,
                             std::make_unique<ContractionModel>(o.calls));
    const Fidus::RunSummary s = sim.run();
    o.steps                   = s.n_steps;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int d = 0; d < 2; ++d)
        {
          const double exact =
            centre[d] +
            (p.particles.positions[i][d] - centre[d]) * std::exp(-k);
          o.error = std::max(o.error, std::abs(s.positions[i][d] - exact));
        }
    o.shear_stress = s.hydrodynamic_stress[1];
    return o;
  }
} // namespace



int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  for (const std::string scheme : {"AB2", "trapezoidal"})
    {
      const unsigned int passes = 2;
      const Outcome      coarse = run(scheme, 0.05, passes);
      const Outcome      fine   = run(scheme, 0.025, passes);
      const double       rate   = std::log2(coarse.error / fine.error);
      check_range(scheme + ": order of convergence to the exact contraction",
                  rate,
                  1.8,
                  2.3);
      check_range(scheme + ": error at dt = 0.025", fine.error, 0., 1e-3);
      const unsigned int per_step = scheme == "AB2" ? 1 : passes;
      check_range(scheme + ": steps", fine.steps, 40, 40);
      check_range(scheme + ": fluid solves - (steps x solves per step + 1)",
                  double(fine.calls) - (40. * per_step + 1.),
                  0.,
                  0.);
      check_range(scheme + ": the model's stress in the summary (3 g)",
                  fine.shear_stress,
                  3. - 1e-14,
                  3. + 1e-14);
      const std::vector<double> cells =
        csv_column("out_" + scheme + "_0.025/statistics.csv", "cells");
      const std::vector<double> fgmres =
        csv_column("out_" + scheme + "_0.025/statistics.csv",
                   "linear_iterations");
      check_range(scheme + ": statistics.csv rows", cells.size(), 41, 41);
      check_range(scheme + ": the model's cells in every row",
                  *std::min_element(cells.begin(), cells.end()),
                  1234,
                  1234);
      const std::vector<double> omega =
        csv_column("out_" + scheme + "_0.025/particles.csv", "omega_z");
      check_range(scheme + ": the model's angular velocity in particles.csv",
                  omega.back(),
                  -0.5,
                  -0.5);
      // The trapezoidal row sums the iterations of its passes.
      check_range(scheme + ": linear iterations of a step's row",
                  fgmres.back(),
                  7. * per_step,
                  7. * per_step);
    }
  return failures() == 0 ? 0 : 1;
}
