#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace granular_dg
{
  /// Bad input: names the parameter, the value given and what is allowed.
  /// main() prints what() as one line on stderr and exits with code 2.
  class InputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /// A run that cannot go on (inadmissible state, NaN time step): main()
  /// prints what() and exits with code 3 after the last good state is written.
  class RunError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /// Where the run's input set a parameter ("Time stepping/CFL number"):
  /// " (case.prm line 12)", " (--set)", or "" for a default (input_path.cc).
  std::string
  parameter_origin(const std::string &parameter);

  /// Throw an InputError "parameter 'name' = 'value' (case.prm line 12) is not
  /// allowed: allowed" (the origin as parameter_origin() gives it).
  template <typename T>
  void
  require(const bool condition, const std::string &parameter, const T &value,
          const std::string &allowed)
  {
    if (condition)
      return;
    std::ostringstream s;
    s << "parameter '" << parameter << "' = '" << value << "'" << parameter_origin(parameter)
      << " is not allowed: " << allowed;
    throw InputError(s.str());
  }
} // namespace granular_dg
