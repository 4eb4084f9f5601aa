#ifndef fidus_fluid_velocity_operator_h
#define fidus_fluid_velocity_operator_h

#include <deal.II/base/table.h>
#include <deal.II/base/utilities.h>
#include <deal.II/base/vectorization.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/matrix_free/fe_evaluation.h>
#include <deal.II/matrix_free/matrix_free.h>
#include <deal.II/matrix_free/operators.h>
#include <deal.II/matrix_free/tools.h>
#include <type_traits>

namespace Fidus
{
  using namespace dealii;

  /**
   * The velocity block of the penalised Stokes system, a(u, v) = (2 eta
   * e(u), e(v)), applied without a matrix (sum factorisation on Q(degree)^dim).
   * One object per multigrid level: eta is a table of values per cell batch
   * and quadrature point, filled by the owner (VelocityMultigrid).
   *
   * Two point sets per direction, chosen by the MatrixFree object given to
   * initialize():
   * - degree + 1 Gauss points, as the assembly (the finest level, and every
   *   level with point-value viscosities);
   * - 2 degree + 1 equidistant points (galerkin_points): e(u):e(v) of two
   *   Q(degree) functions lies in Q(2 degree), and on these points a viscosity
   *   table can reproduce any linear functional of it exactly, which is how
   *   VelocityMultigrid makes a coarse level the Galerkin product of the
   *   finest one.
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
    /// Points per direction of the assembly.
    static constexpr int gauss_points = degree + 1;
    /// Points per direction of a Galerkin coarse level.
    static constexpr int galerkin_points = 2 * degree + 1;
    template <int n_points>
    using EvaluatorWith = FEEvaluation<dim, degree, n_points, dim, double>;
    using Evaluator     = EvaluatorWith<gauss_points>;

    /// The viscosity of cell batch @p batch at quadrature point @p q; the
    /// table has one row per cell batch and one column per point.
    Table<2, VectorizedArray<double>> viscosity;

    /**
     * Call @p f with std::integral_constant<int, n> for the number n of
     * quadrature points per direction of this operator's MatrixFree object.
     */
    template <typename F>
    void
    with_points(F &&f) const
    {
      if (this->data->get_n_q_points(0) ==
          Utilities::pow(static_cast<unsigned int>(gauss_points), dim))
        f(std::integral_constant<int, gauss_points>());
      else
        f(std::integral_constant<int, galerkin_points>());
    }

    /// Compute the inverse diagonal (the Chebyshev smoother's
    /// preconditioner); call after the viscosity changed.
    void
    compute_diagonal() override
    {
      this->inverse_diagonal_entries =
        std::make_shared<DiagonalMatrix<VectorType>>();
      VectorType &diagonal = this->inverse_diagonal_entries->get_vector();
      this->data->initialize_dof_vector(diagonal);
      with_points([&](auto n) {
        MatrixFreeTools::compute_diagonal(
          *this->data,
          diagonal,
          &VelocityOperator::template cell_term<decltype(n)::value>,
          this);
      });
      // Constrained rows (zero here) become the identity.
      for (auto &d : diagonal)
        d = d > 0. ? 1. / d : 1.;
    }

    /// Assemble the operator into @p matrix (the coarse level's AMG).
    template <typename MatrixType>
    void
    compute_matrix(const AffineConstraints<double> &constraints,
                   MatrixType                      &matrix) const
    {
      with_points([&](auto n) {
        MatrixFreeTools::compute_matrix(
          *this->data,
          constraints,
          matrix,
          &VelocityOperator::template cell_term<decltype(n)::value>,
          this);
      });
    }

    /// The integrand on one cell batch, for the operator, its diagonal and
    /// its matrix.
    template <int n_points>
    void
    cell_term(EvaluatorWith<n_points> &phi) const
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
      with_points([&](auto n) {
        this->data->cell_loop(
          &VelocityOperator::template plain_cell_range<decltype(n)::value>,
          this,
          dst,
          field,
          true);
      });
    }

  private:
    template <int n_points>
    void
    plain_cell_range(const MatrixFree<dim, double>               &data,
                     VectorType                                  &dst,
                     const VectorType                            &src,
                     const std::pair<unsigned int, unsigned int> &range) const
    {
      EvaluatorWith<n_points> phi(data);
      for (unsigned int batch = range.first; batch < range.second; ++batch)
        {
          phi.reinit(batch);
          phi.read_dof_values_plain(src);
          cell_term<n_points>(phi);
          phi.distribute_local_to_global(dst);
        }
    }

    void
    apply_add(VectorType &dst, const VectorType &src) const override
    {
      with_points([&](auto n) {
        this->data->cell_loop(
          &VelocityOperator::template cell_range<decltype(n)::value>,
          this,
          dst,
          src);
      });
    }

    template <int n_points>
    void
    cell_range(const MatrixFree<dim, double>               &data,
               VectorType                                  &dst,
               const VectorType                            &src,
               const std::pair<unsigned int, unsigned int> &range) const
    {
      EvaluatorWith<n_points> phi(data);
      for (unsigned int batch = range.first; batch < range.second; ++batch)
        {
          phi.reinit(batch);
          phi.read_dof_values(src);
          cell_term<n_points>(phi);
          phi.distribute_local_to_global(dst);
        }
    }
  };
} // namespace Fidus

#endif
