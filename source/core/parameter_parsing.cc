#include <algorithm>
#include <cmath>
#include <deal.II/base/utilities.h>
#include <fidus/core/input_error.h>
#include <fidus/core/parameter_parsing.h>

namespace Fidus::ParameterParsing
{
  using namespace dealii;

  std::vector<double>
  parse_numbers(const std::string &text, const std::string &entry)
  {
    std::vector<double> values;
    for (const std::string &item : Utilities::split_string_list(text, ','))
      {
        if (item.empty())
          continue;
        std::size_t end = 0;
        double      v   = 0;
        try
          {
            v = std::stod(item, &end);
          }
        catch (...)
          {
            end = 0;
          }
        if (end != item.size() || !std::isfinite(v))
          throw InputError("entry '" + entry + "' has the value '" + text +
                           "': '" + item +
                           "' is not a finite number; allowed: a "
                           "comma-separated list of numbers");
        values.push_back(v);
      }
    return values;
  }



  double
  number_or_auto(const std::string                 &value,
                 const std::string                 &entry,
                 const double                       auto_value,
                 const std::string                 &allowed,
                 const std::function<bool(double)> &valid)
  {
    const std::string text = Utilities::trim(value);
    if (text == "auto")
      return auto_value;
    std::vector<double> v;
    try
      {
        v = parse_numbers(text, entry);
      }
    catch (const InputError &)
      {
        v.clear();
      }
    if (v.size() != 1 || (valid && !valid(v[0])))
      throw InputError("entry '" + entry + "' has the value '" + text +
                       "'; allowed: " + allowed);
    return v[0];
  }



  void
  require_positive(const double value, const std::string &entry)
  {
    if (!(value > 0.))
      throw InputError("entry '" + entry + "' has the value " +
                       std::to_string(value) + "; allowed: a value > 0");
  }



  std::array<double, 3>
  parse_point(const std::string &text,
              const std::string &entry,
              const unsigned int dim)
  {
    const std::vector<double> v = parse_numbers(text, entry);
    if (v.size() != dim)
      throw InputError("entry '" + entry + "' has the value '" + text +
                       "' with " + std::to_string(v.size()) +
                       " coordinates; allowed: exactly " + std::to_string(dim) +
                       " coordinates (Dimension = " + std::to_string(dim) +
                       ")");
    std::array<double, 3> x = {{0., 0., 0.}};
    std::copy(v.begin(), v.end(), x.begin());
    return x;
  }
} // namespace Fidus::ParameterParsing
