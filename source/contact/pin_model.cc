#include <deal.II/base/exceptions.h>

#include <cycloid/contact/pin_model.h>
#include <cycloid/mesh/stage_mesh.h>

#include <cmath>

namespace cycloid
{
  namespace contact
  {
    namespace ids = mesh::ids;

    namespace
    {
      /** Rigid pins: every pin DoF is held (the pins are still meshed, so
       * that the scene and its output match the elastic ones). */
      template <int dim>
      class RigidPins : public PinModel<dim>
      {
      public:
        explicit RigidPins(const PinModelSettings &prm)
          : prm(prm)
        {}

        std::string
        name() const override
        {
          return "rigid";
        }

        void
        add_materials(
          std::map<dealii::types::material_id, parameters::ElasticMaterial>
            &materials) const override
        {
          for (unsigned int j = 0; j < prm.geometry.n_pins; ++j)
            materials[ids::pin(j)] = prm.material.pin;
        }

        bool
        deformable() const override
        {
          return false;
        }

        void
        held_dofs(
          const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
          const std::vector<dealii::types::global_dof_index>           &indices,
          dealii::FEValues<dim> &,
          std::vector<dealii::types::global_dof_index> &held) const override
        {
          if (ids::is_pin(cell->material_id()))
            held.insert(held.end(), indices.begin(), indices.end());
        }

      private:
        const PinModelSettings prm;
      };



      /** Elastic pins held at a rigid core of radius `Pin core radius`
       * around the axis: a line or point support would make the pin's
       * compliance depend on the mesh. */
      template <int dim>
      class ElasticPinsOnAxis : public RigidPins<dim>
      {
      public:
        explicit ElasticPinsOnAxis(const PinModelSettings &prm)
          : RigidPins<dim>(prm)
          , prm(prm)
          , geo(prm.geometry)
        {}

        std::string
        name() const override
        {
          return "elastic-axis";
        }

        bool
        deformable() const override
        {
          return true;
        }

        void
        held_dofs(
          const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
          const std::vector<dealii::types::global_dof_index>           &indices,
          dealii::FEValues<dim>                                        &nodes,
          std::vector<dealii::types::global_dof_index> &held) const override
        {
          const auto m = cell->material_id();
          if (!ids::is_pin(m))
            return;
          const double core = prm.scene.pin_core_radius * (1. + 1e-9);
          const auto   c    = geo.pin_centre(ids::pin_index(m));
          bool         near = false;
          for (const unsigned int v : cell->vertex_indices())
            near |= std::hypot(cell->vertex(v)[0] - c[0],
                               cell->vertex(v)[1] - c[1]) < core;
          if (!near)
            return;
          nodes.reinit(cell);
          const auto &fe = cell->get_fe();
          for (unsigned int i = 0; i < indices.size(); ++i)
            {
              const auto &x =
                nodes.quadrature_point(fe.system_to_component_index(i).second);
              if (std::hypot(x[0] - c[0], x[1] - c[1]) < core)
                held.push_back(indices[i]);
            }
        }

      private:
        const PinModelSettings          prm;
        const geometry::CycloidGeometry geo;
      };



      /** Elastic pins in the meshed housing: the housing's outer surface is
       * held and every seat (groove) node is glued to its pin in every
       * component; a frictionless seat would leave each pin free to spin
       * about its axis (a zero-energy mode). */
      template <int dim>
      class ElasticPinsInHousing : public RigidPins<dim>
      {
      public:
        explicit ElasticPinsInHousing(const PinModelSettings &prm)
          : RigidPins<dim>(prm)
          , prm(prm)
        {}

        std::string
        name() const override
        {
          return "elastic-housing";
        }

        void
        add_materials(
          std::map<dealii::types::material_id, parameters::ElasticMaterial>
            &materials) const override
        {
          RigidPins<dim>::add_materials(materials);
          materials[ids::housing] = prm.material.housing;
        }

        bool
        deformable() const override
        {
          return true;
        }

        void
        configure(ContactProblem<dim> &problem) const override
        {
          problem.set_ties(ids::housing, ids::housing_seat);
        }

        void
        held_dofs(
          const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
          const std::vector<dealii::types::global_dof_index>           &indices,
          dealii::FEValues<dim> &,
          std::vector<dealii::types::global_dof_index> &held) const override
        {
          if (cell->material_id() != ids::housing)
            return;
          const auto &fe = cell->get_fe();
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == ids::housing_outer)
              for (unsigned int i = 0; i < indices.size(); ++i)
                if (fe.has_support_on_face(i, f))
                  held.push_back(indices[i]);
        }

      private:
        const PinModelSettings prm;
      };
    } // namespace



    template <int dim>
    std::unique_ptr<PinModel<dim>>
    create_pin_model(const PinModelSettings &prm)
    {
      using Scene        = parameters::SceneParameters;
      const bool rigid   = prm.scene.pins == Scene::PinModel::rigid;
      const bool housing = prm.scene.pin_support == Scene::PinSupport::housing;
      AssertThrow(!(rigid && housing),
                  dealii::ExcMessage(
                    "Scene: rigid pins need no housing (Pins = rigid holds "
                    "every pin DoF); use Pin support = axis, or Pins = "
                    "elastic with the housing."));
      if (rigid)
        return std::make_unique<RigidPins<dim>>(prm);
      if (housing)
        return std::make_unique<ElasticPinsInHousing<dim>>(prm);
      return std::make_unique<ElasticPinsOnAxis<dim>>(prm);
    }



    template std::unique_ptr<PinModel<2>>
    create_pin_model<2>(const PinModelSettings &);
    template std::unique_ptr<PinModel<3>>
    create_pin_model<3>(const PinModelSettings &);
  } // namespace contact
} // namespace cycloid
