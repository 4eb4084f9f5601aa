#include <dmumps_c.h>
#include <fidus/fluid/cut_element/mumps_solver.h>
#include <stdexcept>

namespace Fidus
{
  namespace
  {
    /// MUMPS's JOB codes.
    constexpr int job_init = -1, job_end = -2, job_factorize = 4, job_solve = 3;

    /// MUMPS's 1-based ICNTL(i), INFOG(i).
    int &
    icntl(DMUMPS_STRUC_C &id, const int i)
    {
      return id.icntl[i - 1];
    }

    int
    infog(const DMUMPS_STRUC_C &id, const int i)
    {
      return id.infog[i - 1];
    }
  } // namespace

  struct MumpsSolver::Instance
  {
    DMUMPS_STRUC_C id;
  };

  MumpsSolver::MumpsSolver(const MPI_Comm comm, const Settings &settings)
    : mumps(std::make_unique<Instance>())
    , comm(comm)
  {
    DMUMPS_STRUC_C &id = mumps->id;
    id.comm_fortran    = static_cast<MUMPS_INT>(MPI_Comm_c2f(comm));
    id.par             = 1; // the host factorises too
    id.sym             = settings.symmetric ? 2 : 0;
    id.job             = job_init;
    dmumps_c(&id);
    if (infog(id, 1) < 0)
      throw std::runtime_error("MUMPS did not start (INFOG(1) = " +
                               std::to_string(infog(id, 1)) + ")");
    // Silent.
    for (const int i : {1, 2, 3, 4})
      icntl(id, i) = i == 4 ? 0 : -1;
    icntl(id, 7) = settings.ordering;
    // The matrix distributed over the ranks as they hand it in; the
    // right-hand side and the solution whole on the host.
    int n_ranks = 1;
    MPI_Comm_size(comm, &n_ranks);
    icntl(id, 18) = n_ranks > 1 ? 3 : 0;
  }

  MumpsSolver::~MumpsSolver()
  {
    mumps->id.job = job_end;
    dmumps_c(&mumps->id);
  }

  void
  MumpsSolver::factorize(const unsigned int  n,
                         std::vector<int>    rows,
                         std::vector<int>    columns,
                         std::vector<double> values)
  {
    for (int &i : rows)
      ++i;
    for (int &j : columns)
      ++j;
    DMUMPS_STRUC_C &id = mumps->id;
    id.n               = n;
    if (icntl(id, 18) == 3)
      {
        id.nnz_loc = rows.size();
        id.irn_loc = rows.data();
        id.jcn_loc = columns.data();
        id.a_loc   = values.data();
      }
    else
      {
        id.nnz = rows.size();
        id.irn = rows.data();
        id.jcn = columns.data();
        id.a   = values.data();
      }
    // Workspace too small (-8, -9): more relaxation, as MUMPS's guide
    // advises, a few times.
    for (int attempt = 0; attempt < 4; ++attempt)
      {
        id.job = job_factorize;
        dmumps_c(&id);
        const int error = infog(id, 1);
        if (error != -8 && error != -9)
          break;
        icntl(id, 14) = 2 * std::max(icntl(id, 14), 20);
      }
    // The entries go when this returns: MUMPS's solve does not read them
    // (no refinement or error analysis inside MUMPS).
    id.irn = id.jcn = id.irn_loc = id.jcn_loc = nullptr;
    id.a = id.a_loc = nullptr;
    if (infog(id, 1) < 0)
      throw std::runtime_error(
        "MUMPS's factorisation failed (INFOG(1) = " +
        std::to_string(infog(id, 1)) +
        ", INFOG(2) = " + std::to_string(infog(id, 2)) +
        (infog(id, 1) == -10 ? ": numerically singular" : "") + ")");
  }

  void
  MumpsSolver::solve(dealii::Vector<double> &b)
  {
    DMUMPS_STRUC_C &id   = mumps->id;
    int             rank = 0;
    MPI_Comm_rank(comm, &rank);
    id.rhs = rank == 0 ? b.begin() : nullptr;
    id.job = job_solve;
    dmumps_c(&id);
    if (infog(id, 1) < 0)
      throw std::runtime_error("MUMPS's solve failed (INFOG(1) = " +
                               std::to_string(infog(id, 1)) + ")");
    MPI_Bcast(b.begin(), b.size(), MPI_DOUBLE, 0, comm);
  }

} // namespace Fidus
