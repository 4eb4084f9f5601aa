// 'Fluid/Lubrication coupling = auto' resolved from the scene
// (Parameters::resolve_lubrication_coupling()). The particles' volume
// fraction is their volumes over the box's: checked against the formula for
// discs and spheres. Then the rule:
//  - the fictitious domain with the correction below 15 % of the box (a
//    pair) solves the bonds with the flow; at 20 % (a generated
//    scene), after the solve;
//  - a dilute pair with 'Lubrication gap in time = step mean', which the
//    coupled solve refuses, gets the correction after the solve;
//  - a setting given by the user is kept; the cut element keeps 'auto'
//    (with the flow is its only way); without the correction nothing is
//    resolved.

#include "../fidus_test.h"

#include <deal.II/base/numbers.h>
#include <fidus/core/parameters.h>

using namespace FidusTest;

namespace
{
  using Coupling = Fidus::LubricationParameters::Coupling;

  Fidus::Parameters
  scene(const unsigned int dim,
        const std::string &fluid_entries,
        const std::string &particles)
  {
    std::ostringstream prm;
    prm << "set Dimension = " << dim << "\n"
        << (dim == 3 ? "subsection Domain\n  set Lower left = 0, 0, 0\n"
                       "  set Upper right = 1, 1, 1\nend\n" :
                       "")
        << "subsection Fluid\n"
        << fluid_entries << "end\n"
        << "subsection Particles\n"
        << particles << "end\n";
    return Fidus::read_parameters_from_string(prm.str());
  }

  const std::string pair_2d = "  set Radius = 0.05\n"
                              "  set Positions = 0.3, 0.5; 0.7, 0.5\n";
  const std::string pair_3d =
    "  set Radius = 0.1\n"
    "  set Positions = 0.3, 0.525, 0.5; 0.7, 0.475, 0.5\n";
  const std::string dense_3d = "  subsection Generator\n"
                               "    set Fraction = 0.2\n"
                               "    set Radii = 0.1\n"
                               "  end\n";
  const std::string on       = "  set Lubrication correction = true\n";

  double
  is(const Coupling c, const Coupling expected)
  {
    return c == expected ? 1. : 0.;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double                             pi = dealii::numbers::PI;

  const auto discs = scene(2, on, pair_2d);
  check_range("two discs: area fraction / (2 pi a^2)",
              discs.particle_volume_fraction() / (2. * pi * 0.05 * 0.05),
              1. - 1e-12,
              1. + 1e-12);
  check_range("two discs: with the flow",
              is(discs.lubrication.coupling, Coupling::with_the_flow),
              1,
              1);

  const auto spheres = scene(3, on, pair_3d);
  check_range("two spheres: volume fraction / (8/3 pi a^3)",
              spheres.particle_volume_fraction() / (8. / 3. * pi * 1e-3),
              1. - 1e-12,
              1. + 1e-12);
  check_range("two spheres: with the flow",
              is(spheres.lubrication.coupling, Coupling::with_the_flow),
              1,
              1);

  const auto dense = scene(3, on, dense_3d);
  // The generator places whole spheres: within one sphere's volume.
  const double one_sphere = 4. / 3. * pi * 1e-3;
  check_range("generated at 0.2: volume fraction",
              dense.particle_volume_fraction(),
              0.2 - one_sphere,
              0.2 + one_sphere);
  check_range("generated at 0.2: after the solve",
              is(dense.lubrication.coupling, Coupling::after_the_solve),
              1,
              1);

  const auto step_mean =
    scene(3, on + "  set Lubrication gap in time = step mean\n", pair_3d);
  check_range("two spheres, step mean: after the solve",
              is(step_mean.lubrication.coupling, Coupling::after_the_solve),
              1,
              1);

  const auto pinned =
    scene(3, on + "  set Lubrication coupling = after the solve\n", pair_3d);
  check_range("two spheres, after the solve set: kept",
              is(pinned.lubrication.coupling, Coupling::after_the_solve),
              1,
              1);

  const auto cut = scene(2, on + "  set Model = cut finite element\n", pair_2d);
  check_range("cut element: auto kept",
              is(cut.lubrication.coupling, Coupling::automatic),
              1,
              1);

  const auto off = scene(3, "", pair_3d);
  check_range("no correction: auto kept",
              is(off.lubrication.coupling, Coupling::automatic),
              1,
              1);
  return exit_code();
}
