// The scene of the squeeze tests (app/disc_wall_squeeze,
// app/disc_pair_squeeze): discs pushed by Particles/External force in the
// closed unit square at rest, with the sub-grid lubrication correction at
// its default ranges, tight fluid tolerances and one time step.

#ifndef FIDUS_TESTS_APP_PUSHED_DISCS_H
#define FIDUS_TESTS_APP_PUSHED_DISCS_H

#include <array>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <sstream>
#include <string>
#include <vector>

namespace FidusTest
{
  /// Runs one step of @p dt with discs of radius @p a at @p positions,
  /// pushed by @p forces (per unit length), at maximum level @p level,
  /// with the extra Fluid entries @p fluid_entries ("set Key = value"
  /// lines); the output goes to run_output/.
  inline void
  run_pushed_discs(const double                              a,
                   const double                              dt,
                   const unsigned int                        level,
                   const std::vector<std::array<double, 2>> &positions,
                   const std::vector<std::array<double, 2>> &forces,
                   const std::string                        &fluid_entries = "")
  {
    const auto list = [](const std::vector<std::array<double, 2>> &v) {
      std::ostringstream s;
      s.precision(17);
      for (std::size_t i = 0; i < v.size(); ++i)
        s << (i == 0 ? "" : "; ") << v[i][0] << ", " << v[i][1];
      return s.str();
    };
    std::ostringstream prm;
    prm.precision(17);
    prm
      << "set Dimension = 2\nset Output directory = run_output\n"
      << "subsection Domain\n  set Boundary condition = linear shear\n"
      << "  set Shear rate = 0\nend\n"
      // Solid retraction 0: the lubrication ranges were measured without
      // retraction (doc/theory/fictitious_domain.md).
      << "subsection Fluid\n  set Solid retraction = 0\n  set Rigidity tolerance = 1e-4\n"
         "  set Rigidity measure = box\n"
      << "  set Rigid velocity tolerance = 1e-5\n"
      << "  set Maximum Uzawa iterations = 30\n"
      << "  set Lubrication correction = true\n"
      // The calibrated correction after the solve unless the caller asks
      // for the coupling (auto would solve a pair with the flow).
      << (fluid_entries.find("Lubrication coupling") == std::string::npos ?
            "  set Lubrication coupling = after the solve\n" :
            "")
      << fluid_entries
      << "  subsection Linear solver\n    set Tolerance = 1e-9\n  end\n"
      << "end\n"
      << "subsection Particles\n  set Radius = " << a << "\n"
      << "  set Positions = " << list(positions) << "\n"
      << "  set External force = " << list(forces) << "\nend\n"
      << "subsection Contact\n  set Model = none\n  set Walls = true\nend\n"
      << "subsection Time stepping\n  set End time = " << dt << "\n"
      << "  set Time step = " << dt << "\nend\n"
      << "subsection Mesh refinement\n"
      << "  set Initial global refinement = 3\n  set Minimum level = 3\n"
      << "  set Maximum level = " << level << "\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
    Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
  }
} // namespace FidusTest

#endif
