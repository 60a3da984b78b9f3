#include <cycloid/contact/node_to_surface.h>

namespace cycloid
{
  namespace contact
  {
    template <int dim>
    std::string
    NodeToSurface<dim>::name() const
    {
      return "node-to-surface";
    }



    template <int dim>
    void
    NodeToSurface<dim>::couple(const SurfaceSearch<dim>    &search,
                               std::vector<SlaveNode<dim>> &slaves) const
    {
      // A rigid master does not move: no master term.
      if (!search.deformable_masters())
        return;
      for (auto &s : slaves)
        {
          if (s.hanging)
            continue;
          std::array<std::vector<dealii::types::global_dof_index>, dim> dofs;
          std::array<std::vector<double>, dim>                          w;
          search.master_weights(s.cylinder,
                                search.project(s.cylinder,
                                               s.position,
                                               s.normal),
                                dofs,
                                w,
                                "slave node");
          for (unsigned int c = 0; c < 2; ++c)
            for (unsigned int a = 0; a < dofs[c].size(); ++a)
              {
                s.master_dofs.push_back(dofs[c][a]);
                s.master_coefficients.push_back(s.normal[c] * w[c][a]);
              }
        }
    }



    template class NodeToSurface<2>;
    template class NodeToSurface<3>;
  } // namespace contact
} // namespace cycloid
