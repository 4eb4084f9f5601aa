#ifndef fidus_contact_step_mean_resistance_h
#define fidus_contact_step_mean_resistance_h

#include <cstddef>
#include <vector>

namespace Fidus::Contact
{
  struct LubricationBond;

  /**
   * The squeeze resistance of lubrication bonds averaged over the gaps one
   * time step passes through (LubricationSettings::gap_in_time).
   *
   * The explicit step takes a bond's resistance at its gap at the start
   * of the step. A pair pushed with a steady drive D closes in the time
   * T(h_1) = (zeta (h_0 - h_1) + 2 int_{h_1}^{h_0} R dh) / (2 D), so an
   * explicit step lands exactly where the squeeze equation does if the
   * resistance is the mean of R over [h_1, h_0]. The end gap h_1 depends
   * on that mean through the corrected velocities, so it is found by a
   * few solves of the correction's system: for each bond, G(h) = h_0 -
   * dt w(h) - h, w the closing speed solved with the mean over [h, h_0],
   * falls with h; the tries are the plain update h_0 - dt w until two of
   * them bracket the root, then regula falsi.
   */
  class StepMeanResistance
  {
  public:
    /**
     * For @p bonds (their gaps at the start of the step) in @p dimension
     * dimensions with viscosity @p viscosity, gaps floored at @p roughness
     * times the smaller radius (the radius for a wall). With
     * @p closing_only, a bond whose gap opens keeps the start's resistance.
     */
    StepMeanResistance(const std::vector<LubricationBond> &bonds,
                       unsigned int                        dimension,
                       double                              viscosity,
                       double                              roughness,
                       bool                                closing_only);

    /**
     * Bond @p k (of the constructor's list, @p b the same bond) reached the
     * gap @p reached in the last solve: the resistance of its next try.
     */
    double
    next_resistance(std::size_t k, const LubricationBond &b, double reached);

    /// The largest change of a try in the last round of next_resistance(),
    /// relative to the bond's start gap (at least its roughness gap); resets
    /// it for the next round.
    double
    take_largest_change();

    /**
     * The mean of the squeeze resistance of bond @p b over the gaps between
     * @p h0 and @p h1, the gap floored at @p roughness_gap.
     */
    static double
    mean(const LubricationBond &b,
         unsigned int           dimension,
         double                 viscosity,
         double                 roughness_gap,
         double                 h0,
         double                 h1);

  private:
    unsigned int        dimension;
    double              viscosity;
    bool                closing_only;
    double              largest_change = 0.;
    std::vector<double> h_try, lo, hi, g_lo, g_hi, rough;
  };
} // namespace Fidus::Contact

#endif
