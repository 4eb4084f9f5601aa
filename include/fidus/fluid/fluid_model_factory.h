#ifndef fidus_fluid_fluid_model_factory_h
#define fidus_fluid_fluid_model_factory_h

#include <deal.II/base/timer.h>
#include <fidus/core/parameters.h>
#include <fidus/core/warning_log.h>
#include <fidus/fluid/fluid_model.h>
#include <fidus/simulation/box_geometry.h>
#include <memory>

namespace Fidus
{
  /**
   * The fluid model that `Fluid/Model` names, for the scene of @p prm in
   * @p box; @p resuming: the run continues from a checkpoint, whose mesh
   * the model loads later (FluidModel::load_checkpoint). The only place
   * that knows the models' types. @p box, @p timer and @p warnings must
   * outlive the model.
   */
  template <int dim>
  std::unique_ptr<FluidModel<dim>>
  create_fluid_model(const Parameters       &prm,
                     const BoxGeometry<dim> &box,
                     bool                    resuming,
                     dealii::TimerOutput    &timer,
                     WarningLog             &warnings);
} // namespace Fidus

#endif
