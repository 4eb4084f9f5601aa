#include <deal.II/base/data_out_base.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/data_out.h>
#include <fidus/fluid/fictitious_domain/solid_indicator.h>
#include <fidus/fluid/fictitious_domain/stokes_solver.h>
#include <fidus/io/field_output.h>
#include <fidus/io/pvd_records.h>
#include <fstream>

namespace Fidus
{
  template <int dim>
  void
  FieldOutput<dim>::write(const StokesSolver<dim>   &solver,
                          const SolidIndicator<dim> &solid,
                          const unsigned int         step,
                          const double               time)
  {
    const DoFHandler<dim> &dof_handler = solver.get_dof_handler();
    const auto            &tria        = dof_handler.get_triangulation();

    std::vector<std::string> names(dim, "velocity");
    names.emplace_back("pressure");
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
      interpretation(dim,
                     DataComponentInterpretation::component_is_part_of_vector);
    interpretation.push_back(DataComponentInterpretation::component_is_scalar);
    std::vector<std::string> lambda_names(dim, "multiplier");
    lambda_names.emplace_back("multiplier_unused");

    // Cell data: solid fraction of the quadrature points, level, rank.
    dealii::Vector<float>     solid_fraction(tria.n_active_cells());
    dealii::Vector<float>     level(tria.n_active_cells());
    dealii::Vector<float>     rank(tria.n_active_cells());
    FEValues<dim>             fe_values(solver.get_fe(),
                            solver.get_quadrature(),
                            update_quadrature_points);
    std::vector<unsigned int> cands;
    const unsigned int        this_rank =
      Utilities::MPI::this_mpi_process(tria.get_communicator());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const unsigned int index = cell->active_cell_index();
          level(index)             = cell->level();
          rank(index)              = this_rank;
          solid.candidates(cell->center(), 0.5 * cell->diameter(), cands);
          if (cands.empty())
            continue;
          fe_values.reinit(cell);
          double inside = 0.;
          for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
            {
              int entry = -1;
              inside +=
                solid.fraction(fe_values.quadrature_point(q), cands, entry);
            }
          solid_fraction(index) = float(inside) / fe_values.n_quadrature_points;
        }

    DataOut<dim> data_out;
    data_out.attach_dof_handler(dof_handler);
    data_out.add_data_vector(solver.get_solution(),
                             names,
                             DataOut<dim>::type_dof_data,
                             interpretation);
    data_out.add_data_vector(solver.get_multiplier(),
                             lambda_names,
                             DataOut<dim>::type_dof_data,
                             interpretation);
    data_out.add_data_vector(solid_fraction, "solid_fraction");
    data_out.add_data_vector(level, "level");
    data_out.add_data_vector(rank, "subdomain");
    data_out.build_patches(solver.get_fe().degree);
    write(data_out, step, time, tria.get_communicator());
  }

  template <int dim>
  void
  FieldOutput<dim>::write(const DataOut<dim> &data_out,
                          const unsigned int  step,
                          const double        time,
                          const MPI_Comm      comm)
  {
    const std::string pvtu =
      data_out.write_vtu_with_pvtu_record(directory + "/",
                                          "solution",
                                          step,
                                          comm,
                                          5,
                                          0);
    records.emplace_back(time, pvtu);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        std::ofstream pvd(directory + "/solution.pvd");
        DataOutBase::write_pvd_record(pvd, records);
      }
  }

  template <int dim>
  void
  FieldOutput<dim>::resume(const unsigned int last_step, const bool writer)
  {
    records = read_pvd_records(directory + "/solution.pvd", last_step);
    if (writer)
      {
        std::ofstream pvd(directory + "/solution.pvd");
        DataOutBase::write_pvd_record(pvd, records);
      }
  }



  template class FieldOutput<2>;
  template class FieldOutput<3>;
} // namespace Fidus
