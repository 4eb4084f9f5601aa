#ifndef fidus_simulation_output_columns_h
#define fidus_simulation_output_columns_h

// The column names of particles.csv and statistics.csv (fixed by the
// interface; more may be appended, none renamed), shared by the files of
// Simulation that open and write them.

#include <fidus/rheology/suspension_stress.h>
#include <string>
#include <vector>

namespace Fidus
{
  namespace OutputColumns
  {
    /// particles.csv.
    inline std::vector<std::string>
    particle_columns()
    {
      return {"step",
              "time",
              "id",
              "x",
              "y",
              "z",
              "ux",
              "uy",
              "uz",
              "omega_x",
              "omega_y",
              "omega_z",
              "radius",
              "stresslet_xx",
              "stresslet_xy",
              "stresslet_xz",
              "stresslet_yy",
              "stresslet_yz",
              "stresslet_zz",
              "contact_stresslet_xx",
              "contact_stresslet_xy",
              "contact_stresslet_xz",
              "contact_stresslet_yy",
              "contact_stresslet_yz",
              "contact_stresslet_zz",
              "lubrication_stresslet_xx",
              "lubrication_stresslet_xy",
              "lubrication_stresslet_xz",
              "lubrication_stresslet_yy",
              "lubrication_stresslet_yz",
              "lubrication_stresslet_zz",
              // The velocities the particle moved with in the step that
              // ended at this row (after lubrication and contact; 0 in
              // the row of step 0), and its orientation as a unit
              // quaternion (2D: a turn by the angle about z).
              "moved_ux",
              "moved_uy",
              "moved_uz",
              "moved_omega_x",
              "moved_omega_y",
              "moved_omega_z",
              "orientation_w",
              "orientation_x",
              "orientation_y",
              "orientation_z"};
    }

    /// statistics.csv: the run's columns, the stress columns, then the
    /// lubrication count.
    inline std::vector<std::string>
    statistics_columns()
    {
      std::vector<std::string> c = {"step",
                                    "time",
                                    "dt",
                                    "cells",
                                    "dofs",
                                    "uzawa_iterations",
                                    "linear_iterations",
                                    "rigidity_residual",
                                    "min_gap",
                                    "active_contacts",
                                    "glued_contacts",
                                    "wall_seconds",
                                    "remeshed",
                                    "contact_iterations",
                                    "shared_cells",
                                    "shared_residual"};
      for (const std::string &name : SuspensionStress::column_names())
        c.push_back(name);
      // Particle-particle and particle-wall gaps that the lubrication
      // correction acted on in this step.
      c.push_back("lubrication_pairs");
      // The Uzawa loop's last change of the rigid velocities.
      c.push_back("rigid_velocity_change");
      // The largest per-particle rigidity residual (Fluid/Rigidity
      // measure), whichever measure the loop stops on.
      c.push_back("particle_rigidity_residual");
      // Contacts whose friction force is on the rim of Coulomb's cone.
      c.push_back("sliding_contacts");
      return c;
    }
  } // namespace OutputColumns
} // namespace Fidus

#endif
