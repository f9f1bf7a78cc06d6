// deal.II's MatrixFree with its mapping and shape data for the native
// VectorizedArray<double> (cmake/simd.cmake): Debian's library has them for
// width 1 only. Empty in a width-1 build.

#include <deal.II/base/config.h>

#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS > 0

#  include <deal.II/matrix_free/dof_info.templates.h>
#  include <deal.II/matrix_free/mapping_info.templates.h>
#  include <deal.II/matrix_free/matrix_free.templates.h>
#  include <deal.II/matrix_free/shape_info.templates.h>

DEAL_II_NAMESPACE_OPEN

template class MatrixFree<1, double, VectorizedArray<double>>;
template class MatrixFree<2, double, VectorizedArray<double>>;

// member templates are not instantiated with their class
#  define GRANULAR_DG_INTERNAL_REINIT(dim, q_dim)                              \
    template void MatrixFree<dim, double, VectorizedArray<double>>::          \
      internal_reinit<double, q_dim>(                                          \
        const std::shared_ptr<hp::MappingCollection<dim>> &,                   \
        const std::vector<const DoFHandler<dim, dim> *> &,                     \
        const std::vector<const AffineConstraints<double> *> &,                \
        const std::vector<IndexSet> &,                                         \
        const std::vector<hp::QCollection<q_dim>> &,                           \
        const AdditionalData &);
GRANULAR_DG_INTERNAL_REINIT(1, 1)
GRANULAR_DG_INTERNAL_REINIT(2, 2)
#  undef GRANULAR_DG_INTERNAL_REINIT

DEAL_II_NAMESPACE_CLOSE

#endif
