#ifndef cycloid_tests_reduced_settings_h
#define cycloid_tests_reduced_settings_h

#include <cycloid/app/all_parameters.h>
#include <cycloid/reduced/coarse_model.h>

namespace cycloid
{
  namespace tests
  {
    /** The reduced model's settings of the stage @p p, quiet, without the
     * error estimate's companion and with the FE error control off: what
     * the unit tests of the reduced model build their coarse models
     * from. */
    inline reduced::ReducedSettings
    quiet_reduced_settings(const app::AllParameters &p)
    {
      reduced::ReducedSettings s;
      s.stage.geometry                   = p.geometry;
      s.stage.material                   = p.material;
      s.stage.scene                      = p.scene;
      s.stage.mesh                       = p.mesh;
      s.stage.contact                    = p.contact;
      s.stage.analytic                   = p.analytic;
      s.stage.bearings                   = p.bearings;
      s.stage.mesh.error.mode            = mesh::ErrorControl::Mode::off;
      s.stage.mesh.error.target_accuracy = 0;
      s.stage.quiet                      = true;
      s.reduced                          = p.reduced;
      s.reduced.error_estimate           = false;
      return s;
    }
  } // namespace tests
} // namespace cycloid

#endif
