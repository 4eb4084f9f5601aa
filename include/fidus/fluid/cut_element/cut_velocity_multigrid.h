#ifndef fidus_fluid_cut_velocity_multigrid_h
#define fidus_fluid_cut_velocity_multigrid_h

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>
#include <fidus/fluid/cut_element/cut_cell_block_jacobi.h>
#include <fidus/fluid/cut_element/distributed_rows.h>
#include <memory>
#include <utility>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * Geometric multigrid for the velocity block A_uu of the cut finite
   * element (CutSaddlePointSolver), for the 3D meshes whose gaps are
   * refined far below the band, where one ML AMG cycle on the Q2 block
   * loses its strength (doc/cut_element.md, "A geometric multigrid for
   * the cut element").
   *
   * - **Levels by global coarsening.** The solve's mesh, then the meshes
   *   obtained by coarsening every cell once, down to the box's single
   *   cell (MGTransferGlobalCoarseningTools). Every level below the finest
   *   carries plain Q2 velocities on all its cells, with its own
   *   hanging-node, periodicity and zero Dirichlet constraints.
   * - **Prolongation** P_l from level l + 1 to level l interpolates the
   *   coarse field on the fine cells (the Q2 embedding of each child),
   *   with the coarse constraints resolved in its columns and the fine
   *   constrained rows left empty. Into the finest level it only reaches
   *   the fluid velocities of the system (cut and fluid cells), divided by
   *   the system's diagonal scaling.
   * - **Galerkin coarse operators** A_{l+1} = P_l^T A_l P_l. No cut cell,
   *   Nitsche term or ghost penalty is integrated on a coarse mesh: each
   *   coarse level is exactly the fine operator on its coarse functions,
   *   whatever the particles do inside a coarse cell. Coarse unknowns that
   *   reach no fluid (inside a particle, or constrained) have empty rows
   *   and get a unit diagonal.
   * - **Smoothing** by Chebyshev polynomials on the operator
   *   preconditioned by CutCellBlockJacobi: point Jacobi plus exact solves
   *   on the unknowns of each cell that a particle surface crosses (the
   *   Nitsche terms and ghost penalties couple those strongly), before and
   *   after the coarse correction (so one cycle is symmetric and serves
   *   CG); the coarsest level is factorised.
   * - **The cycle** (Settings::coarse_visits): a V from the finest level
   *   to level 1, a W below it (each level below 1 corrected twice per
   *   visit of the one above, where it has at most half that one's rows,
   *   so that a chain of slowly shrinking levels under a deeply refined
   *   gap costs no more than in a V). Where the gaps are refined through many
   *   levels with most cells cut (the dense 3D scenes), a V-cycle's
   *   coarse correction is the weak part: on the 37 spheres of the
   *   shipped 3D scene the W below level 1 takes 64 FGMRES iterations
   *   instead of 90, in a fifth less FGMRES time (a W from the finest
   *   level took 58, but cost more than it saved); on one sphere and the
   *   paper's pair it takes 0 to 5 iterations fewer, at a few per cent
   *   of time either way (doc/theory/cut_element.md, "Solvers").
   * - **Separate components** (Settings::separate_components): the
   *   levels are built from the velocity block without its couplings
   *   between different components, A_cc for each component c plus the
   *   rigid rows and columns whole. With the symmetric gradient,
   *   v^T A v = |grad v|^2 + |div v|^2 and v^T A_sep v = |grad v|^2 +
   *   sum_c |d_c v_c|^2 for a velocity held on the boundary, both between
   *   |grad v|^2 and 2 |grad v|^2: the cycle approximates A^-1 within a
   *   factor 2, with a third of the entries in 3D (half in 2D) on every
   *   level. The system FGMRES solves is unchanged.
   * - **Single precision** (Settings::single_precision, the default):
   *   the levels above the coarsest, the prolongations and the smoothing
   *   run in float, since the cycle's products are bound by the memory
   *   traffic of the entries; vmult() takes and returns double vectors.
   * - **Over MPI ranks.** Every level is a DistributedRows, split among the
   *   ranks in contiguous ranges of rows: the finest as the velocity block
   *   handed in, the coarser ones evenly; the Galerkin products are
   *   distributed_galerkin_product(), a cut-cell block is kept by the
   *   rank of its smallest row (with the other ranks' rows it holds), and
   *   the coarsest level is gathered and factorised on every rank. The level
   * meshes are built whole on every rank (the cut element's mesh is). On one
   * rank (initialize() with a SparseMatrix) the same code runs on MPI_COMM_SELF
   * with nothing to communicate.
   */
  template <int dim>
  class CutVelocityMultigrid
  {
  public:
    /// The cycle and its smoothing.
    struct Settings
    {
      /// Matrix-vector products per smoothing, before and after.
      unsigned int smoother_degree = 2;
      /// Ratio of the largest eigenvalue to the smallest one smoothed (15
      /// suits point Jacobi; with the blocks, 8 took a few iterations
      /// fewer; 30 took a tenth fewer on the dense 3D scene, but 60 % more
      /// on the 2D model problems of fluid/cut_multigrid).
      double smoothing_range = 8.;
      /// Cut-cell blocks in the smoother's preconditioner
      /// (CutCellBlockJacobi) on every level above the coarsest; without,
      /// point Jacobi.
      bool cut_cell_blocks = true;
      /// The cycle in single precision above the coarsest level (a
      /// quarter less FGMRES time in 3D, the same iterations); false:
      /// double, as before (for comparisons).
      bool single_precision = true;
      /// The hierarchy built on the velocity block with the couplings
      /// between different velocity components dropped (the rigid rows
      /// kept whole): a third of the entries in 3D on every level, which
      /// the full block bounds within a factor 2 where the velocity is
      /// held on the boundary (Korn). false: the full block, as before.
      bool separate_components = false;
      /// Cycles on each level below level 1 per visit of the level above
      /// (where it has at most half that one's rows): 1 a V-cycle, 2 a
      /// W-cycle below level 1 (visits_of_next()).
      unsigned int coarse_visits = 2;
    };

    /**
     * The particle surfaces (centres and radii, periodic images included):
     * a cell within half its diagonal of one is a cut-cell block of the
     * smoother. Call before initialize(); without, there are no blocks.
     */
    void
    set_surfaces(const std::vector<std::pair<Point<dim>, double>> &surfaces)
    {
      this->surfaces = surfaces;
    }

    /**
     * Keep the system's DoF handler (hp: Taylor-Hood on fluid and cut
     * cells, nothing inside the particles, velocity components first),
     * its constraints and its diagonal scaling (the solved unknowns are
     * x_i / scale[i]); all must outlive the object. @p periodic_axes: the
     * box axes identified by periodicity.
     */
    CutVelocityMultigrid(const DoFHandler<dim>           &system,
                         const AffineConstraints<double> &constraints,
                         const Vector<double>            &scale,
                         const std::vector<unsigned int> &periodic_axes,
                         const Settings                  &settings);

    /**
     * Build the hierarchy for the (scaled) block @p matrix, whose row k <
     * n_u = velocity_unknowns.size() is the system velocity
     * @p velocity_unknowns[k], and whose @p n_rigid last rows are the
     * particles' rigid unknowns: those are carried unchanged through every
     * level, so each coarse level holds them exactly. @p matrix is not
     * read afterwards (the finest level is copied without its couplings
     * between components, in float or double).
     */
    void
    initialize(const SparseMatrix<double>      &matrix,
               const std::vector<unsigned int> &velocity_unknowns,
               const unsigned int               n_rigid = 0);

    /**
     * The same for a block split among the ranks (this rank's rows of it;
     * @p velocity_unknowns lists every row's system DoF, as the DoF
     * handler is whole on every rank). Collective on its communicator.
     */
    void
    initialize(const DistributedRows<double>   &matrix,
               const std::vector<unsigned int> &velocity_unknowns,
               const unsigned int               n_rigid = 0);

    /// dst = one cycle applied to src (zero initial guess), after the
    /// first initialize().
    void
    vmult(Vector<double> &dst, const Vector<double> &src) const;

    /// The same on this rank's rows, after the second initialize().
    void
    vmult(LinearAlgebra::distributed::Vector<double>       &dst,
          const LinearAlgebra::distributed::Vector<double> &src) const;

  private:
    template <typename Number>
    using LevelVector   = LinearAlgebra::distributed::Vector<Number>;
    using Smoother      = PreconditionChebyshev<DistributedRows<double>,
                                           LevelVector<double>,
                                           CutCellBlockJacobi>;
    using FloatSmoother = PreconditionChebyshev<DistributedRows<float>,
                                                LevelVector<float>,
                                                CutCellBlockJacobi>;

    /// initialize() for the finest level's rows @p finest
    /// (SparseMatrixRows or DistributedRows<double>).
    template <typename Rows>
    void
    build(const Rows                      &finest,
          const std::vector<unsigned int> &velocity_unknowns,
          const unsigned int               n_rigid);

    /// The level meshes below the finest (by global coarsening), their
    /// DoFs and constraints; the meshes are held first so that they
    /// outlive their DoF handlers.
    struct Levels
    {
      std::vector<std::shared_ptr<const Triangulation<dim>>> meshes;
      std::vector<std::unique_ptr<DoFHandler<dim>>>          dofs;
      std::vector<AffineConstraints<double>>                 constraints;
    };

    /// The levels below the finest, and #owned: @p finest_rows on the
    /// finest, even ranges of the DoFs and the @p n_rigid rigid unknowns
    /// on the others.
    Levels
    make_levels(const unsigned int n_rigid, const IndexSet &finest_rows);

    /// Each of the @p n_rows finest rows' velocity component (255: none),
    /// by global row.
    std::vector<unsigned char>
    finest_components(const std::vector<unsigned int> &velocity_unknowns,
                      const unsigned int               n_rows) const;

    /// This rank's rows of P_l, from level l + 1 to level @p l.
    std::unique_ptr<DistributedRows<double>>
    make_prolongation(const unsigned int               l,
                      const Levels                    &levels,
                      const std::vector<int>          &local,
                      const std::vector<unsigned int> &velocity_unknowns,
                      const unsigned int               n_rigid) const;

    /// Whether a surface passes within half a diagonal of @p cell's centre.
    template <typename Cell>
    bool
    near_surface(const Cell &cell) const;

    /// The blocks of a level's smoother: the unknowns of each of its cells
    /// near a surface, as the level's global rows, every rank's (@p local
    /// maps a system DoF to its row on the finest level).
    std::vector<std::vector<unsigned int>>
    cut_cell_blocks(const DoFHandler<dim>           &level_dofs,
                    const AffineConstraints<double> &level_constraints,
                    const bool                       finest,
                    const std::vector<int>          &local) const;

    /// The smoothers and the level vectors, once the levels are built.
    void
    setup_cycle();

    /// x = one cycle from level @p level down for the right-hand side @p b:
    /// smoothing, the next coarser level's correction
    /// (visits_of_next(level) cycles on it), smoothing.
    template <typename Number>
    void
    cycle(const unsigned int         level,
          LevelVector<Number>       &x,
          const LevelVector<Number> &b) const;

    /// How many cycles on level @p level + 1 correct level @p level:
    /// Settings::coarse_visits below level 1 where level @p level + 1 has
    /// at most half the rows of level @p level (a W-cycle there), once
    /// otherwise, from the finest level and onto the coarsest.
    unsigned int
    visits_of_next(const unsigned int level) const;

    /// x = the coarsest level's solution for @p b.
    template <typename Number>
    void
    coarsest_solve(LevelVector<Number> &x, const LevelVector<Number> &b) const;

    const DoFHandler<dim>                     &system;
    const AffineConstraints<double>           &system_constraints;
    const Vector<double>                      &scale;
    const std::vector<unsigned int>            periodic_axes;
    const Settings                             settings;
    std::vector<std::pair<Point<dim>, double>> surfaces;
    MPI_Comm                                   communicator = MPI_COMM_SELF;

    /// With Settings::separate_components: each row's velocity component
    /// (255: a rigid row) on the finest level, by global row.
    std::vector<unsigned char> row_component;
    /// The levels in double: the finest (a copy, only for the double
    /// V-cycle) and the coarser ones (in single precision freed as soon as
    /// copied); prolongation[l] from level l + 1 to level l.
    std::unique_ptr<DistributedRows<double>>              finest_double;
    std::vector<std::unique_ptr<DistributedRows<double>>> coarse, prolongation;
    /// The smoothers' preconditioners, shared by the float smoothers.
    std::vector<std::shared_ptr<CutCellBlockJacobi>> block_jacobi;
    std::vector<std::unique_ptr<Smoother>>           smoother;
    /// With Settings::single_precision: the levels above the coarsest, the
    /// prolongations and the smoothers in float.
    std::vector<std::unique_ptr<DistributedRows<float>>> level_float,
      prolongation_float;
    std::vector<std::unique_ptr<FloatSmoother>> smoother_float;
    /// The coarsest level, whole on every rank, factorised.
    SparseMatrix<double> coarsest_matrix;
    SparsityPattern      coarsest_pattern;
    SparseDirectUMFPACK  coarsest;
    /// The rows each rank owns on each level.
    std::vector<IndexSet> owned;
    /// Work vectors per level: residual, restricted right-hand side,
    /// coarse correction; the finest level's in and out; the coarsest
    /// level's whole right-hand side and solution.
    mutable std::vector<LevelVector<float>>  residual_f, rhs_f, solution_f;
    mutable std::vector<LevelVector<double>> residual, level_rhs,
      level_solution;
    /// With Settings::coarse_visits > 1: a level's residual and correction
    /// at its second and later visits.
    mutable std::vector<LevelVector<float>>  again_rhs_f, again_f;
    mutable std::vector<LevelVector<double>> again_rhs, again;
    mutable LevelVector<float>               src_f, dst_f;
    mutable LevelVector<double>              src_d, dst_d;
    mutable Vector<double>                   coarse_x, coarse_b;

    /// The operator of @p level in double below the finest (or the
    /// finest's copy for the double V-cycle).
    const DistributedRows<double> &
    level_matrix(const unsigned int level) const;
  };
} // namespace Fidus

#endif
