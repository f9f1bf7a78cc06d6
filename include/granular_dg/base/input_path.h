#pragma once

#include <string>

namespace granular_dg
{
  /// Record the parameter file of this run (parse_parameters() does).
  void
  set_parameter_file(const std::string &filename);

  /// Record where the input set a parameter ("case.prm line 12", "--set");
  /// the last record of a parameter wins, as its value does.
  void
  set_parameter_origin(const std::string &parameter, const std::string &origin);

  /// Whether path names the parameter file of this run (the same file, by
  /// any name): a file the run must never write over or remove.
  bool
  is_parameter_file(const std::string &path);

  /// A file named in the parameter file (a graph, a table): an absolute path
  /// as it is, a relative one relative to the parameter file's directory, so
  /// that a case and its data files move together.
  std::string
  resolve_input_path(const std::string &path);
} // namespace granular_dg
