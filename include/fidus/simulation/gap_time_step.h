#ifndef fidus_simulation_gap_time_step_h
#define fidus_simulation_gap_time_step_h

#include <array>
#include <fidus/contact/contact_types.h>
#include <fidus/contact/glue_state.h>
#include <fidus/contact/pair_search.h>
#include <vector>

namespace Fidus
{
  /**
   * The time step that resolves the closing of gaps
   * (Time stepping/Gap step fraction).
   *
   * With the step limited only by the shear (a fixed step, or the CFL
   * limit on the fastest particle), a pair approaching contact crosses its
   * closest approach in one or two steps: the step, not the mesh, then
   * sets the smallest gap, and the contact model acts on a gap that the
   * flow would have kept open. The lubrication of a resolved gap (the cut
   * element) or of the sub-grid correction slows the approach in
   * proportion to the gap, so a step that lets each gap close by at most a
   * fixed fraction f of itself,
   *
   *   dt <= f D_ij / v_ij,   v_ij = -(U_j - U_i) . n_ij > 0,
   *
   * follows the approach with a number of steps that grows only with the
   * logarithm of the smallest gap. Particle-wall gaps are treated the same
   * way (the wall's normal velocity is zero).
   *
   * A pair that rolls or slides past each other at a small gap, at the
   * tangential relative speed w_ij, is moved along straight lines by a
   * step, which opens the distance of the centres r_ij by the chord error
   * (w_ij dt)^2 / (2 r_ij). Limiting that to f D_ij as well,
   *
   *   dt <= (2 r_ij f D_ij)^(1/2) / w_ij,
   *
   * keeps the step from setting the gap of a tumbling pair (a wall's gap
   * does not change when a particle slides along it). So no step changes
   * a gap by more than about f of itself.
   *
   * Gaps the contact model holds are left to it: glued pairs (their gap
   * drifts a little above zero as they turn, while their fluid velocities
   * still close it), and any gap below a floor (a fraction of the smaller
   * radius). Otherwise a pair in contact would stop the run.
   *
   * Periodic directions use the minimum image, like the contact module.
   * Only pairs that could limit the step are visited, through the cell
   * list of Contact::PairSearch, so the cost is O(N).
   */
  class GapTimeStep
  {
  public:
    using Vec3 = std::array<double, 3>;

    /// The step a configuration allows, and the gap that set it.
    struct Limit
    {
      /// The step: the smallest f D / v, or the upper bound if no gap
      /// limits it.
      double dt = 0.;
      /// Whether a gap set the step (else dt is the upper bound).
      bool limited = false;
      /// The limiting gap: particles i and j (j = -1 - w for wall w), its
      /// size D, closing speed v and tangential (sliding) speed w.
      int    i = -1, j = -1;
      double gap = 0., closing_speed = 0., sliding_speed = 0.;
    };

    /**
     * @param fraction f in (0, 1]: the largest part of a gap one step may
     *        close.
     * @param floor gaps below floor * (smaller radius; the particle's own
     *        for a wall) do not limit the step, >= 0.
     * @param dimension 2 or 3 (2D ignores z).
     * @param periods period per direction, 0 where not periodic.
     * Throws std::invalid_argument for a fraction outside (0, 1] or a
     * negative floor.
     */
    GapTimeStep(double                            fraction,
                double                            floor,
                unsigned int                      dimension,
                const std::vector<Contact::Wall> &walls,
                const std::array<double, 3>      &periods);

    /**
     * The step allowed to particles at @p positions with radii @p radii
     * moving with @p velocities, at most @p upper (> 0). Pairs glued in
     * @p glue (gamma < 0), if given, do not limit it.
     */
    Limit
    limit(const std::vector<Vec3>   &positions,
          const std::vector<double> &radii,
          const std::vector<Vec3>   &velocities,
          double                     upper,
          const Contact::GlueState  *glue = nullptr) const;

  private:
    double                     fraction, floor;
    unsigned int               dimension;
    std::vector<Contact::Wall> walls;
    /// The cell list (with the periods) and its pairs, kept between steps
    /// so that the time loop does not reallocate their work arrays.
    mutable Contact::PairSearch                    search;
    mutable std::vector<Contact::PairSearch::Pair> pairs;
  };
} // namespace Fidus

#endif
