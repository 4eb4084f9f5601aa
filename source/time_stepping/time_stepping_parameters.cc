// The entries of the subsection Time stepping.

#include <deal.II/base/parameter_handler.h>
#include <fidus/core/input_error.h>
#include <fidus/core/parameter_parsing.h>
#include <fidus/time_stepping/time_stepping_parameters.h>

namespace Fidus
{
  using namespace dealii;

  void
  TimeSteppingParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Time stepping");
    prm.declare_entry("End time",
                      "20",
                      Patterns::Double(0.),
                      "Final time [time], >= 0; 0 does one solve.");
    prm.declare_entry("Time step",
                      "0.01",
                      Patterns::Double(0.),
                      "Time step [time], > 0 (the first and, without "
                      "adaptive stepping, every step).");
    prm.declare_entry("Adaptive time step",
                      "false",
                      Patterns::Bool(),
                      "Use dt = min(Maximum time step, CFL number * h_min "
                      "/ max |U|).");
    prm.declare_entry("CFL number",
                      "0.5",
                      Patterns::Double(0.),
                      "C of the adaptive time step, > 0.");
    prm.declare_entry("Maximum time step",
                      "0.05",
                      Patterns::Double(0.),
                      "Upper bound of the adaptive time step [time], > 0.");
    prm.declare_entry(
      "Gap step fraction",
      "0",
      Patterns::Double(0., 1.),
      "0 to 1. Above 0, the step (the fixed Time step, or the adaptive "
      "one) is cut wherever it would change a gap D_ij by more than this "
      "fraction f of itself, with the velocities at the start of the "
      "step: by closing or opening it (dt <= f D_ij / |v_ij|, v_ij the normal "
      "speed of the pair, or of particle and wall), or by the chord "
      "error of a straight step of a pair sliding past each other at "
      "w_ij (dt <= (2 r_ij f D_ij)^(1/2) / w_ij, r_ij the distance of the "
      "centres). The approach to contact and a tumbling pair are then "
      "followed in steps that shrink with the gap, so the flow, not the "
      "step, sets the gaps; afterwards the step grows back, at most "
      "doubling per step (AB2 extrapolates with the ratio of successive "
      "steps). 0 (default): gaps do not limit the step "
      "(doc/results.md, \"A step that follows the gaps\").");
    prm.declare_entry(
      "Gap step floor",
      "1e-3",
      Patterns::Double(0.),
      "Gaps below this fraction of the smaller radius (the particle's own "
      "for a wall) do not limit the step, >= 0: they belong to the contact "
      "model, which holds a glued pair at a zero gap while the fluid still "
      "closes it. Set it near Contact/Roughness with the lubrication "
      "correction, and near Fluid/Cut minimum gap with the cut finite "
      "element.");
    prm.declare_entry(
      "Scheme",
      "AB2",
      Patterns::Selection("AB2|trapezoidal"),
      "How the positions advance. AB2: the seed's Adams-Bashforth 2 "
      "extrapolation of the solved rigid velocities, one fluid solve per "
      "step. trapezoidal: the mean of the velocities at the start of the "
      "step and at the positions it reaches, found from the AB2 "
      "prediction in Trapezoidal iterations passes of one fluid solve "
      "each; the last pass's velocities serve as the next step's start, "
      "so one pass costs what AB2 does. The trapezoidal rule is symmetric "
      "in time, so a reversed shear retraces the path up to the solver "
      "tolerances; AB2 leaves an O(dt^2) return error (doc/results.md, "
      "\"A time-symmetric scheme\").");
    prm.declare_entry("Trapezoidal iterations",
                      "1",
                      Patterns::Integer(1, 20),
                      "Fixed-point passes of the trapezoidal scheme, 1 to "
                      "20, one fluid solve each: 1 is a predictor-"
                      "corrector; each further pass divides the distance "
                      "to the trapezoidal rule, and that of the last solve "
                      "from the step's end positions, by about dt |grad "
                      "U| / 2.");
    prm.leave_subsection();
  }



  void
  TimeSteppingParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Time stepping");
    {
      end_time               = prm.get_double("End time");
      time_step              = prm.get_double("Time step");
      adaptive_time_step     = prm.get_bool("Adaptive time step");
      cfl_number             = prm.get_double("CFL number");
      maximum_time_step      = prm.get_double("Maximum time step");
      gap_step_fraction      = prm.get_double("Gap step fraction");
      gap_step_floor         = prm.get_double("Gap step floor");
      scheme                 = prm.get("Scheme") == "trapezoidal" ?
                                 TimeSchemeType::trapezoidal :
                                 TimeSchemeType::ab2;
      trapezoidal_iterations = prm.get_integer("Trapezoidal iterations");
    }
    prm.leave_subsection();
  }



  void
  TimeSteppingParameters::check() const
  {
    ParameterParsing::require_positive(time_step, "Time stepping/Time step");
    ParameterParsing::require_positive(cfl_number, "Time stepping/CFL number");
    ParameterParsing::require_positive(maximum_time_step,
                                       "Time stepping/Maximum time step");
  }
} // namespace Fidus
