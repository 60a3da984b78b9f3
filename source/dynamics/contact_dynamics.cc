#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>

#include <cycloid/dynamics/contact_dynamics.h>

#include <algorithm>
#include <cmath>
#include <istream>
#include <ostream>
#include <set>

namespace cycloid
{
  namespace dynamics
  {
    using Vector = dealii::TrilinosWrappers::MPI::Vector;

    template <int dim>
    ContactDynamics<dim>::ContactDynamics(contact::ContactProblem<dim> &contact,
                                          const DynamicsSettings &settings)
      : contact(contact)
      , settings(settings)
      , comm(contact.elasticity().dof_handler().get_communicator())
    {
      AssertThrow(
        settings.spectral_radius >= 0 && settings.spectral_radius <= 1,
        dealii::ExcMessage("Transient/Spectral radius must lie in [0, 1]."));
    }



    template <int dim>
    void
    ContactDynamics<dim>::initialise(const Vector &v0)
    {
      const auto &el = contact.elasticity();
      u.reinit(el.locally_owned_dofs(), el.locally_relevant_dofs(), comm);
      v.reinit(u);
      a.reinit(u);
      if (v0.size() > 0)
        {
          Vector owned(el.locally_owned_dofs(), comm), acc(owned);
          owned = v0;
          v     = owned;
          acc.add(-settings.rayleigh_mass, owned);
          a = acc;
        }
      beta = beta_old = applied = dt_old = 0;
      totals                             = StepReport();
      const auto e                       = el.energies(u, v);
      totals.elastic                     = e.first;
      totals.kinetic                     = e.second;
      record                             = contact_record();
    }



    template <int dim>
    std::map<dealii::types::global_dof_index,
             std::pair<double, contact::SlaveNode<dim>>>
    ContactDynamics<dim>::contact_record() const
    {
      std::map<dealii::types::global_dof_index,
               std::pair<double, contact::SlaveNode<dim>>>
                  r;
      const auto &slaves    = contact.slave_nodes();
      const auto &reactions = contact.slave_reactions();
      for (unsigned int i = 0; i < slaves.size(); ++i)
        {
          if (slaves[i].hanging)
            continue;
          double lambda = 0;
          for (unsigned int c = 0; c < dim; ++c)
            lambda += slaves[i].normal[c] * reactions[i][c];
          r[slaves[i].dofs[0]] = {contact.active_set().count(i) ? lambda : 0.,
                                  slaves[i]};
        }
      return r;
    }



    template <int dim>
    double
    ContactDynamics<dim>::obstacle_work(
      const Vector                                               &u_mid,
      const std::map<dealii::types::global_dof_index,
                     std::pair<double, contact::SlaveNode<dim>>> &new_record)
      const
    {
      const auto &el    = contact.elasticity();
      const auto &owned = el.locally_owned_dofs();
      // Ghosts: every DoF that an old or new constraint reads.
      dealii::IndexSet ghosts = el.locally_relevant_dofs();
      std::vector<dealii::types::global_dof_index> extra;
      for (const auto *rec : {&record, &new_record})
        for (const auto &[d, entry] : *rec)
          {
            const auto &s = entry.second;
            extra.insert(extra.end(),
                         s.master_dofs.begin(),
                         s.master_dofs.end());
            extra.insert(extra.end(), s.dofs.begin(), s.dofs.end());
          }
      std::sort(extra.begin(), extra.end());
      extra.erase(std::unique(extra.begin(), extra.end()), extra.end());
      ghosts.add_indices(extra.begin(), extra.end());
      Vector x(owned, ghosts, comm);
      x            = u_mid;
      const auto G = [&](const contact::SlaveNode<dim> &s) {
        double g = s.gap0;
        for (unsigned int c = 0; c < 2; ++c)
          g += s.normal[c] * x[s.dofs[c]];
        for (unsigned int a = 0; a < s.master_dofs.size(); ++a)
          g -= s.master_coefficients[a] * x[s.master_dofs[a]];
        return g;
      };
      double w = 0;
      for (const auto &[d, entry] : new_record)
        {
          if (!owned.is_element(d))
            continue;
          const auto old = record.find(d);
          if (old == record.end())
            continue;
          // Newmark's multipliers are end-of-step forces: trapezoid.
          // Contact-stabilised reports the step average and
          // generalized-alpha the force at t_{n+1-alpha_f}, inside the
          // step: each is the step's force already.
          const double lambda = settings.scheme == Scheme::newmark ?
                                  0.5 * (old->second.first + entry.first) :
                                  entry.first;
          if (lambda != 0.)
            w -= lambda * (G(entry.second) - G(old->second.second));
        }
      return dealii::Utilities::MPI::sum(w, comm);
    }



    template <int dim>
    StepReport
    ContactDynamics<dim>::step(const double       dt,
                               const bool         load_control,
                               const double       value,
                               const std::string &label)
    {
      AssertThrow(dt > 0,
                  dealii::ExcMessage("Transient/Time step must be > 0"));
      auto       &el    = contact.elasticity_problem();
      const auto &owned = el.locally_owned_dofs();
      const auto  ghost = [&](const Vector &x) {
        Vector g(owned, el.locally_relevant_dofs(), comm);
        g = x;
        return g;
      };
      Vector un(owned, comm), vn(owned, comm), an(owned, comm);
      un              = u;
      vn              = v;
      an              = a;
      const double aR = settings.rayleigh_mass,
                   bR = settings.rayleigh_stiffness;

      StepReport   report;
      unsigned int projection_linear = 0;
      const double Q_old             = totals.state.reaction;
      Vector       u_new(owned, comm), v_new(owned, comm), a_new(owned, comm);
      if (settings.scheme == Scheme::contact_stabilised)
        {
          // 1. Predictor u_n + dt v_n projected onto the admissible set in
          // the mass norm: min |u - u_pred|_M, u admissible.
          Vector pred(un);
          pred.add(dt, vn);
          elasticity::DynamicTerms projection;
          projection.stiffness = 0.;
          projection.mass      = 1.;
          projection.mass_load = ghost(pred);
          contact.set_dynamic_terms(projection);
          // The load surface stays where the predictor puts it: beta_n +
          // dt dbeta/dt, with dbeta/dt read from the velocity of its DoFs
          // (v = dbeta/dt g there); any other choice would make the
          // projection move it and corrupt its velocity.
          double gv = 0, gg = 0;
          for (const auto &[d, g] : contact.load_pattern())
            if (owned.is_element(d))
              {
                gv += g * vn[d];
                gg += g * g;
              }
          gv                     = dealii::Utilities::MPI::sum(gv, comm);
          gg                     = dealii::Utilities::MPI::sum(gg, comm);
          const double beta_pred = beta + (gg > 0 ? dt * gv / gg : 0.);
          const auto   p =
            contact.solve_displacement(beta_pred, label + " (projection)");
          report.iterations += p.iterations;
          projection_linear = p.linear_iterations;
          Vector tilde(owned, comm);
          tilde = contact.displacement();

          // 2. Implicit trapezoidal step from the projected predictor:
          // (4/dt^2 M + 2/dt C + K) u = M (4/dt^2) u~ - K u_n - 2 C v_n
          //                              + (2/dt) C u~ + r.
          elasticity::DynamicTerms terms;
          terms.mass      = 4. / (dt * dt) + 2. * aR / dt;
          terms.stiffness = 1. + 2. * bR / dt;
          Vector wM(tilde), wK(un);
          wM *= terms.mass;
          wM.add(-2. * aR, vn);
          wK *= -1.;
          wK.add(-2. * bR, vn);
          wK.add(2. * bR / dt, tilde);
          terms.mass_load      = ghost(wM);
          terms.stiffness_load = ghost(wK);
          contact.set_dynamic_terms(terms);
          // The load surface's row of this equation is the sum of its
          // forces at t_n and t_{n+1} (M a_n of the trapezoidal rule keeps
          // the load of t_n; only the contact forces of t_n are dropped).
          report.state = load_control ?
                           contact.solve_load(value + applied, label) :
                           contact.solve_displacement(value, label);
          report.state.reaction -= applied;
          // Likewise the multipliers of the contact rows are the sum of the
          // contact forces at t_n and t_{n+1} (the projection absorbs the
          // old one): M (v_{n+1} - v_n) = dt/2 (... + lambda). Report the
          // step average lambda/2, the force that carries the impulse.
          contact.scale_reactions(0.5);
          u_new = contact.displacement();
          // v_{n+1} = v_n + 2/dt (u_{n+1} - u~); the acceleration is not
          // part of the scheme's state.
          v_new = u_new;
          v_new.add(-1., tilde);
          v_new.sadd(2. / dt, 1., vn);
          a_new = 0.;
        }
      else
        {
          double am = 0, af = 0, b = 0.25, g = 0.5;
          if (settings.scheme == Scheme::generalized_alpha)
            {
              const double rho = settings.spectral_radius;
              am               = (2. * rho - 1.) / (rho + 1.);
              af               = rho / (rho + 1.);
              g                = 0.5 - am + af;
              b                = 0.25 * (1. - am + af) * (1. - am + af);
            }
          // u_{n+1} = uh + b dt^2 a_{n+1}, v_{n+1} = vt + g/(b dt) u_{n+1}.
          Vector uh(un), vt(vn), vd(vn);
          uh.add(dt, vn, dt * dt * (0.5 - b), an);
          const double c = g / (b * dt);
          vt.add(dt * (1. - g), an, -c, uh);
          // Damping velocity of the alpha-weighted equation.
          vd.sadd(af, 1. - af, vt);
          elasticity::DynamicTerms terms;
          const double             m = (1. - am) / (b * dt * dt);
          terms.mass                 = m + (1. - af) * c * aR;
          terms.stiffness            = (1. - af) * (1. + c * bR);
          Vector wM(uh), wK(un);
          wM *= m;
          wM.add(-am, an, -aR, vd);
          wK *= -af;
          wK.add(-bR, vd);
          terms.mass_load      = ghost(wM);
          terms.stiffness_load = ghost(wK);
          contact.set_dynamic_terms(terms);
          report.state =
            load_control ?
              contact.solve_load((1. - af) * value + af * applied, label) :
              contact.solve_displacement(value, label);
          u_new = contact.displacement();
          a_new = u_new;
          a_new.add(-1., uh);
          a_new *= 1. / (b * dt * dt);
          v_new = vn;
          v_new.add(dt * (1. - g), an, dt * g, a_new);
        }
      report.iterations += report.state.iterations;
      report.state.linear_iterations += projection_linear;
      contact.set_dynamic_terms(elasticity::DynamicTerms());

      // Energies and work.
      const double beta_new = report.state.beta;
      const double Q_new    = load_control ? value : report.state.reaction;
      const double Q_prev   = load_control ? applied : Q_old;
      totals.bore_work += 0.5 * (Q_prev + Q_new) * (beta_new - beta);
      const auto new_record = contact_record();
      {
        Vector mid(un);
        mid.add(1., u_new);
        mid *= 0.5;
        totals.contact_work += obstacle_work(mid, new_record);
      }
      record = new_record;
      if (aR > 0 || bR > 0)
        {
          Vector mid(vn);
          mid.add(1., v_new);
          mid *= 0.5;
          const Vector gm = ghost(mid);
          const auto   e  = el.energies(gm, gm);
          totals.dissipated += dt * (2. * bR * e.first + 2. * aR * e.second);
        }
      u              = ghost(u_new);
      v              = ghost(v_new);
      a              = ghost(a_new);
      const auto e   = el.energies(u, v);
      totals.elastic = e.first;
      totals.kinetic = e.second;
      double pen     = 0;
      for (unsigned int i = 0; i < contact.slave_nodes().size(); ++i)
        if (!contact.slave_nodes()[i].hanging)
          pen = std::max(pen, -contact.slave_gaps()[i]);
      beta_old = beta;
      beta     = beta_new;
      applied  = load_control ? value : report.state.reaction;
      dt_old   = dt;

      totals.state           = report.state;
      totals.iterations      = report.iterations;
      totals.max_penetration = pen;
      report                 = totals;
      return report;
    }



    template <int dim>
    void
    ContactDynamics<dim>::save(std::ostream &out) const
    {
      const auto write = [&](const double x) {
        out.write(reinterpret_cast<const char *>(&x), sizeof(double));
      };
      const auto write_count = [&](const std::uint64_t n) {
        out.write(reinterpret_cast<const char *>(&n), sizeof(n));
      };
      for (const double x : {beta,
                             beta_old,
                             applied,
                             dt_old,
                             totals.elastic,
                             totals.kinetic,
                             totals.bore_work,
                             totals.contact_work,
                             totals.dissipated,
                             totals.state.reaction,
                             totals.state.beta})
        write(x);
      const auto &owned = contact.elasticity().locally_owned_dofs();
      write_count(owned.n_elements());
      for (const Vector *x : {&u, &v, &a})
        for (const auto i : owned)
          write((*x)[i]);
      write_count(record.size());
      for (const auto &[dof, entry] : record)
        {
          const auto &sn = entry.second;
          write_count(dof);
          write(entry.first);
          write(sn.gap0);
          for (unsigned int c = 0; c < dim; ++c)
            {
              write(sn.normal[c]);
              write_count(sn.dofs[c]);
            }
          write_count(sn.master_dofs.size());
          for (unsigned int a = 0; a < sn.master_dofs.size(); ++a)
            {
              write_count(sn.master_dofs[a]);
              write(sn.master_coefficients[a]);
            }
        }
      std::set<dealii::types::global_dof_index> active;
      for (const unsigned int i : contact.active_set())
        active.insert(contact.slave_nodes()[i].dofs[0]);
      write_count(active.size());
      for (const auto d : active)
        write_count(d);
    }



    template <int dim>
    void
    ContactDynamics<dim>::load(std::istream &in)
    {
      const auto read = [&]() {
        double x;
        in.read(reinterpret_cast<char *>(&x), sizeof(double));
        return x;
      };
      const auto read_count = [&]() {
        std::uint64_t n;
        in.read(reinterpret_cast<char *>(&n), sizeof(n));
        return n;
      };
      beta                  = read();
      beta_old              = read();
      applied               = read();
      dt_old                = read();
      totals                = StepReport();
      totals.elastic        = read();
      totals.kinetic        = read();
      totals.bore_work      = read();
      totals.contact_work   = read();
      totals.dissipated     = read();
      totals.state.reaction = read();
      totals.state.beta     = read();
      const auto &el        = contact.elasticity();
      const auto &owned     = el.locally_owned_dofs();
      AssertThrow(in && read_count() == owned.n_elements(),
                  dealii::ExcMessage(
                    "checkpoint: the mesh or the partition differs from the "
                    "run that wrote it (restart with the same prm and the "
                    "same number of MPI ranks)."));
      for (Vector *x : {&u, &v, &a})
        {
          Vector o(owned, comm);
          for (const auto i : owned)
            o[i] = read();
          o.compress(dealii::VectorOperation::insert);
          x->reinit(owned, el.locally_relevant_dofs(), comm);
          *x = o;
        }
      record.clear();
      const auto n_record = read_count();
      for (std::uint64_t k = 0; k < n_record; ++k)
        {
          const auto              dof    = read_count();
          const double            lambda = read();
          contact::SlaveNode<dim> sn;
          sn.gap0 = read();
          for (unsigned int c = 0; c < dim; ++c)
            {
              sn.normal[c] = read();
              sn.dofs[c]   = read_count();
            }
          const auto n_masters = read_count();
          for (std::uint64_t a = 0; a < n_masters; ++a)
            {
              sn.master_dofs.push_back(read_count());
              sn.master_coefficients.push_back(read());
            }
          record[dof] = {lambda, sn};
        }
      std::set<dealii::types::global_dof_index> active;
      const auto                                n_active = read_count();
      for (std::uint64_t k = 0; k < n_active; ++k)
        active.insert(read_count());
      AssertThrow(in, dealii::ExcMessage("checkpoint: the file is truncated."));
      contact.initialise_active_set([&](const contact::SlaveNode<dim> &s) {
        return active.count(s.dofs[0]) > 0;
      });
    }



    template class ContactDynamics<2>;
    template class ContactDynamics<3>;
  } // namespace dynamics
} // namespace cycloid
