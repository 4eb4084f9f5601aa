// StopRequest: the first SIGTERM / SIGINT / SIGUSR1 is only recorded (the
// run finishes its step and checkpoints), a second one ends the process at
// once with that signal, and the previous handlers come back afterwards.

#include "../fidus_test.h"

#include <csignal>
#include <fidus/simulation/stop_request.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace FidusTest;

int
main(int argc, char **argv)
{
  // The child process of the last check is forked before MPI starts, so
  // that MPI never sees a fork.
  const pid_t child = fork();
  if (child == 0)
    {
      const Fidus::StopRequest stop;
      std::raise(SIGTERM);
      if (Fidus::StopRequest::signal_received() != SIGTERM)
        _exit(3);
      std::raise(SIGTERM);
      _exit(0);
    }
  int status = 0;
  waitpid(child, &status, 0);

  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  {
    const Fidus::StopRequest stop;
    check_range("no signal yet", Fidus::StopRequest::signal_received(), 0, 0);
    std::raise(SIGUSR1);
    check_range("SIGUSR1 recorded, process alive",
                Fidus::StopRequest::signal_received(),
                SIGUSR1,
                SIGUSR1);
  }

  // A new request starts from no signal.
  {
    const Fidus::StopRequest stop;
    check_range("a new request starts clear",
                Fidus::StopRequest::signal_received(),
                0,
                0);
  }

  // Two signals in the child process: the first is recorded, the second
  // kills it with SIGTERM (exit code 0 would mean it survived).
  check_range("second SIGTERM ends the process by that signal",
              WIFSIGNALED(status) ? WTERMSIG(status) : -WEXITSTATUS(status),
              SIGTERM,
              SIGTERM);

  // The handlers are restored: SIGTERM is back to its default action.
  struct sigaction current;
  sigaction(SIGTERM, nullptr, &current);
  check_range("SIGTERM handler restored to the default",
              current.sa_handler == SIG_DFL ? 1 : 0,
              1,
              1);
  return exit_code();
}
