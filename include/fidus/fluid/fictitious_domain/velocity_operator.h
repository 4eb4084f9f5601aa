#ifndef fidus_fluid_velocity_operator_h
#define fidus_fluid_velocity_operator_h

#include <cmath>
#include <deal.II/base/table.h>
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
   * Two kinds of level, chosen by the owner (galerkin_level):
   * - degree + 1 Gauss points per direction, as the assembly (the finest
   *   level, and every level with point-value viscosities);
   * - a Galerkin level: its MatrixFree object holds the Gauss points as
   *   quadrature 0 and the 2 degree + 1 Gauss-Lobatto points per direction
   *   (galerkin_points) as quadrature 1. e(u):e(v) of two Q(degree)
   *   functions lies in Q(2 degree), and on the Gauss-Lobatto points a
   *   viscosity table reproduces any linear functional of it exactly, which
   *   is how VelocityMultigrid makes a coarse level the Galerkin product of
   *   the finest one. Where a cell's viscosity is the same at all its points
   *   (uniform_viscosity), the Gauss points are exact as well and about
   *   (2 degree + 1)^dim / (degree + 1)^dim times cheaper, so products with
   *   the operator and its diagonal take them there; the coarse matrix,
   *   computed once per set-up, takes the Gauss-Lobatto points everywhere.
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
    /// table has one row per cell batch and one column per point of the
    /// exact quadrature (the Gauss-Lobatto points on a Galerkin level).
    Table<2, VectorizedArray<double>> viscosity;

    /// Whether this is a Galerkin level (set before initialize(); its
    /// MatrixFree object then has the two quadratures described above).
    bool galerkin_level = false;

    /// On a Galerkin level, per cell batch: 1 if the viscosity is the same
    /// at every point of each of its cells (all entries of its row of
    /// viscosity are then equal per lane), else 0.
    std::vector<unsigned char> uniform_viscosity;

    /// Whether a cell whose viscosity ranges from @p low to @p high has one
    /// viscosity: its values agree to round-off (the Galerkin moments of a
    /// wholly fluid or wholly solid cell), else the particle surface cuts
    /// it.
    static bool
    same_viscosity(const double low, const double high)
    {
      return high - low <= 1e-12 * std::abs(high);
    }

    /**
     * Call @p f with std::integral_constant<int, n> for the number n of
     * points per direction of the quadrature that is exact on every cell,
     * and the index of that quadrature in the MatrixFree object.
     */
    template <typename F>
    void
    with_points(F &&f) const
    {
      if (galerkin_level)
        f(std::integral_constant<int, galerkin_points>(), 1u);
      else
        f(std::integral_constant<int, gauss_points>(), 0u);
    }

    /// Compute the inverse diagonal (the Chebyshev smoother's
    /// preconditioner); call after the viscosity changed.
    ///
    /// The diagonal is linear in the viscosity table. After the first
    /// call on a mesh, only the change of the table since the last call
    /// is computed, on the cell batches where it changed (the cells the
    /// particles crossed): D(eta) = D(eta_old) + D(eta - eta_old).
    void
    compute_diagonal() override
    {
      const bool incremental =
        diagonal_sum.size() > 0 &&
        diagonal_viscosity.size(0) == viscosity.size(0) &&
        diagonal_viscosity.size(1) == viscosity.size(1);
      const unsigned int n_batches = viscosity.size(0);
      if (!incremental)
        {
          this->data->initialize_dof_vector(diagonal_sum);
          selected_batches.assign(n_batches, 1);
          if (galerkin_level)
            batch_uniform = uniform_viscosity;
          else
            batch_uniform.assign(n_batches, 1);
          add_diagonal(diagonal_sum);
        }
      else
        {
          // The change: on a batch whose viscosity changed, uniform only if
          // it is uniform before and after (the Gauss points are then
          // exact for the change too).
          selected_batches.assign(n_batches, 0);
          batch_uniform.assign(n_batches, 1);
          for (unsigned int b = 0; b < n_batches; ++b)
            {
              for (unsigned int q = 0; q < viscosity.size(1); ++q)
                for (unsigned int v = 0; v < VectorizedArray<double>::size();
                     ++v)
                  if (viscosity(b, q)[v] != diagonal_viscosity(b, q)[v])
                    selected_batches[b] = 1;
              if (galerkin_level)
                batch_uniform[b] = uniform_viscosity[b] && diagonal_uniform[b];
            }
          std::swap(viscosity, diagonal_viscosity);
          // viscosity now holds the old table, diagonal_viscosity the new.
          for (unsigned int b = 0; b < n_batches; ++b)
            if (selected_batches[b])
              for (unsigned int q = 0; q < viscosity.size(1); ++q)
                viscosity(b, q) = diagonal_viscosity(b, q) - viscosity(b, q);
          add_diagonal(diagonal_sum);
          std::swap(viscosity, diagonal_viscosity);
        }
      diagonal_viscosity = viscosity;
      diagonal_uniform   = uniform_viscosity;

      this->inverse_diagonal_entries =
        std::make_shared<DiagonalMatrix<VectorType>>();
      VectorType &diagonal = this->inverse_diagonal_entries->get_vector();
      diagonal             = diagonal_sum;
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
      with_points([&](auto n, const unsigned int quadrature) {
        MatrixFreeTools::compute_matrix(
          *this->data,
          constraints,
          matrix,
          &VelocityOperator::template cell_term<decltype(n)::value>,
          this,
          0,
          quadrature);
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
      if (phi.get_cell_type() == internal::MatrixFreeFunctions::cartesian)
        {
          // The same integrand on the unit-cell gradients, with the
          // diagonal inverse Jacobian of an axis-parallel cell, in plain
          // loops: through get_symmetric_gradient() and
          // submit_symmetric_gradient() the compiler kept the tensors on
          // the stack, and the reloads were two thirds of the time of this
          // function, the largest item of a 3D run (doc/preconditioners.md).
          using Number             = VectorizedArray<double>;
          const auto         inv   = phi.inverse_jacobian(0);
          Number            *grads = phi.begin_gradients();
          const unsigned int n_q   = phi.n_q_points;
          Number             jac[dim];
          for (unsigned int d = 0; d < dim; ++d)
            jac[d] = inv[d][d];
          for (unsigned int q = 0; q < n_q; ++q)
            {
              Number g[dim][dim];
              for (unsigned int c = 0; c < dim; ++c)
                for (unsigned int d = 0; d < dim; ++d)
                  g[c][d] = grads[(c * dim + d) * n_q + q] * jac[d];
              // 2 eta e(u) JxW, tested against the unit-cell gradients of
              // the test functions (the transpose of the same Jacobian).
              const Number w = viscosity(batch, q) * phi.JxW(q);
              for (unsigned int c = 0; c < dim; ++c)
                for (unsigned int d = 0; d < dim; ++d)
                  grads[(c * dim + d) * n_q + q] =
                    (w * (g[c][d] + g[d][c])) * jac[d];
            }
        }
      else
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
      with_points([&](auto n, const unsigned int) {
        this->data->cell_loop(
          &VelocityOperator::template plain_cell_range<decltype(n)::value>,
          this,
          dst,
          field,
          true);
      });
    }

  private:
    /// The diagonal of the last compute_diagonal() (not inverted), and the
    /// viscosity table and uniform flags it was computed with.
    VectorType                        diagonal_sum;
    Table<2, VectorizedArray<double>> diagonal_viscosity;
    std::vector<unsigned char>        diagonal_uniform;
    /// The batches add_diagonal() visits, and which of them take the Gauss
    /// points.
    std::vector<unsigned char> selected_batches;
    std::vector<unsigned char> batch_uniform;

    /// Add to @p diagonal the diagonal of the operator with the current
    /// viscosity table on the selected batches. On a Galerkin level in two
    /// passes, each over the batches the other skips: the Gauss points
    /// where the viscosity is uniform (exact there, and (2 degree + 1)^dim
    /// / (degree + 1)^dim times cheaper), the Gauss-Lobatto points where a
    /// surface cuts the cell.
    void
    add_diagonal(VectorType &diagonal) const
    {
      MatrixFreeTools::compute_diagonal(
        *this->data,
        diagonal,
        &VelocityOperator::template selected_cell_term<gauss_points, true>,
        this,
        0,
        0);
      if (galerkin_level)
        MatrixFreeTools::compute_diagonal(
          *this->data,
          diagonal,
          &VelocityOperator::template selected_cell_term<galerkin_points,
                                                         false>,
          this,
          0,
          1);
    }

    /// cell_term on the selected batches whose batch_uniform flag is
    /// @p uniform, zero on the others (add_diagonal()).
    template <int n_points, bool uniform>
    void
    selected_cell_term(EvaluatorWith<n_points> &phi) const
    {
      const unsigned int batch = phi.get_current_cell_index();
      if (selected_batches[batch] &&
          static_cast<bool>(batch_uniform[batch]) == uniform)
        cell_term<n_points>(phi);
      else
        for (unsigned int i = 0; i < phi.dofs_per_cell; ++i)
          phi.begin_dof_values()[i] = VectorizedArray<double>();
    }

    template <int n_points>
    void
    plain_cell_range(const MatrixFree<dim, double>               &data,
                     VectorType                                  &dst,
                     const VectorType                            &src,
                     const std::pair<unsigned int, unsigned int> &range) const
    {
      EvaluatorWith<n_points> phi(data, 0, n_points == gauss_points ? 0 : 1);
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
      if (galerkin_level)
        this->data->cell_loop(&VelocityOperator::galerkin_cell_range,
                              this,
                              dst,
                              src);
      else
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
          cell_term<gauss_points>(phi);
          phi.distribute_local_to_global(dst);
        }
    }

    /// A Galerkin level: the Gauss points where the viscosity is uniform
    /// (cell_term then reads the first entries of the batch's row, all
    /// equal), the Gauss-Lobatto points elsewhere.
    void
    galerkin_cell_range(
      const MatrixFree<dim, double>               &data,
      VectorType                                  &dst,
      const VectorType                            &src,
      const std::pair<unsigned int, unsigned int> &range) const
    {
      Evaluator                      gauss(data, 0, 0);
      EvaluatorWith<galerkin_points> lobatto(data, 0, 1);
      for (unsigned int batch = range.first; batch < range.second; ++batch)
        {
          auto apply = [&](auto &phi) {
            phi.reinit(batch);
            phi.read_dof_values(src);
            cell_term(phi);
            phi.distribute_local_to_global(dst);
          };
          if (uniform_viscosity[batch])
            apply(gauss);
          else
            apply(lobatto);
        }
    }
  };
} // namespace Fidus

#endif
