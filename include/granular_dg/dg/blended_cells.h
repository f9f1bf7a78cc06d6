#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_handler.h>

#include <granular_dg/dg/boundary.h>
#include <granular_dg/dg/limiter.h>
#include <granular_dg/dg/modal_layout.h>
#include <granular_dg/dg/operator.h>
#include <granular_dg/dg/subcell_blending.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

namespace granular_dg::dg
{
  /**
   * Subcell blending for the MatrixFree engine on axis-aligned Cartesian
   * meshes (2D): after the DG rate R_DG = M^{-1} R(t, u) is computed, the
   * modes k >= 1 of a cell's rate become
   *   (1 - alpha) R_DG + alpha R_FV,
   * R_FV the first-order finite-volume rate of the cell's (p + 1)^dim equal
   * subcells mapped back to the modes (SubcellBlending's tables, one per
   * direction). The FV fluxes are the physics' numerical flux between
   * subcell means inside the cell and with the neighbour's adjacent subcells
   * across its faces (the neighbour's coefficients, so interface-aware
   * fluxes stay interface-aware), and the physics' boundary state at the
   * domain boundary.
   *
   * The cell mean (mode 0) keeps the DG rate, so the scheme conserves to
   * round-off whatever alpha is: the DG face fluxes are shared by both
   * cells of a face. This equals the blend with the FV mean rate corrected
   * by the difference between the DG face fluxes and the FV face fluxes,
   * spread evenly over the subcells. The 1D line engine instead uses the DG
   * face fluxes at the cell's faces of its FV rate (there a face is one
   * point); both conserve exactly.
   *
   * alpha as in the line engine: the modal-energy share of the physics'
   * indicator variable (in 2D by the larger of a mode's two degrees, as the
   * limiter's modal_energy indicator), below a floor of
   * indicator_floor_fraction times the largest cell mean nothing, smoothed
   * as alpha_K = max(alpha_K, alpha_N / 2) over the face neighbours.
   */
  template <int dim, typename Physics>
  class BlendedCells
  {
  public:
    static constexpr unsigned int n_components = Physics::n_components;
    using State        = Tensor<1, n_components, double>;
    using Coefficients =
      std::decay_t<decltype(std::declval<const Physics &>().coefficients(types::material_id()))>;

    /// Set up for the mesh and element of dof_handler; physics and boundary
    /// must outlive this object. alpha_max = 0: off.
    void
    reinit(const DoFHandler<dim> &dof_handler, const Physics &physics,
           const BoundaryMap<dim> &boundary_map, const double alpha_max)
    {
      static_assert(dim > 1, "in 1D the line engine blends");
      phys     = &physics;
      boundary = &boundary_map;
      blend.alpha_max = alpha_max;
      if (!blend.enabled())
        return;
      layout.reinit(dof_handler);
      layout.localize(dof_handler, dof_handler.get_triangulation().get_communicator());
      blend.reinit(layout.degree() + 1, alpha_max);
      coefficients.clear();
      for (unsigned int c = 0; c < layout.n_cells(); ++c)
        coefficients.push_back(physics.coefficients(layout.cell(c)->material_id()));
      lower_corner.assign(layout.n_owned(), Point<dim>());
      for (unsigned int c = 0; c < layout.n_owned(); ++c)
        lower_corner[c] = check_cartesian(layout.cell(c), c);
      raw_alpha.assign(layout.n_cells(), 0.);
      alpha.assign(layout.n_owned(), 0.);
    }

    bool
    enabled() const
    {
      return blend.enabled();
    }

    /// dst = M^{-1} R_DG(t, src) on entry, the blended rate on return.
    void
    apply(const double t, const VectorType &src, VectorType &dst) const
    {
      const VectorType &u = layout.with_ghosts(src);
      raw_factors(u, src.get_mpi_communicator());
      for (unsigned int c = 0; c < layout.n_owned(); ++c)
        {
          double a = raw_alpha[c];
          for (unsigned int f = 0; f < 2 * dim; ++f)
            if (const int nb = layout.neighbor(c, f); nb >= 0)
              a = std::max(a, 0.5 * raw_alpha[nb]);
          alpha[c] = a;
          if (a > 0)
            blend_cell(t, u, c, a, dst);
        }
    }

    /// the smoothed factor of every owned cell in the last apply()
    const std::vector<double> &
    factors() const
    {
      return alpha;
    }

    std::size_t
    memory_consumption() const
    {
      const auto n = [](const auto &v) { return v.capacity() * sizeof(v[0]); };
      return layout.memory_consumption() + n(coefficients) + n(lower_corner) + n(raw_alpha) +
             n(alpha);
    }

  private:
    static constexpr unsigned int max_subcells = Utilities::pow(SubcellBlending::max_modes, dim);
    using Subcells = std::array<State, max_subcells>;
    using Values   = std::array<double, max_subcells>;

    /// The lower corner of cell c; throws unless the cell is an axis-aligned
    /// box whose face neighbours see it through their opposite faces.
    Point<dim>
    check_cartesian(const typename DoFHandler<dim>::active_cell_iterator &cell,
                    const unsigned int c) const
    {
      Point<dim> low = cell->vertex(0);
      for (const unsigned int v : cell->vertex_indices())
        for (int d = 0; d < dim; ++d)
          {
            const double offset = cell->vertex(v)[d] - low[d];
            const bool   far    = v & (1u << d);
            AssertThrow(std::abs(offset - (far ? layout.extent(c, d) : 0.)) <=
                          1e-10 * layout.extent(c, d),
                        ExcMessage("subcell blending in the matrix-free engine needs an "
                                   "axis-aligned Cartesian mesh"));
          }
      for (const unsigned int f : cell->face_indices())
        {
          const unsigned int back = cell->has_periodic_neighbor(f) ? cell->periodic_neighbor_face_no(f) :
                                    cell->at_boundary(f)           ? (f ^ 1u) :
                                                                     cell->neighbor_face_no(f);
          AssertThrow(back == (f ^ 1u),
                      ExcMessage("subcell blending needs neighbours of the same orientation"));
        }
      return low;
    }

    /// The unsmoothed factors of all cells (owned and ghost neighbours).
    void
    raw_factors(const VectorType &u, const MPI_Comm comm) const
    {
      constexpr unsigned int ic = Physics::indicator_component;
      const unsigned int     n1 = layout.degree() + 1, n_modes = layout.n_modes();
      double                 scale = 0;
      for (unsigned int c = 0; c < layout.n_owned(); ++c)
        scale = std::max(scale, std::abs(u.local_element(layout.index(c, ic, 0))));
      const double floor = indicator_floor_fraction * Utilities::MPI::max(scale, comm);
      with_n_modes(n1, [&](const auto n) {
        Values q;
        for (unsigned int c = 0; c < layout.n_cells(); ++c)
          {
            for (unsigned int m = 0; m < n_modes; ++m)
              q[m] = u.local_element(layout.index(c, ic, m));
            const double share = highest_mode_energy_share<dim, decltype(n)::value>(q.data(), floor);
            raw_alpha[c]       = (n1 < 2 || share < 0) ? 0. : blend.factor(share);
          }
      });
    }

    /// the subcell index of the 1D subcell indices j[0..dim)
    unsigned int
    subcell(const std::array<unsigned int, dim> &j) const
    {
      const unsigned int n1 = layout.degree() + 1;
      return dim == 1 ? j[0] : j[0] + n1 * j[dim - 1];
    }

    /// the 1D subcell indices of subcell s
    std::array<unsigned int, dim>
    subcell_index(const unsigned int s) const
    {
      const unsigned int            n1 = layout.degree() + 1;
      std::array<unsigned int, dim> j;
      j[0] = s % n1;
      if constexpr (dim == 2)
        j[1] = s / n1;
      return j;
    }

    /// out = (T x T) in on the n1^dim values of one component (sum
    /// factorisation: out[j0 + n1 j1] = sum_k T[j0][k0] T[j1][k1] in[k0 + n1 k1])
    void
    tensor_product(const SubcellBlending::Table &T, const Values &in, Values &out) const
    {
      static_assert(dim <= 2, "the tensor products are written for 1D and 2D");
      const unsigned int n1 = layout.degree() + 1;
      if constexpr (dim == 1)
        for (unsigned int j = 0; j < n1; ++j)
          {
            double s = 0;
            for (unsigned int k = 0; k < n1; ++k)
              s += T[j][k] * in[k];
            out[j] = s;
          }
      else
        {
          Values along_x;
          for (unsigned int k1 = 0; k1 < n1; ++k1)
            for (unsigned int j0 = 0; j0 < n1; ++j0)
              {
                double s = 0;
                for (unsigned int k0 = 0; k0 < n1; ++k0)
                  s += T[j0][k0] * in[k0 + n1 * k1];
                along_x[j0 + n1 * k1] = s;
              }
          for (unsigned int j1 = 0; j1 < n1; ++j1)
            for (unsigned int j0 = 0; j0 < n1; ++j0)
              {
                double s = 0;
                for (unsigned int k1 = 0; k1 < n1; ++k1)
                  s += T[j1][k1] * along_x[j0 + n1 * k1];
                out[j0 + n1 * j1] = s;
              }
        }
    }

    /// the means of cell c's subcells
    void
    subcell_means(const VectorType &u, const unsigned int c, Subcells &mean) const
    {
      const unsigned int n_modes = layout.n_modes();
      Values             modes, means;
      for (unsigned int i = 0; i < n_components; ++i)
        {
          for (unsigned int m = 0; m < n_modes; ++m)
            modes[m] = u.local_element(layout.index(c, i, m));
          tensor_product(blend.to_subcells, modes, means);
          for (unsigned int s = 0; s < n_modes; ++s)
            mean[s][i] = means[s];
        }
    }

    /// The exterior flux through face f of cell c at its subcell s (on
    /// that face), in the direction of the outward normal.
    State
    face_flux(const double t, const unsigned int c, const unsigned int f, const unsigned int s,
              const Subcells &mean, const Subcells &neighbor_mean) const
    {
      const unsigned int d = f / 2, side = f % 2, n1 = layout.degree() + 1;
      Tensor<1, dim>     n;
      n[d] = side ? 1. : -1.;
      const int nb = layout.neighbor(c, f);
      if (nb >= 0)
        {
          auto j = subcell_index(s);
          j[d]   = side ? 0 : n1 - 1;
          return phys->numerical_flux(mean[s], neighbor_mean[subcell(j)], n, coefficients[c],
                                      coefficients[nb]);
        }
      const auto bc = boundary->find(layout.boundary_id(c, f));
      AssertThrow(bc != boundary->end(),
                  ExcMessage("no boundary condition for boundary id " +
                             std::to_string(layout.boundary_id(c, f))));
      State g;
      if (bc->second.data)
        {
          const auto j = subcell_index(s);
          Point<dim> x = lower_corner[c];
          for (unsigned int e = 0; e < dim; ++e)
            x[e] += e == d ? side * layout.extent(c, e) : (j[e] + 0.5) * layout.extent(c, e) / n1;
          bc->second.data->set_time(t);
          for (unsigned int i = 0; i < n_components; ++i)
            g[i] = bc->second.data->value(x, i);
        }
      const auto &a   = coefficients[c];
      const State U_p = phys->boundary_state(bc->second.kind, mean[s], n, g, a);
      return phys->numerical_flux(mean[s], U_p, n, a, a);
    }

    /// The FV rate of cell c's subcells.
    void
    subcell_rate(const double t, const VectorType &u, const unsigned int c, const Subcells &mean,
                 Subcells &rate) const
    {
      const unsigned int n1 = layout.degree() + 1, n_sub = layout.n_modes();
      const auto        &a  = coefficients[c];
      for (unsigned int s = 0; s < n_sub; ++s)
        rate[s] = State();
      Subcells neighbor_mean;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double   scale  = n1 / layout.extent(c, d);
          const unsigned stride = d == 0 ? 1 : n1;
          Tensor<1, dim> e;
          e[d] = 1.;
          for (unsigned int s = 0; s < n_sub; ++s)
            if (subcell_index(s)[d] + 1 < n1)
              {
                const State F = phys->numerical_flux(mean[s], mean[s + stride], e, a, a);
                rate[s] -= scale * F;
                rate[s + stride] += scale * F;
              }
          for (const unsigned int f : {2 * d, 2 * d + 1})
            {
              if (const int nb = layout.neighbor(c, f); nb >= 0)
                subcell_means(u, nb, neighbor_mean);
              for (unsigned int s = 0; s < n_sub; ++s)
                if (subcell_index(s)[d] == (f % 2 ? n1 - 1 : 0))
                  rate[s] -= scale * face_flux(t, c, f, s, mean, neighbor_mean);
            }
        }
      if constexpr (Physics::has_source_term)
        for (unsigned int s = 0; s < n_sub; ++s)
          {
            const auto j = subcell_index(s);
            Point<dim> x = lower_corner[c];
            for (unsigned int e = 0; e < dim; ++e)
              x[e] += (j[e] + 0.5) * layout.extent(c, e) / n1;
            rate[s] += phys->source(mean[s], x, t, a);
          }
    }

    /// dst's modes k >= 1 of cell c := (1 - a) dst + a R_FV
    void
    blend_cell(const double t, const VectorType &u, const unsigned int c, const double a,
               VectorType &dst) const
    {
      const unsigned int n_modes = layout.n_modes();
      Subcells           mean, rate;
      subcell_means(u, c, mean);
      subcell_rate(t, u, c, mean, rate);
      Values subcell_values, fv;
      for (unsigned int i = 0; i < n_components; ++i)
        {
          for (unsigned int s = 0; s < n_modes; ++s)
            subcell_values[s] = rate[s][i];
          tensor_product(blend.from_subcells, subcell_values, fv);
          for (unsigned int m = 1; m < n_modes; ++m)
            {
              double &r = dst.local_element(layout.index(c, i, m));
              r         = (1. - a) * r + a * fv[m];
            }
        }
    }

    const Physics            *phys     = nullptr;
    const BoundaryMap<dim>   *boundary = nullptr;
    ModalLayout<dim>          layout;
    SubcellBlending           blend;
    std::vector<Coefficients> coefficients;
    std::vector<Point<dim>>   lower_corner;
    mutable std::vector<double> raw_alpha, alpha;
  };
} // namespace granular_dg::dg
