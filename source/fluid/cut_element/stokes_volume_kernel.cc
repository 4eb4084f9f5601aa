#include <Eigen/Core>
#include <cmath>
#include <fidus/fluid/cut_element/stokes_volume_kernel.h>

namespace Fidus
{
  template <int dim>
  void
  StokesVolumeKernel<dim>::add(const FEValues<dim> &fe_values,
                               const double         eta,
                               FullMatrix<double>  &local,
                               FullMatrix<double>  &local_pressure)
  {
    using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic>;
    using Map    = Eigen::Map<Matrix>;
    const auto        &velocity = layout.velocity;
    const auto        &pressure = layout.pressure;
    const unsigned int n_s = velocity[0].size(), n_g = dim * n_s,
                       n_p = pressure.size(),
                       n_q = fe_values.n_quadrature_points;
    g.resize(std::size_t(n_g) * n_q);
    q.resize(std::size_t(n_p) * n_q);
    ggt.resize(std::size_t(n_g) * n_g);
    gqt.resize(std::size_t(n_g) * n_p);
    qqt.resize(std::size_t(n_p) * n_p);
    // Column q of G: the derivatives ∂_d φ_k at point q (row d n_s + k),
    // of Q the pressures, both times √JxW.
    for (unsigned int p = 0; p < n_q; ++p)
      {
        const double w  = std::sqrt(fe_values.JxW(p));
        double      *gp = &g[std::size_t(p) * n_g];
        for (unsigned int k = 0; k < n_s; ++k)
          {
            const Tensor<1, dim> grad = fe_values.shape_grad(velocity[0][k], p);
            for (unsigned int d = 0; d < dim; ++d)
              gp[d * n_s + k] = w * grad[d];
          }
        double *qp = &q[std::size_t(p) * n_p];
        for (unsigned int a = 0; a < n_p; ++a)
          qp[a] = w * fe_values.shape_value(pressure[a], p);
      }
    const Map G(g.data(), n_g, n_q), Q(q.data(), n_p, n_q);
    Map       GGt(ggt.data(), n_g, n_g), GQt(gqt.data(), n_g, n_p),
      QQt(qqt.data(), n_p, n_p);
    GGt.setZero();
    GGt.template selfadjointView<Eigen::Lower>().rankUpdate(G);
    GQt.noalias() = G * Q.transpose();
    QQt.noalias() = Q * Q.transpose();
    // G Gᵀ's entry (d n_s + k, c n_s + l) is ∫ ∂_d φ_k ∂_c φ_l; only its
    // lower triangle is formed.
    const auto z = [&](const unsigned int r, const unsigned int s) {
      return r >= s ? GGt(r, s) : GGt(s, r);
    };
    for (unsigned int c = 0; c < dim; ++c)
      for (unsigned int k = 0; k < n_s; ++k)
        {
          const unsigned int i = velocity[c][k];
          for (unsigned int d = 0; d < dim; ++d)
            for (unsigned int l = 0; l < n_s; ++l)
              {
                double value = z(d * n_s + k, c * n_s + l);
                if (c == d)
                  for (unsigned int e = 0; e < dim; ++e)
                    value += z(e * n_s + k, e * n_s + l);
                local(i, velocity[d][l]) += eta * value;
              }
          for (unsigned int a = 0; a < n_p; ++a)
            {
              const double coupling = GQt(c * n_s + k, a);
              local(i, pressure[a]) -= coupling;
              local(pressure[a], i) -= coupling;
            }
        }
    for (unsigned int a = 0; a < n_p; ++a)
      for (unsigned int b = 0; b < n_p; ++b)
        local_pressure(a, b) += QQt(a, b) / eta;
  }



  template class StokesVolumeKernel<2>;
  template class StokesVolumeKernel<3>;
} // namespace Fidus
