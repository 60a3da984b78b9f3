#include <deal.II/base/exceptions.h>

#include <cycloid/dynamics/contact_dynamics.h>
#include <cycloid/dynamics/contact_stabilised.h>
#include <cycloid/dynamics/newmark.h>
#include <cycloid/dynamics/time_scheme.h>

namespace cycloid
{
  namespace dynamics
  {
    using Vector = dealii::TrilinosWrappers::MPI::Vector;

    template <int dim>
    std::unique_ptr<TimeScheme<dim>>
    create_time_scheme(const DynamicsSettings &settings)
    {
      const double aR = settings.rayleigh_mass,
                   bR = settings.rayleigh_stiffness;
      switch (settings.scheme)
        {
          case Scheme::newmark:
            return std::make_unique<Newmark<dim>>(aR, bR);
          case Scheme::contact_stabilised:
            return std::make_unique<ContactStabilised<dim>>(aR, bR);
          case Scheme::generalized_alpha:
            return std::make_unique<GeneralizedAlpha<dim>>(
              AlphaCoefficients::from_spectral_radius(settings.spectral_radius),
              aR,
              bR);
        }
      AssertThrow(false, dealii::ExcNotImplemented());
      return nullptr;
    }



    template <int dim>
    Vector
    ghosted(const contact::ContactProblem<dim> &contact, const Vector &x)
    {
      const auto &el = contact.elasticity();
      Vector      g(el.locally_owned_dofs(),
               el.locally_relevant_dofs(),
               el.dof_handler().get_communicator());
      g = x;
      return g;
    }



    template <int dim>
    Vector
    owned_copy(const contact::ContactProblem<dim> &contact, const Vector &x)
    {
      const auto &el = contact.elasticity();
      Vector o(el.locally_owned_dofs(), el.dof_handler().get_communicator());
      o = x;
      return o;
    }



    template std::unique_ptr<TimeScheme<2>>
    create_time_scheme<2>(const DynamicsSettings &);
    template std::unique_ptr<TimeScheme<3>>
    create_time_scheme<3>(const DynamicsSettings &);
    template Vector
    owned_copy<2>(const contact::ContactProblem<2> &, const Vector &);
    template Vector
    owned_copy<3>(const contact::ContactProblem<3> &, const Vector &);
    template Vector
    ghosted<2>(const contact::ContactProblem<2> &, const Vector &);
    template Vector
    ghosted<3>(const contact::ContactProblem<3> &, const Vector &);
  } // namespace dynamics
} // namespace cycloid
