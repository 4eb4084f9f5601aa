#ifndef fidus_fluid_cut_element_component_coupling_h
#define fidus_fluid_cut_element_component_coupling_h

#include <vector>

namespace Fidus
{
  /**
   * Whether the entry (i, j) of a velocity block is kept when the block is
   * read without its couplings between different velocity components
   * (CutVelocityMultigrid::Settings::separate_components): @p component
   * gives each row's component, 255 for a row of none (a particle's rigid
   * unknown, which keeps all its entries); an empty @p component keeps
   * every entry.
   */
  inline bool
  couples_within_component(const std::vector<unsigned char> &component,
                           const unsigned int                i,
                           const unsigned int                j)
  {
    return component.empty() || component[i] == 255 || component[j] == 255 ||
           component[i] == component[j];
  }
} // namespace Fidus

#endif
