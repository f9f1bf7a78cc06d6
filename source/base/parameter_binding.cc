#include <granular_dg/base/output.h>
#include <granular_dg/base/parameter_binding.h>

namespace granular_dg
{
  std::string
  parameter_text(const double value)
  {
    return format_number(value);
  }

  std::string
  parameter_text(const bool value)
  {
    return value ? "true" : "false";
  }

  std::string
  parameter_text(const std::string &value)
  {
    return value;
  }

  ParameterBinding::ParameterBinding(ParameterHandler &prm, const Mode mode)
    : prm(prm)
    , mode(mode)
  {}

  ParameterBinding::~ParameterBinding()
  {
    leave();
  }

  void
  ParameterBinding::leave()
  {
    for (; depth > 0; --depth)
      prm.leave_subsection();
    current.clear();
  }

  void
  ParameterBinding::section(const std::string &section_path)
  {
    leave();
    current = section_path;
    for (const auto &name : Utilities::split_string_list(section_path, '/'))
      {
        prm.enter_subsection(name);
        ++depth;
      }
  }

  std::string
  ParameterBinding::path(const std::string &name) const
  {
    return current.empty() ? name : current + "/" + name;
  }

  void
  ParameterBinding::set_default(const std::string &entry_path, const std::string &value)
  {
    if (reading())
      return;
    const std::string here = current;
    leave();
    auto names = Utilities::split_string_list(entry_path, '/');
    const std::string entry = names.back();
    names.pop_back();
    for (const auto &name : names)
      prm.enter_subsection(name);
    prm.set(entry, value);
    for (unsigned int i = 0; i < names.size(); ++i)
      prm.leave_subsection();
    if (!here.empty())
      section(here);
  }

  void
  ParameterBinding::add(const std::string &name, const std::string &default_text,
                        const Patterns::PatternBase &pattern, const std::string &documentation,
                        const std::function<void(const std::string &)> &read)
  {
    if (reading())
      read(prm.get(name));
    else
      prm.declare_entry(name, default_text, pattern, documentation);
  }
} // namespace granular_dg
