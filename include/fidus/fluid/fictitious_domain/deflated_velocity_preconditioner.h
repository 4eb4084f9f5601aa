#ifndef fidus_fluid_deflated_velocity_preconditioner_h
#define fidus_fluid_deflated_velocity_preconditioner_h

#include <deal.II/lac/trilinos_vector.h>
#include <fidus/fluid/fictitious_domain/rigid_mode_correction.h>
#include <fidus/fluid/fictitious_domain/velocity_block.h>

namespace Fidus
{
  using namespace dealii;

  /**
   * A V-cycle @p P for the velocity block A, with the particles' rigid
   * motions corrected before and after it (RigidModeCorrection Q):
   *
   *   x = Q r;  x += P (r - A x);  x += Q (r - A x).
   *
   * Symmetric when P is; two more products with A per application. Without
   * particles it is P.
   */
  template <class VPreconditioner>
  class DeflatedVelocityPreconditioner
  {
  public:
    DeflatedVelocityPreconditioner(const VelocityBlock       &A,
                                   const VPreconditioner     &P,
                                   const RigidModeCorrection &Q)
      : A(A)
      , P(P)
      , Q(Q)
    {}

    /// dst = the preconditioner applied to src.
    void
    vmult(TrilinosWrappers::MPI::Vector       &dst,
          const TrilinosWrappers::MPI::Vector &src) const
    {
      if (Q.empty())
        {
          P.vmult(dst, src);
          return;
        }
      if (r.size() != src.size())
        {
          r.reinit(src, true);
          t.reinit(src, true);
        }
      Q.vmult(dst, src);
      A.vmult(r, dst);
      r.sadd(-1., 1., src);
      P.vmult(t, r);
      dst += t;
      A.vmult(r, dst);
      r.sadd(-1., 1., src);
      Q.vmult(t, r);
      dst += t;
    }

  private:
    const VelocityBlock                  &A;
    const VPreconditioner                &P;
    const RigidModeCorrection            &Q;
    mutable TrilinosWrappers::MPI::Vector r, t;
  };
} // namespace Fidus

#endif
