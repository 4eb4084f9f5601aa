// The entries of the subsection Domain.

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <fidus/core/input_error.h>
#include <fidus/core/parameter_parsing.h>
#include <fidus/mesh/domain_parameters.h>
#include <iostream>
#include <sstream>

namespace Fidus
{
  using namespace dealii;

  void
  DomainParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Domain");
    prm.declare_entry("Lower left",
                      "0, 0",
                      Patterns::Anything(),
                      "Lower-left corner of the box [length], one "
                      "coordinate per dimension, comma separated.");
    prm.declare_entry("Upper right",
                      "1, 1",
                      Patterns::Anything(),
                      "Upper-right corner of the box [length], one "
                      "coordinate per dimension; each larger than the "
                      "lower-left one.");
    prm.declare_entry(
      "Boundary condition",
      "linear shear",
      Patterns::Selection(
        "linear shear|sliding walls|cavity|exact rigid inclusion"),
      "Velocity imposed on the box. 'linear shear': u = shear rate * "
      "(y - y_mid) e_x on every face. 'sliding walls': the faces y = "
      "y_min and y = y_max move at -/+ shear rate * H/2 e_x, the other "
      "directions are periodic. 'cavity': the same moving walls, the "
      "other faces at rest. 'exact rigid inclusion': verification scene "
      "with one particle and the exact solution of a torque-free rigid "
      "particle in linear shear imposed on the box; error norms are "
      "reported.");
    prm.declare_entry("Shear rate",
                      "1",
                      Patterns::Anything(),
                      "Shear rate [1/time] as a function of the time t "
                      "(muparser syntax), e.g. 't < 10 ? 1 : -1' for a "
                      "reversal at t = 10.");
    prm.leave_subsection();
  }



  void
  DomainParameters::parse(ParameterHandler &prm, const unsigned int dim)
  {
    prm.enter_subsection("Domain");
    {
      lower_left  = ParameterParsing::parse_point(prm.get("Lower left"),
                                                 "Domain/Lower left",
                                                 dim);
      upper_right = ParameterParsing::parse_point(prm.get("Upper right"),
                                                  "Domain/Upper right",
                                                  dim);
      const std::string bc = prm.get("Boundary condition");
      boundary_condition =
        bc == "linear shear"  ? BoundaryCondition::linear_shear :
        bc == "sliding walls" ? BoundaryCondition::sliding_walls :
        bc == "cavity"        ? BoundaryCondition::cavity :
                                BoundaryCondition::exact_rigid_inclusion;
      shear_rate = prm.get("Shear rate");
    }
    prm.leave_subsection();
  }



  void
  DomainParameters::check(const unsigned int dim) const
  {
    const char axis[3] = {'x', 'y', 'z'};
    for (unsigned int d = 0; d < dim; ++d)
      if (!(upper_right[d] > lower_left[d]))
        throw InputError(std::string("entries 'Domain/Lower left' and "
                                     "'Domain/Upper right' give an empty "
                                     "box in ") +
                         axis[d] + ": " + std::to_string(lower_left[d]) +
                         " >= " + std::to_string(upper_right[d]) +
                         "; allowed: lower < upper in every direction");

    // The parser reports syntax errors on std::cerr itself; silence it so
    // that the user sees one message only.
    std::ostringstream    swallowed;
    std::streambuf *const cerr_buffer = std::cerr.rdbuf(swallowed.rdbuf());
    struct RestoreCerr
    {
      std::streambuf *buffer;
      ~RestoreCerr()
      {
        std::cerr.rdbuf(buffer);
      }
    } restore{cerr_buffer};
    try
      {
        FunctionParser<1> f(1);
        f.initialize("x,t", shear_rate, {}, true);
        f.set_time(0.);
        const double v = f.value(Point<1>());
        (void)v;
      }
    catch (...)
      {
        throw InputError("entry 'Domain/Shear rate' has the value '" +
                         shear_rate +
                         "', which is not a valid expression; allowed: a "
                         "muparser expression in t, e.g. 't < 10 ? 1 : -1'");
      }
  }
} // namespace Fidus
