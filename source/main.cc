// fidus: rigid particles in creeping shear flow, with contact models that
// keep Stokes reversibility. The program reads one parameter file, picks the
// dimension at run time and runs the scene.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <fidus/core/input_error.h>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

namespace
{
  void
  print_usage(std::ostream &out)
  {
    out
      << "Usage: fidus [options] input.prm   (or input.json)\n"
         "       mpirun -np N fidus input.prm\n\n"
         "Options:\n"
         "  --validate          parse and check the file, print any problem,\n"
         "                      exit non-zero if there is one\n"
         "  --resume            continue from the newest checkpoint in the\n"
         "                      Output directory, up to the file's End time\n"
         "  --print-parameters  print every entry with its default and\n"
         "                      documentation, in .prm form\n"
         "  --help              this text\n";
  }
} // namespace

int
main(int argc, char **argv)
{
  using namespace Fidus;
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool                               root =
    dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;

  bool        validate_only = false;
  bool        resume        = false;
  std::string input;
  for (int i = 1; i < argc; ++i)
    {
      const std::string arg = argv[i];
      if (arg == "--help" || arg == "-h")
        {
          if (root)
            print_usage(std::cout);
          return 0;
        }
      else if (arg == "--print-parameters")
        {
          if (root)
            {
              dealii::ParameterHandler prm;
              Parameters::declare(prm);
              prm.print_parameters(std::cout, dealii::ParameterHandler::PRM);
            }
          return 0;
        }
      else if (arg == "--validate")
        validate_only = true;
      else if (arg == "--resume")
        resume = true;
      else if (!arg.empty() && arg[0] == '-')
        {
          if (root)
            {
              std::cerr << "fidus: error: unknown option '" << arg << "'\n";
              print_usage(std::cerr);
            }
          return 1;
        }
      else if (input.empty())
        input = arg;
      else
        {
          if (root)
            std::cerr << "fidus: error: more than one input file ('" << input
                      << "', '" << arg << "'); allowed: one\n";
          return 1;
        }
    }
  if (input.empty())
    {
      if (root)
        {
          std::cerr << "fidus: error: no parameter file given\n";
          print_usage(std::cerr);
        }
      return 1;
    }

  try
    {
      std::ostringstream used;
      const Parameters   parameters = read_parameters(input, &used);
      if (validate_only)
        {
          if (root)
            std::cout << "fidus: " << input << " is valid ("
                      << parameters.dimension << "D, "
                      << parameters.n_particles()
                      << (parameters.n_particles() == 1 ? " particle)\n" :
                                                          " particles)\n");
          return 0;
        }
      // A resumed run checks its checkpoint before it writes anything.
      std::unique_ptr<Checkpoint::ResumePoint> resume_point;
      if (resume)
        {
          // Rank 0 checks the whole checkpoint (it reads the mesh files in
          // full for their checksums), the others only read state.bin once
          // it passed; every rank then stops or goes on together.
          std::string problem;
          if (root)
            try
              {
                resume_point = std::make_unique<Checkpoint::ResumePoint>(
                  Checkpoint::find_and_check(parameters));
              }
            catch (const InputError &e)
              {
                problem = e.what();
              }
          problem =
            dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, problem, 0);
          if (!problem.empty())
            throw InputError(problem);
          if (!root)
            resume_point = std::make_unique<Checkpoint::ResumePoint>(
              Checkpoint::find_and_check(parameters, false));
        }
      // The fluid model checks the scene against the machine (the number
      // of ranks) before anything is written.
      const RunSummary summary =
        run_simulation(parameters, resume_point.get(), used.str());
      // Stopped by a signal after writing a checkpoint: the shell's
      // convention for a program ended by that signal (128 + number), so
      // that a job script sees that the End time was not reached.
      if (summary.stop_signal != 0)
        return 128 + summary.stop_signal;
    }
  catch (const InputError &e)
    {
      if (root)
        std::cerr << "fidus: error in '" << input << "': " << e.what()
                  << std::endl;
      return 1;
    }
  catch (const RunError &e)
    {
      if (root)
        std::cerr << "fidus: run stopped: " << e.what() << std::endl;
      return 2;
    }
  catch (const std::exception &e)
    {
      std::cerr << "fidus: internal error: " << e.what() << std::endl;
      return 3;
    }
  return 0;
}
