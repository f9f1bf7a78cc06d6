#include <deal.II/base/mpi.h>

#include <granular_dg/base/convergence_study.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace granular_dg
{
  namespace
  {
    /// A value on the terminal: EOCs with 2 decimals, errors with 4
    /// significant digits in exponent form, counts as integers.
    std::string
    terminal_value(const std::string &column, const double x)
    {
      char text[32];
      if (column.rfind("eoc", 0) == 0)
        std::snprintf(text, sizeof text, "%.2f", x);
      else if (column.find("error") != std::string::npos)
        std::snprintf(text, sizeof text, "%.4e", x);
      else if (x == std::round(x) && std::abs(x) < 1e15)
        std::snprintf(text, sizeof text, "%.0f", x);
      else
        std::snprintf(text, sizeof text, "%.4g", x);
      return text;
    }

    void
    print_line(const std::vector<std::string> &fields)
    {
      for (const auto &f : fields)
        std::cout << std::string(f.size() < 12 ? 12 - f.size() : 1, ' ') << f;
      std::cout << std::endl;
    }
  } // namespace

  void
  run_convergence_study(const StudyColumns &columns, const RunParameters &params,
                        const std::function<StudyRow(unsigned int, unsigned int)> &run,
                        JsonObject summary)
  {
    // the table's columns: degree, the values, each rated error's EOC after it
    std::vector<std::string> header{"degree"}, rates_header{"degree"};
    std::vector<int>         rated_of; // for each value: its index in `rated`, or -1
    for (const auto &v : columns.values)
      {
        header.push_back(v);
        const auto r = std::find_if(columns.rated.begin(), columns.rated.end(),
                                    [&](const auto &e) { return e.first == v; });
        rated_of.push_back(r == columns.rated.end() ? -1 : int(r - columns.rated.begin()));
        if (r != columns.rated.end())
          header.push_back(r->second);
      }
    for (const auto &[error, eoc] : columns.rated)
      rates_header.push_back(eoc + "_finest");

    const bool root = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    CsvWriter  table, rates;
    if (root)
      {
        table.open(params.directory + "/convergence.csv", header, columns.table_comment);
        rates.open(params.directory + "/convergence-rates.csv", rates_header,
                   columns.rates_comment);
      }
    JsonObject errors;
    const auto write_summary = [&](const std::string &status) {
      if (!root)
        return;
      summary.add("status", status);
      summary.add_object("errors", errors);
      summary.write(params.directory + "/summary.json");
    };
    for (unsigned int i = 0; i < params.convergence_degrees.size(); ++i)
      {
        const double p = params.convergence_degrees[i];
        if (root)
          print_line(columns.printed);
        std::vector<std::vector<double>> error(columns.rated.size()), eoc(columns.rated.size());
        double                           h_previous = 0.;
        for (const unsigned int cells : params.convergence_cells)
          {
            StudyRow r;
            try
              {
                r = run(i, cells);
              }
            catch (const RunError &e)
              {
                // summary.json with the status and the errors so far
                const std::string what = "convergence study, degree " + format_number(p) +
                                         ", Convergence/cells = " + std::to_string(cells) +
                                         ": " + e.what();
                write_summary("failed: " + what);
                throw RunError(what);
              }
            std::vector<double> row{p};
            for (unsigned int v = 0; v < r.values.size(); ++v)
              {
                row.push_back(r.values[v]);
                if (const int k = rated_of[v]; k >= 0)
                  {
                    const double rate =
                      error[k].empty() || !(error[k].back() > 0) ?
                        NAN :
                        std::log(error[k].back() / r.values[v]) / std::log(h_previous / r.h);
                    error[k].push_back(r.values[v]);
                    eoc[k].push_back(rate);
                    row.push_back(rate);
                  }
              }
            h_previous = r.h;
            if (!root)
              continue;
            table.row(row);
            std::vector<std::string> printed;
            for (const auto &c : columns.printed)
              {
                const auto at = std::find(header.begin(), header.end(), c) - header.begin();
                printed.push_back(terminal_value(c, row.at(at)));
              }
            print_line(printed);
          }
        std::vector<double> finest{p};
        for (unsigned int k = 0; k < columns.rated.size(); ++k)
          {
            finest.push_back(eoc[k].back());
            const std::string degree = "degree_" + std::to_string(params.convergence_degrees[i]);
            errors.add(degree + "_" + columns.rated[k].first + "s", error[k]);
            errors.add(degree + "_" + columns.rated[k].second, eoc[k]);
          }
        if (root)
          rates.row(finest);
      }
    write_summary("completed");
  }
} // namespace granular_dg
