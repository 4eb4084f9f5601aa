#include <EpetraExt_MatrixMatrix.h>
#include <Epetra_Vector.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <fidus/core/input_error.h>
#include <fidus/fluid/weighted_bfbt.h>

namespace Fidus
{
  namespace
  {
    /// K as an operator for deal.II's CG.
    struct KOperator
    {
      const Epetra_CrsMatrix &K;
      void
      vmult(TrilinosWrappers::MPI::Vector       &dst,
            const TrilinosWrappers::MPI::Vector &src) const
      {
        K.Multiply(false, src.trilinos_vector(), dst.trilinos_vector());
      }
    };

    /// Mean of the diagonal of @p m over the rows where @p mask is 1.
    double
    masked_diagonal_mean(const Epetra_CrsMatrix              &m,
                         const TrilinosWrappers::MPI::Vector &mask)
    {
      Epetra_Vector diagonal(m.RowMap());
      m.ExtractDiagonalCopy(diagonal);
      const Epetra_MultiVector &w        = mask.trilinos_vector();
      double                    local[2] = {0., 0.}, global[2];
      for (int i = 0; i < diagonal.MyLength(); ++i)
        {
          local[0] += w[0][i] * std::abs(diagonal[i]);
          local[1] += w[0][i];
        }
      m.Comm().SumAll(local, global, 2);
      return global[1] > 0 ? global[0] / global[1] : 0.;
    }
  } // namespace



  void
  WeightedBFBt::initialize(const TrilinosWrappers::SparseMatrix &B_,
                           const TrilinosWrappers::SparseMatrix &Bt_,
                           const Vector                         &weight,
                           const TrilinosWrappers::SparseMatrix &mass,
                           const Vector                         &free_pressure,
                           const VelocityBlock                  &A_)
  {
    Timer timer;
    B  = &B_;
    Bt = &Bt_;
    A  = &A_;
    c_inverse.reinit(weight, true);
    for (const auto i : weight.locally_owned_elements())
      {
        const double w = weight(i);
        c_inverse(i)   = w > 0. ? 1. / w : 0.;
      }
    c_inverse.compress(VectorOperation::insert);
    ones   = free_pressure;
    n_free = ones * ones;

    TrilinosWrappers::SparseMatrix K0;
    B->mmult(K0, *Bt, c_inverse);

    // The shift: small against the constant's neighbours in K's spectrum
    // (about h^2 times K's diagonal on a fine mesh), large enough for the
    // AMG's direct coarse solve. It also puts a diagonal on the rows of the
    // constrained pressure DoFs, which B leaves empty.
    const double shift =
      1e-8 * masked_diagonal_mean(K0.trilinos_matrix(), free_pressure) /
      masked_diagonal_mean(mass.trilinos_matrix(), free_pressure);
    Epetra_CrsMatrix *sum   = nullptr;
    const int         error = EpetraExt::MatrixMatrix::Add(K0.trilinos_matrix(),
                                                   false,
                                                   1.,
                                                   mass.trilinos_matrix(),
                                                   false,
                                                   shift,
                                                   sum);
    if (error != 0 || sum == nullptr)
      throw RunError("the weighted BFBt Schur approximation could not form "
                     "B C^-1 B^T + shift M (EpetraExt error " +
                     std::to_string(error) + ")");
    sum->FillComplete(K0.trilinos_matrix().DomainMap(),
                      K0.trilinos_matrix().RangeMap());
    K.reset(sum);

    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.higher_order_elements = false;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.02;
    amg.initialize(*K, data);
    setup_seconds = timer.wall_time();
  }



  void
  WeightedBFBt::project(Vector &v) const
  {
    if (n_free > 0.)
      v.add(-(v * ones) / n_free, ones);
  }



  void
  WeightedBFBt::solve_k(Vector &dst, const Vector &src, bool expensive) const
  {
    if (q.size() != src.size())
      q.reinit(src, true);
    q = src;
    project(q);
    if (expensive)
      {
        SolverControl    control(1000, 1e-3 * q.l2_norm());
        SolverCG<Vector> cg(control);
        dst = 0;
        cg.solve(KOperator{*K}, dst, q, amg);
        inner_iterations += control.last_step();
      }
    else
      amg.vmult(dst, q);
    project(dst);
  }



  void
  WeightedBFBt::vmult(Vector &dst, const Vector &src, bool expensive) const
  {
    if (z.size() != src.size())
      z.reinit(src, true);
    if (t.size() != c_inverse.size())
      {
        t.reinit(c_inverse, true);
        s.reinit(c_inverse, true);
      }
    solve_k(z, src, expensive);
    Bt->vmult(t, z);
    t.scale(c_inverse);
    A->vmult(s, t);
    s.scale(c_inverse);
    B->vmult(z, s);
    solve_k(dst, z, expensive);
  }
} // namespace Fidus
