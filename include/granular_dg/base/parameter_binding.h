#pragma once

#include <deal.II/base/parameter_handler.h>

#include <granular_dg/base/errors.h>
#include <granular_dg/base/parameters.h>

#include <functional>
#include <string>
#include <type_traits>
#include <vector>

namespace granular_dg
{
  using namespace dealii;

  /// The text of a parameter value as messages and defaults show it (numbers
  /// by format_number(): shortest round trip, "0.2" not "0.200000000000000011").
  std::string
  parameter_text(double value);
  std::string
  parameter_text(bool value);
  std::string
  parameter_text(const std::string &value);
  template <typename Integer, typename = std::enable_if_t<std::is_integral_v<Integer>>>
  std::string
  parameter_text(const Integer value)
  {
    return std::to_string(value);
  }

  /**
   * Parameters declared once, next to the field each fills, in the manner of
   * deal.II's ParameterAcceptor::add_parameter. A struct's
   * bind(ParameterBinding &) names each entry, the field it fills, its
   * pattern, its documentation and its checks; the field's initial value is
   * the default. The same bind() declares the entries (Mode::declare) and
   * reads them into the fields (Mode::read), running each check as soon as
   * its entry is read, so a check may use the entries read before it:
   *
   *   b.section("Time stepping");
   *   b.add("CFL number", cfl, Patterns::Double(), "Courant number ...")
   *     .check([](double c) { return c > 0; }, "must be > 0");
   *
   * A failed check is an InputError naming "Time stepping/CFL number", the
   * value and what is allowed (require()).
   */
  class ParameterBinding
  {
  public:
    enum class Mode
    {
      declare,
      read
    };

    ParameterBinding(ParameterHandler &prm, Mode mode);
    ~ParameterBinding();
    ParameterBinding(const ParameterBinding &) = delete;
    ParameterBinding &
    operator=(const ParameterBinding &) = delete;

    bool
    reading() const
    {
      return mode == Mode::read;
    }

    /// The section ("Time stepping", or "A/B") of the entries that follow.
    void
    section(const std::string &path);

    /// "Section/name" for an entry of the current section.
    std::string
    path(const std::string &name) const;

    /// An entry just added: check() runs when it is read.
    template <typename T>
    class Entry
    {
    public:
      Entry(const ParameterBinding &binding, std::string path, const T &field)
        : binding(binding)
        , parameter(std::move(path))
        , field(field)
      {}

      /// An InputError "parameter 'path' = 'value' is not allowed: allowed"
      /// unless ok(value), once the entry is read.
      template <typename Ok>
      const Entry &
      check(const Ok &ok, const std::string &allowed) const
      {
        if (binding.reading())
          require(ok(field), parameter, parameter_text(field), allowed);
        return *this;
      }

    private:
      const ParameterBinding &binding;
      std::string             parameter;
      const T                &field;
    };

    /// An entry filling field (bool, an integer type, double, std::string).
    template <typename T>
    Entry<T>
    add(const std::string &name, T &field, const Patterns::PatternBase &pattern,
        const std::string &documentation)
    {
      if (reading())
        try
          {
            field = read<T>(name);
          }
        catch (const std::exception &)
          {
            // deal.II's Double pattern accepts a subnormal number that
            // get_double() then cannot convert
            if constexpr (!std::is_floating_point_v<T>)
              throw;
            require(false, path(name), prm.get(name),
                    "a number that is 0 or of magnitude 2.2e-308 or more (smaller ones are "
                    "subnormal and cannot be read as a double)");
          }
      else
        prm.declare_entry(name, parameter_text(field), pattern, documentation);
      return Entry<T>(*this, path(name), field);
    }

    /// An entry filling an enum field by its names.
    template <typename Enum>
    void
    add(const std::string &name, Enum &field, const EnumNames<Enum> &names,
        const std::string &documentation)
    {
      if (reading())
        field = names.parse(path(name), prm.get(name));
      else
        prm.declare_entry(name, names.name(field), names.pattern(), documentation);
    }

    /// An entry whose text read() converts (lists, expressions, fields that
    /// depend on several entries); default_text is its default.
    void
    add(const std::string &name, const std::string &default_text,
        const Patterns::PatternBase &pattern, const std::string &documentation,
        const std::function<void(const std::string &)> &read);

    /// A scene's own default of an entry declared before ("Discretization/
    /// degree": the method of its paper); nothing when reading.
    void
    set_default(const std::string &entry_path, const std::string &value);

  private:
    /// The entry's value as T (bool, an integer type, double, std::string).
    template <typename T>
    T
    read(const std::string &name) const
    {
      if constexpr (std::is_same_v<T, bool>)
        return prm.get_bool(name);
      else if constexpr (std::is_integral_v<T>)
        return prm.get_integer(name);
      else if constexpr (std::is_floating_point_v<T>)
        return prm.get_double(name);
      else
        return prm.get(name);
    }

    void
    leave();

    ParameterHandler &prm;
    const Mode        mode;
    unsigned int      depth = 0;
    std::string       current;
  };
} // namespace granular_dg
