#ifndef fidus_fluid_cut_element_stokes_volume_kernel_h
#define fidus_fluid_cut_element_stokes_volume_kernel_h

#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <fidus/fluid/cut_element/taylor_hood_layout.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * The Stokes volume terms of one cell of the Taylor–Hood element
   * (FESystem of FE_Q(2)^dim and FE_Q(1)) on any quadrature, such as a cut
   * cell's fluid part: the matrix of 2 η ε(u):ε(v) − p div v − q div u,
   * and the pressure mass divided by η.
   *
   * Each velocity shape function is a scalar Q2 function φ_k times a unit
   * vector e_c, so that 2 ε(φ_k e_c) : ε(φ_l e_d) = δ_cd ∇φ_k·∇φ_l +
   * ∂_d φ_k ∂_c φ_l: every viscous entry is a sum of entries of G Gᵀ, G
   * the scalar functions' weighted partial derivatives (dim · 9 rows in 2D,
   * dim · 27 in 3D, one column per point), and the divergence couplings
   * are G Qᵀ, Q the weighted pressure functions. A cut cell has hundreds of
   * points; G Gᵀ (of which only one triangle is formed) takes about a
   * twentieth of the arithmetic of one product over all shape functions
   * with the strains' components as columns, the form it replaces.
   *
   * One object per thread: it keeps its work matrices.
   */
  template <int dim>
  class StokesVolumeKernel
  {
  public:
    /// Read the element's layout; throws std::invalid_argument unless @p fe
    /// is FESystem(FE_Q(2), dim, FE_Q(1), 1).
    explicit StokesVolumeKernel(const FiniteElement<dim> &fe)
      : layout(fe)
    {}

    /**
     * Add the cell's terms on the quadrature of @p fe_values (values,
     * gradients and JxW updated) to @p local (its first
     * fe.n_dofs_per_cell() rows and columns, the element's numbering) and
     * the pressure mass divided by @p eta to @p local_pressure (the
     * pressure functions in the element's order).
     */
    void
    add(const FEValues<dim> &fe_values,
        double               eta,
        FullMatrix<double>  &local,
        FullMatrix<double>  &local_pressure);

  private:
    const TaylorHoodLayout<dim> layout;
    /// Work: G (dim · n_scalar by points, by columns), Q (pressures by
    /// points), G Gᵀ, G Qᵀ and Q Qᵀ.
    std::vector<double> g, q, ggt, gqt, qqt;
  };
} // namespace Fidus

#endif
