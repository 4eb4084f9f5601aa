#include <cmath>
#include <fidus/simulation/progress_line.h>
#include <iomanip>
#include <sstream>

namespace Fidus
{
  std::string
  ProgressLine::format_duration(const double seconds)
  {
    std::ostringstream s;
    const long         t = std::lround(seconds);
    if (t >= 3600)
      s << t / 3600 << "h" << std::setw(2) << std::setfill('0')
        << (t % 3600) / 60 << "m";
    else if (t >= 60)
      s << t / 60 << "m" << std::setw(2) << std::setfill('0') << t % 60 << "s";
    else
      s << std::fixed << std::setprecision(1) << seconds << "s";
    return s.str();
  }



  std::string
  ProgressLine::text() const
  {
    std::ostringstream s;
    s << "step " << std::setw(6) << step << "  t = " << std::fixed
      << std::setprecision(4) << time << "  dt = " << std::scientific
      << std::setprecision(2) << dt << "  gap = " << gap << std::defaultfloat;
    // What the fluid model did: its mesh, then the Uzawa loop's
    // iterations and residual where it has one.
    if (cells > 0)
      s << "  cells " << cells;
    if (uzawa > 0)
      s << "  Uzawa " << uzawa;
    if (cells > 0)
      s << "  FGMRES " << fgmres;
    if (uzawa > 0)
      s << "  rigidity " << std::scientific << std::setprecision(1)
        << rigidity_residual << std::defaultfloat;
    if (shared > 0)
      s << "  shared " << shared;
    s << "  contacts " << active << "/" << glued;
    // The number a rheology run is for, so that a user sees it settle.
    if (std::isfinite(relative_viscosity))
      s << "  eta_r " << std::fixed << std::setprecision(3)
        << relative_viscosity << std::defaultfloat;
    s << "  ETA " << format_duration(eta);
    return s.str();
  }
} // namespace Fidus
