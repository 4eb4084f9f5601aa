#include <fidus/core/input_error.h>
#include <fidus/io/particle_output.h>
#include <fidus/io/pvd_records.h>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace Fidus
{
  void
  ParticleOutput::write(const unsigned int                        step,
                        const double                              time,
                        const std::vector<std::array<double, 3>> &x,
                        const std::vector<double>                &radii,
                        const std::vector<std::array<double, 3>> &u,
                        const std::vector<std::array<double, 3>> &omega,
                        const std::vector<unsigned int>          &glued)
  {
    if (!active)
      return;
    std::ostringstream name;
    name << "particles-" << std::setw(5) << std::setfill('0') << step << ".vtp";
    std::ofstream out(directory + "/" + name.str());
    if (!out)
      throw RunError("cannot write '" + directory + "/" + name.str() + "'");
    const std::size_t n = x.size();
    out << std::setprecision(12);
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"PolyData\" version=\"0.1\" "
           "byte_order=\"LittleEndian\">\n<PolyData>\n"
        << "<Piece NumberOfPoints=\"" << n
        << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
           "NumberOfPolys=\"0\">\n<Points>\n"
        << "<DataArray type=\"Float64\" NumberOfComponents=\"3\" "
           "format=\"ascii\">\n";
    for (const auto &p : x)
      out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    out << "</DataArray>\n</Points>\n<PointData Scalars=\"radius\">\n";
    auto vector_array = [&](const char                               *nm,
                            const std::vector<std::array<double, 3>> &v) {
      out << "<DataArray type=\"Float64\" Name=\"" << nm
          << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
      for (const auto &a : v)
        out << a[0] << ' ' << a[1] << ' ' << a[2] << '\n';
      out << "</DataArray>\n";
    };
    out << "<DataArray type=\"Float64\" Name=\"radius\" format=\"ascii\">\n";
    for (const double r : radii)
      out << r << '\n';
    out << "</DataArray>\n";
    vector_array("velocity", u);
    vector_array("omega", omega);
    out << "<DataArray type=\"Int32\" Name=\"glued_contacts\" "
           "format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i)
      out << (i < glued.size() ? glued[i] : 0u) << '\n';
    out << "</DataArray>\n<DataArray type=\"Int32\" Name=\"id\" "
           "format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i)
      out << i << '\n';
    out << "</DataArray>\n</PointData>\n</Piece>\n</PolyData>\n</VTKFile>\n";

    records.emplace_back(time, name.str());
    write_collection();
  }



  void
  ParticleOutput::resume(const unsigned int last_step)
  {
    if (!active)
      return;
    records = read_pvd_records(directory + "/particles.pvd", last_step);
    write_collection();
  }



  void
  ParticleOutput::write_collection() const
  {
    std::ofstream pvd(directory + "/particles.pvd");
    pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" "
           "version=\"0.1\" byte_order=\"LittleEndian\">\n<Collection>\n"
        << std::setprecision(12);
    for (const auto &r : records)
      pvd << "  <DataSet timestep=\"" << r.first
          << "\" group=\"\" part=\"0\" file=\"" << r.second << "\"/>\n";
    pvd << "</Collection>\n</VTKFile>\n";
  }
} // namespace Fidus
