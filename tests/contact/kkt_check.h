// Shared by the contact tests: an independent check of the KKT conditions of
// one projection (validation case 6), written from the definitions in
// numerics section 3 and not from the solver's own residual.
#ifndef fidus_tests_contact_kkt_check_h
#define fidus_tests_contact_kkt_check_h

#include <algorithm>
#include <cmath>
#include <fidus/contact/contact_projector.h>
#include <vector>

namespace KKT
{
  using namespace Fidus::Contact;

  /// Largest errors found in the KKT conditions of one projection.
  struct Errors
  {
    double stationarity    = 0.; ///< |u - u* - W^{-1} G^T lambda| * dt
    double sign            = 0.; ///< max(-lambda, 0) * dt on unglued rows
    double feasibility     = 0.; ///< max(-(D + dt G u), 0) on unglued rows
    double complementarity = 0.; ///< min(dt lambda/w_ab, D + dt G u) on unglued
    double equality        = 0.; ///< |D + dt G u| on glued rows
    double glue_flag       = 0.; ///< 1 if a row is glued iff gamma < 0 fails
    unsigned int n_glued_rows   = 0;
    unsigned int n_unglued_rows = 0;

    double
    worst() const
    {
      return std::max({stationarity,
                       sign,
                       feasibility,
                       complementarity,
                       equality,
                       glue_flag});
    }

    void
    merge(const Errors &o)
    {
      stationarity    = std::max(stationarity, o.stationarity);
      sign            = std::max(sign, o.sign);
      feasibility     = std::max(feasibility, o.feasibility);
      complementarity = std::max(complementarity, o.complementarity);
      equality        = std::max(equality, o.equality);
      glue_flag       = std::max(glue_flag, o.glue_flag);
      n_glued_rows += o.n_glued_rows;
      n_unglued_rows += o.n_unglued_rows;
    }
  };

  /**
   * Check the last projection of @p projector: @p predicted went in,
   * @p corrected came out, with walls @p walls and weights @p weights (empty:
   * all 1). Length units throughout (velocities times dt).
   */
  inline Errors
  check(const ContactProjector    &projector,
        const std::vector<Wall>   &walls,
        const std::vector<double> &weights,
        const std::vector<Vec3>   &predicted,
        const std::vector<Vec3>   &corrected,
        const double               dt)
  {
    const auto         &rows = projector.constraints();
    const unsigned      dim  = projector.get_settings().dimension;
    const std::size_t   n    = predicted.size();
    std::vector<Vec3>   u(n + walls.size(), Vec3{{0., 0., 0.}});
    std::vector<double> inv_w(n + walls.size(), 0.);
    for (std::size_t i = 0; i < n; ++i)
      {
        inv_w[i] = weights.empty() ? 1. : 1. / weights[i];
        for (unsigned d = 0; d < dim; ++d)
          u[i][d] = corrected[i][d];
      }
    for (std::size_t w = 0; w < walls.size(); ++w)
      for (unsigned d = 0; d < dim; ++d)
        u[n + w][d] = walls[w].velocity[d];

    Errors            errors;
    std::vector<Vec3> gt_lambda(n + walls.size(), Vec3{{0., 0., 0.}});
    for (std::size_t k = 0; k < rows.size(); ++k)
      {
        const auto   a = rows.first(k), b = rows.second(k);
        const Vec3  &e = rows.normal(k);
        const double l = rows.lambda(k);
        double       g = rows.gap(k);
        for (unsigned d = 0; d < 3; ++d)
          {
            gt_lambda[a][d] -= l * e[d];
            gt_lambda[b][d] += l * e[d];
            g += dt * (u[b][d] - u[a][d]) * e[d];
          }
        if ((rows.gamma(k) < 0.) != rows.glued(k))
          errors.glue_flag = 1.;
        if (rows.glued(k))
          {
            ++errors.n_glued_rows;
            errors.equality = std::max(errors.equality, std::abs(g));
          }
        else
          {
            ++errors.n_unglued_rows;
            errors.sign        = std::max(errors.sign, -l * dt);
            errors.feasibility = std::max(errors.feasibility, -g);
            const double push  = dt * l * (inv_w[a] + inv_w[b]);
            errors.complementarity =
              std::max(errors.complementarity, std::min(push, g));
          }
      }
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned d = 0; d < dim; ++d)
        errors.stationarity =
          std::max(errors.stationarity,
                   dt * std::abs(corrected[i][d] - predicted[i][d] -
                                 inv_w[i] * gt_lambda[i][d]));
    return errors;
  }
} // namespace KKT

#endif
