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
      , scheme(create_time_scheme<dim>(settings))
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
          // The recorded forces are what each scheme reports (end of step,
          // step average, alpha level); the scheme knows the step's force.
          const double lambda =
            scheme->obstacle_force(old->second.first, entry.first);
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
      const auto &el    = contact.elasticity();
      const auto &owned = el.locally_owned_dofs();
      Vector      un(owned, comm), vn(owned, comm), an(owned, comm);
      un              = u;
      vn              = v;
      an              = a;
      const double aR = settings.rayleigh_mass,
                   bR = settings.rayleigh_stiffness;

      const double Q_old = totals.state.reaction;
      StepOutcome  next  = scheme->step(
        contact, {un, vn, an, beta, applied, dt, load_control, value, label});
      // Whatever the scheme set, the next static solve sees A = K again.
      contact.set_dynamic_terms(elasticity::DynamicTerms());
      StepReport report;
      report.state      = next.state;
      report.iterations = next.iterations;

      // Energies and work.
      const double beta_new = report.state.beta;
      const double Q_new    = load_control ? value : report.state.reaction;
      const double Q_prev   = load_control ? applied : Q_old;
      totals.bore_work += 0.5 * (Q_prev + Q_new) * (beta_new - beta);
      const auto new_record = contact_record();
      {
        Vector mid(un);
        mid.add(1., next.u);
        mid *= 0.5;
        totals.contact_work += obstacle_work(mid, new_record);
      }
      record = new_record;
      if (aR > 0 || bR > 0)
        {
          Vector mid(vn);
          mid.add(1., next.v);
          mid *= 0.5;
          const Vector gm = ghosted(contact, mid);
          const auto   e  = el.energies(gm, gm);
          totals.dissipated += dt * (2. * bR * e.first + 2. * aR * e.second);
        }
      u              = ghosted(contact, next.u);
      v              = ghosted(contact, next.v);
      a              = ghosted(contact, next.a);
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
    ContactDynamics<dim>::checkpoint(CheckpointArchive &ar)
    {
      if (ar.loading())
        totals = StepReport();
      for (double *x : {&beta,
                        &beta_old,
                        &applied,
                        &dt_old,
                        &totals.elastic,
                        &totals.kinetic,
                        &totals.bore_work,
                        &totals.contact_work,
                        &totals.dissipated,
                        &totals.state.reaction,
                        &totals.state.beta})
        ar.value(*x);
      const auto &el       = contact.elasticity();
      const auto &owned    = el.locally_owned_dofs();
      const auto &relevant = el.locally_relevant_dofs();
      ar.owned_count(owned);
      for (Vector *x : {&u, &v, &a})
        ar.owned_entries(*x, owned, relevant, comm);
      checkpoint_record(ar);
      std::vector<dealii::types::global_dof_index> active;
      if (!ar.loading())
        {
          const std::set<dealii::types::global_dof_index> set = active_dofs();
          active.assign(set.begin(), set.end());
        }
      ar.sequence(active, [&](auto &dof) { ar.count(dof); });
      ar.check("checkpoint: the file is truncated.");
      // CG's starts: without them the resumed run's solves would differ
      // from the uninterrupted run's at the solver tolerance. (A checkpoint
      // of an older version ends before them: no starts.)
      auto       &starts   = contact.warm_starts();
      std::size_t n_starts = starts.size();
      if (ar.loading() && ar.at_end())
        n_starts = 0;
      else
        ar.count(n_starts);
      starts.resize(n_starts);
      for (contact::WarmStart &w : starts)
        {
          ar.value(w.stiffness);
          ar.value(w.mass);
          for (Vector *x : {&w.u0, &w.u1})
            ar.owned_entries(*x, owned, relevant, comm);
        }
      ar.check("checkpoint: the file is truncated.");
      if (ar.loading())
        {
          const std::set<dealii::types::global_dof_index> set(active.begin(),
                                                              active.end());
          contact.initialise_active_set([&](const contact::SlaveNode<dim> &s) {
            return set.count(s.dofs[0]) > 0;
          });
        }
    }



    template <int dim>
    std::set<dealii::types::global_dof_index>
    ContactDynamics<dim>::active_dofs() const
    {
      std::set<dealii::types::global_dof_index> active;
      for (const unsigned int i : contact.active_set())
        active.insert(contact.slave_nodes()[i].dofs[0]);
      return active;
    }



    template <int dim>
    void
    ContactDynamics<dim>::checkpoint_record(CheckpointArchive &ar)
    {
      std::vector<std::pair<dealii::types::global_dof_index,
                            std::pair<double, contact::SlaveNode<dim>>>>
        entries(record.begin(), record.end());
      ar.sequence(entries, [&](auto &entry) {
        ar.count(entry.first);
        ar.value(entry.second.first);
        contact::SlaveNode<dim> &sn = entry.second.second;
        ar.value(sn.gap0);
        for (unsigned int c = 0; c < dim; ++c)
          {
            ar.value(sn.normal[c]);
            ar.count(sn.dofs[c]);
          }
        std::size_t n = sn.master_dofs.size();
        ar.count(n);
        sn.master_dofs.resize(n);
        sn.master_coefficients.resize(n);
        for (std::size_t k = 0; k < n; ++k)
          {
            ar.count(sn.master_dofs[k]);
            ar.value(sn.master_coefficients[k]);
          }
      });
      if (ar.loading())
        record = {entries.begin(), entries.end()};
    }



    template class ContactDynamics<2>;
    template class ContactDynamics<3>;
  } // namespace dynamics
} // namespace cycloid
