#ifndef fidus_contact_vector_operations_h
#define fidus_contact_vector_operations_h

#include <cmath>
#include <fidus/contact/contact_types.h>

namespace Fidus::Contact
{
  /// Scalar product of two Vec3.
  inline double
  dot(const Vec3 &x, const Vec3 &y)
  {
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
  }

  /// Cross product of two Vec3.
  inline Vec3
  cross(const Vec3 &x, const Vec3 &y)
  {
    return Vec3{{x[1] * y[2] - x[2] * y[1],
                 x[2] * y[0] - x[0] * y[2],
                 x[0] * y[1] - x[1] * y[0]}};
  }

  /// Euclidean length of a Vec3.
  inline double
  norm(const Vec3 &x)
  {
    return std::sqrt(dot(x, x));
  }
} // namespace Fidus::Contact

#endif
