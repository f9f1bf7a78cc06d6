#include <granular_dg/base/input_path.h>

#include <granular_dg/base/errors.h>

#include <filesystem>
#include <map>

namespace granular_dg
{
  namespace
  {
    std::string &
    parameter_file()
    {
      static std::string name;
      return name;
    }

    std::map<std::string, std::string> &
    parameter_origins()
    {
      static std::map<std::string, std::string> origins;
      return origins;
    }
  } // namespace

  void
  set_parameter_origin(const std::string &parameter, const std::string &origin)
  {
    parameter_origins()[parameter] = origin;
  }

  std::string
  parameter_origin(const std::string &parameter)
  {
    const auto it = parameter_origins().find(parameter);
    return it == parameter_origins().end() ? "" : " (" + it->second + ")";
  }

  void
  set_parameter_file(const std::string &filename)
  {
    parameter_file() = filename;
    parameter_origins().clear();
  }

  bool
  is_parameter_file(const std::string &path)
  {
    std::error_code ec;
    return !parameter_file().empty() &&
           std::filesystem::equivalent(parameter_file(), path, ec) && !ec;
  }

  std::string
  resolve_input_path(const std::string &path)
  {
    const std::filesystem::path p(path);
    if (p.is_absolute() || parameter_file().empty())
      return path;
    return (std::filesystem::path(parameter_file()).parent_path() / p).lexically_normal().string();
  }
} // namespace granular_dg
