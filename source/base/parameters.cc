#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/vector.h>

#include <granular_dg/base/input_path.h>
#include <granular_dg/base/parameters.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <regex>
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

  namespace
  {
    /// Silences std::cerr for its lifetime: deal.II's FunctionParser prints
    /// muparser's diagnostics there before it throws, and bad input must
    /// give exactly one line.
    class QuietCerr
    {
    public:
      QuietCerr()
        : saved(std::cerr.rdbuf(sink.rdbuf()))
      {}
      ~QuietCerr()
      {
        std::cerr.rdbuf(saved);
      }

    private:
      std::ostringstream sink;
      std::streambuf    *saved;
    };

    template <int dim>
    void
    initialize_parser(FunctionParser<dim>            &f,
                      const std::string              &vars,
                      const std::vector<std::string> &expressions,
                      const bool                      time_dependent)
    {
      QuietCerr quiet;
      f.initialize(vars,
                   expressions,
                   std::map<std::string, double>{{"pi", numbers::PI}},
                   time_dependent);
      // evaluate once so that errors muparser finds only at evaluation time
      // (unknown variables) surface here, not in the middle of a run
      Vector<double> values(expressions.size());
      f.vector_value(Point<dim>(), values);
    }
  } // namespace

  template <int dim>
  std::shared_ptr<FunctionParser<dim>>
  make_function(const std::vector<std::string> &expressions,
                const std::vector<std::string> &parameters,
                const bool                      time_dependent)
  {
    const std::string vars = std::string(dim == 1 ? "x" : dim == 2 ? "x,y" : "x,y,z") +
                             (time_dependent ? ",t" : "");
    const std::string allowed =
      "an expression in " + vars + " and the constant pi";
    // one at a time first, so that an error names the faulty expression
    for (unsigned int i = 0; i < expressions.size(); ++i)
      {
        const std::string &name = parameters[std::min<std::size_t>(i, parameters.size() - 1)];
        FunctionParser<dim> single(1);
        try
          {
            require(!expressions[i].empty(), name, expressions[i], allowed);
            initialize_parser(single, vars, {expressions[i]}, time_dependent);
          }
        catch (const InputError &)
          {
            throw;
          }
        catch (const std::exception &e)
          {
            std::string reason = one_line_message(e);
            const auto  said   = reason.find("The parser said: ");
            if (said != std::string::npos)
              reason = reason.substr(said + 17);
            require(false, name, expressions[i], allowed + " (" + reason + ")");
          }
      }
    auto f = std::make_shared<FunctionParser<dim>>(expressions.size());
    initialize_parser(*f, vars, expressions, time_dependent);
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

  namespace
  {
    /// Each line of a prm file with the "Section/Sub/" path in force on it
    /// (prefix: the path in force where the file is included).
    std::vector<std::pair<std::string, std::string>>
    lines_with_sections(const std::string &filename, const std::string &prefix = "")
    {
      std::ifstream                                     in(filename);
      std::vector<std::pair<std::string, std::string>> lines;
      std::string                                       path = prefix, text;
      std::vector<std::string>                          stack;
      const std::regex enter(R"(^\s*subsection\s+(.*\S)\s*$)");
      const std::regex leave(R"(^\s*end\s*$)");
      std::smatch      m;
      while (std::getline(in, text))
        {
          text = text.substr(0, text.find('#'));
          lines.emplace_back(path, text);
          if (std::regex_match(text, m, enter))
            stack.push_back(m[1]);
          else if (std::regex_match(text, leave) && !stack.empty())
            stack.pop_back();
          path = prefix;
          for (const auto &s : stack)
            path += s + "/";
        }
      return lines;
    }

    /// the file an `include` line names, or "" for any other line
    std::string
    included_file(const std::string &line)
    {
      static const std::regex include(R"(^\s*include\s+(.*\S)\s*$)");
      std::smatch             m;
      return std::regex_match(line, m, include) ? m[1].str() : "";
    }

    /// The "Section/Sub/" path in force at line `line` (1-based) of a prm
    /// file, so that an error can name the parameter as --set would.
    std::string
    section_path_at(const std::string &filename, const unsigned int line)
    {
      const auto lines = lines_with_sections(filename);
      return line >= 1 && line <= lines.size() ? lines[line - 1].first : "";
    }

    /// f(file, line, path, text) for every line of a prm file (line: 1-based,
    /// path: the "Section/Sub/" in force) and, in place of each `include`
    /// line, for the lines of the file it names, as parse_parameters() reads
    /// them: relative to the top file's directory, in the section where the
    /// include line stands (nested includes too, up to 8 deep).
    template <typename F>
    void
    for_each_line(const std::string &filename, const F &f)
    {
      const auto directory = std::filesystem::path(filename).parent_path();
      const std::function<void(const std::string &, const std::string &, unsigned int)> read =
        [&](const std::string &file, const std::string &prefix, const unsigned int depth) {
          const auto lines = lines_with_sections(file, prefix);
          for (unsigned int n = 0; n < lines.size(); ++n)
            if (const std::string included = included_file(lines[n].second); included.empty())
              f(file, n + 1, lines[n].first, lines[n].second);
            else if (depth < 8)
              read(std::filesystem::path(included).is_absolute() ?
                     included :
                     (directory / included).lexically_normal().string(),
                   lines[n].first, depth + 1);
        };
      read(filename, "", 0);
    }

    /// set_parameter_origin() for every entry the file and the files it
    /// includes set: "FILE line N"; a warning (rank 0) for an entry set twice
    /// in one file, whose last value counts.
    void
    record_parameter_origins(const std::string &filename)
    {
      const std::regex set(R"(^\s*set\s+(.*\S)\s*=.*$)");
      std::smatch      m;
      // (file, entry): the line that sets it first
      std::map<std::pair<std::string, std::string>, unsigned int> first;
      const bool root = !Utilities::MPI::job_supports_mpi() ||
                        Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
      for_each_line(filename, [&](const std::string &file, const unsigned int line,
                                  const std::string &path, const std::string &text) {
        if (!std::regex_match(text, m, set))
          return;
        const std::string name = path + m[1].str();
        if (const auto [at, fresh] = first.emplace(std::make_pair(file, name), line); !fresh && root)
          std::cerr << "granular_dg: warning: '" << name << "' is set twice in " << file
                    << " (lines " << at->second << " and " << line << "): the last value counts"
                    << std::endl;
        set_parameter_origin(name, file + " line " + std::to_string(line));
      });
    }

    /// Turns ParameterHandler's messages into our one-line form naming the
    /// parameter, its value and what is allowed.
    std::string
    translate_parameter_error(const std::string &message,
                              const std::string &filename,
                              const std::string &set_path)
    {
      std::smatch m;
      // parse_input: "Line <3> of file <f.prm>: The entry value 9 for the
      // entry named degree does not match the given pattern: [..]"
      static const std::regex file_pattern(
        R"(Line <(\d+)> of file <[^>]*>: The entry value (.*) for the entry named (.*) does not match the given pattern: (.*))");
      static const std::regex file_unknown(
        R"(Line <(\d+)> of file <[^>]*>: No entry with name <(.*)> was declared in the current subsection.*)");
      static const std::regex file_section(
        R"(Line <(\d+)> of file <[^:>]*>?: There is no such subsection to be entered: .*)");
      static const std::regex file_line(R"(Line <(\d+)> of file <[^>]*>: (.*))");
      // set(): "The string <9> does not match the given pattern <[..]>."
      static const std::regex set_pattern(
        R"(.*The string <(.*)> does not match the given pattern <(.*)>\.?)");
      static const std::regex set_unknown(R"(.*You can't ask for entry <(.*)> you have not yet declared\.?)");
      static const std::regex set_section(R"(.*There is no subsection <(.*)> .*)");

      const std::string hint = " (granular_dg --print-parameters SCENE lists them all)";
      // the line of a file the parameter file includes: that file's
      static const std::regex file_of(R"(Line <\d+> of file <([^>]*)>.*)");
      std::string             file = filename;
      if (std::regex_match(message, m, file_of) && !is_parameter_file(m[1].str()))
        file = resolve_input_path(m[1].str());
      if (std::regex_match(message, m, file_pattern))
        {
          const unsigned int line = std::stoul(m[1]);
          return "parameter '" + section_path_at(file, line) + m[3].str() +
                 "' = '" + m[2].str() + "' (" + file + " line " + m[1].str() +
                 ") is not allowed: " + m[4].str();
        }
      if (std::regex_match(message, m, file_unknown))
        {
          const unsigned int line = std::stoul(m[1]);
          return "unknown parameter '" + section_path_at(file, line) +
                 m[2].str() + "' (" + file + " line " + m[1].str() + ")" + hint;
        }
      if (std::regex_match(message, m, file_section))
        {
          // the path including the subsection opened on that line
          const unsigned int line = std::stoul(m[1]);
          std::string        path = section_path_at(file, line + 1);
          path.pop_back();
          return "unknown section '" + path + "' (" + file + " line " + m[1].str() + ")" +
                 hint;
        }
      if (std::regex_match(message, m, file_line))
        return file + " line " + m[1].str() + ": " + m[2].str();
      if (!set_path.empty())
        {
          if (std::regex_match(message, m, set_pattern))
            return "parameter '" + set_path + "' = '" + m[1].str() +
                   "' (--set) is not allowed: " + m[2].str();
          if (std::regex_match(message, m, set_unknown) ||
              std::regex_match(message, m, set_section))
            return "unknown parameter '" + set_path + "' (--set)" + hint;
          return "in --set '" + set_path + "': " + message;
        }
      return "in parameter file '" + filename + "': " + message;
    }
  } // namespace

  void
  require_readable_parameter_file(const std::string &filename)
  {
    std::ifstream in(filename);
    if (!in)
      throw InputError("cannot open parameter file '" + filename +
                       "': it does not exist or is not readable");
    if (std::filesystem::is_directory(filename))
      throw InputError("cannot read parameter file '" + filename + "': it is a directory");
    // (deal.II would quote the invisible mark as part of the first line)
    char start[3] = {};
    if (in.read(start, 3) && std::string(start, 3) == "\xEF\xBB\xBF")
      throw InputError("parameter file '" + filename +
                       "' starts with a UTF-8 byte-order mark (the bytes EF BB BF, which some "
                       "editors add): save it as UTF-8 without a BOM");
  }

  std::vector<std::pair<std::string, std::string>>
  top_level_settings(const std::string &filename, const std::string &name)
  {
    const std::regex set(R"(^\s*set\s+)" + name + R"(\s*=\s*(.*\S)?\s*$)");
    std::smatch      m;
    std::vector<std::pair<std::string, std::string>> found;
    for_each_line(filename, [&](const std::string &file, const unsigned int line,
                                const std::string &path, const std::string &text) {
      if (path.empty() && std::regex_match(text, m, set))
        found.emplace_back(m[1].str(), file + " line " + std::to_string(line));
    });
    return found;
  }

  void
  parse_parameters(ParameterHandler               &prm,
                   const std::string              &filename,
                   const std::vector<std::string> &overrides)
  {
    require_readable_parameter_file(filename);
    set_parameter_file(filename);
    record_parameter_origins(filename);
    // an `include` line names a file relative to the parameter file, as
    // every path in it does (resolve_input_path()); deal.II opens it
    // relative to the working directory, which is the parameter file's
    // while it parses
    const auto cwd  = std::filesystem::current_path();
    const auto file = std::filesystem::absolute(filename);
    std::filesystem::current_path(file.parent_path());
    try
      {
        // undeclared entries are errors: a typo must never be ignored
        prm.parse_input(file.string(), "", false);
        std::filesystem::current_path(cwd);
      }
    catch (const std::exception &e)
      {
        std::filesystem::current_path(cwd);
        throw InputError(
          translate_parameter_error(one_line_message(e), filename, ""));
      }

    for (const auto &o : overrides)
      {
        const auto eq = o.find('=');
        if (eq == std::string::npos)
          throw InputError("--set '" + o +
                           "' is not of the form Section/name=value");
        const std::string path_text = Utilities::trim(o.substr(0, eq));
        std::vector<std::string> path =
          Utilities::split_string_list(path_text, '/');
        const std::string value = Utilities::trim(o.substr(eq + 1));
        if (path.empty() || path.back().empty())
          throw InputError("--set '" + o + "' is not of the form Section/name=value");
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
            throw InputError(translate_parameter_error(one_line_message(e),
                                                       filename,
                                                       path_text));
          }
        for (; depth > 0; --depth)
          prm.leave_subsection();
        std::string entry;
        for (const auto &section : path)
          entry += section + "/";
        // (the options --resume and --benchmark set these two)
        const std::string origin = entry + name == "Checkpoint/resume" ? "--resume" :
                                   entry + name == "Benchmark/enabled" ? "--benchmark" :
                                                                         "--set";
        set_parameter_origin(entry + name, origin);
      }
  }

  template std::shared_ptr<FunctionParser<1>>
  make_function<1>(const std::vector<std::string> &, const std::vector<std::string> &, bool);
  template std::shared_ptr<FunctionParser<2>>
  make_function<2>(const std::vector<std::string> &, const std::vector<std::string> &, bool);
} // namespace granular_dg
