#include <algorithm>
#include <cmath>
#include <fidus/fluid/fictitious_domain/solid_indicator.h>

namespace Fidus
{
  namespace
  {
    /**
     * Calls @p f for every bin index vector b with lo <= b <= hi
     * (componentwise), the first coordinate running fastest. Used both to
     * file a particle into the bins it overlaps and to collect the
     * particles near a point.
     */
    template <int dim, typename F>
    void
    for_each_bin(const std::array<int, dim> &lo,
                 const std::array<int, dim> &hi,
                 const F                    &f)
    {
      std::array<int, dim> b = lo;
      while (true)
        {
          f(b);
          unsigned int d = 0;
          for (; d < dim; ++d)
            {
              if (++b[d] <= hi[d])
                break;
              b[d] = lo[d];
            }
          if (d == dim)
            return;
        }
    }
  } // namespace


  template <int dim>
  void
  SolidIndicator<dim>::reinit(const std::vector<std::array<double, 3>> &pos,
                              const std::vector<double>                &r,
                              const Point<dim>            &lower_left,
                              const Point<dim>            &upper_right,
                              const std::array<bool, dim> &periodic,
                              const double                 halo)
  {
    n_real = pos.size();
    centers.resize(pos.size());
    for (unsigned int i = 0; i < pos.size(); ++i)
      for (unsigned int d = 0; d < dim; ++d)
        centers[i][d] = pos[i][d];
    radii = r;

    // Periodic images: shift every particle that crosses a periodic face,
    // or comes within the halo of it, by the period, in each direction and
    // in each combination of directions (a particle in a corner has 3
    // images in 2D, up to 7 in 3D).
    image_owner.clear();
    for (unsigned int i = 0; i < n_real; ++i)
      {
        // Per periodic axis, which shifts (by -L, +L) bring an image within
        // reach of the box: +L when the particle (grown by the halo) reaches
        // over the lower face, -L over the upper one; both when the halo is
        // wider than the box.
        std::array<std::array<bool, 2>, dim> shift;
        bool                                 any = false;
        for (unsigned int d = 0; d < dim; ++d)
          {
            shift[d] = {{false, false}};
            if (!periodic[d])
              continue;
            // A smoothed solid reaches w/2 beyond the surface.
            const double reach = radii[i] + 0.5 * smoothing + halo;
            shift[d][0]        = centers[i][d] + reach > upper_right[d];
            shift[d][1]        = centers[i][d] - reach < lower_left[d];
            any                = any || shift[d][0] || shift[d][1];
          }
        if (!any)
          continue;
        // Every combination of an offset in {-1, 0, +1} per axis, but the
        // particle itself (3^dim - 1 candidates).
        std::array<int, dim> offset;
        std::fill(offset.begin(), offset.end(), -1);
        while (true)
          {
            bool valid = false, allowed = true;
            for (unsigned int d = 0; d < dim; ++d)
              if (offset[d] != 0)
                {
                  valid = true;
                  if (!shift[d][offset[d] > 0 ? 1 : 0])
                    allowed = false;
                }
            if (valid && allowed)
              {
                Point<dim> c = centers[i];
                for (unsigned int d = 0; d < dim; ++d)
                  c[d] += offset[d] * (upper_right[d] - lower_left[d]);
                centers.push_back(c);
                radii.push_back(radii[i]);
                image_owner.push_back(i);
              }
            unsigned int d = 0;
            for (; d < dim; ++d)
              {
                if (++offset[d] <= 1)
                  break;
                offset[d] = -1;
              }
            if (d == dim)
              break;
          }
      }

    double max_r = 0;
    for (const double a : radii)
      max_r = std::max(max_r, a);
    largest_radius = max_r;
    double extent  = 0;
    for (unsigned int d = 0; d < dim; ++d)
      extent = std::max(extent, upper_right[d] - lower_left[d]);
    // Bins of about one diameter, but never more than ~1e6 bins in all.
    const double max_bins_per_dir = dim == 2 ? 1000. : 100.;
    bin_size = std::max(2. * max_r + smoothing, extent / max_bins_per_dir);
    if (!(bin_size > 0))
      bin_size = extent;
    origin            = lower_left;
    std::size_t total = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        n_bins[d] =
          std::max(1,
                   int(std::ceil((upper_right[d] - lower_left[d]) / bin_size)));
        total *= n_bins[d];
      }
    bins.assign(total, {});
    for (unsigned int i = 0; i < centers.size(); ++i)
      {
        std::array<int, dim> lo, hi;
        const double         reach = radii[i] + 0.5 * smoothing;
        for (unsigned int d = 0; d < dim; ++d)
          {
            lo[d] = std::clamp(
              int(std::floor((centers[i][d] - reach - origin[d]) / bin_size)),
              0,
              n_bins[d] - 1);
            hi[d] = std::clamp(
              int(std::floor((centers[i][d] + reach - origin[d]) / bin_size)),
              0,
              n_bins[d] - 1);
          }
        for_each_bin<dim>(lo, hi, [&](const std::array<int, dim> &b) {
          bins[bin_index(b)].push_back(i);
        });
      }
  }



  template <int dim>
  unsigned int
  SolidIndicator<dim>::bin_index(const std::array<int, dim> &b) const
  {
    unsigned int index = 0;
    for (int d = dim - 1; d >= 0; --d)
      index = index * n_bins[d] + b[d];
    return index;
  }



  template <int dim>
  void
  SolidIndicator<dim>::candidates(const Point<dim>          &x,
                                  const double               r,
                                  std::vector<unsigned int> &out) const
  {
    out.clear();
    if (centers.empty())
      return;
    std::array<int, dim> lo, hi;
    for (unsigned int d = 0; d < dim; ++d)
      {
        lo[d] = int(std::floor((x[d] - r - origin[d]) / bin_size));
        hi[d] = int(std::floor((x[d] + r - origin[d]) / bin_size));
        if (hi[d] < 0 || lo[d] >= n_bins[d])
          return;
        lo[d] = std::max(lo[d], 0);
        hi[d] = std::min(hi[d], n_bins[d] - 1);
      }
    for_each_bin<dim>(lo, hi, [&](const std::array<int, dim> &b) {
      for (const unsigned int i : bins[bin_index(b)])
        if (x.distance(centers[i]) < r + radii[i] + 0.5 * smoothing)
          out.push_back(i);
    });
    // A particle spanning several bins is found once per bin.
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }



  template <int dim>
  int
  SolidIndicator<dim>::particle_containing(
    const Point<dim>                &x,
    const std::vector<unsigned int> &cands) const
  {
    for (const unsigned int i : cands)
      if (x.distance_square(centers[i]) < radii[i] * radii[i])
        return i;
    return -1;
  }



  template <int dim>
  int
  SolidIndicator<dim>::particle_containing(const Point<dim> &x) const
  {
    if (centers.empty())
      return -1;
    std::array<int, dim> b;
    for (unsigned int d = 0; d < dim; ++d)
      {
        b[d] = int(std::floor((x[d] - origin[d]) / bin_size));
        if (b[d] < 0 || b[d] >= n_bins[d])
          return -1;
      }
    return particle_containing(x, bins[bin_index(b)]);
  }



  template <int dim>
  double
  SolidIndicator<dim>::fraction(const Point<dim>                &x,
                                const std::vector<unsigned int> &cands,
                                int                             &entry) const
  {
    entry = -1;
    if (smoothing == 0.)
      {
        entry = particle_containing(x, cands);
        return entry >= 0 ? 1. : 0.;
      }
    double best = 0.;
    for (const unsigned int i : cands)
      {
        const double phi =
          std::clamp(0.5 - (x.distance(centers[i]) - radii[i]) / smoothing,
                     0.,
                     1.);
        if (phi > best)
          {
            best  = phi;
            entry = int(i);
          }
      }
    return best;
  }



  template <int dim>
  double
  SolidIndicator<dim>::fraction(const Point<dim> &x, int &entry) const
  {
    entry = -1;
    if (centers.empty())
      return 0.;
    candidates(x, 0., scratch);
    return fraction(x, scratch, entry);
  }



  template <int dim>
  double
  SolidIndicator<dim>::distance_to_surfaces(const Point<dim> &x,
                                            const double      search) const
  {
    candidates(x, search, scratch);
    double d = search;
    for (const unsigned int i : scratch)
      d = std::min(d, std::abs(x.distance(centers[i]) - radii[i]));
    return d;
  }

  template class SolidIndicator<2>;
  template class SolidIndicator<3>;
} // namespace Fidus
