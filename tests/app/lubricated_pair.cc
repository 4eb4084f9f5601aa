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
//
// These use the normal squeeze only ('Lubrication tangential terms =
// false'). With the tangential terms (the default) the reference solves, at
// every RK4 stage, the pair's 6 x 6 system zeta (q - q*) = loads(q) for the
// velocities and angular velocities q (q* the undisturbed ones, -1/2 for the
// rotation), with the loads of LubricationCorrection::tangential_loads and
// the squeeze resistance; the program must follow it to 5e-4 a at first
// order in dt, keep the gap positive, and be reversible too (return error
// below 1e-3 a at dt = 0.005, falling at first order in dt).

#include "../fidus_test.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fidus/core/parameters.h>
#include <fidus/lubrication/lubrication_correction.h>
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
        const bool         tangential,
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
        << "\n  set Lubrication tangential terms = "
        << (tangential ? "true" : "false") << "\nend\n"
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
    return csv_column(dir + "/statistics.csv", name);
  }

  /// Velocities of the pair at positions @p x with the tangential terms:
  /// the solution of (zeta + R) q = zeta q* for U_0, w_0, U_1, w_1.
  std::array<std::array<double, 2>, 2>
  lubricated_velocities(const std::array<std::array<double, 2>, 2> &x,
                        const double                                h_c)
  {
    using Fidus::Contact::LubricationBond;
    using Fidus::Contact::LubricationCorrection;
    const double           zeta = 4. * pi, zeta_rot = 4. * pi * a * a;
    std::array<double, 12> q_star{};
    for (unsigned int k = 0; k < 2; ++k)
      {
        q_star[6 * k]     = x[k][1] - 0.5;
        q_star[6 * k + 5] = -0.5;
      }
    const double d = std::hypot(x[1][0] - x[0][0], x[1][1] - x[0][1]);
    const double h = d - 2. * a;
    std::array<std::array<double, 2>, 2> u = {
      {{{q_star[0], 0.}}, {{q_star[6], 0.}}}};
    if (h >= h_c)
      return u;
    LubricationBond b;
    b.i   = 0;
    b.j   = 1;
    b.a_i = b.a_j  = a;
    b.n            = {{(x[1][0] - x[0][0]) / d, (x[1][1] - x[0][1]) / d, 0.}};
    const double R = LubricationCorrection::squeeze_resistance(2, 1., a, a, h);
    const double c =
      LubricationCorrection::tangential_resistance(2, 1., a, a, h, h_c);
    // The system on the 2D unknowns (U_x, U_y, w_z) of both particles.
    const std::array<unsigned int, 6> dof = {{0, 1, 5, 6, 7, 11}};
    double                            A[6][7];
    for (unsigned int m = 0; m < 6; ++m)
      {
        std::array<double, 12> e{};
        e[dof[m]]       = 1.;
        const auto   f  = LubricationCorrection::tangential_loads(b, c, 2, e);
        const double wn = b.n[0] * (e[0] - e[6]) + b.n[1] * (e[1] - e[7]);
        for (unsigned int l = 0; l < 6; ++l)
          {
            double normal = 0.;
            if (dof[l] < 2)
              normal = -R * wn * b.n[dof[l]];
            else if (dof[l] == 6 || dof[l] == 7)
              normal = R * wn * b.n[dof[l] - 6];
            A[l][m] = -f[dof[l]] - normal;
          }
        A[m][m] += (dof[m] % 6 == 5) ? zeta_rot : zeta;
      }
    for (unsigned int l = 0; l < 6; ++l)
      A[l][6] = ((dof[l] % 6 == 5) ? zeta_rot : zeta) * q_star[dof[l]];
    // Gaussian elimination (symmetric positive definite: no pivoting).
    for (unsigned int k = 0; k < 6; ++k)
      for (unsigned int l = k + 1; l < 6; ++l)
        {
          const double f = A[l][k] / A[k][k];
          for (unsigned int m = k; m < 7; ++m)
            A[l][m] -= f * A[k][m];
        }
    double v[6];
    for (int k = 5; k >= 0; --k)
      {
        double sum = A[k][6];
        for (unsigned int m = k + 1; m < 6; ++m)
          sum -= A[k][m] * v[m];
        v[k] = sum / A[k][k];
      }
    u[0] = {{v[0], v[1]}};
    u[1] = {{v[3], v[4]}};
    return u;
  }

  /// Reference relative position at time T (shear rate 1) by RK4, with the
  /// tangential terms.
  std::array<double, 2>
  reference_tangential(const double h_c, const double T)
  {
    using State     = std::array<std::array<double, 2>, 2>;
    const auto step = [&](const State &x, const State &k, const double f) {
      State y = x;
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int d = 0; d < 2; ++d)
          y[i][d] += f * k[i][d];
      return y;
    };
    State        x  = {{{{0.451, 0.51}}, {{0.549, 0.49}}}};
    const int    m  = 100000;
    const double dt = T / m;
    for (int k = 0; k < m; ++k)
      {
        const State k1 = lubricated_velocities(x, h_c);
        const State k2 = lubricated_velocities(step(x, k1, 0.5 * dt), h_c);
        const State k3 = lubricated_velocities(step(x, k2, 0.5 * dt), h_c);
        const State k4 = lubricated_velocities(step(x, k3, dt), h_c);
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int d = 0; d < 2; ++d)
            x[i][d] +=
              dt / 6. * (k1[i][d] + 2. * k2[i][d] + 2. * k3[i][d] + k4[i][d]);
      }
    return {{x[1][0] - x[0][0], x[1][1] - x[0][1]}};
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

  const auto bare = Fidus::run_simulation(Fidus::read_parameters_from_string(
    scene(false, false, "1", T, 0.01, "bare")));
  check_range("without lubrication the pair overlaps: min gap / a",
              bare.min_gap / a,
              -10.,
              -0.1);

  const Fidus::Parameters p =
    Fidus::read_parameters_from_string(scene(true, false, "1", T, 0.01, "x"));
  const double                h_c = p.lubrication.range * p.finest_cell_size();
  const std::array<double, 2> ref = reference(h_c, T);
  double                      err[2];
  int                         k = 0;
  for (const double dt : {0.01, 0.005})
    {
      const std::string dir = "lubricated_" + std::to_string(k);
      const auto s = Fidus::run_simulation(Fidus::read_parameters_from_string(
        scene(true, false, "1", T, dt, dir)));
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
    scene(true, false, "t < 10 ? 1 : -1", T, 0.01, "reversed")));
  const double x0[2][2] = {{0.451, 0.51}, {0.549, 0.49}};
  const auto   back     = [&](const auto &summary) {
    double e = 0.;
    for (unsigned int i = 0; i < 2; ++i)
      e = std::max(e,
                   std::hypot(summary.positions[i][0] - x0[i][0],
                              summary.positions[i][1] - x0[i][1]));
    return e / a;
  };
  check_range("lubricated reversibility: return error / a", back(s), 0., 1e-3);

  // With the tangential terms.
  const std::array<double, 2> ref_t = reference_tangential(h_c, T);
  double                      err_t[2];
  k = 0;
  for (const double dt : {0.01, 0.005})
    {
      const std::string dir = "tangential_" + std::to_string(k);
      const auto        st  = Fidus::run_simulation(
        Fidus::read_parameters_from_string(scene(true, true, "1", T, dt, dir)));
      const std::string tag = " (dt = " + std::to_string(dt).substr(0, 5) + ")";
      check_range("tangential: min gap / a" + tag, st.min_gap / a, 1e-6, 1.);
      err_t[k] =
        std::hypot(st.positions[1][0] - st.positions[0][0] - ref_t[0],
                   st.positions[1][1] - st.positions[0][1] - ref_t[1]) /
        a;
      check_range("tangential: |r - r_ref| / a" + tag, err_t[k], 0., 5e-4);
      ++k;
    }
  check_range("tangential: observed order in dt",
              std::log2(err_t[0] / err_t[1]),
              0.7,
              1.4);
  // Reversal: the return error is the time-stepping error of the explicit
  // positions, first order in dt.
  const double steps[2] = {0.01, 0.005};
  double       back_t[2];
  for (unsigned int r = 0; r < 2; ++r)
    {
      const std::string dir = "reversed_tangential_" + std::to_string(r);
      back_t[r] = back(Fidus::run_simulation(Fidus::read_parameters_from_string(
        scene(true, true, "t < 10 ? 1 : -1", T, steps[r], dir))));
    }
  check_range("tangential reversibility: return error / a (dt = 0.005)",
              back_t[1],
              0.,
              1e-3);
  check_range("tangential reversibility: observed order in dt",
              std::log2(back_t[0] / back_t[1]),
              0.7,
              1.4);
  if (std::getenv("FIDUS_TEST_VERBOSE"))
    std::cout << "errors " << err_t[0] << " " << err_t[1] << " back "
              << back_t[0] << " " << back_t[1] << " ref " << ref_t[0] << " "
              << ref_t[1] << " normal-only ref " << ref[0] << " " << ref[1]
              << std::endl;
  return exit_code();
}
