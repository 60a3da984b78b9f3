#ifndef cycloid_dynamics_transient_h
#define cycloid_dynamics_transient_h

#include <cycloid/contact/quasi_static.h>
#include <cycloid/dynamics/contact_dynamics.h>

#include <memory>
#include <string>
#include <vector>

namespace cycloid
{
  namespace dynamics
  {
    /**
     * @brief `Run = transient`: elastodynamics of a scene with contact while
     * the crank turns at `Transient/Crank speed` and the torque rises over
     * `Transient/Ramp time` to `Loading/Torque` (or the rotation to
     * `Loading/Rotation` under rotation control).
     *
     * The mesh is built once at `Loading/Crank angle` and refined at every
     * contact point that the run's crank sweep meets; the discs' rigid
     * placement at the crank angle of each step enters through
     * contact::ContactProblem::set_placement (gaps, normals and master
     * coefficients recomputed every step), so the elastic displacement is
     * measured from the kinematic placement. The frame's rigid acceleration
     * (eccentric motion) is not applied as a body force; displacements are
     * in the mesh axes (the disc turns by 360 deg/(zp zc) per mesh period,
     * 0.23 deg for the seed).
     *
     * Every step writes one stiffness.csv row (K_secant = T/beta; the
     * quasi-static tangent is not defined in a dynamic state and is NaN),
     * zp pin_forces.csv rows per disc and one energy.csv row (energies and
     * works in J for the whole tooth width, the balance error and the
     * largest penetration); transient.h5 holds the same time series;
     * checkpoints allow an exact restart on the same number of ranks.
     */
    template <int dim>
    class Transient : public contact::QuasiStatic<dim>
    {
    public:
      /** Mesh and contact problem of the scene; nothing solved yet. */
      Transient(const parameters::AllParameters &parameters,
                const MPI_Comm                   comm);

      /** Time-step to the end time (or `Stop after step`). */
      void
      run();

    private:
      /** Time series kept for transient.h5 and the checkpoint. */
      struct History
      {
        std::vector<double> time, crank_deg, torque, rotation, k_secant,
          kinetic, elastic, external_work, dissipated, balance, penetration,
          iterations, angular_momentum;
        /** Per step, nd * zp values each. */
        std::vector<double> fx, fy, fn;

        std::vector<std::vector<double> *>
        all();
      };

      /** Place the discs at crank angle @p psi_now [rad]. */
      void
      place_discs(const double psi_now);

      /** Torque [N m] or rotation [rad] at time @p t. */
      double
      load_at(const double t) const;

      void
      write_checkpoint(const unsigned int step, const double t) const;

      /** Returns the step of the checkpoint. */
      unsigned int
      read_checkpoint();

      void
      write_hdf5() const;

      /** Angular momentum of the discs about their centres, g . M v with g
       * the discs' unit rotation field (zero on other bodies) [N mm s per
       * mm thickness in 2D]. */
      double
      angular_momentum() const;

      /** The discs' unit rotation field (owned entries). */
      dealii::TrilinosWrappers::MPI::Vector rotation_field;

      const double                          psi0;
      std::unique_ptr<ContactDynamics<dim>> dynamics;
      History                               history;
      double                                initial_energy = 0;
      /** Largest of E_kin + E_el + D and |W| so far [J]. */
      double                                      energy_scale = 0;
      std::vector<std::pair<double, std::string>> records;
    };
  } // namespace dynamics
} // namespace cycloid

#endif
