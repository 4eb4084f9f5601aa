#include "output_columns.h"

#include <deal.II/base/mpi.h>
#include <fidus/core/input_error.h>
#include <fidus/simulation/simulation.h>
#include <fidus/simulation/stop_request.h>
#include <filesystem>
#include <iomanip>

// Checkpoints: when to write one, writing it, and resuming from one.

namespace Fidus
{
  namespace
  {
    /**
     * Run @p work and make a failure there stop every rank: rank 0's
     * message is shared and every rank throws it as a RunError headed by
     * @p what. Work that only rank 0 does (files of the output directory)
     * would otherwise fail on rank 0 alone and leave the other ranks
     * waiting in their next collective call.
     */
    template <typename F>
    void
    failure_stops_every_rank(const MPI_Comm     comm,
                             const std::string &what,
                             F                &&work)
    {
      std::string error;
      try
        {
          work();
        }
      catch (const std::exception &e)
        {
          error = e.what();
        }
      error = Utilities::MPI::broadcast(comm, error, 0);
      if (!error.empty())
        throw RunError(what + ": " + error);
    }
  } // namespace



  template <int dim>
  void
  Simulation<dim>::resume_from_checkpoint()
  {
    state = resume->state;
    warnings.restore(state.warnings);
    projector.restore_glue(state.glue);
    projector.restore_overlap_carried(state.carried_overlap);
    {
      TimerOutput::Scope scope(*timer, "checkpoint");
      fluid->load_checkpoint(resume->folder, state);
    }
    // Rows and collection entries after the checkpoint's step are dropped:
    // those steps are computed again. Rank 0 rewrites the files; a problem
    // there (a damaged CSV file) stops every rank.
    failure_stops_every_rank(comm, "resuming from " + resume->folder, [&]() {
      particles_csv =
        std::make_unique<CsvWriter>(prm.output_directory + "/particles.csv",
                                    OutputColumns::particle_columns(),
                                    root,
                                    state.step);
      statistics_csv =
        std::make_unique<CsvWriter>(prm.output_directory + "/statistics.csv",
                                    OutputColumns::statistics_columns(),
                                    root,
                                    state.step);
      particle_output = std::make_unique<ParticleOutput>(
        prm.output_directory,
        root && prm.output.particle_output_interval > 0);
      particle_output->resume(state.step);
      fluid->open_field_output(prm.output_directory, &state.step);
    });
    pcout << "fidus: resumed from " << resume->folder << " at step "
          << state.step << ", t = " << state.time << ", on "
          << Utilities::MPI::n_mpi_processes(comm)
          << (Utilities::MPI::n_mpi_processes(comm) == 1 ? " rank" : " ranks")
          << std::endl;
  }



  template <int dim>
  bool
  Simulation<dim>::checkpoint_or_stop()
  {
    // One collective decision: the largest signal number any rank received
    // (a batch system signals every rank, a user perhaps one), and the
    // wall-clock interval measured on rank 0.
    int local[2] = {StopRequest::signal_received(), 0};
    if (root && prm.output.checkpoint_wall_interval > 0 &&
        wall_clock.wall_time() - last_checkpoint_wall >=
          prm.output.checkpoint_wall_interval)
      local[1] = 1;
    int global[2] = {0, 0};
    MPI_Allreduce(local, global, 2, MPI_INT, MPI_MAX, comm);

    const bool checkpoints_on = prm.output.checkpoint_interval > 0 ||
                                prm.output.checkpoint_wall_interval > 0;
    const bool due = global[0] != 0 || global[1] != 0 ||
                     (prm.output.checkpoint_interval > 0 &&
                      state.step % prm.output.checkpoint_interval == 0) ||
                     (checkpoints_on && finished());
    if (due)
      {
        write_checkpoint();
        // A signal that came while the checkpoint was written stops the run
        // now: this step is saved, and another step might not fit in the
        // grace period a batch system gives.
        if (global[0] == 0)
          global[0] = Utilities::MPI::max(StopRequest::signal_received(), comm);
      }
    if (global[0] == 0)
      return false;

    stop_signal = global[0];
    if (root)
      std::cerr << "fidus: " << StopRequest::name(stop_signal)
                << " received: stopped after step " << state.step
                << ", t = " << state.time << ", with a checkpoint in "
                << Checkpoint::folder(prm.output_directory, state.step)
                << "; continue with 'fidus --resume' and the same parameter "
                   "file"
                << std::endl;
    return true;
  }



  template <int dim>
  void
  Simulation<dim>::write_checkpoint()
  {
    Timer             clock;
    const std::string temporary =
      Checkpoint::temporary_folder(prm.output_directory, state.step);
    const std::string final_folder =
      Checkpoint::folder(prm.output_directory, state.step);
    // Rank 0 makes the folder; a failure (disk full, permissions) stops
    // every rank, not rank 0 alone.
    const std::string failed = "writing the checkpoint of step " +
                               std::to_string(state.step) + " failed";
    failure_stops_every_rank(comm, failed, [&]() {
      if (root)
        {
          std::filesystem::remove_all(temporary);
          std::filesystem::create_directories(temporary);
        }
    });

    TimerOutput::Scope scope(*timer, "checkpoint");
    RunState           saved = state;
    fluid->save_checkpoint(temporary, saved);
    MPI_Barrier(comm);

    saved.glue                = projector.glue_state().entries();
    saved.carried_overlap     = projector.overlap_carried();
    saved.warnings            = warnings.get_tallies();
    saved.wall_seconds_before = elapsed_wall_seconds();
    unsigned long long bytes  = 0;
    failure_stops_every_rank(comm, failed, [&]() {
      if (root)
        bytes = Checkpoint::commit(temporary,
                                   final_folder,
                                   prm,
                                   saved,
                                   Utilities::MPI::n_mpi_processes(comm));
    });
    bytes                = Utilities::MPI::broadcast(comm, bytes, 0);
    last_checkpoint_wall = wall_clock.wall_time();
    pcout << "checkpoint " << final_folder << ": " << bytes << " bytes, "
          << std::fixed << std::setprecision(3) << clock.wall_time() << " s"
          << std::defaultfloat << std::endl;
  }



  template class Simulation<2>;
  template class Simulation<3>;
} // namespace Fidus
