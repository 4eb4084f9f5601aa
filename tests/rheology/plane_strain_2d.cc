// The axial stress of 2D particles (doc/rheology.md, "Plane strain"). A disc
// is the section of a rigid cylinder, whose axial stress the rigid limit of
// an incompressible body fixes at half its in-plane trace. Every particle
// part (hydrodynamic stresslet, contact, sub-grid lubrication) follows that
// rule, so in simple shear, where the fluid's mean strain has no normal
// part, N2 = -N1 / 2 in every row. Up to the commit that adds this test the
// contact and lubrication stresses had no zz entry, and a lubricated dense
// scene reported N2 = -0.66 where the resolved cut element gives -0.03.
//
// Scene: the fictitious domain at level 5 between sliding walls, a pair
// closing along the compressional axis at gap 0.01 a, a pair opening along
// the extensional one, and a disc 0.01 a from the top wall; two steps.
// - with the lubrication correction (gluey contacts): the lubrication's
//   particle pressure is not zero;
// - without it, the closing pair at gap 1e-4 a reaches contact within the
//   first step (inelastic): the contacts' particle pressure is not zero.
// Checks, for both: |N2 + N1/2| <= 1e-8 (|N1| + |Pi|) in every row, and
// every particle's hydrodynamic, contact and lubrication stresslet in
// particles.csv has zz = (xx + yy) / 2 to 1e-12 of its size.

#include "../fidus_test.h"

#include <algorithm>
#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <sstream>

using namespace FidusTest;

namespace
{
  const double a = 0.06;

  std::string
  scene(const std::string &dir,
        const bool         lubrication,
        const double       closing_gap,
        const std::string &contact)
  {
    // The closing pair along (1, -1) about (0.3, 0.5); the opening pair
    // along (1, 1) about (0.7, 0.5), 0.5 a apart; a disc under the top wall.
    const double       c = (2. * a + closing_gap * a) / (2. * std::sqrt(2.));
    const double       o = (2.5 * a) / (2. * std::sqrt(2.));
    std::ostringstream prm;
    prm << "set Dimension = 2\nset Output directory = " << dir << "\n"
        << "subsection Domain\n  set Boundary condition = sliding walls\n"
        << "  set Shear rate = 1\nend\n"
        << "subsection Fluid\n  set Lubrication correction = "
        << (lubrication ? "true" : "false") << "\nend\n"
        << "subsection Mesh refinement\n  set Initial global refinement = 5\n"
        << "  set Minimum level = 5\n  set Maximum level = 5\nend\n"
        << "subsection Particles\n  set Radius = " << a << "\n"
        << "  set Positions = " << 0.3 - c << ", " << 0.5 + c << "; " << 0.3 + c
        << ", " << 0.5 - c << "; " << 0.7 - o << ", " << 0.5 - o << "; "
        << 0.7 + o << ", " << 0.5 + o << "; 0.5, " << 1. - 1.01 * a << "\nend\n"
        << "subsection Contact\n  set Model = " << contact << "\nend\n"
        << "subsection Time stepping\n  set End time = 0.04\n"
        << "  set Time step = 0.02\nend\n"
        << "subsection Output\n  set Verbosity = quiet\nend\n";
    return prm.str();
  }

  /// Largest |N2 + N1/2| / (|N1| + |Pi|) over the rows of statistics.csv.
  double
  n2_defect(const std::string &dir)
  {
    const std::string s     = dir + "/statistics.csv";
    const auto        n1    = csv_column(s, "normal_stress_difference_1");
    const auto        n2    = csv_column(s, "normal_stress_difference_2");
    const auto        pi    = csv_column(s, "particle_pressure");
    double            worst = n1.empty() ? 1. : 0.;
    for (std::size_t k = 0; k < n1.size(); ++k)
      worst = std::max(worst,
                       std::abs(n2[k] + 0.5 * n1[k]) /
                         (std::abs(n1[k]) + std::abs(pi[k]) + 1e-300));
    return worst;
  }

  /// Largest |zz - (xx + yy)/2| / max |entry| over the rows of particles.csv,
  /// for the stresslet columns that begin with @p prefix.
  double
  zz_defect(const std::string &dir, const std::string &prefix)
  {
    const std::string p     = dir + "/particles.csv";
    const auto        xx    = csv_column(p, prefix + "_xx");
    const auto        xy    = csv_column(p, prefix + "_xy");
    const auto        yy    = csv_column(p, prefix + "_yy");
    const auto        zz    = csv_column(p, prefix + "_zz");
    double            worst = xx.empty() ? 1. : 0.;
    for (std::size_t k = 0; k < xx.size(); ++k)
      {
        const double size =
          std::max({std::abs(xx[k]), std::abs(xy[k]), std::abs(yy[k]), 1e-300});
        worst = std::max(worst, std::abs(zz[k] - 0.5 * (xx[k] + yy[k])) / size);
      }
    return worst;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  Fidus::run_simulation(Fidus::read_parameters_from_string(
    scene("lubricated", true, 0.01, "gluey")));
  Fidus::run_simulation(Fidus::read_parameters_from_string(
    scene("contact", false, 1e-4, "inelastic")));

  const auto lubrication_pressure =
    csv_column("lubricated/statistics.csv", "lubrication_particle_pressure");
  const auto contact_pressure =
    csv_column("contact/statistics.csv", "contact_particle_pressure");
  check_range("lubricated: |lubrication particle pressure| at the last row",
              lubrication_pressure.empty() ?
                0. :
                std::abs(lubrication_pressure.back()),
              1e-4,
              1e9);
  check_range("contact: |contact particle pressure| at the last row",
              contact_pressure.empty() ? 0. : std::abs(contact_pressure.back()),
              1e-4,
              1e9);
  for (const std::string dir : {"lubricated", "contact"})
    {
      check_range(dir + ": max |N2 + N1/2| / (|N1| + |Pi|)",
                  n2_defect(dir),
                  0.,
                  1e-8);
      for (const std::string part :
           {"stresslet", "contact_stresslet", "lubrication_stresslet"})
        check_range(dir + ": " + part + ", max |zz - (xx + yy)/2| / size",
                    zz_defect(dir, part),
                    0.,
                    1e-12);
    }
  return exit_code();
}
