#ifndef cycloid_postprocess_time_series_h
#define cycloid_postprocess_time_series_h

#include <cycloid/dynamics/checkpoint.h>
#include <cycloid/postprocess/report.h>
#include <cycloid/results/stage_state.h>

#include <iosfwd>
#include <string>
#include <vector>

#include <mpi.h>

namespace cycloid
{
  namespace postprocess
  {
    /**
     * @brief The time series of a transient run, written as `transient.h5`
     * (readable with h5py): one dataset per quantity over the steps, and
     * the pin forces as [step, disc * number_of_pins + pin] matrices. It
     * holds the whole series in memory so that the file can be rewritten
     * whole (atomically) at every checkpoint and at the end, and saves
     * itself into checkpoints.
     */
    class TimeSeries
    {
    public:
      /** What the file's attributes say about the run. */
      struct Attributes
      {
        std::string  scheme;                    ///< Name of the time scheme.
        double       time_step_s           = 0; ///< Time step [s].
        double       crank_speed_deg_per_s = 0; ///< Crank speed [deg/s].
        unsigned int n_pins                = 0; ///< Number of pins.
        unsigned int n_discs               = 0; ///< Number of discs.
      };

      /** An empty series of a run described by @p attributes. */
      explicit TimeSeries(const Attributes &attributes);

      /** Append the step of @p state with its energy row @p energy. */
      void
      add(const results::StageState &state, const results::EnergyState &energy);

      /** Write @p directory/transient.h5 on rank 0 of @p comm (through a
       * temporary file, so a reader never sees half a file). */
      void
      write_hdf5(const std::string &directory, const MPI_Comm comm) const;

      /** Write the series to a checkpoint or restore them from one. */
      void
      checkpoint(dynamics::CheckpointArchive &ar);

    private:
      /** Every series, in the order of checkpoint(). */
      std::vector<std::vector<double> *>
      all();

      const Attributes    attributes;
      std::vector<double> time, crank_deg, torque, rotation, k_secant, kinetic,
        elastic, external_work, dissipated, balance, penetration, iterations,
        angular_momentum;
      /** Per step, n_discs * n_pins values each. */
      std::vector<double> fx, fy, fn;
    };
  } // namespace postprocess
} // namespace cycloid

#endif
