#include <deal.II/base/exceptions.h>

#include <cycloid/contact/constraint_formulation.h>
#include <cycloid/contact/mortar.h>
#include <cycloid/contact/node_to_surface.h>

#include <cmath>

namespace cycloid
{
  namespace contact
  {
    template <int dim>
    void
    ConstraintFormulation<dim>::constrain(dealii::AffineConstraints<double> &c,
                                          const SlaveNode<dim>              &s,
                                          const bool with_gaps) const
    {
      // n . (u_s - u_M(P)) = -gap0, solved for the dominant normal
      // component so that the division is by |n_k| >= 1/sqrt(2).
      const unsigned int k =
        std::abs(s.normal[0]) >= std::abs(s.normal[1]) ? 0 : 1;
      const auto dk = s.dofs[k];
      if (!c.can_store_line(dk) || c.is_constrained(dk))
        return;
      c.add_line(dk);
      for (unsigned int comp = 0; comp < 2; ++comp)
        if (comp != k)
          c.add_entry(dk, s.dofs[comp], -s.normal[comp] / s.normal[k]);
      for (unsigned int a = 0; a < s.master_dofs.size(); ++a)
        c.add_entry(dk,
                    s.master_dofs[a],
                    s.master_coefficients[a] / s.normal[k]);
      c.set_inhomogeneity(dk, with_gaps ? -s.gap0 / s.normal[k] : 0.);
    }



    template <int dim>
    double
    ConstraintFormulation<dim>::gap(
      const SlaveNode<dim>                        &s,
      const dealii::TrilinosWrappers::MPI::Vector &u0,
      const dealii::TrilinosWrappers::MPI::Vector &u1,
      const double                                 beta) const
    {
      double gap = s.gap0;
      for (unsigned int c = 0; c < 2; ++c)
        gap += s.normal[c] * (u0[s.dofs[c]] + beta * u1[s.dofs[c]]);
      for (unsigned int a = 0; a < s.master_dofs.size(); ++a)
        gap -= s.master_coefficients[a] *
               (u0[s.master_dofs[a]] + beta * u1[s.master_dofs[a]]);
      return gap;
    }



    std::string
    formulation_name(const Formulation formulation)
    {
      switch (formulation)
        {
          case Formulation::node_to_surface:
            return "node-to-surface";
          case Formulation::mortar:
            return "mortar";
        }
      AssertThrow(false, dealii::ExcInternalError());
      return "";
    }



    template <int dim>
    std::unique_ptr<ConstraintFormulation<dim>>
    create_formulation(const std::string &name)
    {
      if (name == "mortar")
        return std::make_unique<Mortar<dim>>();
      if (name == "node-to-surface")
        return std::make_unique<NodeToSurface<dim>>();
      AssertThrow(false,
                  dealii::ExcMessage("contact: unknown formulation '" + name +
                                     "' (mortar or node-to-surface)."));
      return nullptr;
    }



    template class ConstraintFormulation<2>;
    template class ConstraintFormulation<3>;
    template std::unique_ptr<ConstraintFormulation<2>>
    create_formulation<2>(const std::string &);
    template std::unique_ptr<ConstraintFormulation<3>>
    create_formulation<3>(const std::string &);
  } // namespace contact
} // namespace cycloid
