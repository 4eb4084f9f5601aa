// RunState and the checkpoint archive: what is saved is read back to the
// bit, every field; a truncated, damaged or over-long archive is refused
// with an InputError that names the file, before any value is used.

#include "../fidus_test.h"

#include <cstring>
#include <fidus/core/input_error.h>
#include <fidus/simulation/archive_reader.h>
#include <fidus/simulation/archive_writer.h>
#include <fidus/simulation/run_state.h>

using namespace FidusTest;

namespace
{
  bool
  refused(const std::string &image, const std::string &expect)
  {
    try
      {
        Fidus::ArchiveReader reader(image, "state.bin");
        Fidus::RunState      s;
        s.load(reader);
        return false;
      }
    catch (const Fidus::InputError &e)
      {
        return std::string(e.what()).find(expect) != std::string::npos &&
               std::string(e.what()).find("state.bin") != std::string::npos;
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Fidus::RunState                          a;
  a.initialise({{{0.1, 0.2, 0.}}, {{0.3, 0.4, 0.}}, {{0.5, 0.6, 0.}}});
  a.step             = 17;
  a.time             = 1.7000000000000002;
  a.U[1]             = {{1. / 3., -2. / 7., 0.}};
  a.W[2]             = {{0., 0., -0.5}};
  a.U_old[0]         = {{1e-300, 5e-324, 0.}};
  a.W_old[1]         = {{0., 0., 0.1}};
  a.dt_old           = 0.1;
  a.t_old            = 1.6;
  a.have_history     = true;
  a.angle[2]         = 3.25;
  a.quaternion[1]    = {{0.5, 0.5, 0.5, 0.5}};
  a.X_at_remesh[0]   = {{0.09, 0.2, 0.}};
  a.mesh_ready       = true;
  a.multiplier_valid = true;
  Fidus::Contact::GlueState::Entry e;
  e.first                            = 0;
  e.second                           = 2;
  e.gamma                            = -1e-3;
  e.lambda                           = 4.5;
  a.glue                             = {e};
  a.warnings["rigidity not reached"] = {12, 3.5e-2, 9};
  a.warnings["contact projection"]   = {1, 1e-8, 4};
  a.totals.min_gap                   = -3.5e-11;
  a.totals.uzawa_failures            = 12;
  a.wall_seconds_before              = 123.5;

  Fidus::ArchiveWriter w;
  a.save(w);
  const std::string image = w.finish();

  Fidus::ArchiveReader r(image, "state.bin");
  Fidus::RunState      b;
  b.load(r);
  const bool same =
    r.at_end() && b.step == a.step && b.time == a.time && b.X == a.X &&
    b.U == a.U && b.W == a.W && b.U_old == a.U_old && b.W_old == a.W_old &&
    b.dt_old == a.dt_old && b.t_old == a.t_old &&
    b.have_history == a.have_history && b.angle == a.angle &&
    b.quaternion == a.quaternion && b.X_at_remesh == a.X_at_remesh &&
    b.mesh_ready == a.mesh_ready && b.multiplier_valid == a.multiplier_valid &&
    b.glue.size() == 1 && b.glue[0].first == 0 && b.glue[0].second == 2 &&
    b.glue[0].gamma == e.gamma && b.glue[0].lambda == e.lambda &&
    b.warnings.size() == 2 &&
    b.warnings.at("rigidity not reached").count == 12 &&
    b.warnings.at("rigidity not reached").worst_step == 9 &&
    b.totals.min_gap == a.totals.min_gap && b.totals.uzawa_failures == 12 &&
    b.wall_seconds_before == a.wall_seconds_before;
  check_range("every field read back to the bit", same ? 1 : 0, 1, 1);

  check_range("truncated archive refused",
              refused(image.substr(0, image.size() - 5), "truncated"),
              1,
              1);
  check_range("empty file refused", refused("", "truncated"), 1, 1);
  std::string damaged = image;
  damaged[40] ^= 0x10;
  check_range("one flipped bit refused", refused(damaged, "checksum"), 1, 1);
  return exit_code();
}
