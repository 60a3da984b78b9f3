#ifndef cycloid_contact_surface_search_h
#define cycloid_contact_surface_search_h

#include <deal.II/base/mpi.h>
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
    /** Every rank's @p local, concatenated in rank order (collective):
     * how the contact lists of a distributed mesh are gathered. */
    std::vector<double>
    gather_all(const MPI_Comm comm, const std::vector<double> &local);

    /**
     * @brief The geometry of the contact, independent of how the constraint
     * is discretised: the slave nodes (support points of the slave faces)
     * and their nearest exact cylinder, the faces of the cylinders' meshes,
     * the projection of a point onto a cylinder and the master body's
     * shape-function weights there, and the tied nodes.
     *
     * Every rank holds the same nodes, master faces and ties. On a shared
     * triangulation (no artificial cells) every rank finds them all from
     * its own copy of the mesh, in the order of the cell iteration. On a
     * distributed one (p4est) each rank finds those of its locally owned
     * cells and the lists are gathered (slave nodes met on several ranks
     * summed, then ordered by DoF): the surfaces are a small fraction of
     * the mesh, and a slave's master face may live on any rank.
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

      /** A face of a master cylinder's surface as data, so that every rank
       * holds all of them whoever owns the cell: its face number, its
       * vertices (in the cell's face order), its cell's DoF indices and its
       * box of centre angle, half angular width and z range. */
      struct MasterFace
      {
        /** Face number in its cell. */
        unsigned int face = 0;
        /** The face's vertices, GeometryInfo::face_to_cell_vertices order. */
        std::array<dealii::Point<dim>, (1u << (dim - 1))> vertices;
        /** DoF indices of the face's cell. */
        std::vector<dealii::types::global_dof_index> dofs;
        /** Centre angle, half angular width, z min, z max. */
        std::array<double, 4> box;
      };

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
       * for deformable masters or tied nodes. Collective on a distributed
       * mesh, as are find_slave_nodes() and find_tied_nodes(). */
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

      /** This rank's slave faces in the order of the cell iteration: all
       * of them on a shared mesh, the locally owned ones on a distributed
       * mesh (see distributed()). */
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

      /** Whether the mesh is distributed: each rank holds its own cells
       * and a ghost layer, and what is found on the faces of its cells
       * must be summed over the ranks (e.g. mortar integrals). */
      bool
      distributed() const;

      /** The communicator of the mesh. */
      MPI_Comm
      communicator() const;

      /** The elasticity problem searched. */
      const elasticity::LinearElasticity<dim> &
      elasticity() const
      {
        return problem;
      }

    private:
      /** The boundary faces with id @p surface of this rank's cells (see
       * slave_faces()) for which @p body_matches(material id) holds. */
      std::vector<Face>
      boundary_faces(
        const std::function<bool(dealii::types::material_id)> &body_matches,
        const dealii::types::boundary_id                       surface) const;

      /** The nodes of the tied surface that are not hanging, each once:
       * their DoFs and positions (every rank's on a distributed mesh). */
      std::vector<std::pair<std::array<dealii::types::global_dof_index, dim>,
                            dealii::Point<dim>>>
      tied_candidates() const;

      /** Unit-cell point of @p P on master face @p face of cylinder @p j,
       * if the face holds it (@p theta: the angle of P). */
      bool
      unit_point_on_face(const unsigned int        j,
                         const MasterFace         &face,
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
      std::vector<std::vector<MasterFace>> master_faces;
    };
  } // namespace contact
} // namespace cycloid

#endif
