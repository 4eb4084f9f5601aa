// The statistics row at a shear reversal. A row pairs the fluid solved at
// its time with the contact and lubrication forces of the step that led to
// it; when the shear rate jumps at that time, the row must describe one
// instant (the end of the last forward step), not the new fluid stress
// next to the old contact stress divided by the new rate.
//
// Two runs of the same 2D pair in contact (inelastic, lubrication on,
// released shared cells, the multiplier started from zero each solve) to
// t = 1 in steps of 1/8, exact in binary: A with shear rate 1, B with
// 't < 1 ? 1 : -1'. Their steps are identical; only B's last fluid solve
// sees the reversed rate. Checks:
// - B's last fluid solve is A's with the sign flipped (the reversal took
//   place): the velocities are opposite;
// - B's last row equals A's to rounding in every stress column and in the
//   particles' stresslets (Stokes flow is linear in the shear rate, so the
//   rescaled fluid stress is exactly A's);
// - A's row carries a contact and a lubrication part, so the check has
//   something to compare; the particles' lubrication stresslets in
//   particles.csv agree too.
// With the correction after the solve (the bonds' forces of the step) and
// solved with the flow (the forces of the solve at the row's time, which
// the rate's jump reverses and the row rescales; the pair does not touch
// by t = 1 then, so no contact part).

#include "../fidus_test.h"

#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <string>
#include <tuple>
#include <vector>

using namespace FidusTest;

namespace
{
  Fidus::RunSummary
  run(const std::string &shear,
      const std::string &dir,
      const std::string &coupling)
  {
    std::ostringstream prm;
    prm << "set Dimension = 2\nset Output directory = " << dir << "\n"
        << "subsection Domain\n  set Boundary condition = sliding walls\n"
        << "  set Shear rate = " << shear << "\nend\n"
        << "subsection Fluid\n  set Shared cells = fluid\n"
        << "  set Lubrication correction = true\n"
        << "  set Lubrication coupling = " << coupling << "\n"
        << "  set Reuse multiplier = false\nend\n"
        << "subsection Particles\n  set Radius = 0.05\n"
        << "  set Positions = 0.451, 0.51; 0.549, 0.49\nend\n"
        << "subsection Contact\n  set Model = inelastic\nend\n"
        << "subsection Time stepping\n  set End time = 1\n"
        << "  set Time step = 0.125\nend\n"
        << "subsection Mesh refinement\n  set Maximum level = 6\nend\n"
        << "subsection Output\n  set Verbosity = quiet\nend\n";
    return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
  }

  double
  relative_difference(const double b, const double a, const double scale)
  {
    return std::abs(b - a) / scale;
  }
} // namespace

namespace
{
  /// Runs A and B with the lubrication @p coupling and checks B's last
  /// row against A's; @p with_contact: A's row must hold a contact part.
  void
  check_reversal(const std::string &tag,
                 const std::string &coupling,
                 const bool         with_contact)
  {
    const auto A = run("1", "steady_" + tag, coupling);
    const auto B = run("t < 1 ? 1 : -1", "reversed_" + tag, coupling);

    if (with_contact)
      check_range(tag + ": A: contact part of eta_r at t = 1",
                  A.stress.contact_relative_viscosity,
                  1e-5,
                  10.);
    check_range(tag + ": A: lubrication part of eta_r at t = 1",
                A.stress.lubrication_relative_viscosity,
                1e-4,
                10.);

    double u_scale = 0., u_sum = 0.;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int d = 0; d < 2; ++d)
        {
          u_scale = std::max(u_scale, std::abs(A.velocities[i][d]));
          u_sum =
            std::max(u_sum, std::abs(A.velocities[i][d] + B.velocities[i][d]));
        }
    check_range(
      tag + ": B's last solve is A's reversed: max |U_B + U_A| / max |U_A|",
      u_sum / u_scale,
      0.,
      1e-9);

    // Each stress column of B's last row against A's, relative to eta_r(A)
    // for the parts of eta_r and to A's shear stress for the stresses.
    const double eta   = A.stress.relative_viscosity;
    const double sigma = std::abs(A.stress.shear_stress);
    const std::vector<
      std::tuple<std::string, double Fidus::SuspensionStress::*, double>>
      columns = {{"|eta_r(B) - eta_r(A)| / eta_r(A)",
                  &Fidus::SuspensionStress::relative_viscosity,
                  eta},
                 {"contact part, difference / eta_r(A)",
                  &Fidus::SuspensionStress::contact_relative_viscosity,
                  eta},
                 {"lubrication part, difference / eta_r(A)",
                  &Fidus::SuspensionStress::lubrication_relative_viscosity,
                  eta},
                 {"shear stress, difference / sigma_xy(A)",
                  &Fidus::SuspensionStress::shear_stress,
                  sigma},
                 {"N1, difference / sigma_xy(A)",
                  &Fidus::SuspensionStress::normal_stress_difference_1,
                  sigma},
                 {"N2, difference / sigma_xy(A)",
                  &Fidus::SuspensionStress::normal_stress_difference_2,
                  sigma},
                 {"particle pressure, difference / sigma_xy(A)",
                  &Fidus::SuspensionStress::particle_pressure,
                  sigma},
                 {"wall shear stress, difference / sigma_xy(A)",
                  &Fidus::SuspensionStress::wall_shear_stress,
                  sigma}};
    for (const auto &[label, column, scale] : columns)
      check_range(tag + ": reversal row: " + label,
                  relative_difference(B.stress.*column,
                                      A.stress.*column,
                                      scale),
                  0.,
                  1e-9);
    double s_scale = 0., s_diff = 0.;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int c = 0; c < 6; ++c)
        {
          s_scale = std::max(s_scale, std::abs(A.stresslets[i][c]));
          s_diff =
            std::max(s_diff, std::abs(B.stresslets[i][c] - A.stresslets[i][c]));
        }
    check_range(tag + ": reversal row: stresslets, max difference / max |S(A)|",
                s_diff / s_scale,
                0.,
                1e-9);
    // The particles' lubrication stresslets in the last rows of
    // particles.csv (one per particle), which the row's scale reaches too.
    double l_scale = 0., l_diff = 0.;
    for (const std::string c : {"xx", "xy", "yy", "zz"})
      {
        const std::string name = "lubrication_stresslet_" + c;
        const auto a = csv_column("steady_" + tag + "/particles.csv", name);
        const auto b = csv_column("reversed_" + tag + "/particles.csv", name);
        for (std::size_t k = a.size() - 2; k < a.size(); ++k)
          {
            l_scale = std::max(l_scale, std::abs(a[k]));
            l_diff  = std::max(l_diff, std::abs(b[k] - a[k]));
          }
      }
    check_range(tag + ": reversal row: lubrication stresslets in "
                      "particles.csv, max difference / max |S(A)|",
                l_diff / l_scale,
                0.,
                1e-9);
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  check_reversal("after the solve", "after the solve", true);
  // Solved with the flow, the bonds' forces of the row are those of the
  // solve at the new rate, and must be rescaled like the fluid's (they
  // were not: the lubrication part changed sign in B's row). The pair
  // does not touch by t = 1 here.
  check_reversal("with the flow", "with the flow", false);
  return exit_code();
}
