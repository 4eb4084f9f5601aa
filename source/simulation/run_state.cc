#include <fidus/simulation/archive_reader.h>
#include <fidus/simulation/archive_writer.h>
#include <fidus/simulation/run_state.h>

namespace Fidus
{
  void
  RunState::initialise(const std::vector<Vec3> &positions)
  {
    const std::size_t n = positions.size();
    *this               = RunState();
    X                   = positions;
    U.assign(n, Vec3{});
    W.assign(n, Vec3{});
    U_old.assign(n, Vec3{});
    W_old.assign(n, Vec3{});
    angle.assign(n, 0.);
    quaternion.assign(n, {{1., 0., 0., 0.}});
    X_at_remesh = X;
  }



  void
  RunState::save(ArchiveWriter &a) const
  {
    a.put(step);
    a.put(time);
    a.put(X);
    a.put(U);
    a.put(W);
    a.put(U_old);
    a.put(W_old);
    a.put(dt_old);
    a.put(t_old);
    a.put(have_history);
    a.put(shear_rate);
    a.put(shear_rate_old);
    a.put(angle);
    a.put(quaternion);
    a.put(X_at_remesh);
    a.put(mesh_ready);
    a.put(multiplier_valid);
    a.put(glue);
    a.put<std::uint64_t>(warnings.size());
    for (const auto &[kind, tally] : warnings)
      {
        a.put(kind);
        a.put(tally);
      }
    a.put(totals);
    a.put(wall_seconds_before);
    a.put(carried_overlap);
  }



  void
  RunState::load(ArchiveReader &a, const bool with_carried_overlap)
  {
    step             = a.get<unsigned int>();
    time             = a.get<double>();
    X                = a.get_vector<Vec3>();
    U                = a.get_vector<Vec3>();
    W                = a.get_vector<Vec3>();
    U_old            = a.get_vector<Vec3>();
    W_old            = a.get_vector<Vec3>();
    dt_old           = a.get<double>();
    t_old            = a.get<double>();
    have_history     = a.get<bool>();
    shear_rate       = a.get<double>();
    shear_rate_old   = a.get<double>();
    angle            = a.get_vector<double>();
    quaternion       = a.get_vector<std::array<double, 4>>();
    X_at_remesh      = a.get_vector<Vec3>();
    mesh_ready       = a.get<bool>();
    multiplier_valid = a.get<bool>();
    glue             = a.get_vector<Contact::GlueState::Entry>();
    warnings.clear();
    const std::uint64_t n_kinds = a.get<std::uint64_t>();
    for (std::uint64_t k = 0; k < n_kinds; ++k)
      {
        const std::string kind = a.get_string();
        warnings[kind]         = a.get<WarningLog::Tally>();
      }
    totals              = a.get<RunTotals>();
    wall_seconds_before = a.get<double>();
    carried_overlap     = with_carried_overlap ? a.get<double>() : 0.;
  }
} // namespace Fidus
