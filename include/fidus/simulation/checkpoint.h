#ifndef fidus_simulation_checkpoint_h
#define fidus_simulation_checkpoint_h

#include <fidus/core/parameters.h>
#include <fidus/simulation/run_state.h>
#include <string>

namespace Fidus
{
  /**
   * The files of a checkpoint, and the checks that make 'fidus --resume'
   * safe.
   *
   * A checkpoint is the folder <Output directory>/checkpoint-NNNNNN (NNNNNN:
   * the step) holding
   *   - mesh, mesh.info, mesh_fixed.data: the p4est forest and the rigidity
   *     multiplier attached to it (deal.II's Triangulation::save), only for
   *     the fictitious-domain fluid;
   *   - state.bin: a header (what the run must agree on to continue: the
   *     dimension, the particles, the box, the boundary condition, the fluid
   *     model, the velocity degree), the sizes and checksums of the mesh
   *     files, and the RunState, closed by a length and a checksum.
   *
   * It is written under checkpoint-NNNNNN.tmp and renamed when complete;
   * older checkpoints are removed only after that, so an interrupted
   * write leaves the previous checkpoint intact. Resume takes the newest
   * complete folder and checks all of it before anything is written.
   */
  class Checkpoint
  {
  public:
    /// Folder of the checkpoint at @p step (complete), and while written.
    static std::string
    folder(const std::string &output_directory, unsigned int step);
    static std::string
    temporary_folder(const std::string &output_directory, unsigned int step);

    /**
     * Write state.bin into @p temporary (after the mesh files, if any, are
     * in it), rename the folder to its final name, and remove older
     * checkpoints and stale temporary folders of the same output directory.
     * Called on one rank. Returns the bytes of the whole checkpoint.
     */
    static unsigned long long
    commit(const std::string &temporary,
           const std::string &final_folder,
           const Parameters  &prm,
           const RunState    &state,
           const unsigned int n_ranks);

    /// What resume starts from.
    struct ResumePoint
    {
      std::string folder; ///< the checkpoint folder
      RunState    state;
    };

    /**
     * Find the newest checkpoint of @p prm's output directory and check it
     * against @p prm: present, complete (lengths and checksums), from the
     * same dimension, particles, box, boundary condition, fluid model and
     * velocity degree, and the CSV files of the run there; its velocities
     * rescaled to @p prm's shear rates (rescale_to_shear_rate). Every problem
     * is an InputError that names the entry or file, the value found and
     * what is allowed. Reads only. With @p verify_files false only
     * state.bin is read (not the mesh and CSV files): for the ranks other
     * than the one that checked everything.
     */
    static ResumePoint
    find_and_check(const Parameters &prm, bool verify_files = true);

    /**
     * Rescale @p state's velocities (solved at its shear_rate and
     * shear_rate_old) to @p prm's shear rate at their times, so that a
     * file that changes the rate at the checkpoint's time (a reversal
     * from a sheared state) continues as a run that never stopped. An
     * InputError, naming Domain/Shear rate, where they cannot be rescaled:
     * solved at rate 0, or with external forces.
     */
    static void
    rescale_to_shear_rate(const Parameters &prm, RunState &state);

    /// File name of the mesh inside a checkpoint folder (for
    /// Triangulation::save and load).
    static std::string
    mesh_file(const std::string &folder)
    {
      return folder + "/mesh";
    }
  };
} // namespace Fidus

#endif
