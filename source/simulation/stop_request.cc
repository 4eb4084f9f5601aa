#include <csignal>
#include <fidus/simulation/stop_request.h>

namespace Fidus
{
  namespace
  {
    volatile std::sig_atomic_t received = 0;

    constexpr int handled[] = {SIGTERM, SIGINT, SIGUSR1};

    struct sigaction previous[3];

    extern "C" void
    on_stop_signal(const int signal)
    {
      if (received != 0)
        {
          // Second signal: stop now, as if fidus had not handled it.
          std::signal(signal, SIG_DFL);
          std::raise(signal);
          return;
        }
      received = signal;
    }
  } // namespace



  StopRequest::StopRequest()
  {
    received                = 0;
    struct sigaction action = {};
    action.sa_handler       = on_stop_signal;
    sigemptyset(&action.sa_mask);
    // Restart interrupted system calls (file writes, MPI progress), so
    // that the step in progress finishes normally.
    action.sa_flags = SA_RESTART;
    for (unsigned int k = 0; k < 3; ++k)
      sigaction(handled[k], &action, &previous[k]);
  }



  StopRequest::~StopRequest()
  {
    for (unsigned int k = 0; k < 3; ++k)
      sigaction(handled[k], &previous[k], nullptr);
  }



  int
  StopRequest::signal_received()
  {
    return received;
  }



  const char *
  StopRequest::name(const int signal)
  {
    return signal == SIGTERM ? "SIGTERM" :
           signal == SIGINT  ? "SIGINT" :
           signal == SIGUSR1 ? "SIGUSR1" :
                               "a signal";
  }
} // namespace Fidus
