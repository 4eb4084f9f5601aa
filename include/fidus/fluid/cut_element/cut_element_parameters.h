#ifndef fidus_fluid_cut_element_cut_element_parameters_h
#define fidus_fluid_cut_element_cut_element_parameters_h

#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace Fidus
{
  struct Parameters;

  /**
   * The cut finite element's own entries (subsection Fluid, names beginning
   * with 'Cut'), and what the model needs of the rest of the scene.
   */
  struct CutElementParameters
  {
    /// Register Fluid/Cut linear solver, Cut minimum gap, Cut gap cells,
    /// Cut Nitsche parameter, Cut velocity and pressure ghost penalty.
    static void
    declare(dealii::ParameterHandler &prm);

    /// Read them back.
    void
    parse(dealii::ParameterHandler &prm);

    /// Throw an InputError for what 'Fluid/Model = cut finite element'
    /// cannot do with the scene @p scene (its box, boundary condition,
    /// lubrication correction, field output), or a minimum gap or Nitsche
    /// parameter that is not positive.
    void
    check(const Parameters &scene) const;

    /// Throw an InputError naming the first Cut entry set away from its
    /// default, for a scene whose fluid model @p model does not read them.
    void
    check_unused(const std::string &model) const;

    /// Whether the solves are direct in @p dimension D on this run's ranks:
    /// 'direct', or 'auto' in 2D or on more than one MPI rank.
    bool
    direct_solver(unsigned int dimension) const;

    /// The minimum gap that 'auto' gives with Fluid/Lubrication correction
    /// (doc/theory/lubrication.md, "With the cut finite element").
    static constexpr double corrected_minimum_gap = 0.02;

    /// The cells across a thin gap that 'auto' gives without and with
    /// Fluid/Lubrication correction (doc/theory/lubrication.md, "With the
    /// cut finite element").
    static constexpr double resolved_gap_cells  = 2.;
    static constexpr double corrected_gap_cells = 1.;

    /// The fluid sees every gap at least this times the smaller radius
    /// (wall gaps: the radius).
    double minimum_gap = 1e-4;
    /// The Cut entries set away from their defaults.
    std::vector<std::string> entries_set;
    /// The Fluid/Lubrication ranges that are not auto (with the cut
    /// element the correction takes its ranges from minimum_gap).
    std::vector<std::string> ranges_set;
    /// Cells across a thin gap.
    double gap_cells = resolved_gap_cells;
    /// auto (or automatic), direct or iterative.
    std::string linear_solver = "automatic";
    /// Nitsche's penalty, times eta / h (CutStokesInclusion::Settings).
    double nitsche = 100.;
    /// The ghost penalties of the velocity and the pressure.
    double ghost_velocity = 1e-3, ghost_pressure = 1e-3;
    /// Where the iterative solver starts: 'previous solve' or 'zero'.
    std::string initial_guess = "previous solve";
    /// FGMRES stops at this residual relative to the right-hand side
    /// (CutStokesInclusion::Settings::iterative_tolerance; 1e-8 leaves the
    /// velocities within a few 1e-6 of 1e-11's, for a quarter fewer
    /// iterations than 1e-10: doc/theory/cut_element.md, "Solvers").
    double linear_tolerance = 1e-8;
  };
} // namespace Fidus

#endif
