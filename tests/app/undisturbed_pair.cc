// validation.md case 4 through the whole program ('undisturbed shear'
// fluid model): the paper's 2D start, a = 0.05, g = 1. Gluey keeps the
// cross-stream offset 0.02 and stays glued 2 |dx_c| / (g |dy|) = 9.8;
// inelastic leaves the pair at offset 2a = 0.1. Then reversibility: shear
// to T = 15 and back to 2T with 'Shear rate = t < 15 ? 1 : -1': gluey
// particles return to their start within 1 % of a, inelastic ones do not.
// The box is wide in x so that the inelastic pair stays inside.

#include "../fidus_test.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <fstream>
#include <sstream>

using namespace FidusTest;

Fidus::RunSummary
run(const std::string &model,
    const std::string &shear,
    const double       end_time,
    const double       dt,
    const std::string &dir)
{
  std::ostringstream prm;
  prm << "set Dimension = 2\n"
      << "set Output directory = " << dir << "\n"
      << "subsection Domain\n  set Shear rate = " << shear << "\n"
      << "  set Lower left = -1, 0\n  set Upper right = 2, 1\nend\n"
      << "subsection Fluid\n  set Model = undisturbed shear\nend\n"
      << "subsection Particles\n  set Radius = 0.05\n"
      << "  set Positions = 0.451, 0.51; 0.549, 0.49\nend\n"
      << "subsection Contact\n  set Model = " << model << "\nend\n"
      << "subsection Time stepping\n  set End time = " << end_time
      << "\n  set Time step = " << dt << "\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
  return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
}

/// Time during which statistics.csv reports a glued contact.
double
glued_time(const std::string &dir)
{
  std::ifstream in(dir + "/statistics.csv");
  std::string   line;
  std::getline(in, line);
  double total = 0;
  while (std::getline(in, line))
    {
      std::vector<double> v;
      std::stringstream   s(line);
      std::string         item;
      while (std::getline(s, item, ','))
        v.push_back(std::stod(item));
      if (v.size() > 10 && v[10] > 0)
        total += v[2];
    }
  return total;
}

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  const double a = 0.05;
  for (const double dt : {0.01, 0.005})
    {
      const std::string tag = " (dt = " + std::to_string(dt).substr(0, 5) + ")";
      const auto        g   = run("gluey", "1", 20, dt, "gluey");
      check_range("gluey final offset / 0.02" + tag,
                  std::abs(g.positions[0][1] - g.positions[1][1]) / 0.02,
                  0.98,
                  1.02);
      check_range("gluey glued time / 9.8" + tag,
                  glued_time("gluey") / 9.8,
                  0.98,
                  1.02);
      const auto in = run("inelastic", "1", 20, dt, "inelastic");
      check_range("inelastic final offset / 2a" + tag,
                  std::abs(in.positions[0][1] - in.positions[1][1]) / (2 * a),
                  0.98,
                  1.02);
    }
  for (const std::string model : {"gluey", "inelastic"})
    {
      const auto   s = run(model, "t < 15 ? 1 : -1", 30, 0.01, model + "_rev");
      const double x0[2][2] = {{0.451, 0.51}, {0.549, 0.49}};
      double       err      = 0;
      for (unsigned int i = 0; i < 2; ++i)
        err = std::max(err,
                       std::hypot(s.positions[i][0] - x0[i][0],
                                  s.positions[i][1] - x0[i][1]));
      if (model == "gluey")
        check_range("gluey reversibility: return error / a", err / a, 0., 0.01);
      else
        check_range("inelastic irreversibility: return error / a",
                    err / a,
                    0.1,
                    100.);
    }
  return exit_code();
}
