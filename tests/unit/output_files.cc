// The program's writers on a full disk and beside a user's files
// (base/output.h). On /dev/full (every write fails with ENOSPC): a plain
// stream, a writer that throws deal.II's ExcIO as DataOutBase's do, and a
// CSV file each give a RunError naming the file, not a silent success. In an
// output directory: a file the directory's manifest does not list (a user's)
// is refused before it is touched, and stays as it was; a file this run
// wrote may be written again. Bad input found after the directory was
// prepared removes what preparing wrote, and nothing else. Exits 1 when
// anything is wrong.
#include <deal.II/base/exceptions.h>

#include <granular_dg/base/errors.h>
#include <granular_dg/base/output.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

using namespace granular_dg;
namespace fs = std::filesystem;

namespace
{
  bool failed = false;

  /// Run f; print what happened; expect a RunError when fails is true.
  template <typename F>
  void
  attempt(const std::string &what, const bool fails, const F &f)
  {
    std::string outcome = "written";
    try
      {
        f();
      }
    catch (const RunError &e)
      {
        outcome = e.what();
        // (the working directory as ".": the same text on every machine)
        const std::string cwd = fs::current_path().string();
        if (const auto at = outcome.find(cwd); at != std::string::npos)
          outcome.replace(at, cwd.size(), ".");
      }
    const bool ok = (outcome != "written") == fails;
    failed |= !ok;
    std::cout << what << ": " << outcome << (ok ? "" : "  <-- WRONG") << std::endl;
  }

  std::string
  read(const fs::path &file)
  {
    std::ifstream      in(file);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
} // namespace

int
main()
{
  const std::string big(1 << 16, 'x'); // more than a stream buffers
  attempt("a stream on a full disk", true,
          [&] { write_to_file("/dev/full", [&](std::ostream &out) { out << big; }); });
  attempt("a deal.II writer on a full disk", true, [&] {
    write_to_file("/dev/full", [&](std::ostream &out) {
      out << big;
      out.flush();
      AssertThrow(out.fail() == false, dealii::ExcIO());
    });
  });
  attempt("a CSV file on a full disk", true, [] {
    CsvWriter csv;
    csv.open("/dev/full", {"time", "u"});
    csv.row({0., 1.});
  });

  const fs::path directory = "output_files_out";
  fs::remove_all(directory);
  fs::create_directories(directory);
  std::ofstream(directory / "profile-0001.csv") << "the user's own\n";
  begin_manifest(directory.string(), false);
  attempt("a file in the output directory", false, [&] {
    write_to_file((directory / "solution-0000.vtu").string(),
                  [](std::ostream &out) { out << "snapshot\n"; });
    record_output_file((directory / "solution-0000.vtu").string());
  });
  attempt("the same file again (this run's)", false, [&] {
    write_to_file((directory / "solution-0000.vtu").string(),
                  [](std::ostream &out) { out << "snapshot again\n"; });
  });
  attempt("a file of the same name as the user's", true, [&] {
    CsvWriter csv;
    csv.open((directory / "profile-0001.csv").string(), {"x", "u"});
  });
  const bool kept = read(directory / "profile-0001.csv") == "the user's own\n";
  failed |= !kept;
  std::cout << "the user's file is unchanged: " << (kept ? "yes" : "NO") << std::endl;

  // Bad input found after the directory was prepared (abandon_new_output()):
  // what preparing wrote goes, with the directories it created; a user's
  // file, a directory that existed and a run that wrote more stay.
  const auto expect = [&](const std::string &what, const bool ok) {
    failed |= !ok;
    std::cout << what << ": " << (ok ? "yes" : "NO") << std::endl;
  };
  const auto prepare = [](const fs::path &d) {
    prepare_output_directory(d.string(), false);
    write_to_file((d / "parameters.prm").string(), [](std::ostream &out) { out << "set a = 1\n"; });
  };
  fs::remove_all("abandoned");
  fs::create_directories("abandoned/existing");
  std::ofstream("abandoned/existing/notes.txt") << "the user's own\n";
  prepare("abandoned/new/deeper");
  prepare("abandoned/existing");
  prepare("abandoned/wrote_more");
  write_to_file("abandoned/wrote_more/summary.json", [](std::ostream &out) { out << "{}\n"; });
  abandon_new_output();
  expect("a new directory (and its new parent) removed", !fs::exists("abandoned/new"));
  expect("an existing directory kept with the user's file only",
         fs::exists("abandoned/existing/notes.txt") &&
           std::distance(fs::directory_iterator("abandoned/existing"), fs::directory_iterator()) == 1);
  expect("a run that wrote more left alone", fs::exists("abandoned/wrote_more/parameters.prm") &&
                                               fs::exists("abandoned/wrote_more/summary.json"));
  return failed ? 1 : 0;
}
