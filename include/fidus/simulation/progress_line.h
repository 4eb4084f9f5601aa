#ifndef fidus_simulation_progress_line_h
#define fidus_simulation_progress_line_h

#include <limits>
#include <string>

namespace Fidus
{
  /**
   * One progress line on screen: step, time, Δt, smallest gap, and what
   * the fluid model reports (cells and FGMRES iterations where it has a
   * mesh, Uzawa iterations and the rigidity residual where it has a
   * rigidity multiplier, released cells when there are any), the
   * active/glued contacts, the relative viscosity in a sheared box, and
   * the estimated time to finish.
   */
  struct ProgressLine
  {
    unsigned int       step = 0;
    double             time = 0., dt = 0., gap = 0.;
    unsigned long long cells = 0;
    unsigned int       uzawa = 0, fgmres = 0;
    double             rigidity_residual = 0.;
    /// Cells whose solid was released (two particles closer than a cell).
    unsigned int shared = 0;
    unsigned int active = 0, glued = 0;
    /// Estimated wall seconds to the End time.
    double eta = 0.;
    /// The suspension's relative viscosity at this step (statistics.csv:
    /// relative_viscosity); not shown when NaN (a box without shear).
    double relative_viscosity = std::numeric_limits<double>::quiet_NaN();

    /// The formatted line (no newline).
    std::string
    text() const;

    /// Seconds as "12.3s", "4m05s" or "2h07m".
    static std::string
    format_duration(double seconds);
  };
} // namespace Fidus

#endif
