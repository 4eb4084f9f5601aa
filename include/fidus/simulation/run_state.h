#ifndef fidus_simulation_run_state_h
#define fidus_simulation_run_state_h

#include <array>
#include <fidus/contact/glue_state.h>
#include <fidus/core/warning_log.h>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace Fidus
{
  class ArchiveWriter;
  class ArchiveReader;

  /// Quantities accumulated over a run (for RunSummary and the closing
  /// lines); part of the state so that a resumed run reports the whole run.
  struct RunTotals
  {
    double       min_gap                 = std::numeric_limits<double>::max();
    double       min_normalised_distance = std::numeric_limits<double>::max();
    unsigned int max_uzawa_iterations    = 0;
    unsigned int max_linear_iterations   = 0;
    double       max_rigidity_residual   = 0.;
    unsigned int uzawa_failures          = 0;
    unsigned int contact_failures        = 0;
    unsigned int max_contact_iterations  = 0;
    /// Largest number of shared cells of a solve, and the largest rigidity
    /// residual in them (released, so reported only).
    unsigned int max_shared_cells    = 0;
    double       max_shared_residual = 0.;
  };

  /**
   * Everything a run carries from one time step to the next, and nothing
   * else: with this state, the mesh and the rigidity multiplier, the next
   * step computes exactly what it would have computed in an uninterrupted
   * run. That is what a checkpoint stores (numerics: Adams-Bashforth 2 needs
   * the previous velocities and step; the gluey model needs its glue
   * variables; the remesh rule needs the positions at the last remesh).
   * Vectors have one entry per particle; 3-vectors have z = 0 in 2D.
   */
  struct RunState
  {
    using Vec3 = std::array<double, 3>;

    /// Steps done, and the time reached.
    unsigned int step = 0;
    double       time = 0.;

    /// Positions, and the hydrodynamic rigid velocities at them.
    std::vector<Vec3> X, U, W;

    /// AB2 history: velocities, step length and time of the previous step.
    std::vector<Vec3> U_old, W_old;
    double            dt_old = 0., t_old = 0.;
    bool              have_history = false;

    /// The shear rates U, W and U_old, W_old were solved under. A resumed
    /// run whose Domain/Shear rate differs at those times rescales them
    /// (Stokes flow is linear in the rate), so that the schemes, which
    /// take the rates from the parameter file, see consistent velocities.
    double shear_rate = 0., shear_rate_old = 0.;

    /// Orientation: angle (2D) or unit quaternion (3D).
    std::vector<double>                angle;
    std::vector<std::array<double, 4>> quaternion;

    /// Positions at the last remesh, and whether a mesh exists.
    std::vector<Vec3> X_at_remesh;
    bool              mesh_ready = false;

    /// Whether the fluid solver's multiplier is a valid warm start (it is
    /// saved with the mesh).
    bool multiplier_valid = false;

    /// Glue variables and contact multipliers per remembered pair.
    std::vector<Contact::GlueState::Entry> glue;

    /// The overlap the next contact projection accepts beyond its
    /// tolerance, after one that did not converge
    /// (Contact::ContactProjector::overlap_carried()).
    double carried_overlap = 0.;

    /// Warning counters by kind.
    std::map<std::string, WarningLog::Tally> warnings;

    /// Run-wide extrema and failure counts.
    RunTotals totals;

    /// Wall seconds spent before this process started (earlier parts of a
    /// resumed run), so that statistics.csv keeps a cumulative clock.
    double wall_seconds_before = 0.;

    /// Initial state: @p positions, everything else zero.
    void
    initialise(const std::vector<Vec3> &positions);

    /// Append to / read from a checkpoint archive (same order). Archives
    /// of checkpoint format 2 end before carried_overlap: @p
    /// with_carried_overlap false reads them, with 0 for it.
    void
    save(ArchiveWriter &archive) const;
    void
    load(ArchiveReader &archive, bool with_carried_overlap = true);
  };
} // namespace Fidus

#endif
