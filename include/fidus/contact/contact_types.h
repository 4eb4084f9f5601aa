#ifndef fidus_contact_contact_types_h
#define fidus_contact_contact_types_h

#include <array>
#include <cstdint>
#include <string>
#include <vector>

/**
 * The contact corrector of fidus (numerics section 3). This module depends on
 * the C++ standard library, Eigen and Boost only: it never sees a mesh.
 */
namespace Fidus::Contact
{
  /// A point or vector; in 2D the third component is ignored and kept zero.
  using Vec3 = std::array<double, 3>;

  /// Which admissible set K the predicted velocities are projected on.
  enum class Model
  {
    none,
    inelastic,
    gluey
  };

  /// Algorithm for the dual (multiplier) problem of the projection.
  enum class DualSolver
  {
    projected_gradient,
    accelerated_projected_gradient,
    projected_gauss_seidel,
    /// Projected Gauss-Seidel sweeps alternated with conjugate-gradient
    /// steps on the active rows (fast on jammed packings).
    projected_gauss_seidel_subspace
  };

  /**
   * A plane wall x[axis] = position whose inward normal is side * e_axis
   * (side = +1 for a lower wall, -1 for an upper wall). Its velocity must be
   * tangential (zero normal component), which is what makes it a wall.
   */
  struct Wall
  {
    unsigned int axis     = 1;
    double       position = 0.;
    int          side     = 1;
    Vec3         velocity = {{0., 0., 0.}};
  };

  /// How the pairs within the alert distance are found (both O(N)-ish).
  enum class PairSearchMethod
  {
    /// Uniform grid of cells of size 2 a_max + d_a (default, measured faster).
    cell_list,
    /// Boost.Geometry R-tree (bulk loaded), kept for comparison.
    rtree
  };

  /// Settings of the projection.
  struct Settings
  {
    unsigned int dimension = 2;
    Model        model     = Model::gluey;
    DualSolver   solver    = DualSolver::projected_gauss_seidel_subspace;
    /// Absolute tolerance on constraint violation (length).
    double tolerance = 1e-11;
    /// Maximum dual iterations before reporting non-convergence.
    unsigned int max_iterations = 100000;
    /// Pairs with gap below this (length) enter K; the module never uses less
    /// than a safe multiple of dt * max|u*|.
    double alert_distance = 0.;
    /// Glue variables above -glue_snap are snapped to zero (impulse units).
    double glue_snap = 1e-12;
    /// Initial overlaps (negative gaps) smaller than this are accepted; a
    /// value <= 0 means 10 * tolerance. After a converged projection the true
    /// gap is >= -tolerance, so a larger overlap means the input is broken;
    /// after one that did not converge, twice its residual is accepted
    /// (ContactProjector::tolerated_overlap()).
    double overlap_tolerance = 0.;
    /// The alert distance is at least alert_factor * dt * max|u*| (values
    /// below 2 are raised to 2); see ContactProjector::project().
    double alert_factor = 3.;
    /// Pair search algorithm.
    PairSearchMethod pair_search = PairSearchMethod::cell_list;
    /// Coulomb friction coefficient mu >= 0 of every contact (pairs and
    /// walls). 0 leaves the rotations untouched and the projection the
    /// frictionless one; mu > 0 needs the angular velocities
    /// (ContactProjector::project() with rotations).
    double friction = 0.;
    /// Rough contact: particles touch at a gap of contact_distance times
    /// the smaller radius (a particle and a wall: its radius), 0 for smooth
    /// spheres. Must lie in [0, 1).
    double contact_distance = 0.;
  };

  /// What one projection did.
  struct ProjectionStatistics
  {
    unsigned int n_constraints = 0;
    unsigned int n_active      = 0; ///< constraints with lambda != 0
    unsigned int n_glued       = 0; ///< glued pairs after the step
    /// Contacts that slide (tangential impulse on the rim of the cone).
    unsigned int n_sliding  = 0;
    unsigned int iterations = 0;
    double       residual   = 0.; ///< max constraint violation (length)
    bool         converged  = true;
    /// Friction: the smallest fraction of the exact local updates that the
    /// sweeps took after they stalled (1: never relaxed).
    double relaxation     = 1.;
    double min_gap        = 0.; ///< smallest gap before the step
    double alert_distance = 0.; ///< alert distance actually used
    /// How many times the pair search was redone with a larger alert
    /// distance because corrected velocities outran the first one.
    unsigned int n_search_repeats = 0;
    double       search_seconds   = 0.;
    double       solve_seconds    = 0.;
  };
} // namespace Fidus::Contact

#endif
