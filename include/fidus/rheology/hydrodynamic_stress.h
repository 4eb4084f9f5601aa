#ifndef fidus_rheology_hydrodynamic_stress_h
#define fidus_rheology_hydrodynamic_stress_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <fidus/fluid/fictitious_domain/solid_indicator.h>
#include <fidus/fluid/fictitious_domain/stokes_solver.h>
#include <set>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * The hydrodynamic stress of the suspension from the fluid predictor's
   * last solve (doc/rheology.md), computed in two independent ways:
   *
   * - the volume average over the box of the stress that the discrete
   *   momentum equation balances, sigma = -p I + 2 eta(x) e(u) + chi_s
   *   e(lambda) (eta = r eta_f in the held solid, the rigidity multiplier
   *   lambda there; shared cells as fluid), split as
   *   Sigma = -<p>_f I + 2 eta_f <e(u)> + (1/V) sum_a S_a with the particle
   *   stresslets S_a = int_{V_a} (sigma + <p>_f I - 2 eta_f e(u)), which do
   *   not depend on the pressure's additive constant;
   * - the walls: the consistent residual R_j = int sigma : e(phi_j) of the
   *   velocity DoFs with imposed velocity, so that
   *   (1/V) sum_j x_b(j) R_j(a) = (1/V) int sigma_ab whenever the equations
   *   of all other DoFs hold (div sigma = 0 tested with the linear field
   *   x_b e_a). This is the force a rheometer's walls feel; it needs
   *   direction b to have imposed velocity on both faces (sliding walls:
   *   b = y only).
   *
   * The two agree to the linear solver's tolerance; a wrong solid stress or
   * multiplier term breaks the agreement. In 2D the tensors are 3 x 3 in
   * plane strain: sigma_zz = -p in the fluid, and each particle's zz
   * stresslet is half its in-plane trace (with_plane_strain_zz()).
   */
  template <int dim>
  class HydrodynamicStress
  {
  public:
    /// A 3 x 3 symmetric tensor (2D: plane strain).
    using Tensor3 = SymmetricTensor<2, 3>;

    /// The stresses of one solve.
    struct Result
    {
      /// Volume (2D: area) of the box.
      double volume = 0.;
      /// (1/V) int sigma over the box (2D: zz with the particles' rule).
      Tensor3 total;
      /// (1/V) int e(u) over the box.
      Tensor3 mean_strain_rate;
      /// Mean pressure over the fluid (outside every particle).
      double fluid_pressure = 0.;
      /// Solid fraction of the box (quadrature points inside particles).
      double solid_fraction = 0.;
      /// (1/V) sum_a S_a: the particles' hydrodynamic stress.
      Tensor3 particle;
      /// (1/V) sum_j x_b(j) R_j(a) at the DoFs with imposed velocity:
      /// entry (a, b); NaN where direction b has no imposed velocity on
      /// both faces (or b = z in 2D).
      Tensor<2, 3> wall;
      /// Stresslet S_a of every particle (all ranks hold all of them).
      std::vector<Tensor3> stresslets;

      /**
       * Multiply every field that is linear in the boundary data by @p c:
       * the same configuration under a shear rate c times the solved one
       * (Stokes flow without external forces is linear in the shear rate).
       */
      void
      scale(const double c)
      {
        total *= c;
        mean_strain_rate *= c;
        fluid_pressure *= c;
        particle *= c;
        wall *= c;
        for (Tensor3 &s : stresslets)
          s *= c;
      }
    };

    /**
     * @p dirichlet_ids as given to StokesSolver::setup_dofs(): the faces
     * with imposed velocity, which decide which walls carry a traction.
     */
    explicit HydrodynamicStress(
      const std::set<types::boundary_id> &dirichlet_ids);

    /**
     * The stresses of the solver's last solve with the solid @p solid (the
     * one that solve saw). The multiplier is the one the last solution was
     * computed with.
     */
    Result
    compute(const StokesSolver<dim>   &solver,
            const SolidIndicator<dim> &solid) const;

  private:
    std::set<types::boundary_id> dirichlet_ids;
    /// Directions b with imposed velocity on both faces 2b, 2b + 1.
    std::vector<unsigned int> wall_directions;
  };
} // namespace Fidus

#endif
