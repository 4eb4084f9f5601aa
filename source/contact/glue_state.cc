#include <algorithm>
#include <fidus/contact/glue_state.h>

namespace Fidus::Contact
{
  void
  GlueState::clear()
  {
    data.clear();
    row_start.clear();
  }



  void
  GlueState::rebuild(std::vector<Entry> entries)
  {
    entries.erase(std::remove_if(entries.begin(),
                                 entries.end(),
                                 [](const Entry &e) {
                                   return e.gamma == 0. && e.lambda == 0.;
                                 }),
                  entries.end());
    std::uint32_t n_first = 0;
    for (const auto &e : entries)
      n_first = std::max(n_first, e.first + 1);

    // Counting sort by first index (stable, O(entries + particles)).
    row_start.assign(static_cast<std::size_t>(n_first) + 1, 0);
    for (const auto &e : entries)
      ++row_start[e.first + 1];
    for (std::size_t i = 0; i < n_first; ++i)
      row_start[i + 1] += row_start[i];
    data.resize(entries.size());
    std::vector<std::size_t> fill(row_start.begin(), row_start.end() - 1);
    for (const auto &e : entries)
      data[fill[e.first]++] = e;
  }



  long
  GlueState::find(const std::uint32_t first, const std::uint32_t second) const
  {
    if (static_cast<std::size_t>(first) + 1 >= row_start.size())
      return -1;
    for (std::size_t k = row_start[first]; k < row_start[first + 1]; ++k)
      if (data[k].second == second)
        return static_cast<long>(k);
    return -1;
  }



  unsigned int
  GlueState::n_glued() const
  {
    return static_cast<unsigned int>(
      std::count_if(data.begin(), data.end(), [](const Entry &e) {
        return e.gamma < 0.;
      }));
  }



  std::vector<unsigned int>
  GlueState::glued_count_per_particle(const std::size_t n_particles) const
  {
    std::vector<unsigned int> count(n_particles, 0);
    for (const auto &e : data)
      if (e.gamma < 0.)
        {
          if (e.first < n_particles)
            ++count[e.first];
          if (!is_wall_key(e.second) && e.second < n_particles)
            ++count[e.second];
        }
    return count;
  }
} // namespace Fidus::Contact
