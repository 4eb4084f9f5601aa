#include <algorithm>
#include <cmath>
#include <deal.II/base/geometry_info.h>
#include <deal.II/fe/fe.h>
#include <fidus/fluid/cut_element/cut_initial_guess.h>
#include <limits>
#include <stdexcept>

namespace Fidus
{
  template <int dim>
  CutInitialGuess<dim>::CutInitialGuess(const CutFields<dim> &previous,
                                        const double          factor)
    : previous(previous)
    , factor(factor)
  {}



  template <int dim>
  void
  CutInitialGuess<dim>::follow(
    const std::vector<typename CutMesh<dim>::Ball> &new_balls,
    const std::vector<Tensor<1, dim>>              &new_displacement,
    const std::vector<bool>                        &new_periodic)
  {
    balls        = new_balls;
    displacement = new_displacement;
    periodic     = new_periodic;
  }



  template <int dim>
  Point<dim>
  CutInitialGuess<dim>::origin(const Point<dim> &x) const
  {
    if (balls.empty())
      return x;
    // The nearest surface, and x's distance from it in its radii.
    unsigned int nearest = 0;
    double       depth   = std::numeric_limits<double>::infinity();
    for (unsigned int k = 0; k < balls.size(); ++k)
      {
        const double e =
          (x.distance(balls[k].center) - balls[k].radius) / balls[k].radius;
        if (e < depth)
          {
            depth   = e;
            nearest = k;
          }
      }
    // 1 within a radius of the surface, 0 beyond two.
    const double weight = std::clamp(2. - depth, 0., 1.);
    Point<dim>   y      = x - weight * displacement[balls[nearest].owner];
    // Back into the box: wrapped along periodic axes, else onto the wall.
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double side = previous.mesh->side(d);
        if (d < periodic.size() && periodic[d])
          y[d] -= side * std::floor(y[d] / side);
        else
          y[d] = std::clamp(y[d], 0., side);
      }
    return y;
  }



  template <int dim>
  bool
  CutInitialGuess<dim>::applies(const CutFields<dim>      &previous,
                                const std::vector<double> &sides,
                                const unsigned int         n_particles)
  {
    if (!previous.mesh || !previous.dof_handler || sides.size() != dim)
      return false;
    for (unsigned int d = 0; d < dim; ++d)
      if (previous.mesh->side(d) != sides[d])
        return false;
    return previous.centers.size() == n_particles &&
           previous.rigid.size() == n_particles * dim * (dim + 1) / 2;
  }



  template <int dim>
  typename CutInitialGuess<dim>::cell_iterator
  CutInitialGuess<dim>::find(const Point<dim> &x) const
  {
    // The coarse grid's cells tile the box; below them each
    // refinement halves a cell, and child c lies in the upper half along
    // axis d where bit d of c is set.
    const Triangulation<dim> &tria = previous.mesh->get_triangulation();
    typename Triangulation<dim>::cell_iterator cell = tria.end(0);
    for (auto c = tria.begin(0); c != tria.end(0); ++c)
      {
        bool inside = true;
        for (unsigned int d = 0; d < dim; ++d)
          inside =
            inside && x[d] >= c->vertex(0)[d] - 1e-12 &&
            x[d] <=
              c->vertex(GeometryInfo<dim>::vertices_per_cell - 1)[d] + 1e-12;
        if (inside)
          {
            cell = c;
            break;
          }
      }
    if (cell == tria.end(0))
      throw std::logic_error("CutInitialGuess: a point outside the box");
    while (cell->has_children())
      {
        const Point<dim> centre = cell->center();
        unsigned int     child  = 0;
        for (unsigned int d = 0; d < dim; ++d)
          if (x[d] > centre[d])
            child |= 1u << d;
        cell = cell->child(child);
      }
    return cell_iterator(&tria,
                         cell->level(),
                         cell->index(),
                         previous.dof_handler.get());
  }



  template <int dim>
  double
  CutInitialGuess<dim>::rigid_value(const Point<dim>  &x,
                                    const unsigned int component) const
  {
    // The pressure keeps the solver's constant: the system fixes it
    // through the rank-one term, which sees the constant of the start.
    if (component == dim)
      return factor * previous.fluid_pressure;
    // The ball that holds x, or the one whose surface is nearest (a solid
    // cell lies in a ball, but its corners may touch another's surface).
    const auto  &balls = previous.mesh->get_balls();
    unsigned int best  = 0;
    double       depth = std::numeric_limits<double>::infinity();
    for (unsigned int k = 0; k < balls.size(); ++k)
      {
        const double e = x.distance(balls[k].center) - balls[k].radius;
        if (e < depth)
          {
            depth = e;
            best  = k;
          }
      }
    const auto               &b = balls[best];
    const std::vector<double> v = rigid(b.owner);
    const Tensor<1, dim>      r = x - b.center;
    double                    u = v[component];
    // omega x r: in 2D omega is the z component alone.
    if (dim == 2)
      u += (component == 0 ? -v[2] * r[1] : v[2] * r[0]);
    else
      {
        const unsigned int i = (component + 1) % 3, j = (component + 2) % 3;
        u += v[dim + i] * r[j] - v[dim + j] * r[i];
      }
    return u;
  }



  template <int dim>
  double
  CutInitialGuess<dim>::value(const Point<dim>  &at,
                              const unsigned int component) const
  {
    const Point<dim> x    = origin(at);
    cell_iterator    cell = find(x);
    // A point on a face of a cell inside a particle may lie on a fluid
    // cell too (the surface's cut cells), whose field holds there: look
    // at the cells that share the point.
    if (cell->get_fe().n_dofs_per_cell() == 0)
      for (unsigned int corner = 0;
           corner < GeometryInfo<dim>::vertices_per_cell;
           ++corner)
        {
          Point<dim> y = x;
          for (unsigned int d = 0; d < dim; ++d)
            y[d] += (corner & (1u << d) ? 1e-10 : -1e-10);
          bool inside = true;
          for (unsigned int d = 0; d < dim; ++d)
            inside = inside && y[d] > 0. && y[d] < previous.mesh->side(d);
          if (!inside)
            continue;
          const cell_iterator other = find(y);
          if (other->get_fe().n_dofs_per_cell() > 0)
            {
              cell = other;
              break;
            }
        }
    const auto &fe = cell->get_fe();
    if (fe.n_dofs_per_cell() == 0)
      return rigid_value(x, component);
    if (cell->level() != cached_level || cell->index() != cached_index)
      {
        indices.resize(fe.n_dofs_per_cell());
        cell->get_dof_indices(indices);
        cached_values.resize(indices.size());
        for (unsigned int j = 0; j < indices.size(); ++j)
          cached_values[j] = factor * previous.solution[indices[j]];
        cached_level = cell->level();
        cached_index = cell->index();
      }
    // The cells are axis-parallel boxes: the reference point is x mapped
    // axis by axis.
    Point<dim> xi = cell->vertex(0);
    for (unsigned int d = 0; d < dim; ++d)
      xi[d] = std::clamp((x[d] - xi[d]) / cell->extent_in_direction(d), 0., 1.);
    double u = 0.;
    for (unsigned int j = 0; j < indices.size(); ++j)
      if (fe.system_to_component_index(j).first == component)
        u += cached_values[j] * fe.shape_value(j, xi);
    return u;
  }



  template <int dim>
  std::vector<double>
  CutInitialGuess<dim>::rigid(const unsigned int p) const
  {
    const unsigned int  n = dim * (dim + 1) / 2;
    std::vector<double> v(previous.rigid.begin() + p * n,
                          previous.rigid.begin() + (p + 1) * n);
    for (auto &x : v)
      x *= factor;
    return v;
  }

  template class CutInitialGuess<2>;
  template class CutInitialGuess<3>;
} // namespace Fidus
