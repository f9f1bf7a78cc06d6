#include <granular_dg/base/errors.h>
#include <granular_dg/dg/modal_layout.h>
#include <granular_dg/dg/reference_solution.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace granular_dg::dg
{
  ModalReference::ModalReference(const std::string &filename, const unsigned int n_components)
    : dealii::Function<1>(n_components)
  {
    std::ifstream in(filename);
    if (!in)
      throw InputError("cannot open the reference solution '" + filename +
                       "' (a modes-NNNN.csv file of a run with Output/write modes = true)");
    std::string line;
    std::getline(in, line);
    const auto eq = line.find('=');
    if (line.rfind("# time", 0) != 0 || eq == std::string::npos)
      throw InputError("reference solution '" + filename + "': no '# time = T' line");
    file_time = std::strtod(line.substr(eq + 1).c_str(), nullptr);
    std::getline(in, line);
    const unsigned int columns = std::count(line.begin(), line.end(), ',') + 1;
    if (columns < 2 + n_components || (columns - 2) % n_components != 0)
      throw InputError("reference solution '" + filename + "' has " + std::to_string(columns) +
                       " columns; expected x_left, h and the modes of " +
                       std::to_string(n_components) + " components");
    n_modes = (columns - 2) / n_components;
    while (std::getline(in, line))
      {
        std::stringstream row(line);
        std::string       item;
        std::vector<double> values;
        while (std::getline(row, item, ','))
          {
            // strtod, not stod: denormal values must not throw
            char        *end = nullptr;
            const double v   = std::strtod(item.c_str(), &end);
            if (end == item.c_str())
              throw InputError("reference solution '" + filename + "': '" + item +
                               "' is not a number");
            values.push_back(v);
          }
        if (values.size() != columns)
          throw InputError("reference solution '" + filename + "': a row with " +
                           std::to_string(values.size()) + " values instead of " +
                           std::to_string(columns));
        x_left.push_back(values[0]);
        h.push_back(values[1]);
        modes.insert(modes.end(), values.begin() + 2, values.end());
      }
    if (x_left.empty())
      throw InputError("reference solution '" + filename + "' has no cells");
  }

  double
  ModalReference::value(const dealii::Point<1> &p, const unsigned int component) const
  {
    const double x = p[0];
    // the cell whose interval holds x (cells are sorted by x_left)
    std::size_t c = std::upper_bound(x_left.begin(), x_left.end(), x) - x_left.begin();
    c             = c == 0 ? 0 : c - 1;
    const double xi = std::min(1., std::max(0., (x - x_left[c]) / h[c]));
    const auto   L  = legendre_values(n_modes, xi);
    double       u  = 0;
    for (unsigned int k = 0; k < n_modes; ++k)
      u += modes[(c * n_components + component) * n_modes + k] * L[k];
    return u;
  }
} // namespace granular_dg::dg
