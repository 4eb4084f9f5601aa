// The lubrication correction through the whole program, on the paper's 2D
// start (a = 0.05, gap 2e-5) with the 'undisturbed shear' fluid model,
// where nothing is resolved and the pair's relative motion has a reference
// written here from the definition: the relative position r = X_1 - X_0
// moves with the undisturbed relative velocity w* = g r_y e_x, minus the
// part 2R / (zeta + 2R) of its normal component while the gap is below the
// range (R = 3 sqrt(2) pi eta (a/2 / h)^{3/2}, zeta = 4 pi eta), integrated
// by RK4 with a small step.
//
// - With Contact/Model = none and no roughness: the gap stays positive (it
//   goes negative without the correction), the program's final relative
//   position matches the reference, and its error falls at first order in
//   dt (explicit Euler in position).
// - The lubrication part of the relative viscosity is >= 0 at every step
//   (the squeeze only dissipates) and > 0 while the pair is within range.
// - Reversibility: 'Shear rate = t < 10 ? 1 : -1' brings the pair back to
//   its start within 1e-3 a: lubrication is linear in the velocities.

#include "../fidus_test.h"

#include <algorithm>
#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <fstream>
#include <map>
#include <sstream>

using namespace FidusTest;

namespace
{
  const double a = 0.05, pi = 3.14159265358979323846;

  std::string
  scene(const bool         lubrication,
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
        << "subsection Fluid\n  set Model = undisturbed shear\n"
        << "  set Lubrication correction = " << (lubrication ? "true" : "false")
        << "\nend\n"
        << "subsection Mesh refinement\n  set Maximum level = 5\nend\n"
        << "subsection Particles\n  set Radius = " << a << "\n"
        << "  set Positions = 0.451, 0.51; 0.549, 0.49\nend\n"
        << "subsection Contact\n  set Model = none\n  set Roughness = 0\nend\n"
        << "subsection Time stepping\n  set End time = " << end_time
        << "\n  set Time step = " << dt << "\nend\n"
        << "subsection Output\n  set Verbosity = quiet\nend\n";
    return prm.str();
  }

  /// One column of statistics.csv, by name.
  std::vector<double>
  column(const std::string &dir, const std::string &name)
  {
    std::ifstream            in(dir + "/statistics.csv");
    std::string              line, item;
    std::vector<std::string> header;
    std::getline(in, line);
    std::stringstream h(line);
    while (std::getline(h, item, ','))
      header.push_back(item);
    const auto k =
      std::find(header.begin(), header.end(), name) - header.begin();
    std::vector<double> values;
    while (std::getline(in, line))
      {
        std::stringstream s(line);
        for (long c = 0; std::getline(s, item, ','); ++c)
          if (c == k)
            values.push_back(std::stod(item));
      }
    return values;
  }

  /// Reference relative position at time T (shear rate 1) by RK4.
  std::array<double, 2>
  reference(const double h_c, const double T)
  {
    const double zeta = 4. * pi;
    const auto   rhs  = [&](const std::array<double, 2> &r) {
      std::array<double, 2> w = {{r[1], 0.}};
      const double          d = std::hypot(r[0], r[1]);
      const double          h = d - 2. * a;
      if (h < h_c)
        {
          const double R = 3. * std::sqrt(2.) * pi * std::pow(0.5 * a / h, 1.5);
          const double wn  = (w[0] * r[0] + w[1] * r[1]) / d;
          const double cut = 2. * R / (zeta + 2. * R);
          w[0] -= cut * wn * r[0] / d;
          w[1] -= cut * wn * r[1] / d;
        }
      return w;
    };
    std::array<double, 2> r  = {{0.098, -0.02}};
    const int             m  = 200000;
    const double          dt = T / m;
    for (int k = 0; k < m; ++k)
      {
        const auto k1 = rhs(r);
        const auto k2 =
          rhs({{r[0] + 0.5 * dt * k1[0], r[1] + 0.5 * dt * k1[1]}});
        const auto k3 =
          rhs({{r[0] + 0.5 * dt * k2[0], r[1] + 0.5 * dt * k2[1]}});
        const auto k4 = rhs({{r[0] + dt * k3[0], r[1] + dt * k3[1]}});
        for (int d = 0; d < 2; ++d)
          r[d] += dt / 6. * (k1[d] + 2. * k2[d] + 2. * k3[d] + k4[d]);
      }
    return r;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  const double T = 20.;

  const auto bare = Fidus::run_simulation(
    Fidus::read_parameters_from_string(scene(false, "1", T, 0.01, "bare")));
  check_range("without lubrication the pair overlaps: min gap / a",
              bare.min_gap / a,
              -10.,
              -0.1);

  const Fidus::Parameters p =
    Fidus::read_parameters_from_string(scene(true, "1", T, 0.01, "x"));
  const double                h_c = p.lubrication_range * p.finest_cell_size();
  const std::array<double, 2> ref = reference(h_c, T);
  double                      err[2];
  int                         k = 0;
  for (const double dt : {0.01, 0.005})
    {
      const std::string dir = "lubricated_" + std::to_string(k);
      const auto        s   = Fidus::run_simulation(
        Fidus::read_parameters_from_string(scene(true, "1", T, dt, dir)));
      const std::string tag = " (dt = " + std::to_string(dt).substr(0, 5) + ")";
      check_range("lubricated: min gap / a" + tag, s.min_gap / a, 1e-6, 1.);
      err[k] = std::hypot(s.positions[1][0] - s.positions[0][0] - ref[0],
                          s.positions[1][1] - s.positions[0][1] - ref[1]) /
               a;
      check_range("lubricated: |r - r_ref| / a" + tag, err[k], 0., 5e-4);
      const auto eta_l = column(dir, "lubrication_relative_viscosity");
      const auto pairs = column(dir, "lubrication_pairs");
      check_range("lubrication part of the viscosity, smallest" + tag,
                  *std::min_element(eta_l.begin(), eta_l.end()),
                  -1e-12,
                  1e9);
      bool positive_in_range = true;
      for (std::size_t r = 1; r < eta_l.size(); ++r)
        if (pairs[r] > 0 && !(eta_l[r] > 0.))
          positive_in_range = false;
      check_range("lubrication part of the viscosity > 0 while in range" + tag,
                  positive_in_range && pairs[1] > 0 ? 1. : 0.,
                  1.,
                  1.);
      ++k;
    }
  check_range("lubricated: observed order in dt",
              std::log2(err[0] / err[1]),
              0.7,
              1.4);

  const auto   s = Fidus::run_simulation(Fidus::read_parameters_from_string(
    scene(true, "t < 10 ? 1 : -1", T, 0.01, "reversed")));
  const double x0[2][2] = {{0.451, 0.51}, {0.549, 0.49}};
  double       back     = 0.;
  for (unsigned int i = 0; i < 2; ++i)
    back = std::max(back,
                    std::hypot(s.positions[i][0] - x0[i][0],
                               s.positions[i][1] - x0[i][1]));
  check_range("lubricated reversibility: return error / a", back / a, 0., 1e-3);
  return exit_code();
}
