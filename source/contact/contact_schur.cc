#include <deal.II/base/exceptions.h>

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <cycloid/contact/contact_schur.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>

namespace cycloid
{
  namespace contact
  {
    using Vector = dealii::TrilinosWrappers::MPI::Vector;

    template <int dim>
    ContactSchur<dim>::ContactSchur(const MPI_Comm    comm,
                                    const std::size_t max_columns)
      : max_columns(max_columns)
      , comm(comm)
      , factor(comm)
    {
      AssertThrow(max_columns >= 2,
                  dealii::ExcMessage("ContactSchur: keep at least 2 columns"));
    }



    template <int dim>
    bool
    ContactSchur<dim>::begin_state(elasticity::LinearElasticity<dim> &problem,
                                   const std::vector<Constraints>    &supports)
    {
      AssertThrow(supports.size() == 2, dealii::ExcInternalError());
      if (problem.n_distributions() != distribution)
        {
          // A new mesh: the supports of every DoF, for the rows. Those of
          // the unit load, so that a row reaching a loaded DoF is seen.
          distribution = problem.n_distributions();
          open_held.clear();
          dealii::DoFTools::make_hanging_node_constraints(problem.dof_handler(),
                                                          open_held);
          supports[1](open_held);
          held.copy_from(open_held);
          held.close();
          forget_columns();
        }
      // The supports of the last state are still in place unless someone
      // set up constraints since (they are the same for every state).
      if (problem.n_constraint_setups() != installed)
        {
          problem.setup_constraints(supports);
          installed = problem.n_constraint_setups();
        }
      else
        problem.refresh_relevant_dofs();
      // The operator of the last state, factorised: only the history load
      // is new (a time step). Otherwise assemble, and the factor is still
      // kept if the matrix came out the same.
      const bool untouched = factored && problem.assemble_history_load();
      if (!untouched)
        {
          problem.assemble_sets({});
          factored = factor.factorize(problem.matrix());
          if (!factored)
            return false;
        }
      const bool same =
        (untouched || factor.kept_factor()) && x1.size() == problem.n_dofs();
      if (!same)
        forget_columns();
      // x1 (the unit load, no history) depends on the operator alone.
      const auto &owned = problem.locally_owned_dofs();
      for (unsigned int k = 0; k < (same ? 1 : 2); ++k)
        {
          Vector &x = k == 0 ? x0 : x1;
          x.reinit(owned, comm);
          factor.solve(x, problem.right_hand_side(k));
          problem.constraint_set(k).distribute(x);
        }
      return true;
    }



    template <int dim>
    void
    ContactSchur<dim>::forget_columns()
    {
      dofs.clear();
      number.clear();
      columns.clear();
      last_use.clear();
    }



    template <int dim>
    std::vector<typename ContactSchur<dim>::Row>
    ContactSchur<dim>::contact_rows(const Constraints &contact) const
    {
      // The contact lines exactly as the condensed path adds them: after
      // the hanging nodes and the supports, which they leave alone.
      dealii::AffineConstraints<double> c;
      c.copy_from(open_held);
      std::set<dealii::types::global_dof_index> before;
      for (const auto &line : c.get_lines())
        before.insert(line.index);
      contact(c);
      std::vector<Row> rows;
      for (const auto &line : c.get_lines())
        {
          if (before.count(line.index))
            continue;
          // u_d - sum_j w_j u_j = inhomogeneity, the held DoFs replaced.
          std::map<dealii::types::global_dof_index, double> entries;
          const auto add = [&](const dealii::types::global_dof_index j,
                               const double                          w) {
            if (!held.is_constrained(j))
              {
                entries[j] += w;
                return;
              }
            AssertThrow(!held.is_inhomogeneously_constrained(j),
                        dealii::ExcMessage(
                          "contact: a contact line reaches a DoF with a "
                          "prescribed value; the Schur complement cannot "
                          "take it (set Solver/Contact Schur complement = "
                          "false)."));
            for (const auto &[k, v] : *held.get_constraint_entries(j))
              entries[k] += w * v;
          };
          add(line.index, 1.);
          for (const auto &[j, w] : line.entries)
            add(j, -w);
          Row row;
          row.gap = line.inhomogeneity;
          for (const auto &[j, w] : entries)
            if (w != 0.)
              row.entries.emplace_back(j, w);
          rows.push_back(std::move(row));
        }
      return rows;
    }



    template <int dim>
    void
    ContactSchur<dim>::add_columns(const std::vector<Row> &rows)
    {
      ++n_sets;
      std::vector<dealii::types::global_dof_index> fresh;
      for (const Row &row : rows)
        for (const auto &entry : row.entries)
          if (!number.count(entry.first))
            {
              number[entry.first] = dofs.size();
              dofs.push_back(entry.first);
              last_use.push_back(n_sets);
              fresh.push_back(entry.first);
            }
          else
            last_use[number[entry.first]] = n_sets;
      new_columns = fresh.size();
      if (dofs.size() > max_columns)
        {
          // Forget the new ones again and the least recently used old
          // ones, then compute the new ones against what stays.
          for (std::size_t k = 0; k < fresh.size(); ++k)
            {
              number.erase(dofs.back());
              dofs.pop_back();
              last_use.pop_back();
            }
          evict(max_columns / 2);
          for (const auto d : fresh)
            {
              number[d] = dofs.size();
              dofs.push_back(d);
              last_use.push_back(n_sets);
            }
        }
      if (fresh.empty())
        return;
      // The new columns at every kept DoF; by symmetry, their entries at
      // the new DoFs extend the old columns.
      const std::vector<double> block = factor.inverse_entries(fresh, dofs);
      const std::size_t         n_old = columns.size(), n_new = fresh.size();
      for (std::size_t b = 0; b < n_old; ++b)
        for (std::size_t j = 0; j < n_new; ++j)
          columns[b].push_back(block[b * n_new + j]);
      for (std::size_t j = 0; j < n_new; ++j)
        {
          std::vector<double> column(dofs.size());
          for (std::size_t a = 0; a < dofs.size(); ++a)
            column[a] = block[a * n_new + j];
          columns.push_back(std::move(column));
        }
    }



    template <int dim>
    void
    ContactSchur<dim>::evict(const std::size_t keep)
    {
      // The contacts move along the flanks: a DoF whose column was last
      // used long ago is the least likely to be needed again.
      std::vector<unsigned int> order(dofs.size());
      for (unsigned int a = 0; a < order.size(); ++a)
        order[a] = a;
      std::stable_sort(order.begin(),
                       order.end(),
                       [this](const unsigned int a, const unsigned int b) {
                         return last_use[a] > last_use[b];
                       });
      // The current set's columns stay whatever the limit.
      const std::size_t current =
        std::count(last_use.begin(), last_use.end(), n_sets);
      order.resize(std::min(std::max(keep, current), order.size()));
      std::sort(order.begin(), order.end());
      std::vector<dealii::types::global_dof_index> kept_dofs;
      std::vector<unsigned int>                    kept_use;
      std::vector<std::vector<double>>             kept_columns;
      for (const unsigned int b : order)
        {
          std::vector<double> column;
          column.reserve(order.size());
          for (const unsigned int a : order)
            column.push_back(columns[b][a]);
          kept_columns.push_back(std::move(column));
          kept_dofs.push_back(dofs[b]);
          kept_use.push_back(last_use[b]);
        }
      dofs     = std::move(kept_dofs);
      last_use = std::move(kept_use);
      columns  = std::move(kept_columns);
      number.clear();
      for (unsigned int a = 0; a < dofs.size(); ++a)
        number[dofs[a]] = a;
      ++n_evictions;
    }



    template <int dim>
    std::vector<double>
    ContactSchur<dim>::row_products(const std::vector<Row> &rows,
                                    const Vector           &x) const
    {
      const auto         &owned = x.locally_owned_elements();
      std::vector<double> mine(rows.size(), 0.);
      for (std::size_t r = 0; r < rows.size(); ++r)
        for (const auto &[j, w] : rows[r].entries)
          if (owned.is_element(j))
            mine[r] += w * x[j];
      std::vector<double> all(rows.size());
      dealii::Utilities::MPI::sum(mine, comm, all);
      return all;
    }



    template <int dim>
    dealii::LAPACKFullMatrix<double>
    ContactSchur<dim>::factorised_schur(const std::vector<Row> &rows) const
    {
      // S = B A^{-1} B^T: every row has a few entries.
      const std::size_t                                         m = rows.size();
      std::vector<std::vector<std::pair<unsigned int, double>>> kept(m);
      for (std::size_t r = 0; r < m; ++r)
        for (const auto &[j, w] : rows[r].entries)
          kept[r].emplace_back(number.at(j), w);
      dealii::LAPACKFullMatrix<double> S(m, m);
      for (std::size_t r = 0; r < m; ++r)
        for (std::size_t s = 0; s <= r; ++s)
          {
            double v = 0;
            for (const auto &[a, wa] : kept[r])
              for (const auto &[b, wb] : kept[s])
                v += wa * wb * inverse(a, b);
            S(r, s) = S(s, r) = v;
          }
      if (m == 0)
        return S;
      S.set_property(dealii::LAPACKSupport::symmetric);
      try
        {
          S.compute_cholesky_factorization();
        }
      catch (const std::exception &)
        {
          // Each row owns its slave DoF, so S is positive definite unless
          // two rows were dependent.
          AssertThrow(false,
                      dealii::ExcMessage(
                        "contact: the Schur complement of the active set is "
                        "not positive definite (dependent contact rows?); set "
                        "Solver/Contact Schur complement = false."));
        }
      return S;
    }



    template <int dim>
    void
    ContactSchur<dim>::solve_set(
      const elasticity::LinearElasticity<dim> &problem,
      const Constraints                       &contact,
      Vector                                  &u0,
      Vector                                  &u1)
    {
      const std::vector<Row> rows = contact_rows(contact);
      add_columns(rows);
      const std::size_t                      m = rows.size();
      const dealii::LAPACKFullMatrix<double> S = factorised_schur(rows);
      const auto &owned                        = problem.locally_owned_dofs();
      // mu_k = S^{-1} (g_k - B x_k), then u_k = x_k + A^{-1} B^T mu_k; the
      // two back-substitutions in one solve.
      std::array<Vector, 2> load, correction;
      for (unsigned int k = 0; k < 2; ++k)
        {
          load[k].reinit(owned, comm);
          correction[k].reinit(owned, comm);
          if (m == 0)
            continue;
          const std::vector<double> bx = row_products(rows, k == 0 ? x0 : x1);
          dealii::Vector<double>    mu(m);
          for (std::size_t r = 0; r < m; ++r)
            mu[r] = (k == 0 ? rows[r].gap : 0.) - bx[r];
          S.solve(mu);
          for (std::size_t r = 0; r < m; ++r)
            for (const auto &[j, w] : rows[r].entries)
              if (owned.is_element(j))
                load[k][j] += w * mu[r];
          load[k].compress(dealii::VectorOperation::insert);
        }
      if (m > 0)
        factor.solve({&correction[0], &correction[1]}, {&load[0], &load[1]});
      for (unsigned int k = 0; k < 2; ++k)
        {
          // Set 0's supports hold no load: zero where they hold.
          problem.constraint_set(0).distribute(correction[k]);
          correction[k] += k == 0 ? x0 : x1;
          Vector &out = k == 0 ? u0 : u1;
          out.reinit(owned, problem.locally_relevant_dofs(), comm);
          out = correction[k];
        }
    }



    template class ContactSchur<2>;
    template class ContactSchur<3>;
  } // namespace contact
} // namespace cycloid
