#include <cmath>
#include <fidus/fluid/fictitious_domain/anderson_mixing.h>
#include <stdexcept>

namespace Fidus
{
  AndersonMixing::AndersonMixing(const unsigned int depth)
    : max_depth(depth)
  {}



  void
  AndersonMixing::drop_oldest()
  {
    if (gram.empty())
      return;
    gram.pop_front();
    // Row i held the products with the residuals 0..i; the oldest is gone.
    for (auto &row : gram)
      row.erase(row.begin());
  }



  void
  AndersonMixing::push(const std::vector<double> &products)
  {
    if (products.size() != gram.size() + 1)
      throw std::logic_error("AndersonMixing::push: one product per stored "
                             "residual plus the new one's norm expected");
    if (gram.size() == max_depth + 1)
      throw std::logic_error("AndersonMixing::push: history full, call "
                             "drop_oldest() first");
    gram.push_back(products);
  }



  double
  AndersonMixing::product(const unsigned int i, const unsigned int j) const
  {
    return i >= j ? gram[i][j] : gram[j][i];
  }



  std::vector<double>
  AndersonMixing::weights() const
  {
    const unsigned int  n = gram.size();
    std::vector<double> alpha(n, 0.);
    if (n == 0)
      return alpha;
    alpha.back() = 1.;
    if (n == 1)
      return alpha;

    // Minimise |f_new - sum_j gamma_j d_j| over gamma, with the differences
    // d_j = f_(j+1) - f_j (j < n - 1), by the normal equations
    // (d_i, d_j) gamma_j = (d_i, f_new). Near convergence the residuals
    // become nearly dependent; rather than a shift, which bounds how small
    // the combination can get, a difference that adds less than 1e-12 of
    // its own square norm to the span of the newer ones is left out (its
    // gamma is zero). Cholesky factorisation over the kept differences,
    // newest first.
    const unsigned int m    = n - 1;
    auto               diff = [&](const unsigned int i, const unsigned int j) {
      return product(i + 1, j + 1) - product(i + 1, j) - product(i, j + 1) +
             product(i, j);
    };
    std::vector<unsigned int>        kept;
    std::vector<std::vector<double>> l; // rows of L over the kept ones
    for (unsigned int c = m; c-- > 0;)
      {
        std::vector<double> row(kept.size() + 1, 0.);
        for (unsigned int a = 0; a < kept.size(); ++a)
          {
            double v = diff(c, kept[a]);
            for (unsigned int b = 0; b < a; ++b)
              v -= row[b] * l[a][b];
            row[a] = v / l[a][a];
          }
        double       pivot = diff(c, c);
        const double own   = pivot;
        for (unsigned int b = 0; b < kept.size(); ++b)
          pivot -= row[b] * row[b];
        if (!(own > 0.) || !std::isfinite(own) || !(pivot > 1e-12 * own))
          continue;
        row.back() = std::sqrt(pivot);
        kept.push_back(c);
        l.push_back(row);
      }
    if (kept.empty())
      return alpha;
    // Solve L L^T gamma = (d_kept, f_new).
    const unsigned int  k = kept.size();
    std::vector<double> gamma(k);
    for (unsigned int a = 0; a < k; ++a)
      {
        const unsigned int c = kept[a];
        gamma[a]             = product(n - 1, c + 1) - product(n - 1, c);
        for (unsigned int b = 0; b < a; ++b)
          gamma[a] -= l[a][b] * gamma[b];
        gamma[a] /= l[a][a];
      }
    for (unsigned int a = k; a-- > 0;)
      {
        for (unsigned int b = a + 1; b < k; ++b)
          gamma[a] -= l[b][a] * gamma[b];
        gamma[a] /= l[a][a];
      }
    // f_new - sum gamma_c (f_(c+1) - f_c) = sum alpha_i f_i.
    for (unsigned int a = 0; a < k; ++a)
      {
        if (!std::isfinite(gamma[a]))
          {
            std::fill(alpha.begin(), alpha.end(), 0.);
            alpha.back() = 1.;
            return alpha;
          }
        alpha[kept[a]] += gamma[a];
        alpha[kept[a] + 1] -= gamma[a];
      }
    return alpha;
  }



  double
  AndersonMixing::combined_norm(const std::vector<double> &alpha) const
  {
    double s = 0.;
    for (unsigned int i = 0; i < gram.size(); ++i)
      for (unsigned int j = 0; j < gram.size(); ++j)
        s += alpha[i] * alpha[j] * product(i, j);
    return std::sqrt(std::max(s, 0.));
  }
} // namespace Fidus
