#ifndef fidus_fluid_cut_element_taylor_hood_layout_h
#define fidus_fluid_cut_element_taylor_hood_layout_h

#include <deal.II/fe/fe.h>
#include <stdexcept>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * Where the Taylor–Hood element FESystem(FE_Q(2), dim, FE_Q(1), 1) keeps
   * its shape functions: each velocity function is a scalar Q2 function
   * φ_k times a unit vector e_c, and the cut element's kernels
   * (StokesVolumeKernel, the ghost penalties) work on the scalar functions
   * and spread their matrices over the components.
   */
  template <int dim>
  struct TaylorHoodLayout
  {
    /// Read @p fe's layout; throws std::invalid_argument unless it is
    /// FESystem(FE_Q(2), dim, FE_Q(1), 1).
    explicit TaylorHoodLayout(const FiniteElement<dim> &fe)
      : velocity(dim)
    {
      if (fe.n_base_elements() != 2 || fe.element_multiplicity(0) != dim ||
          fe.element_multiplicity(1) != 1 || fe.base_element(0).degree != 2 ||
          fe.base_element(1).degree != 1 || !fe.is_primitive())
        throw std::invalid_argument(
          "TaylorHoodLayout: the element must be FESystem(FE_Q(2), dim, "
          "FE_Q(1), 1), not " +
          fe.get_name());
      for (auto &v : velocity)
        v.assign(fe.base_element(0).n_dofs_per_cell(), 0);
      for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
        {
          const auto base = fe.system_to_base_index(i);
          if (base.first.first == 0)
            velocity[base.first.second][base.second] = i;
          else
            pressure.push_back(i);
        }
    }

    /// velocity[c][k]: the element's index of φ_k e_c.
    std::vector<std::vector<unsigned int>> velocity;
    /// The element's indices of the pressure functions, in order.
    std::vector<unsigned int> pressure;
  };
} // namespace Fidus

#endif
