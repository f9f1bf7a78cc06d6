#include <granular_dg/base/input_path.h>

#include <filesystem>

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
  } // namespace

  void
  set_parameter_file(const std::string &filename)
  {
    parameter_file() = filename;
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
