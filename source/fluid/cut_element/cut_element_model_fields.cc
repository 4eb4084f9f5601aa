#include <deal.II/base/mpi.h>
#include <deal.II/numerics/data_out.h>
#include <fidus/fluid/cut_element/cut_element_model.h>

namespace Fidus
{
  using namespace dealii;

  namespace
  {
    /**
     * DataOut whose patches are moved from the cut solver's box of unit
     * cells to the scene's box, x -> lower + unit x: the solver's mesh is
     * const and belongs to the kept fields, so the points are mapped in
     * the patches instead.
     */
    template <int dim>
    class ScaledDataOut : public DataOut<dim>
    {
    public:
      /// Map every patch point (build_patches() first).
      void
      map_points(const Point<dim> &lower, const double unit)
      {
        for (auto &patch : this->patches)
          {
            for (auto &v : patch.vertices)
              for (unsigned int d = 0; d < dim; ++d)
                v[d] = lower[d] + unit * v[d];
            // Where the patch carries its points, they are the last dim
            // rows of its data table.
            if (patch.points_are_available)
              {
                const unsigned int first = patch.data.n_rows() - dim;
                for (unsigned int d = 0; d < dim; ++d)
                  for (unsigned int k = 0; k < patch.data.n_cols(); ++k)
                    patch.data(first + d, k) =
                      lower[d] + unit * patch.data(first + d, k);
              }
          }
      }
    };
  } // namespace



  template <int dim>
  void
  CutElementModel<dim>::open_field_output(const std::string  &directory,
                                          const unsigned int *resumed_step)
  {
    if (prm.output.field_output_interval == 0)
      return;
    field_output = std::make_unique<FieldOutput<dim>>(directory);
    if (resumed_step)
      field_output->resume(*resumed_step, true);
  }



  template <int dim>
  void
  CutElementModel<dim>::write_fields(const unsigned int step, const double time)
  {
    if (!field_output || step % prm.output.field_output_interval != 0 ||
        !last_fields)
      return;
    const CutFields<dim> &f = *last_fields;
    // Velocities scale with the length unit; the pressure, a stress, does
    // not, and is given relative to its mean over the fluid (the solver
    // fixes its constant at one DoF).
    Vector<double> values(f.solution.size());
    for (unsigned int i = 0; i < values.size(); ++i)
      values[i] = f.is_pressure[i] ? f.solution[i] - f.fluid_pressure :
                                     unit * f.solution[i];
    const Triangulation<dim> &tria = f.mesh->get_triangulation();
    Vector<float>             placement(tria.n_active_cells());
    Vector<float>             level(tria.n_active_cells());
    for (const auto &cell : tria.active_cell_iterators())
      {
        const auto &where                    = f.mesh->placement(cell);
        placement(cell->active_cell_index()) = where.solid     ? 2.f :
                                               where.n_cut > 0 ? 1.f :
                                                                 0.f;
        level(cell->active_cell_index())     = cell->level();
      }

    std::vector<std::string> names(dim, "velocity");
    names.emplace_back("pressure");
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
      interpretation(dim,
                     DataComponentInterpretation::component_is_part_of_vector);
    interpretation.push_back(DataComponentInterpretation::component_is_scalar);
    ScaledDataOut<dim> data_out;
    data_out.attach_dof_handler(*f.dof_handler);
    data_out.add_data_vector(values,
                             names,
                             DataOut<dim>::type_dof_data,
                             interpretation);
    data_out.add_data_vector(placement, "placement");
    data_out.add_data_vector(level, "level");
    // Every rank holds the whole mesh; each writes a piece of the .pvtu,
    // its own range of the active cells.
    const unsigned int ranks = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
    const unsigned int rank  = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
    const std::size_t  cells = tria.n_active_cells();
    const std::size_t  lo    = cells * rank / ranks,
                      hi     = cells * (rank + 1) / ranks;
    using cell_iterator      = typename Triangulation<dim>::cell_iterator;
    using active_iterator = typename Triangulation<dim>::active_cell_iterator;
    const auto in_range   = [&](const Triangulation<dim> &t,
                              active_iterator           c) -> cell_iterator {
      while (c != t.end() && c->active_cell_index() < lo)
        ++c;
      return c != t.end() && c->active_cell_index() < hi ? c : t.end();
    };
    data_out.set_cell_selection(
      [&](const Triangulation<dim> &t) {
        return in_range(t, t.begin_active());
      },
      [&](const Triangulation<dim> &t, const cell_iterator &c) {
        return in_range(t, std::next(active_iterator(c)));
      });
    data_out.build_patches(2);
    data_out.map_points(box.lo, unit);
    field_output->write(data_out, step, time, MPI_COMM_WORLD);
  }



  template void
  CutElementModel<2>::open_field_output(const std::string &,
                                        const unsigned int *);
  template void
  CutElementModel<3>::open_field_output(const std::string &,
                                        const unsigned int *);
  template void
  CutElementModel<2>::write_fields(unsigned int, double);
  template void
  CutElementModel<3>::write_fields(unsigned int, double);
} // namespace Fidus
