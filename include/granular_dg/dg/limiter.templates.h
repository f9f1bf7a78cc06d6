#pragma once

#include <deal.II/fe/fe.h>

#include <granular_dg/dg/limiter.h>

#include <map>

namespace granular_dg::dg
{
  namespace internal
  {
    inline double
    minmod(const double a, const double b, const double c)
    {
      if (a > 0 && b > 0 && c > 0)
        return std::min(a, std::min(b, c));
      if (a < 0 && b < 0 && c < 0)
        return std::max(a, std::max(b, c));
      return 0.;
    }

    /// TVB-modified minmod: a is returned unchanged when |a| <= M h^2.
    inline double
    minmod_tvb(const double a, const double b, const double c, const double Mh2)
    {
      if (std::abs(a) <= Mh2)
        return a;
      return minmod(a, b, c);
    }
  } // namespace internal

  template <int dim, typename Physics>
  void
  ModalLimiter<dim, Physics>::reinit(const DoFHandler<dim> &dof_handler)
  {
    const FiniteElement<dim> &fe = dof_handler.get_fe();
    const unsigned int        p  = fe.degree;
    n_modes_1d                   = p + 1;
    n_modes                      = Utilities::pow(n_modes_1d, dim);
    for (int d = 0; d < dim; ++d)
      stride[d] = Utilities::pow(n_modes_1d, d);

    value_at_1.resize(n_modes_1d);
    value_at_0.resize(n_modes_1d);
    for (unsigned int k = 0; k < n_modes_1d; ++k)
      {
        Polynomials::Legendre L(k);
        value_at_1[k] = L.value(1.);
        value_at_0[k] = L.value(0.);
      }
    L0 = value_at_1[0];

    // system dof -> (component, Legendre mode)
    std::vector<std::pair<unsigned int, unsigned int>> comp_mode(fe.n_dofs_per_cell());
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
      comp_mode[i] = fe.system_to_component_index(i);

    std::map<typename DoFHandler<dim>::cell_iterator, int> cell_number;
    std::vector<typename DoFHandler<dim>::active_cell_iterator> cells;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell_number[cell] = cells.size();
          cells.push_back(cell);
        }
    n_owned = cells.size();
    // ghost (and artificial-free) neighbours get numbers after the owned ones
    for (unsigned int i = 0; i < n_owned; ++i)
      for (const unsigned int f : cells[i]->face_indices())
        {
          typename DoFHandler<dim>::cell_iterator nb;
          if (cells[i]->has_periodic_neighbor(f))
            nb = cells[i]->periodic_neighbor(f);
          else if (!cells[i]->at_boundary(f))
            nb = cells[i]->neighbor(f);
          else
            continue;
          AssertThrow(nb->is_active(),
                      ExcMessage("the limiter needs a conforming mesh"));
          if (cell_number.find(nb) == cell_number.end())
            {
              cell_number[nb] = cells.size();
              cells.push_back(typename DoFHandler<dim>::active_cell_iterator(nb));
            }
        }

    troubled.assign(n_owned, 0);
    cell_h.resize(n_owned * dim);
    neighbor.assign(n_owned * 2 * dim, -1);
    dof_index.resize(cells.size() * n_components * n_modes);
    std::vector<types::global_dof_index> indices(fe.n_dofs_per_cell());
    for (unsigned int i = 0; i < cells.size(); ++i)
      {
        cells[i]->get_dof_indices(indices);
        for (unsigned int j = 0; j < indices.size(); ++j)
          dof_index[(i * n_components + comp_mode[j].first) * n_modes +
                    comp_mode[j].second] = indices[j];
        if (i >= n_owned)
          continue;
        for (int d = 0; d < dim; ++d)
          cell_h[i * dim + d] = cells[i]->extent_in_direction(d);
        for (const unsigned int f : cells[i]->face_indices())
          {
            typename DoFHandler<dim>::cell_iterator nb;
            if (cells[i]->has_periodic_neighbor(f))
              nb = cells[i]->periodic_neighbor(f);
            else if (!cells[i]->at_boundary(f))
              nb = cells[i]->neighbor(f);
            else
              continue;
            neighbor[i * 2 * dim + f] = cell_number[nb];
          }
      }
  }

  template <int dim, typename Physics>
  unsigned int
  ModalLimiter<dim, Physics>::apply(VectorType &u) const
  {
    if (type == LimiterType::none || n_modes_1d == 1)
      return 0;

    const bool had_ghosts = u.has_ghost_elements();
    if (!had_ghosts)
      u.update_ghost_values();

    auto value = [&](const unsigned int cell, const unsigned int c, const unsigned int mode) -> double & {
      return u(dof_index[(cell * n_components + c) * n_modes + mode]);
    };

    unsigned int n_troubled = 0;
    using State = Tensor<1, n_components>;
    for (unsigned int i = 0; i < n_owned; ++i)
      {
        State avg;
        for (unsigned int c = 0; c < n_components; ++c)
          avg[c] = value(i, c, 0) * L0;

        // per direction: jumps to the faces and limited slopes, in the
        // variables the limiter works on (components or characteristic fields)
        std::array<State, dim> new_slope;
        bool                   is_troubled = false;
        std::array<Tensor<2, n_components>, dim> R;
        for (int d = 0; d < dim; ++d)
          {
            const int nb_m = neighbor[i * 2 * dim + 2 * d];
            const int nb_p = neighbor[i * 2 * dim + 2 * d + 1];
            State     avg_m = avg, avg_p = avg, jump_p, jump_m, slope;
            for (unsigned int c = 0; c < n_components; ++c)
              {
                if (nb_m >= 0)
                  avg_m[c] = value(nb_m, c, 0) * L0;
                if (nb_p >= 0)
                  avg_p[c] = value(nb_p, c, 0) * L0;
                for (unsigned int k = 1; k < n_modes_1d; ++k)
                  {
                    const double a = value(i, c, k * stride[d]);
                    jump_p[c] += a * value_at_1[k];
                    jump_m[c] -= a * value_at_0[k];
                  }
                slope[c] = value(i, c, stride[d]) * value_at_1[1];
              }
            State dp = avg_p - avg, dm = avg - avg_m;
            if (type == LimiterType::characteristic)
              {
                Tensor<1, dim> n;
                n[d] = 1.;
                Tensor<2, n_components> L;
                physics.eigenvectors(avg, n, L, R[d]);
                jump_p = L * jump_p;
                jump_m = L * jump_m;
                slope  = L * slope;
                dp     = L * dp;
                dm     = L * dm;
              }
            const double h   = cell_h[i * dim + d];
            const double Mh2 = M * h * h;
            for (unsigned int c = 0; c < n_components; ++c)
              {
                // at a physical boundary the missing difference does not limit
                const double dpc = nb_p >= 0 ? dp[c] : dm[c];
                const double dmc = nb_m >= 0 ? dm[c] : dp[c];
                if (internal::minmod_tvb(jump_p[c], dpc, dmc, Mh2) != jump_p[c] ||
                    internal::minmod_tvb(jump_m[c], dpc, dmc, Mh2) != jump_m[c])
                  is_troubled = true;
                new_slope[d][c] = internal::minmod_tvb(slope[c], dpc, dmc, Mh2);
              }
          }
        troubled[i] = is_troubled;
        if (!is_troubled)
          continue;
        ++n_troubled;
        for (int d = 0; d < dim; ++d)
          {
            State s = new_slope[d];
            if (type == LimiterType::characteristic)
              s = R[d] * s;
            for (unsigned int c = 0; c < n_components; ++c)
              value(i, c, stride[d]) = s[c] / value_at_1[1];
          }
        for (unsigned int c = 0; c < n_components; ++c)
          for (unsigned int m = 1; m < n_modes; ++m)
            {
              bool linear = false;
              for (int d = 0; d < dim; ++d)
                linear |= (m == stride[d]);
              if (!linear)
                value(i, c, m) = 0.;
            }
      }
    if (!had_ghosts)
      u.zero_out_ghost_values();
    return n_troubled;
  }
} // namespace granular_dg::dg
