#include <deal.II/base/polynomial.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe.h>

#include <granular_dg/dg/modal_layout.h>

#include <cmath>
#include <map>

namespace granular_dg::dg
{
  std::vector<double>
  legendre_values(const unsigned int n, const double xi)
  {
    std::vector<double> L(n);
    for (unsigned int k = 0; k < n; ++k)
      L[k] = Polynomials::Legendre(k).value(xi);
    return L;
  }

  template <int dim>
  void
  ModalLayout<dim>::reinit(const DoFHandler<dim> &dof_handler)
  {
    const FiniteElement<dim> &fe = dof_handler.get_fe();
    n_comp                       = fe.n_components();
    n_modes_1d                   = fe.degree + 1;
    n_modes_cell                 = Utilities::pow(n_modes_1d, dim);
    for (int d = 0; d < dim; ++d)
      strides[d] = Utilities::pow(n_modes_1d, d);
    AssertThrow(fe.n_dofs_per_cell() == n_comp * n_modes_cell,
                ExcMessage("ModalLayout expects FESystem(FE_DGQLegendre(p), n)"));

    // FE_DGQLegendre's shape functions are the Legendre polynomials
    // orthonormal on [0, 1]
    at_1 = legendre_values(n_modes_1d, 1.);
    at_0 = legendre_values(n_modes_1d, 0.);
    AssertThrow(std::abs(at_1[0] - 1.) < 1e-14,
                ExcMessage("expected the orthonormal Legendre basis with L_0 = 1"));

    std::map<typename DoFHandler<dim>::cell_iterator, int> number;
    cells.clear();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          number[cell] = cells.size();
          cells.push_back(cell);
        }
    n_owned_cells = cells.size();

    auto neighbor_of = [](const typename DoFHandler<dim>::active_cell_iterator &cell,
                          const unsigned int f) {
      typename DoFHandler<dim>::cell_iterator nb;
      if (cell->has_periodic_neighbor(f))
        nb = cell->periodic_neighbor(f);
      else if (!cell->at_boundary(f))
        nb = cell->neighbor(f);
      return nb;
    };
    for (unsigned int i = 0; i < n_owned_cells; ++i)
      for (const unsigned int f : cells[i]->face_indices())
        {
          const auto nb = neighbor_of(cells[i], f);
          if (nb.state() != IteratorState::valid)
            continue;
          AssertThrow(nb->is_active(), ExcMessage("ModalLayout needs a conforming mesh"));
          if (number.find(nb) == number.end())
            {
              number[nb] = cells.size();
              cells.emplace_back(nb);
            }
        }

    std::vector<std::pair<unsigned int, unsigned int>> comp_mode(fe.n_dofs_per_cell());
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
      comp_mode[i] = fe.system_to_component_index(i);

    neighbors.assign(n_owned_cells * 2 * dim, -1);
    boundary_ids.assign(n_owned_cells * 2 * dim, numbers::invalid_boundary_id);
    extents.resize(n_owned_cells * dim);
    dof_index.resize(cells.size() * n_comp * n_modes_cell);
    std::vector<types::global_dof_index> indices(fe.n_dofs_per_cell());
    for (unsigned int i = 0; i < cells.size(); ++i)
      {
        cells[i]->get_dof_indices(indices);
        for (unsigned int j = 0; j < indices.size(); ++j)
          dof_index[(i * n_comp + comp_mode[j].first) * n_modes_cell + comp_mode[j].second] =
            indices[j];
        if (i >= n_owned_cells)
          continue;
        for (int d = 0; d < dim; ++d)
          extents[i * dim + d] = cells[i]->extent_in_direction(d);
        for (const unsigned int f : cells[i]->face_indices())
          {
            const auto nb = neighbor_of(cells[i], f);
            if (nb.state() == IteratorState::valid)
              neighbors[i * 2 * dim + f] = number[nb];
            else
              boundary_ids[i * 2 * dim + f] = cells[i]->face(f)->boundary_id();
          }
      }
  }

  template <int dim>
  void
  ModalLayout<dim>::localize(const DoFHandler<dim> &dof_handler, const MPI_Comm comm)
  {
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
    partitioner = std::make_shared<Utilities::MPI::Partitioner>(dof_handler.locally_owned_dofs(),
                                                                relevant, comm);
    for (auto &i : dof_index)
      {
        AssertThrow(partitioner->in_local_range(i) || partitioner->is_ghost_entry(i),
                    ExcMessage("ModalLayout: a neighbour's DoF is not locally relevant"));
        i = partitioner->global_to_local(i);
      }
    has_ghosts = Utilities::MPI::max(partitioner->n_ghost_indices(), comm) > 0;
  }

  template <int dim>
  const LinearAlgebra::distributed::Vector<double> &
  ModalLayout<dim>::with_ghosts(const LinearAlgebra::distributed::Vector<double> &u) const
  {
    if (!has_ghosts)
      return u;
    if (ghosted.size() != partitioner->size())
      ghosted.reinit(partitioner);
    ghosted.copy_locally_owned_data_from(u);
    ghosted.update_ghost_values();
    return ghosted;
  }

  template class ModalLayout<1>;
  template class ModalLayout<2>;
} // namespace granular_dg::dg
