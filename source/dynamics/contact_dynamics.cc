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
      // CG's starts: without them the resumed run's solves would differ
      // from the uninterrupted run's at the solver tolerance.
      write_count(contact.warm_starts().size());
      for (const contact::WarmStart &w : contact.warm_starts())
        {
          write(w.stiffness);
          write(w.mass);
          for (const Vector *x : {&w.u0, &w.u1})
            for (const auto i : owned)
              write((*x)[i]);
        }
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
      auto &starts = contact.warm_starts();
      starts.clear();
      // (A checkpoint of an older version ends here: no starts.)
      const auto n_starts = in.peek() == std::char_traits<char>::eof() ?
                              std::uint64_t(0) :
                              read_count();
      for (std::uint64_t k = 0; k < n_starts; ++k)
        {
          contact::WarmStart w;
          w.stiffness = read();
          w.mass      = read();
          for (Vector *x : {&w.u0, &w.u1})
            {
              Vector o(owned, comm);
              for (const auto i : owned)
                o[i] = read();
              o.compress(dealii::VectorOperation::insert);
              x->reinit(owned, el.locally_relevant_dofs(), comm);
              *x = o;
            }
          starts.push_back(std::move(w));
        }
      AssertThrow(in, dealii::ExcMessage("checkpoint: the file is truncated."));
      contact.initialise_active_set([&](const contact::SlaveNode<dim> &s) {
        return active.count(s.dofs[0]) > 0;
      });
    }



    template class ContactDynamics<2>;
    template class ContactDynamics<3>;
  } // namespace dynamics
} // namespace cycloid
