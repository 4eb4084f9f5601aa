#ifndef fidus_rheology_lubrication_stress_h
#define fidus_rheology_lubrication_stress_h

#include <deal.II/base/symmetric_tensor.h>
#include <fidus/lubrication/lubrication_correction.h>
#include <vector>

namespace Fidus
{
  /**
   * The stress of the sub-grid lubrication forces of the last correction
   * (doc/rheology.md):
   *
   *   Sigma_l = -(1/V) sum_b l_b sym(n_b (x) F_b),  F_b = f_b n_b + t_b,
   *
   * over the bonds of @p bonds, with f_b the normal force that pushes the
   * pair apart (LubricationBond::force), t_b the tangential force on j
   * (LubricationBond::tangential_force, zero without tangential terms) and
   * l_b the branch length (centre to centre, or centre to wall). Like the
   * contact stress: a squeeze that resists approach (f > 0) is compressive.
   * A 3 x 3 tensor; in 2D its z row is zero, and the caller adds the
   * plane-strain zz entry (with_plane_strain_zz()).
   */
  dealii::SymmetricTensor<2, 3>
  lubrication_stress(const std::vector<Contact::LubricationBond> &bonds,
                     double                                       volume);

  /**
   * Each particle's share of V Sigma_l (of @p n_particles): a pair bond's
   * term -l sym(n (x) F) is split equally between its two particles, a wall
   * bond's goes to its particle, so that the shares add up to
   * V lubrication_stress() (as contact_stresslets() for the contact part).
   */
  std::vector<dealii::SymmetricTensor<2, 3>>
  lubrication_stresslets(const std::vector<Contact::LubricationBond> &bonds,
                         std::size_t n_particles);
} // namespace Fidus

#endif
