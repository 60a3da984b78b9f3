#include <deal.II/base/mpi.h>

#include <cycloid/mesh/mesh_request.h>
#include <cycloid/reduced/coarse_model.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

namespace cycloid
{
  namespace reduced
  {
    double
    ReducedSettings::load_half_width() const
    {
      if (reduced.load_half_width > 0)
        return reduced.load_half_width;
      // Four elements of the refined contact zone across w, at most a third
      // of the pin radius: the law is exact for a half-space and holds to
      // order (w/R)^2 on the curved bodies.
      return std::min(4. * stage.mesh.contact_size /
                        std::pow(2.,
                                 reduced.refinements(stage.scene.dimension)),
                      stage.geometry.pin_radius / 3.);
    }



    ReducedSettings
    ReducedSettings::coarser() const
    {
      ReducedSettings    c   = *this;
      const unsigned int dim = stage.scene.dimension;
      const unsigned int r   = reduced.refinements(dim);
      // The whole mesh one level coarser: the far field as well as the
      // contacts, since the coarse model shares the FE model's far-field
      // error (up to 1.3 % in 2D at the default sizes, measured by the FE
      // model's bulk estimate).
      if (r > 0)
        c.reduced.contact_refinements = r - 1;
      else
        c.stage.mesh.contact_size *= 2;
      for (double *h : {&c.stage.mesh.flank_size,
                        &c.stage.mesh.pin_size,
                        &c.stage.mesh.coarse_size})
        *h *= 2;
      if (reduced.load_half_width > 0)
        c.reduced.load_half_width *= 2;
      c.reduced.axial_slices   = std::max(1u, reduced.axial_slices / 2);
      c.reduced.error_estimate = false;
      return c;
    }



    std::string
    ReducedSettings::coarser_description() const
    {
      const unsigned int dim = stage.scene.dimension;
      const unsigned int r   = reduced.refinements(dim);
      std::ostringstream d;
      if (r > 0)
        d << "Contact refinements " << r << " -> " << r - 1 << ", ";
      else
        d << "contact elements " << stage.mesh.contact_size << " -> "
          << 2 * stage.mesh.contact_size << " mm, ";
      d << "flank, pin and far-field elements doubled";
      d << ", w " << load_half_width() << " -> " << coarser().load_half_width()
        << " mm";
      if (dim == 3)
        d << ", axial slices " << reduced.axial_slices << " -> "
          << coarser().reduced.axial_slices;
      return d.str();
    }



    namespace
    {
      /** The coarse model's scene: refined at the loaded pins to resolve
       * the probing load, no adaptive cycles, silent. */
      stage::StageSettings
      coarse_settings(const ReducedSettings &settings, const int load_sign)
      {
        stage::StageSettings s = settings.stage;
        s.mesh.contact_refinements =
          settings.reduced.refinements(s.scene.dimension);
        if (s.scene.dimension == 3)
          s.mesh.axial_layers = settings.reduced.axial_layers;
        s.mesh.contact_refinement_radius =
          std::max(s.mesh.contact_refinement_radius,
                   2. * settings.load_half_width());
        s.mesh.refine_loaded_side_only = load_sign != 0;
        s.mesh.adaptive_cycles         = 0;
        s.quiet                        = true;
        s.check_cost                   = false;
        return s;
      }

      /** The mesh request: placement, the crank sweep its fine zones
       * cover, the loaded side. */
      mesh::MeshRequest
      coarse_request(const double psi, const double sweep, const int load_sign)
      {
        mesh::MeshRequest request;
        request.crank_angle = psi;
        request.sweep       = sweep;
        request.load_sign   = load_sign;
        return request;
      }
    } // namespace



    template <int dim>
    CoarseModel<dim>::CoarseModel(const ReducedSettings &settings,
                                  const double           psi,
                                  const double           sweep,
                                  const int              load_sign,
                                  const MPI_Comm         comm)
      : settings(settings)
      , psi_mesh(psi)
      , timing(MPI_COMM_SELF,
               std::cout,
               dealii::TimerOutput::never,
               dealii::TimerOutput::wall_times)
      , scene(coarse_settings(settings, load_sign),
              coarse_request(psi, sweep, load_sign),
              comm)
      , n_dofs(scene.contact_problem().elasticity_problem().n_dofs())
    {
      dealii::TimerOutput::Scope scope(timing, "reduced: assembly");
      scene.contact_problem().assemble_without_contact();
    }



    template <int dim>
    Compliance
    CoarseModel<dim>::condense(const std::vector<ContactPoint> &points,
                               std::ostream                    *progress)
    {
      // One factorisation serves every load case (CG+AMG needs ~100
      // iterations a load case on the glued pins and housing).
      return condense_compliance(scene.contact_problem(),
                                 points,
                                 settings.load_half_width(),
                                 elasticity::LinearSolver::direct,
                                 settings.stage.contact.factorisation(dim,
                                                                      true),
                                 settings.stage.contact.solver_tolerance,
                                 timing,
                                 progress);
    }



    template <int dim>
    std::map<std::string, double>
    CoarseModel<dim>::stage_times()
    {
      auto times =
        scene.timer().get_summary_data(dealii::TimerOutput::total_wall_time);
      for (const auto &[name, t] :
           timing.get_summary_data(dealii::TimerOutput::total_wall_time))
        times[name] += t;
      return times;
    }



    template class CoarseModel<2>;
    template class CoarseModel<3>;
  } // namespace reduced
} // namespace cycloid
