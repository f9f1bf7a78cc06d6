// deal.II's cell evaluation factories (run-time-degree FEEvaluation kernels,
// hanging-node and inverse-mass kernels) for the native VectorizedArray<double>
// (cmake/simd.cmake). Empty in a width-1 build.
//
// A separate translation unit from the face factories: in deal.II 9.4.1
// evaluation_template_factory.templates.h and
// evaluation_template_face_factory.templates.h share one include guard, so
// the second of them in one file is silently empty.

#include <deal.II/base/config.h>

#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS > 0

// The factories serve the kernels of run-time degree (FEEvaluation with
// fe_degree = -1: the 1D MatrixFree engine, the comparison engine of 1D runs,
// and the skeleton scene); every shipped case runs kernels of compiled degree
// (the 2D engine) or the line engine. So only degree 1 gets a compiled path
// here, the others deal.II's general one (doc/performance.md, "Build and
// start-up", has what this saves and costs).
#  define FE_EVAL_FACTORY_DEGREE_MAX 1
#  include <deal.II/matrix_free/evaluation_template_factory.templates.h>
#  include <deal.II/matrix_free/evaluation_template_factory_hanging_nodes.templates.h>

DEAL_II_NAMESPACE_OPEN

namespace internal
{
  template struct FEEvaluationFactory<1, VectorizedArray<double>>;
  template struct FEEvaluationFactory<2, VectorizedArray<double>>;
  template struct FEEvaluationHangingNodesFactory<1, double, VectorizedArray<double>>;
  template struct FEEvaluationHangingNodesFactory<2, double, VectorizedArray<double>>;
  template struct CellwiseInverseMassFactory<1, VectorizedArray<double>>;
  template struct CellwiseInverseMassFactory<2, VectorizedArray<double>>;
} // namespace internal

DEAL_II_NAMESPACE_CLOSE

#endif
