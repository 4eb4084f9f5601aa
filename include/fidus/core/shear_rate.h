#ifndef fidus_core_shear_rate_h
#define fidus_core_shear_rate_h

#include <memory>
#include <string>

namespace dealii
{
  template <int dim>
  class FunctionParser;
}

namespace Fidus
{
  /**
   * The shear rate as a function of time, gamma_dot(t), parsed from the
   * 'Domain/Shear rate' expression. A reversed or oscillatory shear is the
   * same code path as a steady one.
   */
  class ShearRate
  {
  public:
    /// Parse @p expression (muparser syntax, variable t).
    explicit ShearRate(const std::string &expression);
    ~ShearRate();

    /// Value at time @p t.
    double
    operator()(const double t) const;

  private:
    std::unique_ptr<dealii::FunctionParser<1>> parser;
  };
} // namespace Fidus

#endif
