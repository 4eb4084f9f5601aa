#ifndef fidus_core_parameter_parsing_h
#define fidus_core_parameter_parsing_h

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace Fidus
{
  /**
   * Readers of entry values that the modules' parse() functions share. Each
   * throws one InputError that names the entry, its value and what is
   * allowed.
   */
  namespace ParameterParsing
  {
    /// A comma-separated list of finite numbers (empty text: none).
    std::vector<double>
    parse_numbers(const std::string &text, const std::string &entry);

    /// An entry that is 'auto' (then @p auto_value) or one number for which
    /// @p valid holds (any number if it is empty).
    double
    number_or_auto(const std::string                 &value,
                   const std::string                 &entry,
                   const double                       auto_value,
                   const std::string                 &allowed,
                   const std::function<bool(double)> &valid = {});

    /// Throw unless @p value > 0 (and not NaN), naming @p entry (its full
    /// path, e.g. 'Fluid/Viscosity').
    void
    require_positive(const double value, const std::string &entry);

    /// A point with exactly @p dim coordinates; the unused ones are zero.
    std::array<double, 3>
    parse_point(const std::string &text,
                const std::string &entry,
                const unsigned int dim);
  } // namespace ParameterParsing
} // namespace Fidus

#endif
