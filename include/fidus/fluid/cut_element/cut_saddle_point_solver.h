#ifndef fidus_fluid_cut_saddle_point_solver_h
#define fidus_fluid_cut_saddle_point_solver_h

#include <Epetra_MultiVector.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/point.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/la_parallel_block_vector.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/vector.h>
#include <fidus/fluid/cut_element/cut_system_blocks.h>
#include <fidus/fluid/cut_element/cut_velocity_multigrid.h>
#include <fidus/fluid/cut_element/distributed_rows.h>
#include <fidus/fluid/cut_element/row_pattern.h>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * The iterative solver of the cut finite element's system
   * (CutStokesInclusion), for the sizes where a sparse direct factorisation
   * is too slow (3D beyond a few tens of thousands of unknowns,
   * doc/cut_element.md, "The iterative solver").
   *
   * The system is symmetric, with the fluid velocity u and the particles'
   * rigid unknowns V (dim (dim + 1) / 2 each) forming a positive definite
   * block K, coupled to the pressure p:
   *
   *   [ A_uu  A_uV  B_u^T ]
   *   [ A_Vu  A_VV  B_V^T ]
   *   [ B_u   B_V   -C    ]
   *
   * (C the pressure's ghost penalty). Without a pinned pressure value
   * (Layout::pressure_mean given) the pressure block is -C - m m^T, where
   * m = M c / (c^T M c)^(1/2), c the constant pressure and M the pressure
   * mass below: the term fixes the pressure's mean to zero and gives the
   * Schur complement on the constant exactly what M gives it, so the
   * constant needs no iterations of its own (pinning one value instead
   * makes the constant a mode of the Schur complement whose eigenvalue
   * falls with the mesh size: FGMRES grew with the level).
   * FGMRES runs on it with the upper
   * block-triangular preconditioner [K B^T; 0 -S]^-1, where S is the
   * pressure mass matrix over the fluid (divided by the viscosity) plus C,
   * inverted by CG with point Jacobi to a relative residual of 1e-2 (one
   * AMG cycle on it, used before, left FGMRES 10-45 % more iterations in
   * 3D: doc/theory/cut_element.md, "The pressure side"; FGMRES takes a
   * preconditioner that changes from one application to the next). K^-1 is, by
   * default, one cycle of the geometric multigrid CutVelocityMultigrid on K,
   * which carries the rigid unknowns through all its levels. Without it
   * (VelocityPreconditioner::amg of CutStokesInclusion), K is inverted through
   * its Schur complement on the rigid unknowns: W = A_uu^-1 A_uV is solved for
   * once (one CG solve per rigid unknown) and S_V = A_VV - A_Vu W is a small
   * dense matrix, so the rigid unknowns, which couple to every cut cell of
   * their particle, never enter the AMG; one ML AMG cycle on A_uu (with the
   * rigid motions as near-null space) stands for A_uu^-1 in each application.
   */
  template <int dim>
  class CutSaddlePointSolver
  {
  public:
    /// What each unknown of the system is.
    struct Layout
    {
      /// 0: velocity, 1: pressure, 2: rigid.
      std::vector<unsigned char> kind;
      /// Unknowns fixed by constraints: their rows and columns hold the
      /// diagonal only.
      std::vector<bool> constrained;
      /// For a velocity unknown: its support point and component (the
      /// AMG's near-null space); unused for the others.
      std::vector<Point<dim>>    support_point;
      std::vector<unsigned char> component;
      /// m, the vector of the rank-one term that fixes the pressure's
      /// mean (see the class's documentation); empty when a pressure value
      /// is pinned instead.
      Vector<double> pressure_mean;
      /// For a pressure unknown: true where it lies in a thin gap; empty:
      /// none does.
      std::vector<bool> in_gap;
      /// The weight w of the thin gaps' pressure Laplacian in the Schur
      /// complement's preconditioner, S^-1 ~ (M + C)^-1 + w L_gap^-1 (see
      /// build_gap_laplacian()); 0: the pressure mass alone.
      double gap_laplacian = 0.;
      /// The ranks that share the solve: with the multigrid, every block
      /// and the multigrid's levels are split among them by rows (each
      /// rank keeps its own: K's and B^T's in its range of K, B's, the
      /// pressure block's and S's in a range of the pressures), and
      /// FGMRES and the pressure side run on those ranges
      /// (split_blocks()).
      MPI_Comm communicator = MPI_COMM_SELF;
      /// On more than one rank: the rows of K (velocities, then rigid
      /// unknowns) whose velocity rows this rank's K holds; the others are
      /// empty there, as CutSystemBlocks::reinit() leaves them with k_first
      /// and k_end.
      unsigned int k_first = 0, k_end = 0;
      /// On more than one rank: the pressures (counted in the system's
      /// order) whose rows this rank holds.
      unsigned int p_first = 0, p_end = 0;
    };

    /// The cost of one solve.
    struct Statistics
    {
      /// FGMRES iterations on the whole system.
      unsigned int iterations = 0;
      /// CG iterations summed over the solves for W.
      unsigned int setup_iterations = 0;
      /// Wall seconds: AMG setups and W; the FGMRES iterations.
      double setup_seconds = 0., solve_seconds = 0.;
      /// Of setup_seconds: copying the blocks (0 when the system came
      /// as its blocks); the pressure Schur
      /// complement's preconditioner (with the gap Laplacian's AMG); the
      /// velocity block's multigrid or AMG.
      double blocks_seconds = 0., pressure_seconds = 0., velocity_seconds = 0.;
      /// ||b - matrix x0|| / ||b|| of the start x0.
      double initial_residual = 1.;
    };

    /**
     * Set up for the (scaled) system @p matrix, with the pressure mass
     * matrix @p pressure_mass (same numbering; only its pressure rows are
     * read). With @p multigrid, one cycle of it stands for A_uu^-1 (it is
     * initialised here), and the solver keeps the system as its blocks
     * (K, B^T, B and the pressure block, which the preconditioner needs
     * anyway) and multiplies by them: it reads neither @p matrix nor
     * @p pressure_mass after the constructor, and the caller may free them
     * before the multigrid's levels are built (see @p release). Without,
     * one ML AMG cycle, and @p matrix must outlive the object.
     *
     * @p release, called (if given) once the blocks are copied and before
     * the multigrid is set up, is where the caller frees @p matrix: the
     * system and its copies in blocks were the solve's peak memory.
     */
    CutSaddlePointSolver(const SparseMatrix<double>  &matrix,
                         const SparseMatrix<double>  &pressure_mass,
                         const Layout                &layout,
                         CutVelocityMultigrid<dim>   *multigrid = nullptr,
                         const std::function<void()> &release   = {});

    /**
     * The same with @p multigrid, for a system assembled directly into its
     * blocks (@p blocks, CutSystemBlocks, whose kinds are @p layout's),
     * which the solver takes over: nothing is copied, and the system is
     * never held as one matrix. @p release, if given, is called before
     * the multigrid is set up, to free the caller's @p pressure_mass.
     */
    CutSaddlePointSolver(std::unique_ptr<CutSystemBlocks> blocks,
                         const SparseMatrix<double>      &pressure_mass,
                         const Layout                    &layout,
                         CutVelocityMultigrid<dim>       &multigrid,
                         const std::function<void()>     &release = {});

    /**
     * Solve matrix x = b to ||b - matrix x|| <= tolerance ||b||, from
     * x = 0, or with @p from_x from the @p x given (from zero instead if
     * its residual is not below ||b||: a guess worse than none). The
     * tolerance is the same either way, so the answer is. Throws
     * std::runtime_error, naming the iterations and the residual reached,
     * if that takes more than @p max_iterations.
     */
    Statistics
    solve(Vector<double>       &x,
          const Vector<double> &b,
          const double          tolerance,
          const unsigned int    max_iterations,
          const bool            from_x = false);

    /// The preconditioner: dst = P^-1 src.
    void
    vmult(Vector<double> &dst, const Vector<double> &src) const;

    /// dst = (matrix - m m^T) src: the system FGMRES solves (by its blocks
    /// with the multigrid).
    void
    system_vmult(Vector<double> &dst, const Vector<double> &src) const;

  private:
    /// Each unknown's index within its kind (local), and the lists of
    /// each kind (velocity, pressure, rigid), from @p layout.
    void
    number_unknowns(const Layout &layout);

    /// Copies the blocks of the system that the preconditioner needs: K or
    /// A_uu, B^T with A_Vu, and A_Vu alone without the multigrid; the
    /// pressure block.
    void
    extract_blocks(const Layout &layout);

    /// The set-up after the blocks: the pressure side, @p release, the
    /// velocity side (the constructors' common part).
    void
    setup(const SparseMatrix<double>  &pressure_mass,
          const Layout                &layout,
          const std::function<void()> &release);

    /// Assembles S = M / eta + C on the pressures, with a unit diagonal
    /// for the constrained ones (which apply_pressure_inverse() sets
    /// apart).
    void
    build_pressure_schur(const SparseMatrix<double> &pressure_mass,
                         const Layout               &layout);

    /// z = -S^-1 r on the pressures: CG with point Jacobi on S to 1e-2,
    /// and the constrained pressures' rows exactly.
    void
    apply_pressure_inverse(Vector<double> &z, const Vector<double> &r) const;

    /// Sets up the AMG of A_uu with the rigid motions as near-null space
    /// (the preconditioner of the velocities without the multigrid).
    void
    setup_velocity_amg(const Layout &layout);

    /// Computes W = A_uu^-1 A_uV and the inverse of S_V = A_VV - A_Vu W
    /// (the rigid unknowns without the multigrid).
    void
    compute_rigid_schur();

    /**
     * The thin gaps' part of the pressure preconditioner. In a gap of
     * width delta the Schur complement S acts on the pressure's smooth
     * lateral modes like (delta^2/12) times a Laplacian (they drive a
     * Poiseuille flow across the gap), far below the pressure mass M that
     * stands for S elsewhere; so M alone leaves FGMRES counts that grow as
     * the gap thins. L_gap = B D^-1 B^T + C over the pressures in thin
     * gaps (D the velocity block's diagonal, C the pressure's ghost
     * penalty, the region's outside a Dirichlet boundary) has the
     * Laplacian's form scaled by the local cell size squared, and its
     * inverse, added to M's, gives those modes their weight: the sum of
     * inverses that Sande, Koch, Kuchta and Mardal's norm L^2 + W H^1 for
     * slender domains calls for. Without C, pressures whose fluid is a
     * sliver (B hardly sees them) made L_gap nearly singular and FGMRES
     * slower than with M alone.
     */
    void
    build_gap_laplacian(const Layout &layout);
    /// The pressures in thin gaps, not constrained (gap_pressures, in
    /// the pressures' order; gap_weight), and each pressure's index among
    /// them (-1: none).
    std::vector<int>
    select_gap_pressures(const Layout &layout);

    /// With the multigrid on more than one rank: K's rows split among
    /// the ranks (read in place from K, which holds no other), on which the
    /// multigrid is built.
    void
    split_velocity_block(const Layout &layout);
    /// K's diagonal (every rank holds its own velocity rows only): from
    /// the ranks with the split, from K without.
    Vector<double> k_diagonal;

    /// A vector of the split solve: block 0 this rank's range of K's rows
    /// (velocities, then rigid unknowns), block 1 its range of the
    /// pressures.
    using PartVector  = LinearAlgebra::distributed::Vector<double>;
    using PartsVector = LinearAlgebra::distributed::BlockVector<double>;
    /**
     * With the split: B^T's rows with K's, B's, the pressure block's and
     * S's by ranges of the pressures, the mean's part and S's inverse
     * diagonal, copied from the whole blocks (which are freed), so that
     * FGMRES and the pressure side run on this rank's rows only
     * (solve_split()).
     */
    void
    split_blocks(const Layout &layout);
    /// build_gap_laplacian() with the split, after split_blocks(): L_gap's
    /// rows on this rank's gap pressures, B D^-1 B^T as a Galerkin product
    /// of the ranks' rows of B^T, and its AMG over the ranks.
    void
    split_gap_laplacian(const Layout &layout);
    /// A zero vector over this rank's ranges.
    PartsVector
    make_parts() const;
    /// @p parts = this rank's entries of the whole @p whole.
    void
    to_parts(const Vector<double> &whole, PartsVector &parts) const;
    /// The whole vector @p whole from every rank's @p parts (collective).
    void
    from_parts(const PartsVector &parts, Vector<double> &whole) const;
    /// dst = @p op(src) for whole vectors, through this rank's parts
    /// (system_vmult() and vmult() with the split).
    void
    through_parts(Vector<double>       &dst,
                  const Vector<double> &src,
                  void (CutSaddlePointSolver::*op)(PartsVector &,
                                                   const PartsVector &)
                    const) const;
    /// system_vmult() on the ranks' rows.
    void
    split_system_vmult(PartsVector &dst, const PartsVector &src) const;
    /// vmult() on the ranks' rows.
    void
    split_vmult(PartsVector &dst, const PartsVector &src) const;
    /// apply_pressure_inverse() on the ranks' pressures.
    void
    split_pressure_inverse(PartVector &z, const PartVector &r) const;
    /// solve() with the split.
    Statistics
    solve_split(Vector<double>       &x,
                const Vector<double> &b,
                const double          tolerance,
                const unsigned int    max_iterations,
                const bool            from_x);
    /// FGMRES on @p system with @p preconditioner from @p x (or from zero
    /// if @p from_x is false or x's residual is not below b's), to
    /// @p tolerance: what solve() and solve_split() share; fills the
    /// statistics' iterations, seconds and initial residual.
    template <typename VectorType, typename SystemType, typename Preconditioner>
    void
    run_fgmres(const SystemType     &system,
               const Preconditioner &preconditioner,
               VectorType           &x,
               const VectorType     &b,
               const double          tolerance,
               const unsigned int    max_iterations,
               const bool            from_x);
    std::unique_ptr<DistributedRows<double>> k_rows, bt_rows, p_rows, s_rows;
    /// This rank's ranges of K's rows and of the pressures.
    IndexSet k_owned, p_owned;
    /// S's inverse diagonal and m, on this rank's pressures.
    PartVector s_inverse_diagonal, mean_part;
    /// With the split: this rank's range of the gap pressures, L_gap's
    /// rows on it and the AMG's vectors there.
    IndexSet                       gap_owned;
    TrilinosWrappers::SparseMatrix gap_rows;
    mutable PartVector             r_gap, z_gap;
    /// This rank's constrained pressures (local indices) and their
    /// diagonal in the system.
    std::vector<unsigned int> own_constrained;
    std::vector<double>       own_constrained_diagonal;
    mutable PartVector        k_in;

    /// The system; nullptr when it came as blocks, and not read after the
    /// constructor with the multigrid.
    const SparseMatrix<double> *matrix;
    /// Global indices of the velocity, pressure and rigid unknowns, and
    /// each unknown's index within its kind.
    std::vector<unsigned int> velocity, pressure, rigid, local;
    /// The system's blocks, and the names the solver gives them: A_uu (K
    /// with the multigrid), B^T (rows: velocities, then rigid unknowns)
    /// and the system's pressure block. B is not held: the system is
    /// symmetric, and B's products are B^T's transposed ones.
    std::unique_ptr<CutSystemBlocks> blocks;
    SparseMatrix<double> &velocity_matrix, &coupling, &pressure_block;
    /// The row ranges' buffers of B's products (transposed_vmult_add()).
    mutable std::vector<double> transposed_scratch;
    RowPattern                  rigid_sparsity;
    SparsityPattern             pressure_sparsity;
    /// S; A_Vu (without the multigrid).
    SparseMatrix<double>                     pressure_schur, rigid_coupling;
    TrilinosWrappers::SparseMatrix           velocity_trilinos;
    TrilinosWrappers::PreconditionAMG        velocity_amg;
    PreconditionJacobi<SparseMatrix<double>> pressure_jacobi;
    /// The constrained pressures (their numbers among the pressures) and
    /// their diagonal in the system.
    std::vector<unsigned int>           constrained_pressures;
    std::vector<double>                 constrained_diagonal;
    CutVelocityMultigrid<dim>          *multigrid;
    std::unique_ptr<Epetra_MultiVector> null_space;
    /// W = A_uu^-1 A_uV, one column per rigid unknown, and S_V^-1.
    std::vector<Vector<double>> w;
    FullMatrix<double>          rigid_schur_inverse;
    Statistics                  statistics;
    /// The pressures in thin gaps (their indices among the pressures), the
    /// gap Laplacian on them, its AMG and its weight (build_gap_laplacian).
    std::vector<unsigned int>         gap_pressures;
    TrilinosWrappers::SparseMatrix    gap_trilinos;
    TrilinosWrappers::PreconditionAMG gap_amg;
    double                            gap_weight = 0.;
    mutable Vector<double>            r_g, z_g;
    /// The system as FGMRES multiplies by it (system_vmult()).
    struct System
    {
      const CutSaddlePointSolver &solver;
      void
      vmult(Vector<double> &dst, const Vector<double> &src) const
      {
        solver.system_vmult(dst, src);
      }
    };

    /// m (see the class's documentation), or empty.
    Vector<double> mean;

    /// Work vectors of vmult and system_vmult.
    mutable Vector<double> r_u, y_u, r_p, z_p, coupling_product, r_v, z_v, x_k,
      x_p, y_k, y_p;
  };

  template <int dim>
  template <typename VectorType, typename SystemType, typename Preconditioner>
  void
  CutSaddlePointSolver<dim>::run_fgmres(const SystemType     &system,
                                        const Preconditioner &preconditioner,
                                        VectorType           &x,
                                        const VectorType     &b,
                                        const double          tolerance,
                                        const unsigned int    max_iterations,
                                        const bool            from_x)
  {
    Timer        timer;
    const double b_norm       = b.l2_norm();
    bool         start_from_x = from_x;
    if (start_from_x)
      {
        VectorType r;
        r.reinit(b);
        system.vmult(r, x);
        r.sadd(-1., 1., b);
        statistics.initial_residual = r.l2_norm() / b_norm;
        if (!(statistics.initial_residual < 1.))
          start_from_x = false;
      }
    if (!start_from_x)
      {
        x                           = 0.;
        statistics.initial_residual = 1.;
      }
    SolverControl control(max_iterations, tolerance * b_norm, false, false);
    // Thin gaps take FGMRES past 100 iterations (the pressure's mass
    // matrix weakens there), and a restart at 100 then stalls: the paper's
    // 3D pair at a gap of 0.022 a took 1340 iterations with restarts at
    // 100 (doc/history/cut_element.md). A basis of 300 costs 2 x 300
    // vectors.
    SolverFGMRES<VectorType> fgmres(
      control,
      typename SolverFGMRES<VectorType>::AdditionalData(300));
    try
      {
        fgmres.solve(system, x, b, preconditioner);
      }
    catch (const SolverControl::NoConvergence &e)
      {
        std::ostringstream message;
        message << "CutSaddlePointSolver: FGMRES did not reach the relative "
                   "residual "
                << tolerance << " in " << max_iterations
                << " iterations (reached " << e.last_residual / b_norm << ")";
        throw std::runtime_error(message.str());
      }
    statistics.iterations    = control.last_step();
    statistics.solve_seconds = timer.wall_time();
  }
} // namespace Fidus

#endif
