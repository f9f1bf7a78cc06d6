// The modal-energy indicator's measure (dg::highest_mode_energy_share, used
// by the limiter's modal_energy indicator and by subcell blending) does not
// depend on the scale of the solution: for mode vectors in 1D and 2D,
// degrees 1-3, the share at the scales 1e-300 ... 1e300 equals the share at
// scale 1 to round-off, and the floor scales with them (a cell below it
// stays "round-off", -1). The squares of modes beyond ~1e154 overflowed
// (inf / inf: the cell was never flagged) and those below ~1e-154 underflowed
// (every cell read as round-off). Prints yes/no per case; fails itself.
#include <granular_dg/dg/limiter.h>

#include <cmath>
#include <iostream>
#include <vector>

using namespace granular_dg;

namespace
{
  bool failed = false;

  template <int dim, unsigned int n1>
  void
  check(const std::vector<double> &q, const double floor)
  {
    const double reference = dg::highest_mode_energy_share<dim, n1>(q.data(), floor);
    bool         same      = reference > 0;
    for (const double scale : {1e-300, 1e-200, 1e-160, 1e-100, 1e100, 1e155, 1e200, 1e300})
      {
        std::vector<double> s = q;
        for (double &x : s)
          x *= scale;
        const double share = dg::highest_mode_energy_share<dim, n1>(s.data(), floor * scale);
        same &= std::abs(share - reference) <= 1e-13 * reference;
        // below the floor at every scale
        same &= dg::highest_mode_energy_share<dim, n1>(s.data(), 2e3 * scale) == -1.;
      }
    failed |= !same;
    std::cout << dim << "D degree " << n1 - 1 << ": share " << reference
              << ", the same at every scale: " << (same ? "yes" : "NO") << std::endl;
  }
} // namespace

int
main()
{
  check<1, 2>({1., 0.3}, 1e-3);
  check<1, 3>({1., -0.4, 0.05}, 1e-3);
  check<1, 4>({-2., 0.7, 0.2, -0.1}, 1e-3);
  check<2, 2>({1., 0.3, -0.2, 0.1}, 1e-3);
  check<2, 3>({1., 0.3, 0.02, -0.2, 0.1, 0.01, 0.03, -0.01, 0.005}, 1e-3);
  return failed ? 1 : 0;
}
