#ifndef fidus_fluid_weighted_bfbt_h
#define fidus_fluid_weighted_bfbt_h

#include <Epetra_CrsMatrix.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <fidus/fluid/velocity_block.h>
#include <memory>

namespace Fidus
{
  using namespace dealii;

  /**
   * The weighted BFBt approximation of the inverse Schur complement
   * (Rudi, Stadler and Ghattas, SIAM J. Sci. Comput. 39, 2017):
   *
   *     S^{-1} ~ K^{-1} (B C^{-1} A C^{-1} B^T) K^{-1},  K = B C^{-1} B^T,
   *
   * with C the velocity mass lumped with the weight sqrt(eta). Where the
   * viscosity jumps by r across a particle surface, the 1/eta pressure mass
   * sees each cell's viscosity alone, whereas this approximation sees A
   * itself; fidus offers it as `Fluid/Linear solver/Schur complement
   * approximation = weighted BFBt` for penalties of 1e4 and more.
   *
   * K is formed once per step as a sparse product (it changes with eta
   * through C) and approximately inverted by one ML V-cycle ("cheap") or by
   * CG with that V-cycle to a relative 1e-3 ("expensive"). Every fidus box
   * has its velocity imposed on the whole boundary, so K has the constant
   * pressure (on the unconstrained pressure DoFs) in its kernel: it is
   * shifted by a tiny multiple of the pressure mass for the AMG's coarse
   * solve, and both K^{-1} are applied on the complement of the constant.
   */
  class WeightedBFBt
  {
  public:
    using Vector = TrilinosWrappers::MPI::Vector;

    /// Form K and its AMG. @p B: the pressure-velocity block of the system
    /// (constrained rows and columns empty); @p Bt: the velocity-pressure
    /// block; @p weight: the diagonal of C on the velocity DoFs (0 on
    /// constrained ones); @p mass: the pressure mass of the Schur
    /// approximation it replaces (for the shift and for the constrained
    /// pressure rows); @p free_pressure: 1 on unconstrained pressure DoFs,
    /// 0 elsewhere; @p A: the velocity block (kept by reference).
    void
    initialize(const TrilinosWrappers::SparseMatrix &B,
               const TrilinosWrappers::SparseMatrix &Bt,
               const Vector                         &weight,
               const TrilinosWrappers::SparseMatrix &mass,
               const Vector                         &free_pressure,
               const VelocityBlock                  &A);

    /// dst = S^{-1} src (an approximation of the positive Schur complement
    /// B A^{-1} B^T); @p expensive: K^{-1} by CG instead of one V-cycle.
    void
    vmult(Vector &dst, const Vector &src, bool expensive) const;

    /// Whether initialize() has been called.
    bool
    empty() const
    {
      return K == nullptr;
    }

    /// Seconds of the last initialize().
    double setup_seconds = 0.;
    /// CG iterations on K so far (expensive mode).
    mutable unsigned int inner_iterations = 0;

  private:
    /// dst = K^{-1} src on the complement of the constant.
    void
    solve_k(Vector &dst, const Vector &src, bool expensive) const;
    /// Remove the component along the free-pressure constant.
    void
    project(Vector &v) const;

    const TrilinosWrappers::SparseMatrix *B  = nullptr;
    const TrilinosWrappers::SparseMatrix *Bt = nullptr;
    const VelocityBlock                  *A  = nullptr;
    Vector                                c_inverse, ones;
    double                                n_free = 0.;
    std::unique_ptr<Epetra_CrsMatrix>     K;
    TrilinosWrappers::PreconditionAMG     amg;
    mutable Vector                        z, t, s, q;
  };
} // namespace Fidus

#endif
