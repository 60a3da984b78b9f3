#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>

#include <cycloid/mesh/extrusion.h>
#include <cycloid/reduced/reduced_model.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>

namespace cycloid
{
  namespace reduced
  {
    std::function<std::pair<double, double>(double)>
    linearised_rigid_gap(const geometry::CycloidGeometry &geo,
                         const double                     psi,
                         const geometry::PinContact      &c)
    {
      const dealii::Point<2> q =
        geo.to_disc(c.disc, psi, geo.pin_centre(c.pin));
      const geometry::DiscProfile &profile = geo.disc_profile(c.disc);
      const double                 phi0    = profile.closest_point(q).phi;
      // Gap G and arm L of the flank point at profile parameter phi, with
      // the rigid rotation linearised as in the FE model (small
      // displacements: each flank point closes on the pin by beta times
      // the arm of the line from it to the pin centre).
      const auto gap_arm = [&profile, &q](const double phi) {
        const dealii::Point<2>     x = profile.profile(phi).point;
        const dealii::Tensor<1, 2> d = q - x;
        const dealii::Tensor<1, 2> n = d / d.norm();
        return std::make_pair(d.norm(), x[0] * n[1] - x[1] * n[0]);
      };
      const double h  = 1e-4; // [rad] of phi; the fit spans a few um
      const auto   g0 = gap_arm(phi0), gm = gap_arm(phi0 - h),
                 gp          = gap_arm(phi0 + h);
      const double curvature = (gp.first - 2. * g0.first + gm.first) / (h * h);
      const double arm_slope = (gp.second - gm.second) / (2. * h);
      AssertThrow(curvature > 0,
                  dealii::ExcMessage("reduced model: pin " +
                                     std::to_string(c.pin) +
                                     " does not touch the flank at a "
                                     "closest point (curvature of its gap " +
                                     std::to_string(curvature) + ")."));
      const double clearance = c.clearance, arm = g0.second;
      // min over phi of G(phi) - beta L(phi) on the quadratic model: the
      // contact slides to phi0 + beta L' / G''.
      return [clearance, arm, curvature, arm_slope](const double beta) {
        const double shift = beta * arm_slope / curvature;
        return std::make_pair(clearance - beta * arm -
                                0.5 * beta * arm_slope * shift,
                              arm + arm_slope * shift);
      };
    }



    bool
    can_carry(const geometry::CycloidGeometry &geo,
              const double                     psi,
              const geometry::PinContact      &c,
              const int                        load_sign)
    {
      // Its arm, once the disc has turned (the contact slides), has the
      // torque's sign: a pin at the root with zero arm unloaded still takes
      // some (probe: 1e-3 rad, more than any elastic rotation of a stage).
      const auto gap = linearised_rigid_gap(geo, psi, c);
      return (load_sign >= 0 && gap(1e-3).second > 0) ||
             (load_sign <= 0 && gap(-1e-3).second < 0);
    }



    template <int dim>
    std::function<std::pair<double, double>(double)>
    ReducedModel<dim>::rigid_gap(const geometry::PinContact &c) const
    {
      return linearised_rigid_gap(model.geometry(), psi, c);
    }



    std::set<PinKey>
    carrying_pins(const analytic::StageModel &model,
                  const double                psi,
                  const int                   load_sign)
    {
      std::set<PinKey> pins;
      for (const analytic::PinLoad &p : model.unloaded_pins(psi))
        if (can_carry(model.geometry(), psi, p.contact, load_sign))
          pins.insert({p.contact.disc, p.contact.pin});
      return pins;
    }



    template <int dim>
    ReducedModel<dim>::ReducedModel(const ReducedSettings &settings,
                                    CoarseModel<dim>      &coarse,
                                    const double           psi,
                                    const int              load_sign,
                                    std::ostream          *progress)
      : ReducedModel(settings,
                     coarse,
                     psi,
                     carrying_pins(analytic::StageModel(
                                     settings.stage.model_settings()),
                                   psi,
                                   load_sign),
                     progress)
    {}



    template <int dim>
    ReducedModel<dim>::ReducedModel(const ReducedSettings  &settings,
                                    CoarseModel<dim>       &coarse,
                                    const double            psi,
                                    const std::set<PinKey> &only,
                                    std::ostream           *progress)
      : settings(settings)
      , psi(psi)
      , psi_mesh(coarse.crank_angle())
      , model(settings.stage.model_settings())
      , pins(model.unloaded_pins(psi))
      , n_dofs(coarse.dofs())
    {
      select_contacts([&](const geometry::PinContact &c) {
        return only.count({c.disc, c.pin}) > 0;
      });
      if (progress)
        *progress << "    condensing " << points.size() << " contacts at "
                  << psi * 180. / dealii::numbers::PI
                  << " deg on the coarse model" << std::endl;
      condensed = coarse.condense(points, progress);
      build_solver();
    }



    template <int dim>
    ReducedModel<dim>::ReducedModel(const ReducedSettings     &settings,
                                    const CoarseModel<dim>    &coarse,
                                    const double               psi,
                                    const int                  load_sign,
                                    const CompliancePath<dim> &path)
      : settings(settings)
      , psi(psi)
      , psi_mesh(coarse.crank_angle())
      , model(settings.stage.model_settings())
      , pins(model.unloaded_pins(psi))
      , n_dofs(coarse.dofs())
    {
      select_contacts([&](const geometry::PinContact &c) {
        return can_carry(model.geometry(), psi, c, load_sign);
      });
      condensed.matrix = path.at(psi, keys);
      build_solver();
    }



    template <int dim>
    ReducedModel<dim>::ReducedModel(const ReducedSettings &sample,
                                    const ReducedModel    &nominal)
      : settings(sample)
      , psi(nominal.psi)
      , psi_mesh(nominal.psi_mesh)
      , model(sample.stage.model_settings())
      , pins(model.unloaded_pins(psi))
      , n_dofs(nominal.n_dofs)
    {
      std::map<ContactKey, unsigned int> index;
      for (unsigned int i = 0; i < nominal.keys.size(); ++i)
        index[nominal.keys[i]] = i;
      select_contacts([&](const geometry::PinContact &c) {
        return index.count({{c.disc, c.pin, 0}}) > 0;
      });
      std::vector<unsigned int> at(keys.size());
      for (unsigned int i = 0; i < keys.size(); ++i)
        at[i] = index.at(keys[i]);
      condensed        = nominal.condensed;
      condensed.matrix = dealii::FullMatrix<double>(keys.size(), keys.size());
      for (unsigned int i = 0; i < keys.size(); ++i)
        for (unsigned int j = 0; j < keys.size(); ++j)
          condensed.matrix(i, j) = nominal.condensed.matrix(at[i], at[j]);
      build_solver();
    }



    template <int dim>
    void
    ReducedModel<dim>::select_contacts(
      const std::function<bool(const geometry::PinContact &)> &take)
    {
      const geometry::CycloidGeometry &geo = model.geometry();
      const auto                      &g   = settings.stage.geometry;
      const unsigned int slices = dim == 3 ? settings.reduced.axial_slices : 1;
      for (unsigned int k = 0; k < pins.size(); ++k)
        {
          const geometry::PinContact &c = pins[k].contact;
          if (!take(c))
            continue;
          ContactPoint p;
          p.disc      = c.disc;
          p.pin       = c.pin;
          p.point     = c.contact_point;
          p.normal    = c.normal;
          p.clearance = c.clearance;
          // The same disc point where the coarse model has the disc.
          p.disc_point =
            geo.to_housing(c.disc,
                           psi_mesh,
                           geo.to_disc(c.disc, psi, c.contact_point));
          const double turn = geo.disc_rotation(c.disc, psi_mesh) -
                              geo.disc_rotation(c.disc, psi);
          p.disc_normal = dealii::Tensor<1, 2>(
            {std::cos(turn) * c.normal[0] - std::sin(turn) * c.normal[1],
             std::sin(turn) * c.normal[0] + std::cos(turn) * c.normal[1]});
          std::pair<double, double> range{0., g.tooth_width};
          if (dim == 3)
            range =
              mesh::disc_axial_range(settings.stage.mesh_settings(), c.disc);
          for (unsigned int s = 0; s < slices; ++s)
            {
              const double dz = (range.second - range.first) / slices;
              p.z_min         = range.first + s * dz;
              p.z_max         = p.z_min + dz;
              points.push_back(p);
              pin_of.push_back(k);
              keys.push_back({{c.disc, c.pin, s}});
            }
        }
      AssertThrow(!points.empty(),
                  dealii::ExcMessage("reduced model: no pin can carry the "
                                     "load at this crank angle."));
    }



    template <int dim>
    void
    ReducedModel<dim>::build_solver()
    {
      const auto &m     = settings.stage.material;
      const bool  rigid = settings.stage.scene.pins ==
                         parameters::SceneParameters::PinModel::rigid;
      const double body_compliance =
        1. / m.disc.plane_strain_modulus() +
        (rigid ? 0. : 1. / m.pin.plane_strain_modulus());
      // 2D: the FE model is per unit thickness, loaded by 1 N/mm; a force
      // F over the tooth width b is the line load F / b.
      const double scale =
        dim == 2 ? 1. / settings.stage.geometry.tooth_width : 1.;
      dealii::FullMatrix<double> C(condensed.matrix);
      C *= scale;
      std::vector<ContactPair> pairs;
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          const analytic::PinLoad &pin = pins[pin_of[i]];
          const double             rho = pin.contact.curvature_radius;
          ContactPair              p;
          p.arm       = pin.contact.arm;
          p.clearance = pin.contact.clearance;
          p.length    = dim == 2 ? settings.stage.geometry.tooth_width :
                                   points[i].z_max - points[i].z_min;
          p.law       = LocalContact(settings.load_half_width(),
                               body_compliance,
                               1. / pin.pair.pin_radius -
                                 (std::isfinite(rho) ? 1. / rho : 0.));
          p.rigid_gap = rigid_gap(pin.contact);
          p.disc      = pin.contact.disc;
          p.normal    = pin.contact.normal;
          pairs.push_back(p);
        }
      solver = std::make_unique<ComplementaritySolver>(
        C,
        pairs,
        std::max(settings.stage.analytic.tolerance, 1e-10),
        settings.stage.analytic.max_iterations);
      if (settings.stage.bearings.needle())
        solver->set_supports(model.supports(psi));
    }



    template <int dim>
    analytic::LoadState
    ReducedModel<dim>::solve(const double torque, const double beta_guess) const
    {
      namespace u = results::units;
      // The analytical model gives the take-up and, for a first state, the
      // first active set (its beta is smaller: it is stiffer). Bearings
      // without clearance leave the take-up to the pins: the rigid
      // supports' solve gives it at a third of the cost.
      const auto         &b = settings.stage.bearings;
      analytic::LoadState load =
        b.needle() && b.radial_clearance == 0 ?
          model.solve_on_rigid_supports(pins, torque, beta_guess) :
          model.solve(pins, torque, beta_guess, psi);
      if (torque == 0)
        return load;
      const ReducedSolution s =
        solver->solve(torque * u::Nmm_per_Nm,
                      beta_guess != 0 ? beta_guess : load.rotation);
      load.rotation        = s.rotation;
      load.k_tangent       = s.k_tangent * u::Nm_per_Nmm;
      load.iterations      = s.iterations;
      load.reaction_torque = 0;
      for (analytic::PinLoad &p : load.pins)
        p.force = p.stiffness = 0;
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          analytic::PinLoad &p = load.pins[pin_of[i]];
          p.force += s.force[i];
          // Slices of one pin act in parallel.
          if (s.force[i] > 0)
            p.stiffness += 1. / s.compliance[i];
        }
      load.pins_in_contact = 0;
      for (analytic::PinLoad &p : load.pins)
        {
          // The disc's motion: its turn (the rotation on rigid supports)
          // and, on bearings, its translation.
          const unsigned int d = p.contact.disc;
          const double       theta =
            s.motions.empty() ? s.rotation : s.motions[d].rotation;
          const double closing = s.motions.empty() ?
                                   0. :
                                   p.contact.normal * s.motions[d].translation;
          // A loaded pin acts at the point the turned disc touches it.
          if (p.force > 0)
            p.contact.arm = rigid_gap(p.contact)(theta).second;
          p.approach =
            std::max(0., closing + theta * p.contact.arm - p.contact.clearance);
          load.reaction_torque += p.force * p.contact.arm * u::Nm_per_Nmm;
          if (p.force > 0)
            ++load.pins_in_contact;
        }
      set_supported_figures(s, torque * u::Nmm_per_Nm, load);
      return load;
    }



    template <int dim>
    void
    ReducedModel<dim>::set_supported_figures(const ReducedSolution &s,
                                             const double           torque,
                                             analytic::LoadState   &load) const
    {
      load.motions = s.motions;
      load.bearings.clear();
      if (!s.motions.empty())
        {
          const support::CrankSupports supports = model.supports(psi);
          for (unsigned int d = 0; d < s.motions.size(); ++d)
            for (const auto &b : supports.states(d, s.motions[d], s.rotation))
              load.bearings.push_back(b);
        }
      // Each part's share of the output work T beta, over T.
      load.breakdown.bodies   = s.bodies_work / torque;
      load.breakdown.bearings = s.bearings_work / torque;
      load.breakdown.contacts =
        s.rotation - load.breakdown.bodies - load.breakdown.bearings;
    }



    template <int dim>
    results::StageState
    ReducedModel<dim>::stage_state(const analytic::LoadState &load) const
    {
      results::StageState s = model.stage_state(load, psi);
      s.dofs                = n_dofs;
      s.linear_iterations   = condensed.linear_iterations;
      return s;
    }



    template <int dim>
    CompliancePath<dim>::CompliancePath(const ReducedSettings     &settings,
                                        CoarseModel<dim>          &coarse,
                                        const std::vector<double> &anchors,
                                        const std::vector<double> &angles,
                                        const int                  load_sign,
                                        std::ostream              *progress)
      : anchors(anchors)
    {
      // Every pin that can carry the load at some angle of the sweep.
      const analytic::StageModel model(settings.stage.model_settings());
      std::set<PinKey>           pins;
      for (const double psi : angles)
        for (const PinKey &k : carrying_pins(model, psi, load_sign))
          pins.insert(k);
      for (const double psi : anchors)
        {
          const ReducedModel<dim> probe(settings, coarse, psi, pins, progress);
          if (index.empty())
            for (unsigned int i = 0; i < probe.contact_keys().size(); ++i)
              index[probe.contact_keys()[i]] = i;
          AssertThrow(probe.contact_keys().size() == index.size(),
                      dealii::ExcInternalError());
          matrices.push_back(probe.compliance().matrix);
        }
    }



    template <int dim>
    dealii::FullMatrix<double>
    CompliancePath<dim>::at(const double                   psi,
                            const std::vector<ContactKey> &keys) const
    {
      // Lagrange weights of the anchors at psi.
      std::vector<double> weight(anchors.size(), 1.);
      for (unsigned int a = 0; a < anchors.size(); ++a)
        for (unsigned int b = 0; b < anchors.size(); ++b)
          if (b != a)
            weight[a] *= (psi - anchors[b]) / (anchors[a] - anchors[b]);
      std::vector<unsigned int> at;
      for (const ContactKey &k : keys)
        {
          const auto it = index.find(k);
          AssertThrow(it != index.end(),
                      dealii::ExcMessage("reduced model: a contact outside "
                                         "the sweep's anchors."));
          at.push_back(it->second);
        }
      dealii::FullMatrix<double> C(keys.size(), keys.size());
      for (unsigned int a = 0; a < anchors.size(); ++a)
        for (unsigned int i = 0; i < keys.size(); ++i)
          for (unsigned int j = 0; j < keys.size(); ++j)
            C(i, j) += weight[a] * matrices[a](at[i], at[j]);
      return C;
    }



    template class ReducedModel<2>;
    template class ReducedModel<3>;
    template class CompliancePath<2>;
    template class CompliancePath<3>;
  } // namespace reduced
} // namespace cycloid
