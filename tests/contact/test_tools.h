// Small helpers shared by the contact tests: a portable random generator
// (std::uniform_real_distribution is implementation-defined, so outputs
// would differ between standard libraries) and OK/FAILED reporting.
#ifndef fidus_tests_contact_test_tools_h
#define fidus_tests_contact_test_tools_h

#include <cmath>
#include <cstdint>
#include <fidus/contact/contact_error.h>
#include <fidus/contact/contact_types.h>
#include <iostream>
#include <string>
#include <vector>

namespace TestTools
{
  using Fidus::Contact::Vec3;

  /// xorshift64*: the same sequence everywhere.
  class Random
  {
  public:
    explicit Random(std::uint64_t seed)
      : state(seed * 2685821657736338717ull + 1)
    {}

    /// Uniform in [lo, hi).
    double
    uniform(double lo = 0., double hi = 1.)
    {
      state ^= state >> 12;
      state ^= state << 25;
      state ^= state >> 27;
      const std::uint64_t r = state * 2685821657736338717ull;
      return lo + (hi - lo) * static_cast<double>(r >> 11) * 0x1.0p-53;
    }

  private:
    std::uint64_t state;
  };

  /// Counts failed checks; main() returns failures() != 0.
  inline int &
  failures()
  {
    static int n = 0;
    return n;
  }

  /// Print "<what>: OK" or "<what>: FAILED" and count failures.
  inline bool
  check(const std::string &what, const bool ok)
  {
    std::cout << what << ": " << (ok ? "OK" : "FAILED") << std::endl;
    if (!ok)
      ++failures();
    return ok;
  }

  /**
   * Random sequential addition of n non-overlapping particles with radii in
   * [a_min, a_max] in the box [lo, hi]^dim (z = 0 in 2D), keeping @p margin
   * from the box faces. Cheap enough for a few thousand particles (uses a
   * coarse grid to test overlaps).
   */
  inline void
  random_packing(Random              &random,
                 const unsigned       dim,
                 const std::size_t    n,
                 const double         a_min,
                 const double         a_max,
                 const double         lo,
                 const double         hi,
                 const double         margin,
                 std::vector<Vec3>   &x,
                 std::vector<double> &a)
  {
    x.clear();
    a.clear();
    const double h  = 2. * a_max;
    const int    nc = std::max(1, static_cast<int>((hi - lo) / h));
    std::vector<std::vector<std::size_t>> cells(dim == 2 ? nc * nc :
                                                           nc * nc * nc);
    auto                                  cell = [&](const double c) {
      return std::min(nc - 1, std::max(0, static_cast<int>((c - lo) / h)));
    };
    std::size_t attempts = 0;
    while (x.size() < n)
      {
        if (++attempts > 1000 * n)
          throw std::runtime_error("random_packing: too dense");
        const double r = random.uniform(a_min, a_max);
        Vec3         p{{0., 0., 0.}};
        for (unsigned d = 0; d < dim; ++d)
          p[d] = random.uniform(lo + r + margin, hi - r - margin);
        const int cx = cell(p[0]), cy = cell(p[1]),
                  cz = dim == 3 ? cell(p[2]) : 0;
        bool free    = true;
        for (int dz = (dim == 3 ? -1 : 0); dz <= (dim == 3 ? 1 : 0) && free;
             ++dz)
          for (int dy = -1; dy <= 1 && free; ++dy)
            for (int dx = -1; dx <= 1 && free; ++dx)
              {
                const int ix = cx + dx, iy = cy + dy, iz = cz + dz;
                if (ix < 0 || iy < 0 || iz < 0 || ix >= nc || iy >= nc ||
                    iz >= nc)
                  continue;
                for (const auto j : cells[ix + nc * (iy + nc * iz)])
                  {
                    double r2 = 0.;
                    for (unsigned d = 0; d < dim; ++d)
                      r2 += (x[j][d] - p[d]) * (x[j][d] - p[d]);
                    if (r2 < (r + a[j]) * (r + a[j]))
                      {
                        free = false;
                        break;
                      }
                  }
              }
        if (!free)
          continue;
        cells[cx + nc * (cy + nc * cz)].push_back(x.size());
        x.push_back(p);
        a.push_back(r);
      }
  }
  /// Run @p f, expect a ContactError whose message contains all @p parts.
  template <typename F>
  void
  expect_error(const std::string              &what,
               F                               f,
               const std::vector<std::string> &parts)
  {
    std::string message;
    bool        thrown = false;
    try
      {
        f();
      }
    catch (const Fidus::Contact::ContactError &e)
      {
        thrown  = true;
        message = e.what();
      }
    bool ok = thrown;
    for (const auto &p : parts)
      ok = ok && message.find(p) != std::string::npos;
    check(what, ok);
    if (!ok)
      std::cout << "  message was: '" << message << "'" << std::endl;
  }
} // namespace TestTools

#endif
