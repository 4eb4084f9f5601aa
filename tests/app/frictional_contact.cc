// Coulomb friction through the whole program (Contact/Friction
// coefficient), on free-draining spheres (Fluid/Model = undisturbed shear)
// where the answer is exact, read back from particles.csv:
//
// 1. A sphere of radius a pushed onto the lower wall by a force F in a
//    linear shear g, viscosity eta. Relative to the wall, it rolls without
//    slip (v = 5/7 g a, omega = -5/7 g) when mu F >= 12/7 pi eta g a^2, and
//    otherwise slides with v = g a - mu F / (6 pi eta a),
//    omega = -g/2 - mu F / (8 pi eta a^2). Both sides of the threshold and
//    mu = 0 (v = g a, omega = -g/2), with the wall moving at -g/2 (the
//    flow's velocity there) in the box [0, 1]^3.
// 2. Two spheres pressed together by opposite forces along their line of
//    centres, inclined in the shear: with mu = 100 the contact rolls
//    without slip; with mu = 0 the particles move exactly as without the
//    entry, and turn with the flow's vorticity.

#include "../fidus_test.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <iomanip>
#include <sstream>

using namespace FidusTest;

namespace
{
  const double eta = 2., g = 1.5, a = 0.1, force = 0.2;

  /// Run the scene; return the output directory.
  std::string
  run(const std::string &name,
      const std::string &positions,
      const std::string &forces,
      const double       mu,
      const bool         set_mu)
  {
    std::ostringstream prm;
    prm << "set Dimension = 3\n"
        << "set Output directory = " << name << "\n"
        << "subsection Domain\n  set Shear rate = " << g << "\n"
        << "  set Lower left = 0, 0, 0\n  set Upper right = 1, 1, 1\nend\n"
        << "subsection Fluid\n  set Model = undisturbed shear\n"
        << "  set Viscosity = " << eta << "\nend\n"
        << "subsection Particles\n  set Radius = " << a << "\n"
        << "  set Positions = " << positions << "\n"
        << "  set External force = " << forces << "\nend\n"
        << "subsection Contact\n  set Model = inelastic\n";
    if (set_mu)
      prm << "  set Friction coefficient = " << std::setprecision(17) << mu
          << "\n";
    prm << "end\n"
        << "subsection Time stepping\n  set End time = 0.03\n"
        << "  set Time step = 0.01\nend\n"
        << "subsection Output\n  set Verbosity = quiet\nend\n";
    Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
    return name;
  }

  /// Column @p column of particle @p id at step @p step (the last step
  /// when negative) in particles.csv.
  double
  last(const std::string &dir,
       const std::string &column,
       const unsigned     id,
       const int          step = -1)
  {
    const std::string         file  = dir + "/particles.csv";
    const std::vector<double> v     = csv_column(file, column);
    const std::vector<double> ids   = csv_column(file, "id");
    const std::vector<double> steps = csv_column(file, "step");
    for (std::size_t r = v.size(); r-- > 0;)
      if (ids[r] == id && (step < 0 || steps[r] == step))
        return v[r];
    return std::nan("");
  }

  void
  sphere_on_wall()
  {
    const double threshold = 12. * M_PI * eta * g * a * a / 7.; // mu F
    const double wall      = -0.5 * g; // the flow at y = 0
    for (const double factor : {1.2, 0.8, 0.})
      {
        const double      mu  = factor * threshold / force;
        const std::string dir = run("friction_wall_" + std::to_string(factor),
                                    "0.5, " + std::to_string(a) + ", 0.5",
                                    "0, -" + std::to_string(force) + ", 0",
                                    mu,
                                    true);
        double            v, omega;
        if (factor >= 1.)
          {
            v     = 5. / 7. * g * a;
            omega = -5. / 7. * g;
          }
        else
          {
            v     = g * a - mu * force / (6. * M_PI * eta * a);
            omega = -0.5 * g - mu * force / (8. * M_PI * eta * a * a);
          }
        std::ostringstream what;
        what << "sphere on a wall, mu F = " << factor << " x threshold: ";
        // One contact: its local Coulomb problem is solved exactly, so
        // only round-off remains.
        const double tol = 1e-12 * g * a;
        check_range(what.str() + "|v - exact|",
                    std::abs(last(dir, "moved_ux", 0) - wall - v),
                    0.,
                    tol);
        check_range(what.str() + "|omega - exact| a",
                    std::abs(last(dir, "moved_omega_z", 0) - omega) * a,
                    0.,
                    tol);
        check_range(what.str() + "|normal velocity|",
                    std::abs(last(dir, "moved_uy", 0)),
                    0.,
                    tol);
        // The contact stresslet -l (f_n e e + sym(e f_t)) with l = a: the
        // friction force f_t (on the sphere, against its slip) gives
        // S_xy = a f_t / 2, the normal force S_yy = -a F.
        const double f_t =
          factor >= 1. ? threshold : mu * force; // |friction force|
        check_range(what.str() + "|contact stresslet xy - a f_t / 2|",
                    std::abs(last(dir, "contact_stresslet_xy", 0) -
                             0.5 * a * f_t),
                    0.,
                    1e-12 * a * force);
        check_range(what.str() + "|contact stresslet yy + a F|",
                    std::abs(last(dir, "contact_stresslet_yy", 0) + a * force),
                    0.,
                    1e-12 * a * force);
        if (factor >= 1.)
          check_range(
            what.str() + "sliding contacts",
            csv_column(dir + "/statistics.csv", "sliding_contacts").back(),
            0.,
            0.);
        else if (factor > 0.)
          check_range(
            what.str() + "sliding contacts",
            csv_column(dir + "/statistics.csv", "sliding_contacts").back(),
            1.,
            1.);
      }
  }

  void
  pressed_pair()
  {
    // Line of centres at -30 degrees to the flow (where the shear
    // compresses the pair), gap 1e-6 a.
    const double       c = std::cos(M_PI / 6.), s = -std::sin(M_PI / 6.);
    const double       r = a * (1. + 0.5e-6);
    std::ostringstream positions, forces;
    positions << std::setprecision(17) << 0.5 - r * c << ", " << 0.5 - r * s
              << ", 0.5; " << 0.5 + r * c << ", " << 0.5 + r * s << ", 0.5";
    forces << std::setprecision(17) << force * c << ", " << force * s << ", 0; "
           << -force * c << ", " << -force * s << ", 0";
    const std::string rough =
      run("friction_pair_rough", positions.str(), forces.str(), 100., true);
    // Relative velocity of the contact points in the last step (3), on the
    // line of centres at its start (step 2), where the projection takes it.
    double x[2][3], u[2][3], w[2][3];
    for (unsigned id = 0; id < 2; ++id)
      for (unsigned d = 0; d < 3; ++d)
        {
          const char *axis[3] = {"x", "y", "z"};
          x[id][d]            = last(rough, axis[d], id, 2);
          u[id][d] = last(rough, std::string("moved_u") + axis[d], id);
          w[id][d] = last(rough, std::string("moved_omega_") + axis[d], id);
        }
    double e[3], length = 0.;
    for (unsigned d = 0; d < 3; ++d)
      {
        e[d] = x[1][d] - x[0][d];
        length += e[d] * e[d];
      }
    length = std::sqrt(length);
    for (double &v : e)
      v /= length;
    // v_b - v_a at the contact: u + omega x (-a e) for b, u + omega x (a e)
    // for a.
    double slip[3];
    for (unsigned d = 0; d < 3; ++d)
      {
        const unsigned p = (d + 1) % 3, q = (d + 2) % 3;
        const double   wa = w[0][p] * e[q] - w[0][q] * e[p];
        const double   wb = w[1][p] * e[q] - w[1][q] * e[p];
        slip[d]           = u[1][d] - a * wb - u[0][d] - a * wa;
      }
    const double normal     = slip[0] * e[0] + slip[1] * e[1] + slip[2] * e[2];
    double       tangential = 0.;
    for (unsigned d = 0; d < 3; ++d)
      tangential += std::pow(slip[d] - normal * e[d], 2);
    // The contact tolerance, 1e-9 a in length per step of 0.01, allows
    // velocities of 1e-7 a per unit time: 7e-8 g a.
    check_range("pressed pair, mu = 100: tangential slip at the contact / "
                "(g a)",
                std::sqrt(tangential) / (g * a),
                0.,
                2e-7);
    // The contact holds the gap: D / dt + v_n = 0 with D the gap at the
    // start of the step (a pair that turns opens a gap of order dt^2 along
    // the chord, which the next step closes).
    const double dt = 0.01, gap = length - 2. * a;
    check_range("pressed pair, mu = 100: D / dt + normal velocity at the "
                "contact, / (g a)",
                std::abs(gap / dt + normal) / (g * a),
                0.,
                2e-7);
    const std::string smooth =
      run("friction_pair_smooth", positions.str(), forces.str(), 0., true);
    const std::string unset =
      run("friction_pair_unset", positions.str(), forces.str(), 0., false);
    double identical = 0.;
    for (unsigned id = 0; id < 2; ++id)
      for (const char *col : {"x", "y", "z", "moved_ux", "moved_uy"})
        identical =
          std::max(identical,
                   std::abs(last(smooth, col, id) - last(unset, col, id)));
    check_range("pressed pair, mu = 0: same as without the entry",
                identical,
                0.,
                0.);
    check_range("pressed pair, mu = 0: omega_z + g/2",
                std::abs(last(smooth, "moved_omega_z", 0) + 0.5 * g),
                0.,
                1e-14);
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  sphere_on_wall();
  pressed_pair();
  return exit_code();
}
