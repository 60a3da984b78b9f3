#ifndef cycloid_runs_transient_h
#define cycloid_runs_transient_h

#include <cycloid/dynamics/checkpoint.h>
#include <cycloid/dynamics/contact_dynamics.h>
#include <cycloid/dynamics/energy_account.h>
#include <cycloid/dynamics/time_control.h>
#include <cycloid/postprocess/report.h>
#include <cycloid/postprocess/solution_record.h>
#include <cycloid/postprocess/time_series.h>
#include <cycloid/runs/quasi_static.h>

#include <memory>
#include <string>

#include <mpi.h>

namespace cycloid
{
  namespace runs
  {
    /**
     * @brief `Run = transient`: elastodynamics of a scene with contact while
     * the crank turns at `Transient/Crank speed` and the torque rises over
     * `Transient/Ramp time` to `Loading/Torque` (or the rotation to
     * `Loading/Rotation` under rotation control).
     *
     * It composes pieces that know nothing of each other: the FE scene
     * (stage::StageScene, its mesh built once at `Loading/Crank angle` and
     * refined at every contact point of the run's crank sweep, the discs
     * placed at each step's crank angle), the time scheme
     * (dynamics::ContactDynamics), the time control
     * (dynamics::TimeControl), the energy account
     * (dynamics::EnergyAccount), checkpoints (dynamics::Checkpoint), and
     * the outputs (postprocess::Report for stiffness.csv, pin_forces.csv
     * and energy.csv, postprocess::TimeSeries for transient.h5,
     * postprocess::SolutionRecord for the fields).
     *
     * The elastic displacement is measured from the kinematic placement;
     * the frame's rigid acceleration (eccentric motion) is not applied as a
     * body force; displacements are in the mesh axes. Every step writes one
     * stiffness.csv row (K_secant = T/beta; the quasi-static tangent is not
     * defined in a dynamic state and is NaN), zp pin_forces.csv rows per
     * disc and one energy.csv row (energies and works in J for the whole
     * tooth width, the balance error, the largest penetration and the
     * discs' angular momentum). Checkpoints allow an exact restart on the
     * same number of ranks.
     */
    template <int dim>
    class TransientRun
    {
    public:
      /** What the run reads from the parameter file. */
      struct Settings
      {
        FeRunSettings                 run;       ///< The FE scene and its load.
        dynamics::TransientParameters transient; ///< Subsection `Transient`.
      };

      /** Build the scene and the time scheme on it; nothing solved yet. */
      TransientRun(const Settings &settings, const MPI_Comm comm);

      /** Time-step to the end time (or `Stop after step`). */
      void
      run();

    private:
      /** Place the discs at the start and start at rest; or resume from
       * the checkpoint. Returns the first step to solve minus one, and the
       * CSV sizes to resume from (empty for a fresh start). */
      unsigned int
      start(std::vector<std::uintmax_t> &sizes);

      /** Solve step @p step: its state and energy row. */
      std::pair<results::StageState, results::EnergyState>
      advance(const unsigned int step);

      /** Write the checkpoint of step @p step. */
      void
      write_checkpoint(const unsigned int         step,
                       const postprocess::Report &report);

      /** The one list of what a checkpoint holds (the dynamics, the energy
       * account, the time series and the CSV sizes @p sizes), written or
       * restored through @p ar. */
      void
      checkpoint_fields(dynamics::CheckpointArchive &ar,
                        std::vector<std::uintmax_t> &sizes);

      /** Angular momentum of the discs about their centres, g . M v with g
       * the discs' unit rotation field [N mm s per mm thickness in 2D]. */
      double
      angular_momentum() const;

      /** The progress line of step @p step. */
      void
      print_progress(const unsigned int          step,
                     const unsigned int          first,
                     const results::StageState  &state,
                     const results::EnergyState &energy,
                     const double                elapsed) const;

      const Settings                                  settings;
      const MPI_Comm                                  comm;
      dealii::ConditionalOStream                      pcout;
      const dynamics::TimeControl                     time;
      stage::StageScene<dim>                          scene;
      std::unique_ptr<dynamics::ContactDynamics<dim>> dynamics;
      dynamics::EnergyAccount                         energy;
      dynamics::Checkpoint                            checkpoint;
      postprocess::TimeSeries                         series;
      postprocess::SolutionRecord                     record;
    };
  } // namespace runs
} // namespace cycloid

#endif
