#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <cycloid/contact/mortar.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace cycloid
{
  namespace contact
  {
    namespace
    {
      /** The master side seen from one slave quadrature point: the normal
       * of a cylinder there and the master weights at its projection. */
      template <int dim>
      struct MasterAt
      {
        dealii::Tensor<1, dim>                                        normal;
        std::array<std::vector<dealii::types::global_dof_index>, dim> dofs;
        std::array<std::vector<double>, dim>                          weights;
      };

      /** The integrals int psi_i n ds and int psi_i n . phi_m ds of every
       * slave node, summed over its faces. */
      template <int dim>
      struct DualIntegrals
      {
        explicit DualIntegrals(const unsigned int n_slaves)
          : normals(n_slaves)
          , coefficients(n_slaves)
        {}

        std::vector<dealii::Tensor<1, dim>> normals;
        std::vector<std::map<dealii::types::global_dof_index, double>>
          coefficients;

        /** On a distributed mesh each rank integrated its own slave faces:
         * add up every rank's integrals, the same sums on every rank (the
         * normals by one reduction, the coefficients in rank order). */
        void
        sum_over_ranks(const MPI_Comm comm)
        {
          std::vector<double> packed;
          for (unsigned int i = 0; i < normals.size(); ++i)
            for (const auto &[m, value] : coefficients[i])
              packed.insert(packed.end(), {double(i), double(m), value});
          std::vector<double> flat;
          for (const auto &n : normals)
            for (unsigned int c = 0; c < dim; ++c)
              flat.push_back(n[c]);
          dealii::Utilities::MPI::sum(flat, comm, flat);
          for (unsigned int i = 0; i < normals.size(); ++i)
            for (unsigned int c = 0; c < dim; ++c)
              normals[i][c] = flat[i * dim + c];
          for (auto &c : coefficients)
            c.clear();
          const std::vector<double> all = gather_all(comm, packed);
          for (std::size_t k = 0; k < all.size(); k += 3)
            coefficients[static_cast<unsigned int>(all[k])]
                        [static_cast<dealii::types::global_dof_index>(
                          all[k + 1])] += all[k + 2];
        }
      };

      /** The nodes of slave face @p f: the cell-local indices of their x
       * components (@p local) and their slave numbers (@p slave; invalid
       * for a node out of reach). Returns whether any is a slave node. */
      template <int dim>
      bool
      face_nodes(
        const dealii::FiniteElement<dim>                              &fe,
        const unsigned int                                             f,
        const std::vector<dealii::types::global_dof_index>            &indices,
        const std::map<dealii::types::global_dof_index, unsigned int> &index_of,
        std::vector<unsigned int>                                     &local,
        std::vector<unsigned int>                                     &slave)
      {
        local.clear();
        slave.clear();
        for (unsigned int k = 0; k < fe.n_dofs_per_face(f); ++k)
          {
            const unsigned int i = fe.face_to_cell_index(k, f);
            if (fe.system_to_component_index(i).first != 0)
              continue;
            local.push_back(i);
            const auto it = index_of.find(indices[i]);
            slave.push_back(it == index_of.end() ?
                              dealii::numbers::invalid_unsigned_int :
                              it->second);
          }
        return std::any_of(slave.begin(),
                           slave.end(),
                           [](const unsigned int s) {
                             return s != dealii::numbers::invalid_unsigned_int;
                           });
      }

      /** The coefficients A_ab = D_a (M^-1)_ab of the dual basis psi_a =
       * sum_b A_ab phi_b of the face in @p fe_face, with M the face mass
       * matrix and D_a = int phi_a: biorthogonal, int psi_a phi_b =
       * delta_ab int phi_a. */
      template <int dim>
      dealii::FullMatrix<double>
      dual_basis(const dealii::FEFaceValues<dim> &fe_face,
                 const std::vector<unsigned int> &local)
      {
        const unsigned int         n = local.size();
        dealii::FullMatrix<double> M(n, n), Minv(n, n), A(n, n);
        dealii::Vector<double>     D(n);
        for (const unsigned int q : fe_face.quadrature_point_indices())
          for (unsigned int a = 0; a < n; ++a)
            {
              const double pa = fe_face.shape_value(local[a], q);
              D(a) += pa * fe_face.JxW(q);
              for (unsigned int b = 0; b < n; ++b)
                M(a, b) +=
                  pa * fe_face.shape_value(local[b], q) * fe_face.JxW(q);
            }
        Minv.invert(M);
        for (unsigned int a = 0; a < n; ++a)
          for (unsigned int b = 0; b < n; ++b)
            A(a, b) = D(a) * Minv(a, b);
        return A;
      }

      /** The master side of cylinder @p j at the slave point @p x. */
      template <int dim>
      MasterAt<dim>
      master_at(const SurfaceSearch<dim> &search,
                const unsigned int        j,
                const dealii::Point<dim> &x)
      {
        MasterAt<dim> m;
        m.normal = search.normal(j, x);
        if (search.deformable_masters())
          search.master_weights(j,
                                search.project(j, x, m.normal),
                                m.dofs,
                                m.weights,
                                "slave quadrature point");
        return m;
      }

      /** Add the contributions of quadrature point @p q of a slave face
       * (of body @p body; nodes @p local, @p slave, dual basis @p A) to
       * @p sums. */
      template <int dim>
      void
      add_quadrature_point(const SurfaceSearch<dim>          &search,
                           const std::vector<SlaveNode<dim>> &slaves,
                           const dealii::FEFaceValues<dim>   &fe_face,
                           const unsigned int                 q,
                           const dealii::types::material_id   body,
                           const std::vector<unsigned int>   &local,
                           const std::vector<unsigned int>   &slave,
                           const dealii::FullMatrix<double>  &A,
                           DualIntegrals<dim>                &sums)
      {
        const dealii::Point<dim> x =
          search.place(body, fe_face.quadrature_point(q));
        // Per cylinder met on this face: normal and master weights.
        std::map<unsigned int, MasterAt<dim>> at;
        for (unsigned int a = 0; a < local.size(); ++a)
          {
            if (slave[a] == dealii::numbers::invalid_unsigned_int)
              continue;
            const SlaveNode<dim> &s = slaves[slave[a]];
            if (s.hanging)
              continue;
            auto it = at.find(s.cylinder);
            if (it == at.end())
              it =
                at.emplace(s.cylinder, master_at(search, s.cylinder, x)).first;
            const MasterAt<dim> &m   = it->second;
            double               psi = 0;
            for (unsigned int b = 0; b < local.size(); ++b)
              psi += A(a, b) * fe_face.shape_value(local[b], q);
            const double w = psi * fe_face.JxW(q);
            for (unsigned int c = 0; c < 2; ++c)
              sums.normals[slave[a]][c] += w * m.normal[c];
            for (unsigned int c = 0; c < 2; ++c)
              for (unsigned int k = 0; k < m.dofs[c].size(); ++k)
                sums.coefficients[slave[a]][m.dofs[c][k]] +=
                  w * m.normal[c] * m.weights[c][k];
          }
      }
    } // namespace



    template <int dim>
    std::string
    Mortar<dim>::name() const
    {
      return "mortar";
    }



    template <int dim>
    void
    Mortar<dim>::couple(const SurfaceSearch<dim>    &search,
                        std::vector<SlaveNode<dim>> &slaves) const
    {
      const auto &fe = search.elasticity().finite_element();
      // More points than the slave polynomials need: the master field is
      // only piecewise smooth along the slave face.
      const dealii::QGauss<dim - 1> quadrature(fe.degree + 4);
      dealii::FEFaceValues<dim>     fe_face(search.elasticity().mapping(),
                                        fe,
                                        quadrature,
                                        dealii::update_values |
                                          dealii::update_quadrature_points |
                                          dealii::update_JxW_values);
      std::map<dealii::types::global_dof_index, unsigned int> index_of;
      for (unsigned int i = 0; i < slaves.size(); ++i)
        index_of[slaves[i].dofs[0]] = i;
      DualIntegrals<dim>                           sums(slaves.size());
      std::vector<dealii::types::global_dof_index> indices(
        fe.n_dofs_per_cell());
      std::vector<unsigned int> local, slave;
      for (const auto &[cell, f] : search.slave_faces())
        {
          cell->get_dof_indices(indices);
          if (!face_nodes(fe, f, indices, index_of, local, slave))
            continue;
          fe_face.reinit(cell, f);
          const dealii::FullMatrix<double> A = dual_basis(fe_face, local);
          for (const unsigned int q : fe_face.quadrature_point_indices())
            add_quadrature_point(search,
                                 slaves,
                                 fe_face,
                                 q,
                                 cell->material_id(),
                                 local,
                                 slave,
                                 A,
                                 sums);
        }
      if (search.distributed())
        sums.sum_over_ranks(search.communicator());
      for (unsigned int i = 0; i < slaves.size(); ++i)
        {
          SlaveNode<dim> &s = slaves[i];
          if (s.hanging || s.weight <= 0)
            continue;
          // The initial gap stays collocated at the node (see
          // Formulation): the dual-weighted gap would carry a bias of
          // -kappa h^2 / 6 (kappa: curvature of the gap function), which on
          // coarse faces reaches the size of micrometre clearances.
          // The weighted normal (not of unit length on a curved face):
          // with it the master coefficients of each direction sum to the
          // slave's, so action equals reaction exactly.
          s.normal = sums.normals[i] / s.weight;
          s.master_dofs.clear();
          s.master_coefficients.clear();
          for (const auto &[m, value] : sums.coefficients[i])
            if (std::abs(value) > 1e-14 * s.weight)
              {
                s.master_dofs.push_back(m);
                s.master_coefficients.push_back(value / s.weight);
              }
        }
    }



    template class Mortar<2>;
    template class Mortar<3>;
  } // namespace contact
} // namespace cycloid
