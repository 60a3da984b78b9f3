#ifndef cycloid_parameters_all_parameters_h
#define cycloid_parameters_all_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <cycloid/analytic/analytic_parameters.h>
#include <cycloid/contact/contact_parameters.h>
#include <cycloid/dynamics/transient_parameters.h>
#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/mesh/mesh_parameters.h>
#include <cycloid/parameters/loading.h>
#include <cycloid/parameters/material.h>
#include <cycloid/parameters/run.h>
#include <cycloid/parameters/scene.h>

#include <string>

namespace cycloid
{
  namespace parameters
  {
    /**
     * @brief Every parameter of a run, grouped by subsection; each group
     * declares and parses its own subsection. Passed whole to the run
     * modes.
     */
    struct AllParameters
    {
      RunParameters                run;
      geometry::GeometryParameters geometry;
      MaterialParameters           material;
      LoadingParameters            loading;
      SceneParameters              scene;
      analytic::AnalyticParameters analytic;
      mesh::MeshParameters         mesh;
      contact::ContactParameters   contact;
      /** Subsection Transient. */
      dynamics::TransientParameters transient;

      /** Declare every subsection. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Parse every subsection from an already read handler. */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /**
       * Declare, read @p filename (with a clear error if it does not exist
       * or does not parse) and parse.
       */
      static AllParameters
      read(const std::string &filename);
    };
  } // namespace parameters
} // namespace cycloid

#endif
