#include <granular_dg/base/checkpoint.h>
#include <granular_dg/base/errors.h>
#include <granular_dg/base/output.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace granular_dg
{
  namespace fs = std::filesystem;

  std::string
  format_number(const double x)
  {
    if (std::isnan(x))
      return "nan";
    if (std::isinf(x))
      return x > 0 ? "inf" : "-inf";
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.12g", x);
    return buffer;
  }

  namespace
  {
    std::string
    quoted(const std::string &s)
    {
      std::string out = "\"";
      for (const char c : s)
        {
          if (c == '"' || c == '\\')
            out += '\\';
          if (c == '\n')
            {
              out += "\\n";
              continue;
            }
          out += c;
        }
      return out + "\"";
    }

    std::string
    json_number(const double x)
    {
      // JSON has no NaN/inf: write them as strings
      return std::isfinite(x) ? format_number(x) : quoted(format_number(x));
    }
  } // namespace

  void
  JsonObject::add(const std::string &key, const double value)
  {
    items.emplace_back(key, json_number(value));
  }

  void
  JsonObject::add(const std::string &key, const long long value)
  {
    items.emplace_back(key, std::to_string(value));
  }

  void
  JsonObject::add(const std::string &key, const std::string &value)
  {
    items.emplace_back(key, quoted(value));
  }

  void
  JsonObject::add(const std::string &key, const std::vector<double> &values)
  {
    std::string s = "[";
    for (unsigned int i = 0; i < values.size(); ++i)
      s += (i ? ", " : "") + json_number(values[i]);
    items.emplace_back(key, s + "]");
  }

  void
  JsonObject::add_object(const std::string &key, const JsonObject &object)
  {
    // summary.json nests one level deep: render with that indentation
    items.emplace_back(key, object.str(2));
  }

  std::string
  JsonObject::str(const unsigned int indent) const
  {
    const std::string pad(indent + 2, ' ');
    std::string       s = "{\n";
    for (unsigned int i = 0; i < items.size(); ++i)
      {
        s += pad + quoted(items[i].first) + ": " + items[i].second +
             (i + 1 < items.size() ? ",\n" : "\n");
      }
    return s + std::string(indent, ' ') + "}";
  }

  void
  JsonObject::write(const std::string &filename) const
  {
    const std::string tmp = filename + ".tmp";
    {
      std::ofstream out(tmp);
      out << str() << '\n';
    }
    fs::rename(tmp, filename);
  }

  void
  CsvWriter::open(const std::string              &filename,
                  const std::vector<std::string> &header,
                  const std::string              &comment)
  {
    out.open(filename);
    if (!comment.empty())
      out << "# " << comment << '\n';
    for (unsigned int i = 0; i < header.size(); ++i)
      out << (i ? "," : "") << header[i];
    out << '\n';
    out.flush();
  }

  void
  CsvWriter::row(const std::vector<double> &values)
  {
    for (unsigned int i = 0; i < values.size(); ++i)
      out << (i ? "," : "") << format_number(values[i]);
    out << '\n';
    out.flush();
  }

  std::uint64_t
  CsvWriter::size()
  {
    out.flush();
    return out.is_open() ? static_cast<std::uint64_t>(out.tellp()) : 0;
  }

  void
  truncate_file(const std::string &filename, const std::uint64_t size)
  {
    std::error_code ec;
    const auto      now = fs::file_size(filename, ec);
    if (ec || now < size)
      throw RunError("cannot resume: " + filename + " has " +
                     (ec ? std::string("gone missing") : std::to_string(now) + " bytes") +
                     ", the checkpoint expects at least " + std::to_string(size));
    fs::resize_file(filename, size);
  }

  void
  CsvWriter::reopen(const std::string &filename, const std::uint64_t size)
  {
    truncate_file(filename, size);
    out.open(filename, std::ios::app);
  }

  void
  prepare_output_directory(const std::string &directory, const bool overwrite)
  {
    const std::string parameter = "Output/directory";
    require(!directory.empty(), parameter, directory, "a directory name");
    std::error_code ec;
    fs::create_directories(directory, ec);
    require(!ec && fs::is_directory(directory),
            parameter,
            directory,
            "a directory that can be created (" + ec.message() + ")");

    // results of an earlier run?
    const char *markers[] = {"summary.json", "solution.pvd", "timeseries.csv",
                             "convergence.csv"};
    for (const char *m : markers)
      if (fs::exists(fs::path(directory) / m))
        {
          require(overwrite,
                  parameter,
                  directory,
                  std::string("a directory without a previous run's results (it holds ") +
                    m + "); choose another one or set Output/overwrite = true" +
                    (has_checkpoints(directory, true) ?
                       ", or continue that run with --resume" :
                       ""));
          fs::remove_all(checkpoint_directory(directory));
          // remove what this program writes, so that nothing stale stays
          for (const auto &entry : fs::directory_iterator(directory))
            {
              const std::string name = entry.path().filename().string();
              // the scenes' files too (a stale slice or stress table must
              // not pass for a result of the new run)
              const char *prefixes[] = {"summary.json", "solution", "timeseries.csv",
                                        "parameters.prm", "convergence", "profile-",
                                        "modes-", "slice-", "stress-", "hopper-",
                                        "radial-field", "fig9-scan.csv", "sgn-map.csv",
                                        "history.csv", "final-profile.csv"};
              bool ours = false;
              for (const char *prefix : prefixes)
                ours = ours || name.rfind(prefix, 0) == 0;
              if (ours && entry.is_regular_file())
                fs::remove(entry.path());
            }
          break;
        }

    const fs::path probe = fs::path(directory) / ".granular_dg-write-test";
    {
      std::ofstream test(probe);
      require(static_cast<bool>(test << "x" << std::flush),
              parameter,
              directory,
              "a writable directory");
    }
    fs::remove(probe, ec);
  }

  void
  write_pvd(const std::string                                  &filename,
            const std::vector<std::pair<double, std::string>> &records)
  {
    const std::string tmp = filename + ".tmp";
    {
      std::ofstream out(tmp);
      out << "<?xml version=\"1.0\"?>\n"
          << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
          << "  <Collection>\n";
      for (const auto &r : records)
        out << "    <DataSet timestep=\"" << format_number(r.first)
            << "\" group=\"\" part=\"0\" file=\"" << r.second << "\"/>\n";
      out << "  </Collection>\n</VTKFile>\n";
    }
    fs::rename(tmp, filename);
  }

  std::string
  format_duration(const double seconds)
  {
    std::ostringstream s;
    if (!std::isfinite(seconds))
      return "?";
    if (seconds < 60)
      s << std::fixed << std::setprecision(1) << seconds << " s";
    else if (seconds < 3600)
      s << int(seconds / 60) << " min " << std::setw(2) << std::setfill('0')
        << int(seconds) % 60 << " s";
    else
      s << int(seconds / 3600) << " h " << std::setw(2) << std::setfill('0')
        << int(seconds / 60) % 60 << " min";
    return s.str();
  }

  Progress::Progress(const double t_start, const double t_end, const double interval_s)
    : t_start(t_start)
    , t_end(t_end)
    , interval(interval_s)
    , wall_start(Clock::now())
    , last_print(wall_start)
  {}

  void
  Progress::update(const unsigned long step, const double t, const double dt)
  {
    if (interval <= 0)
      return;
    const auto now = Clock::now();
    if (std::chrono::duration<double>(now - last_print).count() < interval &&
        t < t_end)
      return;
    last_print           = now;
    const double elapsed = std::chrono::duration<double>(now - wall_start).count();
    const double fraction = (t - t_start) / (t_end - t_start);
    const double eta = fraction > 0 ? elapsed * (1. - fraction) / fraction : NAN;
    std::cout << "  step " << std::setw(7) << step << "  (" << std::setw(3)
              << int(100 * fraction) << "%)  t = " << std::setw(10)
              << format_number(t) << "  dt = " << std::setw(10)
              << format_number(dt) << "  elapsed " << format_duration(elapsed)
              << "  ETA " << format_duration(eta) << std::endl;
  }
} // namespace granular_dg
