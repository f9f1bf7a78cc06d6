#include <deal.II/base/exceptions.h>
#include <deal.II/lac/vector.h>

#include <granular_dg/base/parameters.h>

#include <fstream>
#include <map>
#include <sstream>

namespace granular_dg
{
  std::vector<std::string>
  split_expressions(const std::string &text, const char separator)
  {
    std::vector<std::string> out;
    std::stringstream        s(text);
    std::string              item;
    while (std::getline(s, item, separator))
      out.push_back(Utilities::trim(item));
    if (!text.empty() && text.back() == separator)
      out.emplace_back();
    return out;
  }

  template <int dim>
  std::shared_ptr<FunctionParser<dim>>
  make_function(const std::vector<std::string> &expressions,
                const std::string              &parameter,
                const bool                      time_dependent)
  {
    const std::string vars = std::string(dim == 1 ? "x" : dim == 2 ? "x,y" : "x,y,z") +
                             (time_dependent ? ",t" : "");
    auto f = std::make_shared<FunctionParser<dim>>(expressions.size());
    try
      {
        f->initialize(vars,
                      expressions,
                      std::map<std::string, double>{{"pi", numbers::PI}},
                      time_dependent);
        // evaluate once so that errors muparser finds only at evaluation time
        // (unknown variables) surface here, not in the middle of a run
        Vector<double> values(expressions.size());
        f->vector_value(Point<dim>(), values);
      }
    catch (const std::exception &e)
      {
        std::string joined;
        for (const auto &x : expressions)
          joined += (joined.empty() ? "" : "; ") + x;
        require(false,
                parameter,
                joined,
                "expressions in " + vars + " and the constant pi (" +
                  one_line_message(e) + ")");
      }
    return f;
  }

  std::string
  one_line_message(const std::exception &e)
  {
    std::ostringstream out;
    if (const auto *deal = dynamic_cast<const ExceptionBase *>(&e))
      deal->print_info(out);
    else
      out << e.what();
    // collapse white space and line breaks
    std::string text = out.str(), result;
    bool        space = false;
    for (const char c : text)
      {
        if (std::isspace(static_cast<unsigned char>(c)))
          space = !result.empty();
        else
          {
            if (space)
              result += ' ';
            result += c;
            space = false;
          }
      }
    return result;
  }

  void
  parse_parameters(ParameterHandler               &prm,
                   const std::string              &filename,
                   const std::vector<std::string> &overrides)
  {
    {
      std::ifstream in(filename);
      if (!in)
        throw InputError("cannot open parameter file '" + filename +
                         "': it does not exist or is not readable");
    }
    try
      {
        prm.parse_input(filename, "", true);
      }
    catch (const std::exception &e)
      {
        throw InputError("in parameter file '" + filename +
                         "': " + one_line_message(e));
      }

    for (const auto &o : overrides)
      {
        const auto eq = o.find('=');
        if (eq == std::string::npos)
          throw InputError("--set '" + o +
                           "' is not of the form Section/name=value");
        std::vector<std::string> path =
          Utilities::split_string_list(o.substr(0, eq), '/');
        const std::string value = Utilities::trim(o.substr(eq + 1));
        const std::string name  = path.back();
        path.pop_back();
        unsigned int depth = 0;
        try
          {
            for (const auto &section : path)
              {
                prm.enter_subsection(section);
                ++depth;
              }
            prm.set(name, value);
          }
        catch (const std::exception &e)
          {
            for (; depth > 0; --depth)
              prm.leave_subsection();
            throw InputError("in --set '" + o + "': " + one_line_message(e));
          }
        for (; depth > 0; --depth)
          prm.leave_subsection();
      }
  }

  template std::shared_ptr<FunctionParser<1>>
  make_function<1>(const std::vector<std::string> &, const std::string &, bool);
  template std::shared_ptr<FunctionParser<2>>
  make_function<2>(const std::vector<std::string> &, const std::string &, bool);
} // namespace granular_dg
