#ifndef fidus_fluid_velocity_multigrid_h
#define fidus_fluid_velocity_multigrid_h

#include <deal.II/base/point.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <fidus/fluid/fictitious_domain/cell_block_preconditioner.h>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * Geometric multigrid for the velocity block A = (2 eta e(u), e(v)) of the
   * penalised Stokes system: one V-cycle is one application of the
   * preconditioner.
   *
   * - Levels by global coarsening: the simulation mesh, then the meshes
   *   obtained by coarsening every cell once, down to the coarse box mesh.
   *   Each level is an ordinary active mesh with its own hanging-node,
   *   periodicity and (zero) Dirichlet constraints, so hanging nodes on
   *   periodic faces (sliding walls with adaptive refinement), which
   *   deal.II's local smoothing refuses, need no mesh rule.
   * - Matrix-free level operators (VelocityOperator), Chebyshev smoothing
   *   on the inverse diagonal, a coarse solve by CG with an AMG
   *   preconditioner on the assembled coarse matrix.
   * - The finest level uses the owner's viscosity at its Gauss points, so
   *   its operator is the system's A. Below it, either
   *   - Averaging::galerkin: level l is the Galerkin product P^T A_{l+1} P,
   *     hence of the finest A. The coarse functions are finest-level
   *     functions, so their energy is the finest quadrature sum of eta
   *     e(u):e(v) over the finest cells in each coarse cell; e(u):e(v) lies
   *     in Q(2 degree) on the coarse cell, so the sum is a linear functional
   *     of Q(2 degree), and a table on 2 degree + 1 equidistant points per
   *     direction reproduces it exactly: eta_Q JxW_Q = L(l_Q), with l_Q the
   *     Lagrange basis of FE_DGQ(2 degree). These moments L(l_Q) are
   *     computed on the finest level and restricted level by level with the
   *     FE_DGQ(2 degree) transfer (the transpose of the embedding);
   *   - or the viscosity asked from the owner at the level's own quadrature
   *     points, averaged over each cell by the chosen rule.
   */
  template <int dim>
  class VelocityMultigrid
  {
  public:
    /// How the viscosity is averaged over a cell below the finest level.
    enum class Averaging
    {
      none,
      arithmetic,
      harmonic,
      geometric,
      /// No averaging: each level below the finest is the Galerkin product
      /// P^T A P of the finest operator, exactly (see the class
      /// documentation).
      galerkin
    };

    /// Settings of the V-cycle.
    struct Settings
    {
      unsigned int degree          = 2;
      unsigned int smoother_degree = 4;
      double       smoothing_range = 15.;
      /// The range with smoother blocks (measured, doc/preconditioners.md).
      double       smoothing_range_with_blocks = 8.;
      unsigned int eigenvalue_cg_steps         = 10;
      Averaging    averaging                   = Averaging::galerkin;
      /// Relative tolerance of the coarse CG.
      double coarse_tolerance = 1e-3;
      /// Which cells the smoothers solve exactly as blocks instead of point
      /// Jacobi (CellBlockPreconditioner).
      SmootherBlocks smoother_blocks = SmootherBlocks::cut_cells;
    };

    /// Size and cost of the hierarchy.
    struct Info
    {
      unsigned int            n_levels       = 0;
      types::global_dof_index coarse_dofs    = 0;
      double                  setup_seconds  = 0.; ///< last setup()
      double                  update_seconds = 0.; ///< last update()
      /// Parts of the last update(): the levels' viscosity tables, their
      /// diagonals, the smoothers' cell blocks, the coarse matrix and AMG.
      double viscosity_seconds = 0.;
      double diagonal_seconds  = 0.;
      double blocks_seconds    = 0.;
      double coarse_seconds    = 0.;
      /// Blocks of the smoothers, summed over levels (this rank).
      unsigned int smoother_blocks = 0;
    };

    /**
     * The viscosity at @p points of @p cell, written to @p eta. @p cell
     * belongs to the simulation mesh when @p active_mesh is set, else to a
     * coarser level mesh (a different triangulation).
     */
    using ViscosityFunction =
      std::function<void(const typename Triangulation<dim>::cell_iterator &cell,
                         bool                           active_mesh,
                         const std::vector<Point<dim>> &points,
                         std::vector<double>           &eta)>;

    /// Parse "none|arithmetic|harmonic|geometric|galerkin".
    static Averaging
    parse_averaging(const std::string &name);

    VelocityMultigrid(const parallel::distributed::Triangulation<dim> &tria,
                      const Settings &settings);
    ~VelocityMultigrid();

    /**
     * Build the level meshes, DoFs, constraints, operators and transfers
     * after the simulation mesh changed. @p system: the Stokes DoF handler
     * (velocity components first, numbered as DoFRenumbering::hierarchical
     * then by velocity/pressure block); its velocity block is mapped onto
     * the finest level.
     */
    void
    setup(const DoFHandler<dim>              &system,
          const std::vector<unsigned int>    &periodic_directions,
          const std::set<types::boundary_id> &dirichlet_ids);

    /**
     * New viscosity (the particles moved): level coefficients, diagonals,
     * Chebyshev bounds, coarse matrix and its AMG. @p system_constraints:
     * the constraints of the system; their rows (zero in every right-hand
     * side) hold only a diagonal, which the V-cycle inverts exactly: the
     * diagonal of the assembled @p velocity_block, or 1 where A is not
     * assembled (nullptr), as in apply_velocity_block().
     */
    void
    update(const ViscosityFunction              &viscosity,
           const TrilinosWrappers::SparseMatrix *velocity_block,
           const AffineConstraints<double>      &system_constraints);

    /**
     * Check of the hierarchy (after update()): for a random vector v on
     * each level below the finest, with w = P v on the level above, the
     * largest |v^T A_l v - w^T A_{l+1} w| / w^T A_{l+1} w. Round-off with
     * Averaging::galerkin.
     */
    double
    galerkin_defect() const;

    /// dst = one V-cycle applied to src (velocity block vectors).
    void
    vmult(TrilinosWrappers::MPI::Vector       &dst,
          const TrilinosWrappers::MPI::Vector &src) const;

    /**
     * dst = A src with the finest level's matrix-free operator, on the
     * system's velocity vectors (after update()): the same product as the
     * assembled velocity block, but for the constrained rows, which act as
     * the diagonal given to update().
     */
    void
    apply_velocity_block(TrilinosWrappers::MPI::Vector       &dst,
                         const TrilinosWrappers::MPI::Vector &src) const;

    /**
     * rhs -= C^T A g: the load of the constrained values @p g (the system's
     * velocity vector with the inhomogeneities of its constraints, zero
     * elsewhere) on the free rows, which the assembly leaves out when A is
     * not assembled. C resolves hanging-node and periodic constraints;
     * Dirichlet rows get nothing. After update().
     */
    void
    subtract_constraint_load(TrilinosWrappers::MPI::Vector       &rhs,
                             const TrilinosWrappers::MPI::Vector &g) const;

    /// Levels, coarse size and set-up times.
    const Info &
    get_info() const;

    class Implementation;

  private:
    const parallel::distributed::Triangulation<dim> &triangulation;
    const Settings                                   settings;
    std::unique_ptr<Implementation>                  implementation;
  };
} // namespace Fidus

#endif
