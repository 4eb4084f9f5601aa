#ifndef fidus_fluid_anderson_mixing_h
#define fidus_fluid_anderson_mixing_h

#include <deque>
#include <vector>

namespace Fidus
{
  /**
   * The weights of Anderson acceleration for a fixed-point iteration
   * x <- G(x), from the inner products of the residuals f_i = G(x_i) - x_i
   * alone, so that the vectors themselves stay with the caller.
   *
   * The caller keeps its last iterates x_i and residuals f_i (oldest
   * first, at most depth() + 1 of them) and tells push() the inner
   * products of each new residual with the stored ones. weights() returns
   * the alpha_i with sum alpha_i = 1 that minimise |sum alpha_i f_i|; the
   * next iterate is sum alpha_i G(x_i). For an affine G and exact
   * evaluations this is GMRES on x = G(x) over the last depth() + 1
   * residuals (Walker and Ni, SIAM J. Numer. Anal. 49, 2011), so with a
   * full history it ends in at most n + 1 iterations on an n-dimensional
   * problem; with depth 0 it is the plain iteration.
   *
   * The Uzawa loop of the fictitious domain uses it on its multiplier
   * (StokesSolver, Fluid/Uzawa acceleration depth): the iteration contracts
   * each constraint mode at its own rate, and a Krylov combination removes
   * the slow modes together instead of one factor per solve.
   */
  class AndersonMixing
  {
  public:
    /// Keep at most @p depth earlier residuals besides the newest.
    explicit AndersonMixing(unsigned int depth);

    /// The number of earlier residuals combined with the newest.
    unsigned int
    depth() const
    {
      return max_depth;
    }

    /// How many residuals are stored.
    unsigned int
    size() const
    {
      return gram.size();
    }

    /// Forget the oldest residual (the caller drops its vectors too).
    void
    drop_oldest();

    /**
     * Store a new residual f: @p products holds (f, f_i) for the stored
     * residuals, oldest first, followed by (f, f). If depth() + 1
     * residuals are stored already, drop_oldest() must be called first.
     */
    void
    push(const std::vector<double> &products);

    /**
     * The weights alpha_i of the stored iterates, oldest first, with
     * sum 1, that minimise |sum alpha_i f_i|. Differences of residuals
     * that are linearly dependent on newer ones to round-off are left out
     * of the minimisation; where nothing is left (or the products are not
     * finite), the weights are those of the plain iteration (1 on the
     * newest).
     */
    std::vector<double>
    weights() const;

    /// The norm |sum alpha_i f_i| that @p alpha gives, from the products.
    double
    combined_norm(const std::vector<double> &alpha) const;

  private:
    unsigned int max_depth;
    /// gram[i][j] = (f_i, f_j) for j <= i, oldest first.
    std::deque<std::vector<double>> gram;

    double
    product(unsigned int i, unsigned int j) const;
  };
} // namespace Fidus

#endif
