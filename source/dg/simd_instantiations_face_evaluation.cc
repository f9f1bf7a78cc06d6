// deal.II's face evaluation factories (run-time-degree FEFaceEvaluation
// kernels, with and without gathering from the global vector) for the native
// VectorizedArray<double> (cmake/simd.cmake). Empty in a width-1 build; see
// simd_instantiations_cell_evaluation.cc for why the cell factories live in
// another file.

#include <deal.II/base/config.h>

#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS > 0

// The factories serve the kernels of run-time degree (FEEvaluation with
// fe_degree = -1: the 1D MatrixFree engine, the comparison engine of 1D runs,
// and the skeleton scene); every shipped case runs kernels of compiled degree
// (the 2D engine) or the line engine. So only degree 1 gets a compiled path
// here, the others deal.II's general one (doc/performance.md, "Build and
// start-up", has what this saves and costs).
#  define FE_EVAL_FACTORY_DEGREE_MAX 1
#  include <deal.II/matrix_free/evaluation_template_face_factory.templates.h>

DEAL_II_NAMESPACE_OPEN

namespace internal
{
  template struct FEFaceEvaluationFactory<1, VectorizedArray<double>>;
  template struct FEFaceEvaluationFactory<2, VectorizedArray<double>>;
  template struct FEFaceEvaluationGatherFactory<1, double, VectorizedArray<double>>;
  template struct FEFaceEvaluationGatherFactory<2, double, VectorizedArray<double>>;
} // namespace internal

DEAL_II_NAMESPACE_CLOSE

#endif
