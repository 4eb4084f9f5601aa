// The sub-grid lubrication against walls that slide (doc/lubrication.md,
// "The dense stress against the level"). Two discs (a = 0.05) between
// sliding walls, each 0.01 a from a wall, mirror images of each other
// through the box's centre; the undisturbed shear flow (nothing resolved),
// lubrication with its tangential terms, no contact, one step of 0.01.
// The wall moves faster than the flow at the disc's centre, so the
// lubrication of the gap drags the disc towards the wall's speed:
//   f = (u - u_flow(y)) / (u_wall - u_flow(y)) in (0, 1]
// for the velocity u that moved it. Up to the commit that adds this test
// the walls stood still for the correction, and it braked both discs
// instead (f < 0). Checks, at shear rates 1 and -1 (the walls' velocity
// follows the rate):
// - f in (0, 1] for both discs, and the two equal (mirror symmetry);
// - the same f at both rates (Stokes flow is linear in the rate);
// - the lubrication part of the viscosity is positive (dissipative).

#include "../fidus_test.h"

#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

namespace
{
  const double a = 0.05, gap = 0.01 * a, dt = 0.01;

  struct Result
  {
    double f_top = 0., f_bottom = 0., eta_lubrication = 0.;
  };

  Result
  run(const double rate)
  {
    const std::string  out = rate > 0 ? "positive" : "negative";
    const double       y   = 1. - a - gap; // the top disc's centre
    std::ostringstream prm;
    prm << "set Dimension = 2\nset Output directory = " << out << "\n"
        << "subsection Domain\n  set Boundary condition = sliding walls\n"
        << "  set Shear rate = " << rate << "\nend\n"
        << "subsection Fluid\n  set Model = undisturbed shear\n"
        << "  set Lubrication correction = true\n"
        << "  set Lubrication tangential terms = true\nend\n"
        << "subsection Particles\n  set Radius = " << a << "\n"
        << "  set Positions = 0.3, " << y << "; 0.7, " << 1. - y << "\nend\n"
        << "subsection Contact\n  set Model = none\nend\n"
        << "subsection Time stepping\n  set End time = " << dt
        << "\n  set Time step = " << dt << "\nend\n"
        << "subsection Output\n  set Verbosity = quiet\nend\n";
    Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));

    const auto x    = csv_column(out + "/particles.csv", "x");
    const auto step = csv_column(out + "/particles.csv", "step");
    const auto eta =
      csv_column(out + "/statistics.csv", "lubrication_relative_viscosity");
    Result r;
    // Rows: step 0 (top, bottom), step 1 (top, bottom).
    if (x.size() != 4 || step[2] != 1.)
      return r;
    const double u_wall   = 0.5 * rate;
    const double flow_top = rate * (y - 0.5), flow_bottom = -flow_top;
    r.f_top    = ((x[2] - x[0]) / dt - flow_top) / (u_wall - flow_top);
    r.f_bottom = ((x[3] - x[1]) / dt - flow_bottom) / (-u_wall - flow_bottom);
    r.eta_lubrication = eta.back();
    return r;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  const Result forward = run(1.), backward = run(-1.);
  for (const auto &[name, r] :
       {std::make_pair(std::string("rate 1"), forward),
        std::make_pair(std::string("rate -1"), backward)})
    {
      check_range(name + ": top disc, share of the wall's lead it follows",
                  r.f_top,
                  1e-3,
                  1.);
      check_range(name + ": bottom disc, the same minus the top's",
                  r.f_bottom - r.f_top,
                  -1e-9,
                  1e-9);
      check_range(name + ": lubrication part of the relative viscosity",
                  r.eta_lubrication,
                  1e-6,
                  1e9);
    }
  check_range("top disc's share, rate -1 minus rate 1",
              backward.f_top - forward.f_top,
              -1e-9,
              1e-9);
  return exit_code();
}
