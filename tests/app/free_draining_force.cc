// Free-draining particles ('Fluid/Model = undisturbed shear') pushed by an
// external force: each moves with the undisturbed shear at its centre plus
// F over its isolated drag, 6 pi eta a for a sphere and 4 pi eta for a
// disc, and turns with the vorticity -g/2. With the force along the flow
// and across it in z (not in y), the velocity stays constant and the
// position after a time T is known exactly:
// x = x0 + T (g (y0 - y_mid) + F_x / drag), z = z0 + T F_z / drag.

#include "../fidus_test.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <sstream>

using namespace FidusTest;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  for (const unsigned int dim : {2u, 3u})
    {
      const double       a = dim == 3 ? 0.1 : 0.05, eta = 2., g = 1.5;
      const double       fx = 0.2, fz = dim == 3 ? -0.05 : 0.;
      const double       x0 = 0.3, y0 = 0.65, z0 = 0.5, T = 1.;
      std::ostringstream prm;
      prm << "set Dimension = " << dim << "\n"
          << "set Output directory = free_draining_" << dim << "d\n"
          << "subsection Domain\n  set Shear rate = " << g << "\n"
          << "  set Lower left = 0, 0" << (dim == 3 ? ", 0" : "")
          << "\n  set Upper right = 2, 1" << (dim == 3 ? ", 1" : "")
          << "\nend\n"
          << "subsection Fluid\n  set Model = undisturbed shear\n"
          << "  set Viscosity = " << eta << "\nend\n"
          << "subsection Particles\n  set Radius = " << a << "\n"
          << "  set Positions = " << x0 << ", " << y0
          << (dim == 3 ? ", " + std::to_string(z0) : std::string()) << "\n"
          << "  set External force = " << fx << ", 0"
          << (dim == 3 ? ", " + std::to_string(fz) : std::string()) << "\nend\n"
          << "subsection Contact\n  set Model = none\nend\n"
          << "subsection Time stepping\n  set End time = " << T
          << "\n  set Time step = 0.1\nend\n"
          << "subsection Output\n  set Verbosity = quiet\nend\n";
      const Fidus::RunSummary s =
        Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
      const double      drag = dim == 3 ? 6. * M_PI * eta * a : 4. * M_PI * eta;
      const double      x    = x0 + T * (g * (y0 - 0.5) + fx / drag);
      const double      z    = z0 + T * fz / drag;
      const std::string w    = std::to_string(dim) + "D: ";
      check_range(w + "|x - exact|",
                  std::abs(s.positions[0][0] - x),
                  0.,
                  1e-12);
      check_range(w + "|y - y0|", std::abs(s.positions[0][1] - y0), 0., 1e-14);
      if (dim == 3)
        check_range(w + "|z - exact|",
                    std::abs(s.positions[0][2] - z),
                    0.,
                    1e-12);
      check_range(w + "omega_z + g/2", s.omegas[0][2] + 0.5 * g, -1e-14, 1e-14);
    }
  return exit_code();
}
