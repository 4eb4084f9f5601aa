#ifndef fidus_time_stepping_time_stepping_parameters_h
#define fidus_time_stepping_time_stepping_parameters_h

namespace dealii
{
  class ParameterHandler;
}

namespace Fidus
{
  /// Time integration of the particle positions (Time stepping/Scheme).
  enum class TimeSchemeType
  {
    ab2,
    trapezoidal
  };

  /**
   * The run's length, the time step and its limits, the scheme: the entries
   * of the subsection Time stepping.
   */
  struct TimeSteppingParameters
  {
    /// Register the entries of the subsection Time stepping.
    static void
    declare(dealii::ParameterHandler &prm);

    /// Read them back.
    void
    parse(dealii::ParameterHandler &prm);

    /// Throw an InputError if a step or the CFL number is not positive.
    void
    check() const;

    double         end_time               = 20.;
    double         time_step              = 0.01;
    bool           adaptive_time_step     = false;
    double         cfl_number             = 0.5;
    double         maximum_time_step      = 0.05;
    TimeSchemeType scheme                 = TimeSchemeType::ab2;
    unsigned int   trapezoidal_iterations = 1;
    /// The largest part of a gap one step may change (0: the step is not
    /// limited by gaps).
    double gap_step_fraction = 0.;
    /// Gaps below this times the smaller radius are left to the contact
    /// model.
    double gap_step_floor = 1e-3;
  };
} // namespace Fidus

#endif
