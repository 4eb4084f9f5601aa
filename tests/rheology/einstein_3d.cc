// Einstein's dilute limit in 3D, through the program, (eta_r - 1) / (2.5 phi)
// with phi = 4 pi a^3 / 3, one sphere at (0.513, 0.493, 0.507) in the unit
// cube between sliding walls (periodic in x and z), one time step:
// - at the defaults (nothing set but the walls, the sphere and the maximum
//   level 6), a = 0.1: within 5 % of 1. The default retraction (0.3) is
//   what takes it there: with the seed's c = 0 the same run gives 1.143
//   (doc/validation.md, section 10);
// - a = 0.05 (H/a = 20), level 7 (h/a = 0.156), tight rigidity and linear
//   tolerances: within a few per cent of 1 (measured 1.0103 on 2026-11-25;
//   the walls' confinement at H/a = 20 is about +1 %, and the value moves
//   by up to 1 % between levels, doc/history/rheology.md), and the walls'
//   shear stress equals the volume average.

#include "../fidus_test.h"

#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

namespace
{
  /// One step of one sphere of radius @p a at (0.513, 0.493, 0.507) in the
  /// unit cube between sliding walls; @p fluid and @p mesh are the entries
  /// of the subsections Fluid and Mesh refinement (empty: the defaults).
  Fidus::RunSummary
  run_sphere(const double a, const std::string &fluid, const std::string &mesh)
  {
    std::ostringstream prm;
    prm << "set Dimension = 3\nset Output directory = run_output\n"
        << "subsection Domain\n  set Lower left = 0, 0, 0\n"
        << "  set Upper right = 1, 1, 1\n"
        << "  set Boundary condition = sliding walls\nend\n"
        << "subsection Fluid\n"
        << fluid << "end\n"
        << "subsection Particles\n  set Radius = " << a << "\n"
        << "  set Positions = 0.513, 0.493, 0.507\nend\n"
        << "subsection Time stepping\n  set End time = 0\nend\n"
        << "subsection Mesh refinement\n"
        << mesh << "end\n"
        << "subsection Output\n  set Verbosity = quiet\nend\n";
    return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
  }

  /// (eta_r - 1) / (2.5 phi) of @p s for a sphere of radius @p a.
  double
  einstein_coefficient(const Fidus::RunSummary &s, const double a)
  {
    const double phi = 4. / 3. * dealii::numbers::PI * a * a * a;
    return (s.stress.relative_viscosity - 1.) / (2.5 * phi);
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  const auto defaults = run_sphere(0.1, "", "  set Maximum level = 6\n");
  check_range("3D sphere at the defaults, a = 0.1, level 6: "
              "(eta_r - 1) / (2.5 phi)",
              einstein_coefficient(defaults, 0.1),
              0.95,
              1.05);

  const auto s = run_sphere(0.05,
                            "  set Rigidity tolerance = 1e-4\n"
                            "  set Rigidity measure = box\n"
                            "  subsection Linear solver\n"
                            "    set Tolerance = 1e-9\n  end\n",
                            "  set Initial global refinement = 2\n"
                            "  set Minimum level = 2\n"
                            "  set Maximum level = 7\n");
  check_range("3D sphere, H/a = 20, level 7: (eta_r - 1) / (2.5 phi)",
              einstein_coefficient(s, 0.05),
              0.97,
              1.04);
  check_range("3D sphere: |wall - volume shear stress| / shear stress",
              std::abs(s.stress.wall_shear_stress -
                       s.stress.hydrodynamic_shear_stress) /
                s.stress.shear_stress,
              0.,
              1e-6);
  return exit_code();
}
