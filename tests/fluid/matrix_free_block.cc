// The matrix-free velocity block (Fluid/Linear solver/Matrix-free velocity
// block = true with Preconditioner = GMG) solves the same system as the
// assembled one, on 1 and 2 ranks: the velocity block is not assembled, the
// boundary values' load comes from the operator (f - C^T A g), constrained
// rows act as the identity. Particles across a periodic face put hanging
// nodes on it. Both variants do exactly two Uzawa iterations (the same
// system twice). Checks, at linear tolerance 1e-9:
// - 2D pair across x = 0 (sliding walls): particle velocities, matrix-free
//   minus assembled, below 1e-7 (gamma_dot a units);
// - 3D sphere across x = 0 (sliding walls): velocities, rotation and the
//   relative viscosity, matrix-free minus assembled, below 1e-7; and against
//   the ML AMG (another preconditioner, the same system) below 1e-6;
// - a 2D pair in the box with the velocity imposed on every face (linear
//   shear, whose values on the faces x = 0 and x = 1 have a divergence
//   in the cells there), over three time steps on one mesh (Remesh
//   fraction 100) with a shear rate that grows with time: matrix-free,
//   the coupling B is assembled on the first step and kept, and only the
//   boundary values' load through it is new on each step; the velocities
//   of the last step, matrix-free minus assembled, below 1e-7;
// - the 3D geometric multigrid's answer, printed to 6 digits, is the same on
//   1 and 2 ranks (the two .output files are identical): the partition
//   changes the coarse AMG and the order of sums, not the answer.

#include "../fidus_test.h"
#include "summary_tools.h"

#include <algorithm>
#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

Fidus::RunSummary
run(const unsigned int dim,
    const std::string &preconditioner,
    const bool         matrix_free,
    const double       end_time = 0.)
{
  std::ostringstream prm;
  prm
    << "set Dimension = " << dim << "\nset Output directory = run_output\n"
    << "subsection Domain\n"
    << "  set Lower left = " << (dim == 2 ? "0, 0" : "0, 0, 0") << "\n"
    << "  set Upper right = " << (dim == 2 ? "1, 1" : "1, 1, 1") << "\n"
    << (end_time > 0. ? "  set Boundary condition = linear shear\n"
                        "  set Shear rate = 1 + 10 * t\n" :
                        "  set Boundary condition = sliding walls\n")
    << "end\n"
    // Solid retraction 0: the seed's model, in which the bounds below were
    // measured.
    << "subsection Fluid\n  set Solid retraction = 0\n  set Rigidity tolerance = 1e-12\n"
       "  set Rigidity measure = box\n"
    << "  set Maximum Uzawa iterations = 2\n"
    << "  subsection Linear solver\n    set Tolerance = 1e-9\n"
    << "    set Preconditioner = " << preconditioner << "\n"
    << "    set Matrix-free velocity block = "
    << (matrix_free ? "true" : "false") << "\n  end\nend\n"
    << "subsection Particles\n"
    << (end_time > 0. ?
          "  set Radius = 0.05\n  set Positions = 0.4, 0.52; 0.6, 0.48\n" :
        dim == 2 ?
          "  set Radius = 0.05\n  set Positions = 0.951, 0.51; 0.049, 0.49\n" :
          "  set Radius = 0.2\n  set Positions = 0.96, 0.48, 0.51\n")
    << "end\n"
    << "subsection Time stepping\n  set End time = " << end_time
    << "\n  set Time step = 0.02\nend\n"
    << "subsection Mesh refinement\n  set Remesh fraction = 100\n"
    << "  set Initial global refinement = 2\n  set Minimum level = 2\n"
    << "  set Maximum level = " << (dim == 2 ? 5 : 3) << "\nend\n"
    << "subsection Output\n  set Verbosity = quiet\nend\n";
  return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
}

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  check_range("2D pair across x = 0: |dU|/a, |d omega|, matrix-free minus "
              "assembled",
              difference(run(2, "GMG", true), run(2, "GMG", false), 0.05),
              0.,
              1e-7);

  check_range("2D pair, linear shear, three steps on one mesh, shear rate "
              "1 + 10 t: "
              "|dU|/a, |d omega| of the last step, matrix-free minus "
              "assembled",
              difference(run(2, "GMG", true, 0.06),
                         run(2, "GMG", false, 0.06),
                         0.05),
              0.,
              1e-7);

  const auto free      = run(3, "GMG", true);
  const auto assembled = run(3, "GMG", false);
  const auto amg       = run(3, "AMG", true);
  check_range("3D sphere across x = 0: |dU|/a, |d omega|, matrix-free "
              "minus assembled",
              difference(free, assembled, 0.2),
              0.,
              1e-7);
  check_range("3D sphere across x = 0: relative viscosity, matrix-free "
              "minus assembled",
              std::abs(free.stress.relative_viscosity -
                       assembled.stress.relative_viscosity),
              0.,
              1e-7);
  check_range("3D sphere across x = 0: |dU|/a, |d omega|, GMG matrix-free "
              "minus AMG",
              difference(free, amg, 0.2),
              0.,
              1e-6);
  print_value("3D sphere, GMG: U_x / (gamma_dot a)",
              free.velocities[0][0] / 0.2,
              6);
  print_value("3D sphere, GMG: U_y / (gamma_dot a)",
              free.velocities[0][1] / 0.2,
              4);
  print_value("3D sphere, GMG: omega_z / (-gamma_dot / 2)",
              free.omegas[0][2] / -0.5,
              6);
  print_value("3D sphere, GMG: relative viscosity",
              free.stress.relative_viscosity,
              6);
  check_range("3D sphere: omega_z / (-gamma_dot / 2)",
              free.omegas[0][2] / -0.5,
              0.9,
              1.1);
  return exit_code();
}
