#ifndef fidus_rheology_plane_strain_h
#define fidus_rheology_plane_strain_h

#include <deal.II/base/symmetric_tensor.h>

namespace Fidus
{
  /**
   * The zz entry of a 2D particle stress in plane strain (doc/rheology.md,
   * "Plane strain"): @p s with s_zz replaced by (s_xx + s_yy) / 2.
   *
   * A disc is the section of a long rigid cylinder. Its in-plane stresses
   * follow from the forces on it, but its axial stress does not: a rigid
   * body takes any uniform s_zz. The limit of an incompressible body
   * (Poisson ratio 1/2, the rigid limit of the penalised solid) fixes it at
   * half the in-plane trace, which is what the pressure inside a resolved
   * particle carries. Every 2D particle stress (hydrodynamic stresslets,
   * contacts, sub-grid lubrication) uses this rule, so that the forces of
   * a close pair count the same in N2 whether the mesh resolves the gap's
   * pressure or the correction adds it.
   */
  inline dealii::SymmetricTensor<2, 3>
  with_plane_strain_zz(dealii::SymmetricTensor<2, 3> s)
  {
    s[2][2] = 0.5 * (s[0][0] + s[1][1]);
    return s;
  }
} // namespace Fidus

#endif
