#pragma once

#include <granular_dg/base/output.h>
#include <granular_dg/base/run_parameters.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace granular_dg
{
  /**
   * The columns of a convergence study (Convergence/enabled = true): a run
   * on every mesh of Convergence/cells for every degree of
   * Convergence/degrees, one row of convergence.csv each.
   */
  struct StudyColumns
  {
    /// the values of a run, in the order of its row (after "degree")
    std::vector<std::string> values;
    /// (error column, its EOC column): the EOC log(e_coarse/e)/log(h_coarse/h)
    /// between consecutive meshes, in the column right after the error's; the
    /// finest EOC of each goes into convergence-rates.csv as <EOC column>_finest,
    /// the errors and EOCs of each degree into summary.json
    std::vector<std::pair<std::string, std::string>> rated;
    /// the comments of convergence.csv and convergence-rates.csv
    std::string table_comment, rates_comment;
    /// the columns printed on the terminal, a line per run
    std::vector<std::string> printed;
  };

  /// One run of a study: its mesh size and the values of StudyColumns::values.
  struct StudyRow
  {
    double              h = 0.;
    std::vector<double> values;
  };

  /**
   * Runs the study: run(i, cells) for degree i of Convergence/degrees on
   * every mesh. Rank 0 writes convergence.csv, convergence-rates.csv and
   * summary.json (`summary`, the status and the errors) into the output
   * directory and prints the table. A run that fails ends the study with
   * summary.json's status naming it (and the errors so far).
   */
  void
  run_convergence_study(const StudyColumns &columns, const RunParameters &params,
                        const std::function<StudyRow(unsigned int, unsigned int)> &run,
                        JsonObject summary);
} // namespace granular_dg
