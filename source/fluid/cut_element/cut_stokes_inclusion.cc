#include "cut_stokes_solve.h"

#include <fidus/fluid/cut_element/cut_stokes_inclusion.h>

namespace Fidus
{
  template <int dim>
  typename CutStokesInclusion<dim>::Result
  CutStokesInclusion<dim>::solve(const Settings &settings)
  {
    // The stages of the solve, and what they share, are CutStokesSolve's.
    return CutStokesSolve<dim>(settings).run();
  }

  template class CutStokesInclusion<2>;
  template class CutStokesInclusion<3>;
} // namespace Fidus
