#include <fidus/fluid/cut_element/cut_element_model.h>
#include <fidus/fluid/fictitious_domain/fictitious_domain_model.h>
#include <fidus/fluid/fluid_model_factory.h>
#include <fidus/fluid/undisturbed/undisturbed_shear_model.h>

namespace Fidus
{
  template <int dim>
  std::unique_ptr<FluidModel<dim>>
  create_fluid_model(const Parameters       &prm,
                     const BoxGeometry<dim> &box,
                     const bool              resuming,
                     dealii::TimerOutput    &timer,
                     WarningLog             &warnings)
  {
    switch (prm.fluid.model)
      {
        case FluidModelType::fictitious_domain:
          return std::make_unique<FictitiousDomainModel<dim>>(prm,
                                                              box,
                                                              resuming,
                                                              timer,
                                                              warnings);
        case FluidModelType::cut_finite_element:
          return std::make_unique<CutElementModel<dim>>(prm,
                                                        box,
                                                        timer,
                                                        warnings);
        case FluidModelType::undisturbed_shear:
          return std::make_unique<UndisturbedShearModel<dim>>(prm, box);
      }
    return nullptr;
  }

  template std::unique_ptr<FluidModel<2>>
  create_fluid_model(const Parameters &,
                     const BoxGeometry<2> &,
                     bool,
                     dealii::TimerOutput &,
                     WarningLog &);
  template std::unique_ptr<FluidModel<3>>
  create_fluid_model(const Parameters &,
                     const BoxGeometry<3> &,
                     bool,
                     dealii::TimerOutput &,
                     WarningLog &);
} // namespace Fidus
