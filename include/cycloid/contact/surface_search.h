#ifndef cycloid_contact_surface_search_h
#define cycloid_contact_surface_search_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <cycloid/contact/contact_types.h>
#include <cycloid/elasticity/elasticity.h>

#include <array>
#include <functional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace cycloid
{
  namespace contact
  {
    /**
     * @brief The geometry of the contact, independent of how the constraint
     * is discretised: the slave nodes (support points of the slave faces)
     * and their nearest exact cylinder, the faces of the cylinders' meshes,
     * the projection of a point onto a cylinder and the master body's
     * shape-function weights there, and the tied nodes.
     *
     * Works on a shared triangulation without artificial cells: every rank
     * sees every cell and its DoF indices, so every rank finds the same
     * nodes in the same order.
     */
    template <int dim>
    class SurfaceSearch
    {
    public:
      /** Rigid placement of a body: maps (body, x) to the position of x. */
      using Placement =
        std::function<dealii::Point<dim>(dealii::types::material_id,
                                         const dealii::Point<dim> &)>;
      /** A face of the mesh: (cell, face number). */
      using Face =
        std::pair<typename dealii::DoFHandler<dim>::active_cell_iterator,
                  unsigned int>;

      /** Search on the DoFs, mapping and hanging nodes of @p problem (held
       * by reference; it must outlive the search). */
      explicit SurfaceSearch(const elasticity::LinearElasticity<dim> &problem);

      /** Slave nodes of @p slave_surface on @p slave_bodies against the
       * @p cylinders, deformable bodies of the mesh if
       * @p deformable_masters. */
      void
      set_contact(const std::set<dealii::types::material_id> &slave_bodies,
                  const dealii::types::boundary_id            slave_surface,
                  const std::vector<MasterCylinder>          &cylinders,
                  const bool deformable_masters);

      /** Nodes of @p surface of body @p body to be tied to their nearest
       * cylinder. */
      void
      set_ties(const dealii::types::material_id body,
               const dealii::types::boundary_id surface);

      /** Rigid placement of the slave bodies applied to slave positions
       * (see ContactProblem::set_placement()); empty: none. */
      void
      set_placement(const Placement &placement);

      /** After a DoF distribution: collect the faces of the cylinders'
       * surfaces with their (angle, z) boxes. Only needed, and only done,
       * for deformable masters or tied nodes. */
      void
      collect_master_faces();

      /**
       * The slave nodes within @p search_distance of their nearest
       * cylinder, with the collocated gap and unit normal at the node and
       * their weight int phi_i ds; no master coefficients yet (the
       * constraint formulation adds them).
       */
      std::vector<SlaveNode<dim>>
      find_slave_nodes(const double search_distance) const;

      /** The tied nodes (none unless set_ties() was called) with the master
       * weights at their projections; needs collect_master_faces(). */
      std::vector<TiedNode<dim>>
      find_tied_nodes() const;

      /** The slave faces in the order of the cell iteration. */
      std::vector<Face>
      slave_faces() const;

      /** Position of @p x of body @p body under the placement. */
      dealii::Point<dim>
      place(const dealii::types::material_id body,
            const dealii::Point<dim>        &x) const;

      /** Unit normal of cylinder @p j at the point closest to @p x, from
       * the axis towards x (no z component). */
      dealii::Tensor<1, dim>
      normal(const unsigned int j, const dealii::Point<dim> &x) const;

      /** Projection of @p x onto cylinder @p j along the unit normal
       * @p n (from normal()); z stays. */
      dealii::Point<dim>
      project(const unsigned int            j,
              const dealii::Point<dim>     &x,
              const dealii::Tensor<1, dim> &n) const;

      /**
       * Shape-function weights of the master body of cylinder @p j at
       * @p P (a point on the cylinder), per displacement component: u_c(P)
       * = sum_a weights[c][a] u_(dofs[c][a]). Throws, naming @p what (the
       * point's role, for the message), if no master face holds P.
       */
      void
      master_weights(
        const unsigned int                                             j,
        const dealii::Point<dim>                                      &P,
        std::array<std::vector<dealii::types::global_dof_index>, dim> &dofs,
        std::array<std::vector<double>, dim>                          &weights,
        const std::string &what) const;

      /** The master cylinders. */
      const std::vector<MasterCylinder> &
      cylinders() const
      {
        return masters;
      }

      /** Whether the cylinders are deformable bodies of the mesh. */
      bool
      deformable_masters() const
      {
        return deformable;
      }

      /** The elasticity problem searched. */
      const elasticity::LinearElasticity<dim> &
      elasticity() const
      {
        return problem;
      }

    private:
      /** The boundary faces with id @p surface of the cells for which
       * @p body_matches(material id) holds. */
      std::vector<Face>
      boundary_faces(
        const std::function<bool(dealii::types::material_id)> &body_matches,
        const dealii::types::boundary_id                       surface) const;

      /** Unit-cell point of @p P on master face @p face of cylinder @p j,
       * if the face holds it (@p theta: the angle of P). */
      bool
      unit_point_on_face(const unsigned int        j,
                         const Face               &face,
                         const dealii::Point<dim> &P,
                         const double              theta,
                         dealii::Point<dim>       &unit) const;

      const elasticity::LinearElasticity<dim> &problem;

      std::set<dealii::types::material_id> slave_bodies;
      dealii::types::boundary_id           slave_surface = 0;
      std::vector<MasterCylinder>          masters;
      bool                                 deformable   = false;
      bool                                 with_ties    = false;
      dealii::types::material_id           tied_body    = 0;
      dealii::types::boundary_id           tied_surface = 0;
      Placement                            placement;

      /** Per cylinder: the faces of its surface. */
      std::vector<std::vector<Face>> master_faces;
      /** Per master face: centre angle, half angular width, z range. */
      std::vector<std::vector<std::array<double, 4>>> master_boxes;
    };
  } // namespace contact
} // namespace cycloid

#endif
