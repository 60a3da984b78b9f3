#include <deal.II/base/mpi.h>

#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <cycloid/contact/vtu_output.h>

#include <cmath>
#include <fstream>

namespace cycloid
{
  namespace contact
  {
    namespace
    {
      /** Von Mises stress per body material (2D: plane strain, sigma_zz =
       * lambda tr(eps)). */
      template <int dim>
      class VonMises : public dealii::DataPostprocessorScalar<dim>
      {
      public:
        explicit VonMises(
          const std::map<dealii::types::material_id,
                         parameters::ElasticMaterial> &materials)
          : dealii::DataPostprocessorScalar<dim>("von_Mises",
                                                 dealii::update_gradients)
          , materials(materials)
        {}

        void
        evaluate_vector_field(
          const dealii::DataPostprocessorInputs::Vector<dim> &inputs,
          std::vector<dealii::Vector<double>> &computed) const override
        {
          const auto  cell        = inputs.template get_cell<dim>();
          const auto &m           = materials.at(cell->material_id());
          const auto [lambda, mu] = elasticity::lame_parameters(m);
          for (unsigned int q = 0; q < computed.size(); ++q)
            {
              const auto &g = inputs.solution_gradients[q];
              double      eps[3][3]{};
              for (unsigned int a = 0; a < dim; ++a)
                for (unsigned int b = 0; b < dim; ++b)
                  eps[a][b] = 0.5 * (g[a][b] + g[b][a]);
              const double tr = eps[0][0] + eps[1][1] + eps[2][2];
              double       s[3][3];
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int b = 0; b < 3; ++b)
                  s[a][b] = 2 * mu * eps[a][b] + (a == b ? lambda * tr : 0.);
              computed[q](0) =
                std::sqrt(0.5 * ((s[0][0] - s[1][1]) * (s[0][0] - s[1][1]) +
                                 (s[1][1] - s[2][2]) * (s[1][1] - s[2][2]) +
                                 (s[2][2] - s[0][0]) * (s[2][2] - s[0][0])) +
                          3 * (s[0][1] * s[0][1] + s[1][2] * s[1][2] +
                               s[0][2] * s[0][2]));
            }
        }

      private:
        const std::map<dealii::types::material_id, parameters::ElasticMaterial>
          &materials;
      };
    } // namespace



    template <int dim>
    void
    write_vtu(const elasticity::LinearElasticity<dim>     &problem,
              const std::map<dealii::types::material_id,
                             parameters::ElasticMaterial> &materials,
              const std::vector<SlaveNode<dim>>           &slaves,
              const ContactSolution<dim>                  &solution,
              const std::string                           &directory,
              const std::string                           &name)
    {
      const MPI_Comm comm =
        problem.dof_handler().get_triangulation().get_communicator();
      const auto &u = solution.displacement;
      // Nodal contact fields, one scalar per displacement component of a
      // slave node: x slot the contact pressure (normal reaction / node
      // weight, MPa), y slot the active flag, z slot (3D) the gap [um].
      const auto &owned = problem.locally_owned_dofs();
      dealii::TrilinosWrappers::MPI::Vector contact(owned, comm);
      for (unsigned int i = 0; i < slaves.size(); ++i)
        {
          double lambda = 0;
          for (unsigned int c = 0; c < dim; ++c)
            lambda += solution.reactions[i][c] * slaves[i].normal[c];
          const double values[3] = {slaves[i].weight > 0 ?
                                      lambda / slaves[i].weight :
                                      0.,
                                    solution.active.count(i) ? 1. : 0.,
                                    solution.gaps[i] * 1e3};
          for (unsigned int c = 0; c < dim; ++c)
            if (owned.is_element(slaves[i].dofs[c]))
              contact[slaves[i].dofs[c]] = values[c];
        }
      contact.compress(dealii::VectorOperation::insert);
      dealii::TrilinosWrappers::MPI::Vector contact_g(
        owned, problem.locally_relevant_dofs(), comm);
      contact_g = contact;

      dealii::DataOut<dim> data_out;
      data_out.attach_dof_handler(problem.dof_handler());
      const std::vector<
        dealii::DataComponentInterpretation::DataComponentInterpretation>
        vector(
          dim,
          dealii::DataComponentInterpretation::component_is_part_of_vector);
      data_out.add_data_vector(u,
                               std::vector<std::string>(dim, "displacement"),
                               dealii::DataOut<dim>::type_dof_data,
                               vector);
      std::vector<std::string> names{"contact_pressure",
                                     "active_set",
                                     "gap_um"};
      names.resize(dim);
      data_out.add_data_vector(contact_g, names);
      const VonMises<dim> von_mises(materials);
      data_out.add_data_vector(u, von_mises);
      const auto           &tria = problem.dof_handler().get_triangulation();
      dealii::Vector<float> body(tria.n_active_cells()),
        rank(tria.n_active_cells());
      for (const auto &cell : tria.active_cell_iterators())
        {
          body(cell->active_cell_index()) = cell->material_id();
          rank(cell->active_cell_index()) = cell->subdomain_id();
        }
      data_out.add_data_vector(body, "body_id");
      data_out.add_data_vector(rank, "mpi_rank");
      data_out.build_patches(problem.mapping(),
                             problem.finite_element().degree,
                             dealii::DataOut<dim>::curved_inner_cells);

      const unsigned int r = dealii::Utilities::MPI::this_mpi_process(comm);
      {
        std::ofstream out(directory + "/" + name + "." +
                          dealii::Utilities::int_to_string(r, 4) + ".vtu");
        data_out.write_vtu(out);
      }
      if (r == 0)
        {
          std::vector<std::string> pieces;
          for (unsigned int k = 0;
               k < dealii::Utilities::MPI::n_mpi_processes(comm);
               ++k)
            pieces.push_back(name + "." +
                             dealii::Utilities::int_to_string(k, 4) + ".vtu");
          std::ofstream pvtu(directory + "/" + name + ".pvtu");
          data_out.write_pvtu_record(pvtu, pieces);
        }
    }



    template void
    write_vtu<2>(
      const elasticity::LinearElasticity<2> &,
      const std::map<dealii::types::material_id, parameters::ElasticMaterial> &,
      const std::vector<SlaveNode<2>> &,
      const ContactSolution<2> &,
      const std::string &,
      const std::string &);
    template void
    write_vtu<3>(
      const elasticity::LinearElasticity<3> &,
      const std::map<dealii::types::material_id, parameters::ElasticMaterial> &,
      const std::vector<SlaveNode<3>> &,
      const ContactSolution<3> &,
      const std::string &,
      const std::string &);
  } // namespace contact
} // namespace cycloid
