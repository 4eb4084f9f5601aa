#ifndef fidus_core_parameters_h
#define fidus_core_parameters_h

#include <array>
#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace Fidus
{
  /// Outer boundary condition of the box (numerics section 1).
  enum class BoundaryCondition
  {
    linear_shear,
    sliding_walls,
    cavity,
    exact_rigid_inclusion
  };

  /// How particle velocities are obtained (numerics section 6).
  enum class FluidModelType
  {
    fictitious_domain,
    undisturbed_shear,
    /// The fluid outside the particles only, rigid motions by Nitsche's
    /// method (CutStokesInclusion): serial, unit box, linear shear.
    cut_finite_element
  };

  /// Contact model (numerics section 3).
  enum class ContactModel
  {
    none,
    inelastic,
    gluey
  };

  /// Screen verbosity.
  /// Time stepping/Scheme: how the positions advance (doc/results.md, "A
  /// time-symmetric scheme").
  enum class TimeSchemeType
  {
    /// Adams-Bashforth 2 on the solved rigid velocities (the seed's).
    ab2,
    /// Trapezoidal rule, by fixed-point passes from the AB2 prediction.
    trapezoidal
  };

  enum class Verbosity
  {
    quiet,
    normal,
    verbose
  };

  /**
   * All run-time parameters of fidus, with the names of interface.md.
   *
   * declare() registers every entry with a documentation string (units,
   * range) and a pattern; parse() reads them back and checks the scene as a
   * whole (particles inside the box, no overlap, ...). Every problem is thrown
   * as an InputError that names the entry, the value and what is allowed.
   * The struct is dimension independent: vectors always have three components
   * and the third is zero in 2D.
   */
  struct Parameters
  {
    /// Register all entries in @p prm.
    static void
    declare(dealii::ParameterHandler &prm);

    /// Read all entries from @p prm and check the scene. @p input_name is the
    /// name of the parameter file, used to resolve a relative positions file.
    void
    parse(dealii::ParameterHandler &prm, const std::string &input_name);

    /// The shortest side of the box.
    double
    smallest_side() const;

    /// Edge of a cell at the Maximum level (the box mesh has square cells
    /// whose coarse size is the shortest side).
    double
    finest_cell_size() const;

    /// Check the scene as a whole (called by parse()).
    void
    check_scene() const;

    /// What 'Fluid/Model = cut finite element' needs of the scene (called
    /// by check_scene()).
    void
    check_cut_finite_element() const;

    /// Number of particles.
    unsigned int
    n_particles() const
    {
      return positions.size();
    }

    unsigned int dimension        = 2;
    std::string  output_directory = "output";

    // Domain
    std::array<double, 3> lower_left         = {{0., 0., 0.}};
    std::array<double, 3> upper_right        = {{1., 1., 1.}};
    BoundaryCondition     boundary_condition = BoundaryCondition::linear_shear;
    std::string           shear_rate         = "1";

    // Fluid
    FluidModelType fluid_model        = FluidModelType::fictitious_domain;
    double         viscosity          = 1.;
    double         penalty_factor     = 1e3;
    unsigned int   velocity_degree    = 2;
    double         rigidity_tolerance = 5e-3;
    /// Fluid/Rigidity measure = particle (false: box).
    bool rigidity_per_particle = true;
    /// Uzawa stop on the change of the rigid velocities (0: off).
    double rigid_velocity_tolerance = 0.;
    /// Solid share of a cell below which the multiplier leaves it out.
    double       sliver_threshold     = 0.;
    unsigned int max_uzawa_iterations = 50;
    /// Fluid/Reuse multiplier, its auto resolved (true with rigid shared
    /// cells).
    bool reuse_multiplier = true;
    /// Fluid/Shared cells = fluid, its auto resolved (fluid with a contact
    /// model or the lubrication correction).
    bool release_shared_cells = false;
    /// The held solid of each particle is a ball of radius
    /// a - solid_retraction * h_finest (Fluid/Solid retraction).
    double solid_retraction = 0.;
    /// Width of the smoothed solid layer in finest cells (Fluid/Solid
    /// smoothing); 0 samples the solid sharply.
    double solid_smoothing = 0.;
    /// Fluid/Cut minimum gap: the cut element's fluid sees every gap at
    /// least this times the smaller radius (wall gaps: the radius).
    double cut_minimum_gap = 1e-4;
    /// Fluid/Cut gap cells: cells across a thin gap of the cut element.
    double cut_gap_cells = 2.;
    /// Fluid/Cut linear solver: automatic, direct or iterative.
    std::string cut_linear_solver = "automatic";
    /// Sub-grid lubrication (Fluid/Lubrication correction) for gaps below
    /// lubrication_range * h_finest (Fluid/Lubrication range).
    bool lubrication = false;
    /// Ranges of particle pairs and of particle-wall gaps; 'auto': 0.65 and
    /// 0.33 in 2D, 0.3 and 0.2 in 3D.
    double lubrication_range      = 2.;
    double lubrication_wall_range = 2.;
    /// The pairs' range in the fluid solve's response to the flow
    /// (Fluid/Lubrication flow range); 'auto': 2 in 2D, 0.45 in 3D.
    double lubrication_flow_range = 2.;
    /// Fluid/Lubrication tangential range of particle pairs and of
    /// particle-wall gaps, in finest cells.
    double lubrication_tangential_range      = 2.;
    double lubrication_wall_tangential_range = 1.;
    /// Also the tangential terms (Fluid/Lubrication tangential terms).
    bool         lubrication_tangential    = true;
    double       linear_tolerance          = 1e-6;
    double       inexact_uzawa_factor      = 0.;
    unsigned int max_cheap_iterations      = 1000;
    unsigned int max_linear_iterations     = 1000;
    double       amg_aggregation_threshold = 0.;
    unsigned int amg_smoother_sweeps       = 4;
    std::string  amg_smoother_type         = "Chebyshev";
    /// Fluid/Linear solver/Method, resolved: a direct factorisation on
    /// meshes of at most this many unknowns, FGMRES above (0: never).
    unsigned long long direct_max_unknowns        = 0;
    bool               geometric_multigrid        = false;
    unsigned int       mg_smoother_degree         = 4;
    std::string        mg_viscosity_averaging     = "none";
    std::string        mg_smoother_blocks         = "cut cells";
    bool               rigid_body_correction      = true;
    bool               matrix_free_velocity_block = true;

    // Particles
    std::vector<std::array<double, 3>> positions;
    std::vector<double>                radii;
    /// External force on each particle (Particles/External force); empty
    /// when every particle is force-free.
    std::vector<std::array<double, 3>> external_forces;
    std::string                        positions_file;

    // Contact
    ContactModel contact_model     = ContactModel::gluey;
    bool         walls             = true;
    double       contact_tolerance = 1e-9;
    std::string  dual_solver       = "projected Gauss-Seidel";
    double       alert_distance    = 0.1;
    /// Drag coefficient zeta that turns a contact correction of velocity
    /// into a force (F = zeta (u - u*)) for the contact stress; 0: the
    /// isolated particle's Stokes drag (see doc/rheology.md).
    double drag_coefficient = 0.;
    /// Contact/Roughness: gaps below roughness * (smaller radius) count as
    /// that gap in the lubrication resistance.
    double roughness = 5e-3;
    /// Contact/Friction coefficient: Coulomb's mu of every contact.
    double friction_coefficient = 0.;
    /// Contact/Rough contact: particles touch at a gap of roughness *
    /// (smaller radius) instead of 0.
    bool rough_contact = false;

    // Time stepping
    double         end_time               = 20.;
    double         time_step              = 0.01;
    bool           adaptive_time_step     = false;
    double         cfl_number             = 0.5;
    double         maximum_time_step      = 0.05;
    TimeSchemeType time_scheme            = TimeSchemeType::ab2;
    unsigned int   trapezoidal_iterations = 1;

    /// Gap step fraction: the largest part of a gap one step may change (0:
    /// the step is not limited by gaps); Gap step floor: gaps below it
    /// times the smaller radius are left to the contact model.
    double gap_step_fraction = 0.;
    double gap_step_floor    = 1e-3;

    // Mesh refinement
    unsigned int initial_global_refinement = 3;
    unsigned int minimum_level             = 3;
    unsigned int maximum_level             = 8;
    double       interface_band            = 1.;
    double       gap_refinement_distance   = 0.5;
    double       remesh_fraction           = 0.5;

    // Output
    unsigned int field_output_interval    = 0;
    unsigned int particle_output_interval = 0;
    /// Steps between the rows of particles.csv (Output/Particle CSV interval).
    unsigned int particle_csv_interval    = 1;
    unsigned int progress_interval        = 0;
    double       progress_wall_interval   = 5.;
    unsigned int checkpoint_interval      = 0;
    double       checkpoint_wall_interval = 0.;
    Verbosity    verbosity                = Verbosity::normal;
  };

  /**
   * Read and check a parameter file (.prm or .json). Every problem, including
   * those the ParameterHandler finds (unknown entry, value not matching its
   * pattern), is thrown as one InputError naming the file and the entry.
   * If @p used_parameters is not null, the complete set of parameters as
   * used (defaults included) is written to it in .prm form.
   */
  Parameters
  read_parameters(const std::string &filename,
                  std::ostream      *used_parameters = nullptr);

  /// Same, from the text of a parameter file (for tests and scripts).
  Parameters
  read_parameters_from_string(const std::string &text);
} // namespace Fidus

#endif
