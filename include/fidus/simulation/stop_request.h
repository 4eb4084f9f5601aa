#ifndef fidus_simulation_stop_request_h
#define fidus_simulation_stop_request_h

namespace Fidus
{
  /**
   * SIGTERM, SIGINT and SIGUSR1 ask a run to stop cleanly: the current step
   * is finished, a checkpoint written, and the program exits. A second
   * signal stops the program at once (the default action of that signal).
   *
   * Batch systems send SIGTERM to every rank before a wall-time limit;
   * OpenMPI's mpirun forwards SIGUSR1 to every rank but answers SIGTERM by
   * killing the ranks after a short delay, so with mpirun send SIGUSR1 (or
   * SIGTERM to the ranks themselves). The handlers are installed for the
   * lifetime of this object; the previous ones come back afterwards.
   */
  class StopRequest
  {
  public:
    StopRequest();
    ~StopRequest();
    StopRequest(const StopRequest &) = delete;
    StopRequest &
    operator=(const StopRequest &) = delete;

    /// The signal received by this process (0: none).
    static int
    signal_received();

    /// Name of a signal number, e.g. "SIGTERM".
    static const char *
    name(int signal);
  };
} // namespace Fidus

#endif
