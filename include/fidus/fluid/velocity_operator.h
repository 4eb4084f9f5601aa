#ifndef fidus_fluid_velocity_operator_h
#define fidus_fluid_velocity_operator_h

#include <deal.II/base/table.h>
#include <deal.II/base/vectorization.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/matrix_free/fe_evaluation.h>
#include <deal.II/matrix_free/matrix_free.h>
#include <deal.II/matrix_free/operators.h>
#include <deal.II/matrix_free/tools.h>

namespace Fidus
{
  using namespace dealii;

  /**
   * The velocity block of the penalised Stokes system, a(u, v) = (2 eta
   * e(u), e(v)), applied without a matrix (sum factorisation on Q(degree)^dim,
   * degree + 1 Gauss points per direction, as the assembly). One object per
   * multigrid level: eta is a table of values per cell batch and quadrature
   * point, filled by the owner (VelocityMultigrid) from the particles.
   *
   * Rows of DoFs with a Dirichlet constraint act as the identity (from
   * MatrixFreeOperators::Base), hanging-node and periodic constraints are
   * resolved by MatrixFree.
   */
  template <int dim, int degree>
  class VelocityOperator
    : public MatrixFreeOperators::
        Base<dim, LinearAlgebra::distributed::Vector<double>>
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;
    using Evaluator  = FEEvaluation<dim, degree, degree + 1, dim, double>;

    /// The viscosity of cell batch @p batch at quadrature point @p q; the
    /// table has one row per cell batch and one column per point.
    Table<2, VectorizedArray<double>> viscosity;

    /// Compute the inverse diagonal (the Chebyshev smoother's
    /// preconditioner); call after the viscosity changed.
    void
    compute_diagonal() override
    {
      this->inverse_diagonal_entries =
        std::make_shared<DiagonalMatrix<VectorType>>();
      VectorType &diagonal = this->inverse_diagonal_entries->get_vector();
      this->data->initialize_dof_vector(diagonal);
      MatrixFreeTools::compute_diagonal(*this->data,
                                        diagonal,
                                        &VelocityOperator::cell_term,
                                        this);
      // Constrained rows (zero here) become the identity.
      for (auto &d : diagonal)
        d = d > 0. ? 1. / d : 1.;
    }

    /// The integrand on one cell batch, for the operator, its diagonal and
    /// its matrix (coarse level).
    void
    cell_term(Evaluator &phi) const
    {
      const unsigned int batch = phi.get_current_cell_index();
      phi.evaluate(EvaluationFlags::gradients);
      for (unsigned int q = 0; q < phi.n_q_points; ++q)
        phi.submit_symmetric_gradient(2. * viscosity(batch, q) *
                                        phi.get_symmetric_gradient(q),
                                      q);
      phi.integrate(EvaluationFlags::gradients);
    }

    /// dst = C^T A field, with @p field (ghosted) read as it stands,
    /// constrained entries included, instead of from its free entries: the
    /// load of the inhomogeneous constraints on the free rows.
    void
    compute_load(VectorType &dst, const VectorType &field) const
    {
      this->data->cell_loop(&VelocityOperator::plain_cell_range,
                            this,
                            dst,
                            field,
                            true);
    }

  private:
    void
    plain_cell_range(const MatrixFree<dim, double>               &data,
                     VectorType                                  &dst,
                     const VectorType                            &src,
                     const std::pair<unsigned int, unsigned int> &range) const
    {
      Evaluator phi(data);
      for (unsigned int batch = range.first; batch < range.second; ++batch)
        {
          phi.reinit(batch);
          phi.read_dof_values_plain(src);
          cell_term(phi);
          phi.distribute_local_to_global(dst);
        }
    }

    void
    apply_add(VectorType &dst, const VectorType &src) const override
    {
      this->data->cell_loop(&VelocityOperator::cell_range, this, dst, src);
    }

    void
    cell_range(const MatrixFree<dim, double>               &data,
               VectorType                                  &dst,
               const VectorType                            &src,
               const std::pair<unsigned int, unsigned int> &range) const
    {
      Evaluator phi(data);
      for (unsigned int batch = range.first; batch < range.second; ++batch)
        {
          phi.reinit(batch);
          phi.read_dof_values(src);
          cell_term(phi);
          phi.distribute_local_to_global(dst);
        }
    }
  };
} // namespace Fidus

#endif
