#ifndef cycloid_contact_pin_model_h
#define cycloid_contact_pin_model_h

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_values.h>

#include <cycloid/contact/contact_problem.h>
#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/parameters/material.h>
#include <cycloid/parameters/scene.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace cycloid
{
  namespace contact
  {
    /**
     * @brief How the pins are modelled and held: the swappable part of a
     * stage scene that decides which bodies exist besides the discs, whether
     * the pins deform, and which DoFs are held. Chosen from `Scene/Pins`
     * and `Scene/Pin support` by create_pin_model():
     *
     * | name            | Pins    | Pin support | held                         |
     * |-----------------|---------|-------------|------------------------------|
     * | rigid           | rigid   | axis        | every pin DoF                |
     * | elastic-axis    | elastic | axis        | pin DoFs within the core     |
     * | elastic-housing | elastic | housing     | housing outer surface; seats |
     * |                 |         |             | glued to the pins            |
     */
    template <int dim>
    class PinModel
    {
    public:
      virtual ~PinModel() = default;

      /** Name (see the table). */
      virtual std::string
      name() const = 0;

      /** Add the materials of the pins (and housing) to @p materials. */
      virtual void
      add_materials(std::map<dealii::types::material_id,
                             parameters::ElasticMaterial> &materials) const = 0;

      /** Do the pins deform (deformable master cylinders)? */
      virtual bool
      deformable() const = 0;

      /** Further contact set-up (ties of the housing seats). */
      virtual void
      configure(ContactProblem<dim> &) const
      {}

      /**
       * Append to @p held the DoFs of @p cell that this model holds at
       * zero. @p indices are the cell's DoFs, @p nodes an FEValues at the
       * cell's support points (reinit by the callee when needed).
       */
      virtual void
      held_dofs(
        const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
        const std::vector<dealii::types::global_dof_index>           &indices,
        dealii::FEValues<dim>                                        &nodes,
        std::vector<dealii::types::global_dof_index> &held) const = 0;
    };

    /** What the pin models read from the parameter file. */
    struct PinModelSettings
    {
      geometry::GeometryParameters   geometry; ///< Subsection `Geometry`.
      parameters::MaterialParameters material; ///< Subsection `Material`.
      parameters::SceneParameters    scene;    ///< Subsection `Scene`.
    };

    /** The pin model of the prm's `Scene` (throws naming the entries for a
     * combination that does not exist). */
    template <int dim>
    std::unique_ptr<PinModel<dim>>
    create_pin_model(const PinModelSettings &settings);
  } // namespace contact
} // namespace cycloid

#endif
