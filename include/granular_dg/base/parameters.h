#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>

#include <granular_dg/base/errors.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace granular_dg
{
  using namespace dealii;

  /// Names of an enum's values, in one place: the prm pattern
  /// (Patterns::Selection, so a typo lists the allowed values) and the
  /// conversion both come from it.
  template <typename Enum>
  class EnumNames
  {
  public:
    EnumNames(std::vector<std::pair<Enum, std::string>> names)
      : names(std::move(names))
    {}

    std::string
    selection() const
    {
      std::string s;
      for (const auto &n : names)
        s += (s.empty() ? "" : "|") + n.second;
      return s;
    }

    Patterns::Selection
    pattern() const
    {
      return Patterns::Selection(selection());
    }

    Enum
    parse(const std::string &parameter, const std::string &value) const
    {
      for (const auto &n : names)
        if (n.second == value)
          return n.first;
      require(false, parameter, value, "one of " + selection());
      return names.front().first;
    }

    const std::string &
    name(const Enum e) const
    {
      for (const auto &n : names)
        if (n.first == e)
          return n.second;
      return names.front().second;
    }

  private:
    std::vector<std::pair<Enum, std::string>> names;
  };

  /// Split "a; b; c" into trimmed expressions.
  std::vector<std::string>
  split_expressions(const std::string &text, char separator = ';');

  /// A FunctionParser of x (and y in 2D) and, when time_dependent, t, with the
  /// constant pi. A malformed expression is an InputError naming its
  /// parameter: parameters[i] for expression i (one name for all is fine).
  template <int dim>
  std::shared_ptr<FunctionParser<dim>>
  make_function(const std::vector<std::string> &expressions,
                const std::vector<std::string> &parameters,
                bool                            time_dependent = true);

  /// An InputError unless filename is a readable file.
  void
  require_readable_parameter_file(const std::string &filename);

  /// The values of the top-level entry `name` (set outside any subsection)
  /// in a parameter file and in the files it includes at its top level, as
  /// parse_parameters() reads them (includes relative to the file), each with
  /// where it is set ("FILE line N"), in the order they are read.
  std::vector<std::pair<std::string, std::string>>
  top_level_settings(const std::string &filename, const std::string &name);

  /// Parse a file into prm and apply "Section/sub/name=value" overrides;
  /// deal.II's errors become one-line InputErrors.
  void
  parse_parameters(ParameterHandler               &prm,
                   const std::string              &filename,
                   const std::vector<std::string> &overrides);

  /// Turn any deal.II exception text into one line without the
  /// file/line/function banner.
  std::string
  one_line_message(const std::exception &e);
} // namespace granular_dg
