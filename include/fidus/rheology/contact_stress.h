#ifndef fidus_rheology_contact_stress_h
#define fidus_rheology_contact_stress_h

#include <deal.II/base/symmetric_tensor.h>
#include <fidus/contact/constraint_system.h>
#include <vector>

namespace Fidus
{
  /**
   * The contact stress of the last projection (doc/rheology.md):
   *
   *   Sigma_c = -(1/V) sum_k l_k f_k e_k (x) e_k,   f_k = zeta lambda_k,
   *
   * over the rows k of @p rows (bodies 0..N-1 are the particles of @p radii,
   * the others walls). The projection is the metric projection
   * min |v - u*|^2 of velocities, u = u* + G^T lambda, so lambda_k is the
   * velocity a row adds along its normal e_k; the force that gives an
   * isolated particle that velocity in the fluid is zeta lambda_k, with
   * zeta = @p drag (a force per unit velocity). l_k is the branch length:
   * centre to centre, D_k + a_i + a_j, for a pair; centre to the wall,
   * D_k + a_i, for a particle-wall row. Repulsion (lambda > 0) gives a
   * compressive (negative) normal stress, glue under tension the opposite.
   * A 3 x 3 tensor; in 2D its z row is zero, and the caller adds the
   * plane-strain zz entry (with_plane_strain_zz()).
   */
  dealii::SymmetricTensor<2, 3>
  contact_stress(const Contact::ConstraintSystem &rows,
                 const std::vector<double>       &radii,
                 double                           drag,
                 double                           volume);

  /**
   * The same contact forces per particle: the stresslet S_i of particle i,
   * with each pair row's -l f e (x) e shared half and half between its two
   * particles and a wall row's given whole to its particle, so that
   * sum_i S_i / V is contact_stress(). One tensor per radius.
   */
  std::vector<dealii::SymmetricTensor<2, 3>>
  contact_stresslets(const Contact::ConstraintSystem &rows,
                     const std::vector<double>       &radii,
                     double                           drag);
} // namespace Fidus

#endif
