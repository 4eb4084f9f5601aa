// A dense 3D suspension gives the same answer on 1, 2 and 3 ranks (the
// three .output files are identical): 48 spheres of radius 0.1 placed by the
// generator at phi = 0.2 in the unit cube between sliding walls (periodic in
// x and z), maximum level 4 (a/h = 1.6), released shared cells with the
// sub-grid lubrication correction, inelastic contact, two steps of 0.02 and
// a linear tolerance of 1e-9. The partition changes the order of sums, the
// coarse solver and where each sphere's integrals are summed, not the
// answer: the relative viscosity, N1 and the particle pressure after the
// second step to 4 digits, and the spheres' mean displacement to 4 digits.
// Whatever the partition, the walls' shear stress equals the volume
// average of the stress (to the linear tolerance), and every sphere stays
// in the box and apart from the others to the contact tolerance.

#include "../fidus_test.h"

#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <sstream>

using namespace FidusTest;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  const double       a = 0.1;
  std::ostringstream prm;
  prm << "set Dimension = 3\nset Output directory = run_output\n"
      << "subsection Domain\n  set Lower left = 0, 0, 0\n"
      << "  set Upper right = 1, 1, 1\n"
      << "  set Boundary condition = sliding walls\nend\n"
      << "subsection Fluid\n  set Lubrication correction = true\n"
      << "  set Rigidity tolerance = 3e-3\n  set Rigidity measure = box\n"
      << "  set Maximum Uzawa iterations = 30\n"
      << "  subsection Linear solver\n    set Tolerance = 1e-9\n  end\nend\n"
      << "subsection Particles\n  subsection Generator\n"
      << "    set Fraction = 0.2\n    set Radii = " << a << "\n"
      << "    set Minimum separation = 0.01\n    set Seed = 3\n  end\nend\n"
      << "subsection Contact\n  set Model = inelastic\nend\n"
      << "subsection Time stepping\n  set End time = 0.04\n"
      << "  set Time step = 0.02\nend\n"
      << "subsection Mesh refinement\n  set Maximum level = 4\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
  const Fidus::Parameters prm_read =
    Fidus::read_parameters_from_string(prm.str());
  const auto s = Fidus::run_simulation(prm_read);

  const auto &X0           = prm_read.particles.positions;
  double      displacement = 0.;
  for (std::size_t i = 0; i < s.positions.size(); ++i)
    {
      double d2 = 0.;
      for (unsigned int d = 0; d < 3; ++d)
        d2 += std::pow(s.positions[i][d] - X0[i][d], 2);
      displacement += std::sqrt(d2);
    }
  displacement /= double(s.positions.size());

  print_value("spheres", double(s.positions.size()), 4);
  print_value("relative viscosity", s.stress.relative_viscosity, 4);
  print_value("N1 / (eta gamma_dot)", s.stress.normal_stress_difference_1, 4);
  print_value("particle pressure / (eta gamma_dot)",
              s.stress.particle_pressure,
              4);
  print_value("mean displacement / a", displacement / a, 4);
  check_range("|wall - volume shear stress| / shear stress",
              std::abs(s.stress.wall_shear_stress -
                       s.stress.hydrodynamic_shear_stress) /
                s.stress.shear_stress,
              0.,
              1e-6);
  check_range("smallest gap / a over the run", s.min_gap / a, -2e-9, 1.);
  return exit_code();
}
