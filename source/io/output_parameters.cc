// The entries of the subsection Output.

#include <deal.II/base/parameter_handler.h>
#include <fidus/io/output_parameters.h>

namespace Fidus
{
  using namespace dealii;

  void
  OutputParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry("Field output interval",
                      "0",
                      Patterns::Integer(0),
                      "Steps between VTU field outputs; 0 = never.");
    prm.declare_entry("Particle output interval",
                      "0",
                      Patterns::Integer(0),
                      "Steps between VTP particle outputs; 0 = never.");
    prm.declare_entry("Particle CSV interval",
                      "1",
                      Patterns::Integer(1),
                      "Steps between the rows of particles.csv (step 0 "
                      "and every multiple of this value), >= 1; long "
                      "runs such as many shear cycles would otherwise "
                      "write every particle every step.");
    prm.declare_entry(
      "Progress interval",
      "0",
      Patterns::Integer(0),
      "Steps between progress lines on screen; 0 (the default) writes one "
      "line every 'Progress wall interval' seconds instead, plus the "
      "first and the last step.");
    prm.declare_entry("Progress wall interval",
                      "5",
                      Patterns::Double(0.),
                      "Seconds of wall clock between progress lines when "
                      "'Progress interval' is 0; 0 writes every step.");
    prm.declare_entry(
      "Checkpoint interval",
      "0",
      Patterns::Integer(0),
      "Steps between checkpoints (Output directory/checkpoint-NNNNNN); "
      "0 = never. Whenever checkpoints are on, the last step of the run "
      "is checkpointed too. Resume with 'fidus --resume input.prm'.");
    prm.declare_entry(
      "Checkpoint wall interval",
      "0",
      Patterns::Double(0.),
      "Seconds of wall clock between checkpoints, so that a stopped run "
      "loses at most that much; 0 = never. Combines with 'Checkpoint "
      "interval' (whichever comes first).");
    prm.declare_entry("Verbosity",
                      "normal",
                      Patterns::Selection("quiet|normal|verbose"),
                      "Screen output: 'quiet' (errors and warnings only), "
                      "'normal' (progress lines and timing table), "
                      "'verbose' (solver details).");
    prm.leave_subsection();
  }



  void
  OutputParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    {
      field_output_interval    = prm.get_integer("Field output interval");
      particle_output_interval = prm.get_integer("Particle output interval");
      particle_csv_interval    = prm.get_integer("Particle CSV interval");
      progress_interval        = prm.get_integer("Progress interval");
      progress_wall_interval   = prm.get_double("Progress wall interval");
      checkpoint_interval      = prm.get_integer("Checkpoint interval");
      checkpoint_wall_interval = prm.get_double("Checkpoint wall interval");
      const std::string v      = prm.get("Verbosity");
      verbosity                = v == "quiet"  ? Verbosity::quiet :
                                 v == "normal" ? Verbosity::normal :
                                                 Verbosity::verbose;
    }
    prm.leave_subsection();
  }
} // namespace Fidus
