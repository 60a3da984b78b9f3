#ifndef cycloid_app_run_h
#define cycloid_app_run_h

#include <cycloid/parameters/all_parameters.h>

#include <mpi.h>

namespace cycloid
{
  namespace app
  {
    /** Run the mode selected by `Run` in @p parameters on @p comm. */
    void
    run(const parameters::AllParameters &parameters, const MPI_Comm comm);

    /**
     * `Run = analytic`: the analytical model over every crank angle of
     * `Loading` and every torque; writes stiffness.csv and pin_forces.csv
     * (rank 0 computes and writes, other ranks return at once).
     */
    void
    run_analytic(const parameters::AllParameters &parameters,
                 const MPI_Comm                   comm);

    /**
     * `Run = quasi-static`: FE contact of the scene (2D one disc, 3D one
     * or two discs) at `Crank angle`, for each `Torque` in turn (each
     * warm-started from the previous); writes stiffness.csv,
     * pin_forces.csv and the VTU fields.
     */
    void
    run_quasi_static(const parameters::AllParameters &parameters,
                     const MPI_Comm                   comm);

    /**
     * `Run = phase-sweep`: the quasi-static FE contact at `Number of
     * phases` crank angles over one mesh period 360/zp degrees (both ends
     * included), each torque warm-started from the previous phase's active
     * set at that torque; the CSV rows are flushed per state, progress and
     * the remaining time are printed, and fluctuation.csv gets the
     * stiffness fluctuation (max - min)/mean per torque.
     */
    void
    run_phase_sweep(const parameters::AllParameters &parameters,
                    const MPI_Comm                   comm);

    /**
     * `Run = transient`: elastodynamics with contact while the crank turns
     * (dynamics::Transient); writes energy.csv, stiffness.csv,
     * pin_forces.csv per step, transient.h5, and optionally VTU and
     * checkpoints.
     */
    void
    run_transient(const parameters::AllParameters &parameters,
                  const MPI_Comm                   comm);

    /**
     * `Run = mesh`: generate the scene's mesh (Scene/Dimension), write it
     * as mesh.pvtu / mesh_boundary.pvtu with body, boundary and rank ids,
     * print cell counts and quality, and fail on inverted cells.
     */
    template <int dim>
    void
    run_mesh(const parameters::AllParameters &parameters, const MPI_Comm comm);
  } // namespace app
} // namespace cycloid

#endif
