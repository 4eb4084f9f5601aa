#include <deal.II/base/function_parser.h>
#include <fidus/core/shear_rate.h>

namespace Fidus
{
  ShearRate::ShearRate(const std::string &expression)
    : parser(std::make_unique<dealii::FunctionParser<1>>(1))
  {
    parser->initialize("x,t", expression, {}, true);
  }

  ShearRate::~ShearRate() = default;

  double
  ShearRate::operator()(const double t) const
  {
    parser->set_time(t);
    return parser->value(dealii::Point<1>());
  }
} // namespace Fidus
