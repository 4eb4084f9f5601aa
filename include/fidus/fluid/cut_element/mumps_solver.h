#ifndef fidus_fluid_cut_element_mumps_solver_h
#define fidus_fluid_cut_element_mumps_solver_h

#include <deal.II/lac/vector.h>
#include <memory>
#include <mpi.h>
#include <string>
#include <vector>

namespace Fidus
{
  /**
   * A sparse direct solver over the ranks of a communicator: MUMPS called
   * through its own C interface, for the cut element's bordered saddle-point
   * system.
   *
   * Each rank hands in any part of the matrix's entries (duplicates are
   * summed), MUMPS analyses, factorises over all the ranks, and solves for
   * right-hand sides held whole on every rank, returning the whole solution
   * on every rank. For a symmetric matrix, MUMPS's LDL^T factorisation
   * (with 2 x 2 pivots for indefinite matrices) takes the entries of one
   * triangle only and needs about half the work and memory of LU.
   *
   * Called directly rather than through Trilinos' Amesos: through Amesos
   * (Debian's Trilinos 13.2) the cut element's upper triangle stopped as
   * numerically singular with either of its matrix-type parameters, as a
   * general matrix given one triangle would.
   */
  class MumpsSolver
  {
  public:
    /// What the factorisation takes.
    struct Settings
    {
      /// LDL^T from the upper triangle (row <= column) of a symmetric
      /// matrix; false: LU of a general matrix.
      bool symmetric = false;
      /// MUMPS's ICNTL(7), the fill-reducing ordering: 0 approximate
      /// minimum degree, 4 PORD, 7 MUMPS's choice.
      int ordering = 7;
    };

    /// Start MUMPS on @p comm (collective).
    MumpsSolver(MPI_Comm comm, const Settings &settings);

    /// End MUMPS (collective).
    ~MumpsSolver();

    MumpsSolver(const MumpsSolver &) = delete;
    MumpsSolver &
    operator=(const MumpsSolver &) = delete;

    /**
     * Analyse and factorise the matrix of size @p n whose entries on this
     * rank are (@p rows[k], @p columns[k], @p values[k]), 0-based
     * (collective; the entries are freed when it returns: MUMPS's solve
     * does not read them). Throws std::runtime_error, naming MUMPS's error
     * code,
     * if it fails; a numerically singular matrix is error -10. Where MUMPS
     * reports its workspace too small, the factorisation is repeated with
     * twice the relaxation, up to three times.
     */
    void
    factorize(unsigned int        n,
              std::vector<int>    rows,
              std::vector<int>    columns,
              std::vector<double> values);

    /// Solve A x = b in place: @p b, whole on every rank, becomes x, whole
    /// on every rank (collective).
    void
    solve(dealii::Vector<double> &b);

  private:
    /// The MUMPS instance, opaque here.
    struct Instance;
    std::unique_ptr<Instance> mumps;
    MPI_Comm                  comm;
  };
} // namespace Fidus

#endif
