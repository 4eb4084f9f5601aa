#ifndef fidus_fluid_rigid_mode_h
#define fidus_fluid_rigid_mode_h

#include <deal.II/base/tensor.h>

namespace Fidus
{
  using namespace dealii;

  /**
   * The k-th rigid motion at offset @p r from its centre: e_0..e_{dim-1}
   * for k < dim, then the rotations (one, about z, in 2D; e_m x r with
   * m = k - dim in 3D). The cut element imposes them on particle surfaces
   * and its iterative solver gives them to the AMG as near-null space.
   */
  template <int dim>
  inline Tensor<1, dim>
  rigid_mode(const unsigned int k, const Tensor<1, dim> &r)
  {
    Tensor<1, dim> w;
    if (k < dim)
      w[k] = 1.;
    else if (dim == 2)
      {
        w[0] = -r[1];
        w[1] = r[0];
      }
    else
      {
        const unsigned int m  = k - dim;
        const unsigned int m1 = (m + 1) % 3, m2 = (m + 2) % 3;
        w[m2] = r[m1];
        w[m1] = -r[m2];
      }
    return w;
  }
} // namespace Fidus

#endif
