#ifndef cycloid_runs_quasi_static_h
#define cycloid_runs_quasi_static_h

#include <cycloid/parameters/loading.h>
#include <cycloid/postprocess/report.h>
#include <cycloid/stage/stage_scene.h>

#include <memory>

#include <mpi.h>

namespace cycloid
{
  namespace runs
  {
    /** What an FE run of load states reads from the parameter file. */
    struct FeRunSettings
    {
      stage::StageSettings          stage;   ///< The FE scene.
      parameters::LoadingParameters loading; ///< Loads and crank angles.
      /** Write the solution fields of every state. */
      bool write_solution = true;
    };

    /** The mesh request of a run with @p settings at crank angle @p psi
     * [rad] (the loaded side from the sign of its loads). */
    mesh::MeshRequest
    mesh_request(const FeRunSettings &settings, const double psi);

    /** The load of largest magnitude in @p loads (0 if empty): the one a
     * run's expected contact resolution is announced for
     * (StageScene::announce_resolution()). */
    double
    largest_load(const std::vector<double> &loads);

    /** Whether state @p i of @p loads is a zero of the torque cycle of
     * @p loading, reported as its branch's limit (StageScene::
     * zero_torque_limit()) instead of solved. */
    bool
    cycle_zero(const parameters::LoadingParameters &loading,
               const std::vector<double>           &loads,
               const unsigned int                   i);

    /** The report of a run of load states with @p settings. */
    postprocess::Report::Options
    report_options(const FeRunSettings &settings);

    /**
     * @brief `Run = quasi-static`: the FE contact of the scene at
     * `Loading/Crank angle`, for each load in turn (each warm-started from
     * the previous); writes stiffness.csv, pin_forces.csv and the solution
     * fields.
     */
    template <int dim>
    class QuasiStaticRun
    {
    public:
      /** Build the scene (checking it: no files for a scene that cannot be
       * solved). */
      QuasiStaticRun(const FeRunSettings &settings, const MPI_Comm comm);

      /** Solve and write every load state. */
      void
      run();

    private:
      /** Print what the run does (rank 0) and give the scene's settings:
       * the announcement comes before the scene is built. */
      static const stage::StageSettings &
      announce(const FeRunSettings &settings, const MPI_Comm comm);

      const FeRunSettings    settings;
      const MPI_Comm         comm;
      stage::StageScene<dim> scene;
    };
  } // namespace runs
} // namespace cycloid

#endif
