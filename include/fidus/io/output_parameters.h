#ifndef fidus_io_output_parameters_h
#define fidus_io_output_parameters_h

namespace dealii
{
  class ParameterHandler;
}

namespace Fidus
{
  /// Screen output (Output/Verbosity).
  enum class Verbosity
  {
    quiet,
    normal,
    verbose
  };

  /**
   * What is written and how often: the entries of the subsection Output
   * (the folder is the top-level entry Output directory).
   */
  struct OutputParameters
  {
    /// Register the entries of the subsection Output.
    static void
    declare(dealii::ParameterHandler &prm);

    /// Read them back.
    void
    parse(dealii::ParameterHandler &prm);

    unsigned int field_output_interval    = 0;
    unsigned int particle_output_interval = 0;
    /// Steps between the rows of particles.csv.
    unsigned int particle_csv_interval    = 1;
    unsigned int progress_interval        = 0;
    double       progress_wall_interval   = 5.;
    unsigned int checkpoint_interval      = 0;
    double       checkpoint_wall_interval = 0.;
    Verbosity    verbosity                = Verbosity::normal;
  };
} // namespace Fidus

#endif
