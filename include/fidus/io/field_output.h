#ifndef fidus_io_field_output_h
#define fidus_io_field_output_h

#include <deal.II/base/mpi.h>
#include <deal.II/numerics/data_out.h>
#include <string>
#include <utility>
#include <vector>

namespace Fidus
{
  template <int dim>
  class StokesSolver;
  template <int dim>
  class SolidIndicator;

  /**
   * Writes the fluid fields of one time step as solution-NNNNN.pvtu (one
   * .vtu per rank) and keeps solution.pvd up to date. For the fictitious
   * domain: velocity, pressure, the rigidity multiplier, and per cell the
   * solid fraction (the discrete characteristic function, i.e. the
   * viscosity indicator), the refinement level and the owning rank; other
   * models hand in their own DataOut.
   */
  template <int dim>
  class FieldOutput
  {
  public:
    /// Files go to @p directory.
    explicit FieldOutput(const std::string &directory)
      : directory(directory)
    {}

    /// Write the fields of @p solver for output number @p step at @p time.
    void
    write(const StokesSolver<dim>   &solver,
          const SolidIndicator<dim> &solid,
          const unsigned int         step,
          const double               time);

    /// Write the patches of @p data_out (built) for output number
    /// @p step at @p time, on the ranks of @p comm.
    void
    write(const dealii::DataOut<dim> &data_out,
          unsigned int                step,
          double                      time,
          MPI_Comm                    comm);

    /// A resumed run: keep the collection entries of steps up to
    /// @p last_step (the checkpoint's) and rewrite solution.pvd with them
    /// (rank 0 writes, every rank keeps the records).
    void
    resume(unsigned int last_step, bool writer);

  private:
    std::string                                 directory;
    std::vector<std::pair<double, std::string>> records;
  };
} // namespace Fidus

#endif
