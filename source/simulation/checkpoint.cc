#include <algorithm>
#include <fcntl.h>
#include <fidus/core/input_error.h>
#include <fidus/core/shear_rate.h>
#include <fidus/simulation/archive_reader.h>
#include <fidus/simulation/archive_writer.h>
#include <fidus/simulation/checkpoint.h>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <unistd.h>
#include <utility>
#include <vector>

namespace Fidus
{
  namespace
  {
    namespace fs = std::filesystem;

    const std::string magic = "fidus checkpoint";
    // Raised whenever the layout of state.bin changes.
    // 2: the run state holds the shear rates of its velocities.
    // 3: and, at its end, the overlap a stalled contact projection left
    //    for the next one (format 2 is read with none).
    constexpr std::uint32_t format_version         = 3;
    constexpr std::uint32_t oldest_readable_format = 2;

    const char *const boundary_names[] = {"linear shear",
                                          "sliding walls",
                                          "cavity",
                                          "exact rigid inclusion"};
    const char *const fluid_names[]    = {"fictitious domain",
                                          "undisturbed shear",
                                          "cut finite element"};

    std::string
    read_file(const std::string &name)
    {
      std::ifstream in(name, std::ios::binary);
      if (!in)
        throw InputError("--resume: the checkpoint file '" + name +
                         "' is missing; allowed: a checkpoint folder "
                         "written completely by fidus");
      std::ostringstream s;
      s << in.rdbuf();
      return s.str();
    }

    /// Step of a complete checkpoint folder name (checkpoint- and six or
    /// more digits: a run may pass step 999999), or -1.
    long
    step_of_folder(const std::string &name)
    {
      const std::string prefix = "checkpoint-";
      if (name.size() < prefix.size() + 6 || name.rfind(prefix, 0) != 0 ||
          name.size() > prefix.size() + 18)
        return -1;
      const std::string digits = name.substr(prefix.size());
      if (!std::all_of(digits.begin(), digits.end(), [](char c) {
            return c >= '0' && c <= '9';
          }))
        return -1;
      return std::stol(digits);
    }

    /// Size and FNV-1a checksum of a file, read in chunks (a 3D mesh file
    /// can be large); size -1 if it cannot be read.
    std::pair<long long, std::uint64_t>
    size_and_checksum(const std::string &name)
    {
      std::ifstream in(name, std::ios::binary);
      if (!in)
        return {-1, 0};
      std::uint64_t     h    = ArchiveWriter::checksum(nullptr, 0);
      long long         size = 0;
      std::vector<char> chunk(1 << 20);
      while (in)
        {
          in.read(chunk.data(), chunk.size());
          const std::streamsize got = in.gcount();
          h = ArchiveWriter::checksum(chunk.data(), got, h);
          size += got;
        }
      return {size, h};
    }

    /// Write a file's data (or a folder's entries) to the disk before a
    /// rename makes it the checkpoint: a crash must not leave a complete
    /// name over incomplete content.
    void
    flush_to_disk(const std::string &name)
    {
      const int fd = ::open(name.c_str(), O_RDONLY);
      if (fd >= 0)
        {
          ::fsync(fd);
          ::close(fd);
        }
    }

    std::string
    point_text(const std::array<double, 3> &p, const unsigned int dim)
    {
      std::ostringstream s;
      s << std::setprecision(15);
      for (unsigned int d = 0; d < dim; ++d)
        s << (d ? "," : "") << p[d];
      return s.str();
    }

    [[noreturn]] void
    mismatch(const std::string &entry,
             const std::string &value,
             const std::string &folder,
             const std::string &saved)
    {
      throw InputError("--resume: entry '" + entry + "' is " + value +
                       ", but the checkpoint '" + folder + "' was written " +
                       "with " + saved + "; allowed: " + saved +
                       " (a resumed run must be the same scene; start a new "
                       "run in another Output directory to change it)");
    }
  } // namespace



  std::string
  Checkpoint::folder(const std::string &output_directory,
                     const unsigned int step)
  {
    std::ostringstream s;
    s << output_directory << "/checkpoint-" << std::setw(6) << std::setfill('0')
      << step;
    return s.str();
  }



  std::string
  Checkpoint::temporary_folder(const std::string &output_directory,
                               const unsigned int step)
  {
    return folder(output_directory, step) + ".tmp";
  }



  unsigned long long
  Checkpoint::commit(const std::string &temporary,
                     const std::string &final_folder,
                     const Parameters  &prm,
                     const RunState    &state,
                     const unsigned int n_ranks)
  {
    ArchiveWriter a;
    a.put(magic);
    a.put(format_version);
    a.put<std::uint32_t>(prm.dimension);
    a.put<std::uint32_t>(n_ranks);
    a.put(prm.particles.radii);
    a.put(prm.domain.lower_left);
    a.put(prm.domain.upper_right);
    a.put<std::int32_t>(
      static_cast<std::int32_t>(prm.domain.boundary_condition));
    a.put<std::int32_t>(static_cast<std::int32_t>(prm.fluid.model));
    a.put<std::uint32_t>(prm.fluid.velocity_degree);

    // The mesh files written by Triangulation::save, with their sizes and
    // checksums, so that resume can tell a truncated one before p4est reads
    // it (p4est aborts without a message on a bad file).
    std::vector<std::string> mesh_files;
    for (const auto &entry : fs::directory_iterator(temporary))
      if (entry.path().filename().string().rfind("mesh", 0) == 0)
        mesh_files.push_back(entry.path().filename().string());
    std::sort(mesh_files.begin(), mesh_files.end());
    unsigned long long bytes = 0;
    a.put<std::uint64_t>(mesh_files.size());
    for (const std::string &name : mesh_files)
      {
        const auto [size, sum] = size_and_checksum(temporary + "/" + name);
        if (size < 0)
          throw RunError("cannot read the checkpoint file '" + temporary + "/" +
                         name + "'");
        a.put(name);
        a.put<std::uint64_t>(size);
        a.put<std::uint64_t>(sum);
        bytes += size;
        flush_to_disk(temporary + "/" + name);
      }
    state.save(a);

    const std::string image = a.finish();
    {
      std::ofstream out(temporary + "/state.bin", std::ios::binary);
      out.write(image.data(), image.size());
      out.close();
      if (!out)
        throw RunError("cannot write the checkpoint file '" + temporary +
                       "/state.bin'");
    }
    bytes += image.size();
    flush_to_disk(temporary + "/state.bin");
    flush_to_disk(temporary);

    // The new checkpoint is complete and on disk: give it its name, then
    // remove the older ones (and temporary folders of writes that were cut
    // off).
    fs::remove_all(final_folder);
    fs::rename(temporary, final_folder);
    flush_to_disk(fs::path(final_folder).parent_path().string());
    const fs::path    parent = fs::path(final_folder).parent_path();
    const std::string keep   = fs::path(final_folder).filename().string();
    for (const auto &entry : fs::directory_iterator(parent))
      {
        const std::string name = entry.path().filename().string();
        if (name == keep || name.rfind("checkpoint-", 0) != 0)
          continue;
        const bool stale_temporary = name.size() > 4 &&
                                     name.substr(name.size() - 4) == ".tmp" &&
                                     entry.path() != fs::path(temporary);
        if (step_of_folder(name) >= 0 || stale_temporary)
          fs::remove_all(entry.path());
      }
    return bytes;
  }



  void
  Checkpoint::rescale_to_shear_rate(const Parameters &prm, RunState &state)
  {
    // The checkpoint's velocities were solved under the shear rates of the
    // file that wrote it. A file that changes the rate at the checkpoint's
    // time (a reversal started from a sheared state) would otherwise move
    // the particles one step with the old rate's velocities taken as the
    // new rate's. Stokes flow is linear in the rate, so they are rescaled;
    // external forces add a part that does not scale, and a velocity
    // solved at rate 0 has no scale.
    const ShearRate shear(prm.domain.shear_rate);
    const auto      rescale = [&](std::vector<RunState::Vec3> &U,
                             std::vector<RunState::Vec3> &W,
                             double                      &solved,
                             const double                 t) {
      const double g = shear(t);
      if (g == solved)
        return;
      if (solved == 0. || !prm.particles.external_forces.empty())
        {
          std::ostringstream m;
          m << "entry 'Domain/Shear rate' gives " << g << " at t = " << t
            << ", where the checkpoint's velocities were solved at the rate "
            << solved << "; allowed: the checkpoint's rate at that time ("
            << (solved == 0. ? "a velocity solved at rate 0 cannot be "
                                    "rescaled" :
                                    "external forces add a part that does not "
                                    "scale with the rate")
            << ")";
          throw InputError(m.str());
        }
      for (std::vector<RunState::Vec3> *v : {&U, &W})
        for (RunState::Vec3 &x : *v)
          for (double &c : x)
            c *= g / solved;
      solved = g;
    };
    rescale(state.U, state.W, state.shear_rate, state.time);
    if (state.have_history)
      rescale(state.U_old, state.W_old, state.shear_rate_old, state.t_old);
  }



  Checkpoint::ResumePoint
  Checkpoint::find_and_check(const Parameters &prm, const bool verify_files)
  {
    const std::string dir    = prm.output_directory;
    long              newest = -1;
    if (fs::is_directory(dir))
      for (const auto &entry : fs::directory_iterator(dir))
        if (entry.is_directory())
          newest =
            std::max(newest, step_of_folder(entry.path().filename().string()));
    if (newest < 0)
      throw InputError(
        "--resume: the Output directory '" + dir +
        "' holds no checkpoint (no folder checkpoint-NNNNNN); allowed: the "
        "Output directory of a run that wrote one (Output/Checkpoint "
        "interval or Checkpoint wall interval above 0, or a run stopped by "
        "SIGTERM or SIGINT)");

    ResumePoint r;
    r.folder = folder(dir, newest);
    ArchiveReader a(read_file(r.folder + "/state.bin"),
                    r.folder + "/state.bin");
    if (a.get_string() != magic)
      throw InputError("--resume: '" + r.folder +
                       "/state.bin' is not a fidus checkpoint");
    const auto version = a.get<std::uint32_t>();
    if (version < oldest_readable_format || version > format_version)
      throw InputError("--resume: '" + r.folder + "/state.bin' has format " +
                       std::to_string(version) + "; allowed: formats " +
                       std::to_string(oldest_readable_format) + " to " +
                       std::to_string(format_version) +
                       " (written by another version of fidus)");
    const auto dimension = a.get<std::uint32_t>();
    if (dimension != prm.dimension)
      mismatch("Dimension",
               std::to_string(prm.dimension),
               r.folder,
               "Dimension = " + std::to_string(dimension));
    a.get<std::uint32_t>(); // ranks that wrote it: any number may resume
    const std::vector<double> radii = a.get_vector<double>();
    if (radii.size() != prm.particles.radii.size())
      mismatch("Particles/Positions",
               std::to_string(prm.particles.radii.size()) + " particles",
               r.folder,
               std::to_string(radii.size()) + " particles");
    for (std::size_t i = 0; i < radii.size(); ++i)
      if (radii[i] != prm.particles.radii[i])
        {
          std::ostringstream v, s;
          v << std::setprecision(15) << "radius " << prm.particles.radii[i]
            << " for particle " << i;
          s << std::setprecision(15) << "radius " << radii[i]
            << " for particle " << i;
          mismatch("Particles/Radius", v.str(), r.folder, s.str());
        }
    const auto lower = a.get<std::array<double, 3>>();
    const auto upper = a.get<std::array<double, 3>>();
    if (lower != prm.domain.lower_left)
      mismatch("Domain/Lower left",
               point_text(prm.domain.lower_left, prm.dimension),
               r.folder,
               point_text(lower, prm.dimension));
    if (upper != prm.domain.upper_right)
      mismatch("Domain/Upper right",
               point_text(prm.domain.upper_right, prm.dimension),
               r.folder,
               point_text(upper, prm.dimension));
    const auto boundary = a.get<std::int32_t>();
    if (boundary != static_cast<std::int32_t>(prm.domain.boundary_condition))
      mismatch(
        "Domain/Boundary condition",
        std::string("'") +
          boundary_names[static_cast<int>(prm.domain.boundary_condition)] + "'",
        r.folder,
        std::string("'") + boundary_names[boundary] + "'");
    const auto fluid = a.get<std::int32_t>();
    if (fluid != static_cast<std::int32_t>(prm.fluid.model))
      mismatch("Fluid/Model",
               std::string("'") +
                 fluid_names[static_cast<int>(prm.fluid.model)] + "'",
               r.folder,
               std::string("'") + fluid_names[fluid] + "'");
    const auto degree = a.get<std::uint32_t>();
    if (degree != prm.fluid.velocity_degree)
      mismatch("Fluid/Velocity degree",
               std::to_string(prm.fluid.velocity_degree),
               r.folder,
               "Velocity degree = " + std::to_string(degree));

    const auto n_mesh_files = a.get<std::uint64_t>();
    for (std::uint64_t k = 0; k < n_mesh_files; ++k)
      {
        const std::string name     = a.get_string();
        const auto        size     = a.get<std::uint64_t>();
        const auto        checksum = a.get<std::uint64_t>();
        const std::string path     = r.folder + "/" + name;
        if (!verify_files)
          continue;
        const auto [found, sum] = size_and_checksum(path);
        if (found < 0)
          read_file(path); // throws, naming the missing file
        if (found != static_cast<long long>(size) || sum != checksum)
          throw InputError(
            "--resume: the checkpoint file '" + path + "' has " +
            std::to_string(found) + " bytes" +
            (found == static_cast<long long>(size) ?
               " and a different checksum" :
               "") +
            ", but was written with " + std::to_string(size) +
            " bytes (truncated or damaged); allowed: a checkpoint written "
            "completely by fidus (remove this checkpoint folder to start "
            "the run anew)");
      }
    r.state.load(a, version >= 3);
    if (!a.at_end())
      throw InputError("--resume: '" + r.folder +
                       "/state.bin' holds more than a checkpoint (damaged)");
    if (r.state.X.size() != prm.particles.radii.size())
      throw InputError("--resume: '" + r.folder +
                       "/state.bin' is inconsistent (damaged)");
    rescale_to_shear_rate(prm, r.state);

    // The run's CSV files are continued, so they must be there.
    for (const char *csv : {"particles.csv", "statistics.csv"})
      if (verify_files)
        if (!fs::exists(dir + "/" + csv))
          throw InputError("--resume: the file '" + dir + "/" + csv +
                           "' of the run that wrote '" + r.folder +
                           "' is missing; allowed: the Output directory as "
                           "that run left it");
    return r;
  }
} // namespace Fidus
