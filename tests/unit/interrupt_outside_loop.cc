// A SIGINT or SIGTERM outside a time loop (base/checkpoint.h,
// handle_interrupts_outside_time_loops): the process ends at once with exit
// 128 + signal and, on the reporting rank, one line saying when: during
// set-up (no time loop has begun) or after one. Each case runs in a child
// process whose stderr goes to a pipe; prints the exit code and the line.
// A rank that does not report writes nothing. Exits 1 when anything is wrong.
#include <granular_dg/base/checkpoint.h>

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <iostream>
#include <string>

using namespace granular_dg;

namespace
{
  bool failed = false;

  /// In a child: the handlers installed (report), a time loop begun and
  /// ended first when after_loop, then signal raised; the child's exit code
  /// and stderr.
  std::pair<int, std::string>
  interrupted(const int signal, const bool report, const bool after_loop)
  {
    int ends[2];
    if (pipe(ends) != 0)
      return {-1, "pipe failed"};
    const pid_t child = fork();
    if (child == 0)
      {
        dup2(ends[1], 2);
        close(ends[0]);
        handle_interrupts_outside_time_loops(report);
        if (after_loop)
          const InterruptHandlers loop;
        raise(signal);
        _exit(0); // not reached when the signal ends the process
      }
    close(ends[1]);
    std::string text;
    char        buffer[512];
    for (ssize_t n; (n = read(ends[0], buffer, sizeof(buffer))) > 0;)
      text.append(buffer, n);
    close(ends[0]);
    int status = 0;
    waitpid(child, &status, 0);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text};
  }

  void
  expect(const std::string &what, const int signal, const bool report, const bool after_loop,
         const int code, const bool line)
  {
    const auto [exit_code, text] = interrupted(signal, report, after_loop);
    const bool ok = exit_code == code && (line ? !text.empty() && text.back() == '\n' &&
                                                   text.find('\n') == text.size() - 1 :
                                                 text.empty());
    failed |= !ok;
    std::cout << what << ": exit " << exit_code << ", stderr: " << (text.empty() ? "(none)\n" : text)
              << (ok ? "" : "FAILED\n");
  }
} // namespace

int
main()
{
  expect("SIGINT during set-up", SIGINT, true, false, 130, true);
  expect("SIGTERM during set-up", SIGTERM, true, false, 143, true);
  expect("SIGINT after a time loop", SIGINT, true, true, 130, true);
  expect("SIGTERM on a rank that does not report", SIGTERM, false, false, 143, false);
  return failed ? 1 : 0;
}
