#include <deal.II/base/mpi.h>

#include <cycloid/process/heap.h>
#include <cycloid/results/cost_figures.h>
#include <cycloid/results/error_estimate.h>
#include <cycloid/stage/cost_estimate.h>
#include <cycloid/stage/stage_scene.h>

#include <cmath>
#include <iomanip>
#include <sstream>

// What a scene will cost and how well it will resolve its contacts, said
// before the work (ASPECT-style: StageScene's members by stage, this file
// the announcements and the memory check of the set-up).

namespace cycloid
{
  namespace stage
  {
    template <int dim>
    bool
    StageScene<dim>::plain_amg() const
    {
      const auto &c = settings.contact;
      return c.linear_solver == elasticity::LinearSolver::cg_amg &&
             c.hierarchy(dim) == elasticity::AMGHierarchy::plain_w;
    }



    template <int dim>
    CostInputs
    StageScene<dim>::cost_inputs(
      const dealii::types::global_dof_index n_dofs) const
    {
      CostInputs in{dim,
                    settings.scene.n_discs,
                    n_dofs,
                    settings.mesh.degree,
                    0,
                    dealii::Utilities::MPI::n_mpi_processes(comm),
                    false};
      in.plain_amg     = plain_amg();
      in.heap_released = process::mmap_threshold() != 0;
      return in;
    }



    template <int dim>
    void
    StageScene<dim>::announce_cost() const
    {
      // The DoFs exist, the matrices not yet (they are allocated at the
      // first solve): the last moment to stop a run that cannot fit.
      const auto &m       = settings.mesh;
      CostInputs  in      = cost_inputs(contact->elasticity().n_dofs());
      in.adaptive_cycles  = m.adaptive_cycles;
      in.error_estimate   = m.error.estimates(dim);
      in.bulk_estimate    = m.error.bulk_level(dim);
      const auto estimate = estimate_cost(in);
      pcout << "  " << estimate.line();
      if (m.error.target_accuracy > 0)
        {
          // A state that misses the target on the mesh asked for costs
          // more: say how much at worst, before the user waits for it.
          in.adaptive_cycles += m.error.max_cycles;
          std::ostringstream worst;
          worst << std::setprecision(2) << estimate_cost(in).seconds_per_state;
          pcout << ", at most " << worst.str()
                << " s if Target accuracy takes all its " << m.error.max_cycles
                << " cycles";
        }
      pcout << std::endl;
      // The bulk level is skipped when it would not fit (refinement_fits):
      // only the mesh asked for must fit.
      in.adaptive_cycles = m.adaptive_cycles;
      in.bulk_estimate   = false;
      check_memory(estimate_cost(in), available_memory_bytes(comm), m);
    }



    template <int dim>
    void
    StageScene<dim>::announce_resolution(const double torque) const
    {
      const auto &e = settings.mesh.error;
      if (settings.rotation_control || torque == 0 || e.estimates(dim))
        return;
      // The analytical model's largest pin force is within a few per cent
      // of the FE model's (doc/scene-guide.md) and n goes as its square
      // root; but it may sit on a neighbour of the FE model's most loaded
      // pin, whose flank curvature, so Hertz width, differs (by about
      // 20 % in n on the seed).
      const results::StageState a =
        model.stage_state(model.solve(psi, torque, 0.), psi);
      const auto most = a.most_loaded_pin();
      if (most == a.pins.end() || !(most->fn > 0))
        return;
      const double h = state_builder().flank_node_spacing(most->disc,
                                                          most->pin,
                                                          most->contact_point);
      if (!(h > 0))
        return;
      const double       n = 2. * most->hertz_halfwidth / h;
      const double       r = results::resolution_constant / (n * n);
      std::ostringstream line;
      line << "  contact resolution expected at " << torque
           << " N m: " << std::setprecision(2) << n
           << " node(s) across the Hertz width of the most loaded pin (disc "
           << most->disc << " pin " << most->pin << ", "
           << std::lround(most->fn) << " N in the analytical model), pin "
           << "forces to about " << 100. * r << " %";
      if (e.warning_threshold > 0 && r > e.warning_threshold)
        line << ": above Mesh/Warning threshold, so the states will be "
                "flagged; about "
             << std::ceil(std::log(r / e.warning_threshold) / std::log(4.))
             << " more Contact refinements would resolve it";
      pcout << line.str() << std::endl;
    }



    template <int dim>
    double
    StageScene<dim>::memory_needed(
      const dealii::types::global_dof_index n_dofs) const
    {
      return estimate_cost(cost_inputs(n_dofs)).memory_bytes;
    }



    template class StageScene<2>;
    template class StageScene<3>;
  } // namespace stage
} // namespace cycloid
