#ifndef cycloid_elasticity_elasticity_h
#define cycloid_elasticity_elasticity_h

#include <deal.II/base/function.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/types.h>

#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <cycloid/parameters/material.h>

#include <functional>
#include <map>
#include <memory>

#include <Epetra_MultiVector.h>

namespace cycloid
{
  namespace elasticity
  {
    /**
     * @brief Small-strain linear elasticity of several bodies, each with its
     * own isotropic material (by material id), on a parallel triangulation:
     * Q_p elements, Trilinos matrices and vectors, CG with an algebraic
     * multigrid (ML) that is given the rigid-body modes (translations and
     * rotations) as its near-null space, or a direct solver.
     *
     * In 2D the problem is plane strain; forces are per unit thickness.
     *
     * The weak form is
     * @f[
     *  \sum_{\text{bodies}} \int_{\Omega_b} \varepsilon(v) :
     *   C_b : \varepsilon(u)\,dx = \int_{\Gamma_N} v \cdot t\,ds ,
     *  \qquad C_b = \lambda_b\, I\otimes I + 2\mu_b\, \mathbb{I}
     * @f]
     * with Dirichlet and other constraints supplied by the caller.
     */
    template <int dim>
    class LinearElasticity
    {
    public:
      /** Linear solver. */
      enum class Solver
      {
        /** CG preconditioned with ML AMG given the rigid-body modes. */
        cg_amg,
        /** CG with ML AMG given only the translations (for studies: how
         * much the rotations matter). */
        cg_amg_translations_only,
        /** Direct sparse solver (Amesos KLU). */
        direct
      };

      /** @p materials maps each material id of the mesh to its material. */
      LinearElasticity(
        const dealii::parallel::TriangulationBase<dim> &triangulation,
        const unsigned int                              degree,
        const std::map<dealii::types::material_id, parameters::ElasticMaterial>
          &materials);

      /** DoFs to hold as ghosts on every rank in addition to the locally
       * relevant ones (e.g. the master DoFs that contact constraints of
       * this rank's slave nodes refer to). Takes effect at setup_system(). */
      void
      set_extra_relevant_dofs(
        const std::vector<dealii::types::global_dof_index> &extra)
      {
        extra_relevant = extra;
      }

      /** Distribute the DoFs and build the sparsity pattern. @p constrain
       * adds the problem's constraints (e.g. Dirichlet values) to the
       * hanging-node constraints; it is called with the constraint object
       * already initialised. */
      void
      setup_system(
        const std::function<void(dealii::AffineConstraints<double> &)>
          &constrain);

      /**
       * Assemble the stiffness matrix and the load vector with the
       * tractions @p tractions on the given boundary ids (each a function
       * with dim components, in force per area; per length in 2D).
       */
      void
      assemble(const std::map<dealii::types::boundary_id,
                              const dealii::Function<dim> *> &tractions);

      /**
       * Internal force vector f_int = sum_cells int B^T sigma(u) of a
       * displacement @p u (with ghosts), assembled without constraints: at
       * a constrained DoF it is the reaction of the constraint on the body,
       * at a free DoF (equilibrium, no load) zero. Returned with ghosts.
       */
      dealii::TrilinosWrappers::MPI::Vector
      internal_forces(const dealii::TrilinosWrappers::MPI::Vector &u) const;

      /** Support points of all locally relevant DoFs. */
      std::map<dealii::types::global_dof_index, dealii::Point<dim>>
      support_points() const;

      /** Locally owned DoFs. */
      const dealii::IndexSet &
      locally_owned_dofs() const
      {
        return locally_owned;
      }

      /** Locally relevant DoFs. */
      const dealii::IndexSet &
      locally_relevant_dofs() const
      {
        return locally_relevant;
      }

      /** Solve; returns the number of iterations (0 for direct). Throws
       * with the solver's message when it fails. */
      unsigned int
      solve(const Solver solver, const double relative_tolerance = 1e-10);

      /** The solution (with ghost entries). */
      const dealii::TrilinosWrappers::MPI::Vector &
      solution() const
      {
        return locally_relevant_solution;
      }

      /** The DoF handler. */
      const dealii::DoFHandler<dim> &
      dof_handler() const
      {
        return dofs;
      }

      /** The constraints (hanging nodes and the caller's). */
      const dealii::AffineConstraints<double> &
      constraints() const
      {
        return all_constraints;
      }

      /** The mapping (of the same degree, following the manifolds). */
      const dealii::Mapping<dim> &
      mapping() const
      {
        return *map;
      }

      /** Number of degrees of freedom. */
      dealii::types::global_dof_index
      n_dofs() const
      {
        return dofs.n_dofs();
      }

      /**
       * Rigid-body modes of the locally owned DoFs, one column per mode
       * (dim translations, then dim(dim-1)/2 rotations about the origin),
       * on the row map of the system matrix.
       */
      std::unique_ptr<Epetra_MultiVector>
      rigid_body_modes(const bool with_rotations) const;

    private:
      const dealii::parallel::TriangulationBase<dim> &triangulation;
      const MPI_Comm                                  comm;
      const dealii::FESystem<dim>                     fe;
      std::unique_ptr<dealii::MappingQ<dim>>          map;
      dealii::DoFHandler<dim>                         dofs;
      const std::map<dealii::types::material_id, parameters::ElasticMaterial>
        materials;

      std::vector<dealii::types::global_dof_index> extra_relevant;
      dealii::IndexSet                             locally_owned;
      dealii::IndexSet                             locally_relevant;
      dealii::AffineConstraints<double>            all_constraints;
      dealii::TrilinosWrappers::SparseMatrix       system_matrix;
      dealii::TrilinosWrappers::MPI::Vector        system_rhs;
      dealii::TrilinosWrappers::MPI::Vector        locally_relevant_solution;

      std::unique_ptr<Epetra_MultiVector>       null_space;
      dealii::TrilinosWrappers::PreconditionAMG amg;
    };
  } // namespace elasticity
} // namespace cycloid

#endif
