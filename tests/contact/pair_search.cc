// The pair search (cell list and R-tree) finds exactly the pairs with gap
// below the cut-off that a brute-force O(N^2) loop finds, in 2D and 3D, for
// polydisperse radii, several cut-offs, and a spread-out configuration where
// the cell list has to enlarge its cells.

#include "test_tools.h"

#include <algorithm>
#include <cmath>
#include <fidus/contact/pair_search.h>

using namespace Fidus::Contact;

int
main()
{
  for (const unsigned dim : {2u, 3u})
    for (const bool spread : {false, true})
      {
        TestTools::Random   random(dim + 10 * spread);
        const std::size_t   n = 1500;
        std::vector<Vec3>   x(n, Vec3{{0., 0., 0.}});
        std::vector<double> a(n);
        for (std::size_t i = 0; i < n; ++i)
          {
            for (unsigned d = 0; d < dim; ++d)
              x[i][d] = random.uniform(0., 1.);
            // A few far-away particles force large cells.
            if (spread && i % 100 == 0)
              x[i][0] = 1000. * random.uniform(0., 1.);
            a[i] = random.uniform(0.005, 0.02);
          }
        for (const double cutoff : {0., 0.003, 0.02})
          {
            std::vector<PairSearch::Pair> expected;
            for (std::uint32_t i = 0; i < n; ++i)
              for (std::uint32_t j = i + 1; j < n; ++j)
                {
                  double r2 = 0.;
                  for (unsigned d = 0; d < dim; ++d)
                    r2 += (x[j][d] - x[i][d]) * (x[j][d] - x[i][d]);
                  if (std::sqrt(r2) - a[i] - a[j] < cutoff)
                    expected.emplace_back(i, j);
                }
            for (const auto method :
                 {PairSearchMethod::cell_list, PairSearchMethod::rtree})
              {
                PairSearch                    search(dim, method);
                std::vector<PairSearch::Pair> found;
                search.find_pairs(x, a, cutoff, found);
                std::sort(found.begin(), found.end());
                TestTools::check(
                  std::to_string(dim) + "D " +
                    (spread ? "spread-out" : "compact") + ", cut-off " +
                    std::to_string(cutoff) + ", " +
                    (method == PairSearchMethod::rtree ? "R-tree" :
                                                         "cell list") +
                    ": same pairs as brute force (" +
                    (expected.size() > 100 ? "more than 100" : "few") + ")",
                  found == expected);
              }
          }
      }
  return TestTools::failures() == 0 ? 0 : 1;
}
