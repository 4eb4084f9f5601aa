#ifndef fidus_mesh_domain_parameters_h
#define fidus_mesh_domain_parameters_h

#include <array>
#include <string>

namespace dealii
{
  class ParameterHandler;
}

namespace Fidus
{
  /// Velocity imposed on the box (Domain/Boundary condition).
  enum class BoundaryCondition
  {
    linear_shear,
    sliding_walls,
    cavity,
    exact_rigid_inclusion
  };

  /**
   * The box, its boundary condition and the shear rate: the entries of the
   * subsection Domain. Vectors always have three components; the third is
   * zero in 2D.
   */
  struct DomainParameters
  {
    /// Register the entries of the subsection Domain.
    static void
    declare(dealii::ParameterHandler &prm);

    /// Read them back for a scene in @p dim dimensions.
    void
    parse(dealii::ParameterHandler &prm, const unsigned int dim);

    /// Throw an InputError if the box is empty in one of its @p dim
    /// directions or the shear rate is not a valid expression in t.
    void
    check(const unsigned int dim) const;

    std::array<double, 3> lower_left         = {{0., 0., 0.}};
    std::array<double, 3> upper_right        = {{1., 1., 1.}};
    BoundaryCondition     boundary_condition = BoundaryCondition::linear_shear;
    /// Shear rate as a muparser expression in t.
    std::string shear_rate = "1";
  };
} // namespace Fidus

#endif
