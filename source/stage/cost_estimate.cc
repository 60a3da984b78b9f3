#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <cycloid/stage/cost_estimate.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

namespace cycloid
{
  namespace stage
  {
    namespace
    {
      /**
       * One family of the cost model, fitted by least squares to the
       * 2-rank, one-state, a-priori-mesh runs of doc/ladder/ladder.csv
       * (idle machine; doc/scene-guide.md "Cost model" gives the fit and
       * its error against every run).
       */
      struct Family
      {
        const char *name;       ///< As printed.
        double      kb_per_dof; ///< Peak memory per DoF at 2 ranks [kB].
        double      c;          ///< Time of a state at 2 ranks = c N^p [s].
        double      p;          ///< Exponent of the time.
        double      growth;     ///< DoFs growth of one adaptive cycle.
      };

      // Memory: fitted on ladder.csv's runs of 2026-12-04 (the smoothed
      // hierarchy; plain_amg_memory and heap_memory bring it to today's
      // defaults); rms error 3 % (2D, 18 runs), 4 % (3D one disc, 5), 8 %
      // (3D two discs, 7).
      //
      // Time: 2D from ladder.csv, rms 54 % (a 2D state's seconds follow
      // its active-set iterations more than its DoFs). 3D from the runs
      // re-timed on 2026-12-06 (doc/ladder/retimed-2026-12-06.csv), rms
      // 13 % (one disc, 3 runs) and 31 % (two discs, 7 runs, -33 to
      // +59 %); the fits of 2026-12-04 were 14-171 % high by then. Those
      // runs had CG's start set in the constrained rows, since reverted:
      // the shipped build takes up to 5-15 % more CG iterations.
      //
      // Adaptive growth per cycle: cr1+ad2 (2D), c1 ax1 cr1+ad1 (3D one
      // disc) and the 3D seed case under Target accuracy 0.01 (two
      // cycles), with the 3D rule measuring cells in the section plane.
      //
      // Bulk level (Mesh/Bulk error estimate: every cell below the two
      // finest levels refined once): 2D 86.7 k -> 222 k DoFs on the first
      // mesh of prm/quasi-static-2d.prm (Contact refinements 3), 92 k ->
      // 342 k after Target accuracy's cycles (the peak); 3D 148 k -> 545 k
      // (the 3D test scene, one disc, one axial layer, Contact
      // refinements 2); not measured on two discs, taken as one disc's.
      constexpr Family two_d{"2D", 2.681, 2.259e-10, 2.059, 1.15};
      constexpr Family one_disc{"3D one disc", 3.585, 1.416e-6, 1.261, 1.28};
      constexpr Family two_discs{"3D two discs", 4.384, 1.016e-5, 1.162, 1.36};

      /** DoFs of the bulk level over the mesh's, in every family (the
       * measurements above agree; not measured on two discs). */
      constexpr double bulk_dofs = 3.7;

      /** Time of a 2D state with the bulk level over the time without:
       * the level is solved on the first mesh and again after Target
       * accuracy's cycles. Side by side: 1.44-1.63 on the slab's default
       * run, 1.43-1.47 on the seed's (doc/error-estimate.md §5); the 2D
       * examples, which refine more, up to 2. In 3D the bulk level is
       * costed as one more state on its DoFs. */
      constexpr double two_d_bulk_time = 1.5;

      /** Resident memory of a rank before the FE system [MB]: the
       * analytic runs' peak (151 MB) and the intercept of the fits. */
      constexpr double mb_per_rank = 150;
      /** Per-DoF memory on one rank relative to two (0.71-0.79 measured
       * in 2D, 0.73 in 3D, ladder.csv 1- and 2-rank pairs): every rank
       * holds the whole mesh (parallel::shared::Triangulation), so it
       * grows with the ranks. Fitted on the shared mesh: on the
       * distributed mesh it errs high (0.92 of it on the 3D seed case on
       * 2 ranks, doc/ranks.md). */
      constexpr double one_rank_memory = 0.74;
      /** Time on n ranks = time on 2 x (2/n)^this: the solve speed-up
       * from 1 to 2 ranks, 1.53-2.20, mean 1.78 (ladder/ranks.csv). */
      constexpr double rank_exponent = 0.83;

      /** "1.23" with @p digits significant digits. */
      std::string
      significant(const double x, const int digits)
      {
        std::ostringstream s;
        s << std::setprecision(digits) << x;
        return s.str();
      }
    } // namespace



    std::string
    CostEstimate::line() const
    {
      return "DoFs " + std::to_string(n_dofs) + "; estimated peak memory " +
             significant(memory_bytes / 1e9, 2) +
             " GB (summed over ranks), estimated time " +
             significant(seconds_per_state, 2) + " s per state";
    }



    CostEstimate
    estimate_cost(const CostInputs &in)
    {
      const Family &f     = in.dimension == 2 ? two_d :
                            in.n_discs == 1   ? one_disc :
                                                two_discs;
      const double  n     = static_cast<double>(in.n_dofs);
      const double  q2    = in.degree > 1 ? 2. : 1.;
      const double  ranks = std::max(1u, in.n_ranks);
      // Peak at the finest mesh, time summed over the adaptive cycles.
      double seconds = 0, finest = n;
      for (unsigned int k = 0; k <= in.adaptive_cycles; ++k)
        {
          finest = n * std::pow(f.growth, k);
          seconds += f.c * std::pow(finest, f.p);
        }
      const double rank_memory =
        one_rank_memory + (1. - one_rank_memory) * (ranks - 1.);
      CostEstimate e;
      e.family = f.name;
      e.n_dofs = in.n_dofs;
      // The heap's factor is measured in 3D only, and the trim acts only
      // on large ranks (heap_memory_dofs_per_rank).
      const double heap = in.dimension == 3 && in.heap_released &&
                              n / ranks >= heap_memory_dofs_per_rank ?
                            heap_memory :
                            1.;
      if (in.bulk_estimate)
        {
          const double bulk = n * bulk_dofs;
          finest            = std::max(finest, bulk);
          seconds           = in.dimension == 2 ? two_d_bulk_time * seconds :
                                                  seconds + f.c * std::pow(bulk, f.p);
        }
      e.memory_bytes = 1e6 * mb_per_rank * ranks +
                       1e3 * f.kb_per_dof * q2 * rank_memory * finest *
                         (in.plain_amg ? plain_amg_memory : 1.) * heap;
      e.seconds_per_state = seconds * (in.degree > 1 ? 1.5 : 1.) *
                            (in.error_estimate ? 1.5 : 1.) *
                            std::pow(2. / ranks, rank_exponent);
      return e;
    }



    namespace
    {
      /** MemAvailable of this node [bytes], or a negative number. */
      double
      node_memory_available()
      {
        std::ifstream in("/proc/meminfo");
        std::string   key;
        double        kb = -1;
        std::string   unit;
        while (in >> key >> kb >> unit)
          if (key == "MemAvailable:")
            return 1024. * kb;
        return -1;
      }
    } // namespace



    double
    available_memory_bytes(const MPI_Comm comm)
    {
      // One reading per node: the ranks of a node share its memory.
      MPI_Comm node;
      MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
      const bool leader = dealii::Utilities::MPI::this_mpi_process(node) == 0;
      MPI_Comm_free(&node);
      const double mine  = leader ? node_memory_available() : 0.;
      const double total = dealii::Utilities::MPI::sum(mine, comm);
      const bool   unknown =
        dealii::Utilities::MPI::min(leader ? mine : 0., comm) < 0;

      dealii::Utilities::System::MemoryStats stats;
      dealii::Utilities::System::get_memory_stats(stats);
      const double held =
        dealii::Utilities::MPI::sum(1024. * stats.VmRSS, comm);

      // The whole figure, not added to what the ranks hold: a test can
      // then put it between the estimates of two meshes.
      if (const char *limit = std::getenv("CYCLOID_AVAILABLE_MEMORY_MB"))
        return 1e6 * std::atof(limit);
      if (unknown)
        return std::numeric_limits<double>::infinity();
      return total + held;
    }



    void
    check_memory(const CostEstimate         &estimate,
                 const double                available,
                 const mesh::MeshParameters &mesh)
    {
      if (estimate.memory_bytes <= available)
        return;
      std::ostringstream advice;
      advice << "Mesh/Contact refinements (now " << mesh.contact_refinements
             << ")";
      if (!mesh.refine_loaded_side_only)
        advice << ", Mesh/Contact refinement side = loaded (refines only "
                  "the pins that carry the torque)";
      advice << ", a larger Mesh/Contact element size (now "
             << mesh.contact_size << " mm)";
      if (mesh.global_refinements > 0)
        advice << ", Mesh/Global refinements (now " << mesh.global_refinements
               << ")";
      if (mesh.adaptive_cycles > 0)
        advice << ", Mesh/Adaptive refinement cycles (now "
               << mesh.adaptive_cycles << ")";
      if (mesh.degree > 1)
        advice << ", Mesh/Polynomial degree = 1";
      if (mesh.error.mode == mesh::ErrorControl::Mode::on)
        advice << ", Mesh/Error estimate = false (its coarser levels need "
                  "Contact refinements >= "
               << mesh::ErrorControl::coarser_levels << ")";
      if (estimate.family != "2D")
        advice << ", Mesh/Axial layers per disc (now " << mesh.axial_layers
               << ")";
      AssertThrow(false,
                  dealii::ExcMessage(
                    "the FE scene needs an estimated " +
                    significant(estimate.memory_bytes / 1e9, 3) +
                    " GB of memory (summed over the ranks; " +
                    std::to_string(estimate.n_dofs) + " DoFs, cost model " +
                    estimate.family + ", doc/scene-guide.md), more than the " +
                    significant(available / 1e9, 3) +
                    " GB available (MemAvailable); stopped before the "
                    "matrices are allocated. Reduce " +
                    advice.str() + "."));
    }



    namespace
    {
      /**
       * The reduced model's condensation, fitted to 2-rank runs of the
       * seed stage on 2026-12-07 (benchmarks/reduced/cost_model.sh,
       * doc/reduced/cost-model.csv; load average about 1): memory
       * = 150 MB a rank + n (kb_per_dof + kb_per_dof_contact m), time of
       * one condensation = c n^p + d m n, with n the coarse DoFs and m the
       * contacts. 3D (MUMPS L D L^T on both ranks): 141 k to 417 k DoFs,
       * 42 to 168 contacts, one and two discs; memory rms 1.2 %, time rms
       * 5 % (-10 to +3 %). 2D (CHOLMOD on rank 0; 61 k to 163 k DoFs, 21
       * and 40 contacts): memory rms 1.6 %, time within -13 to +115 %
       * (the 2D condensations take 0.2 to 1.1 s, where the machine's
       * noise is as large; p = 1.5 fixed). The contact term is the load
       * vectors and solution columns of the block solve (17 bytes a DoF
       * and contact in 3D, about two doubles; 42 in 2D, gathered on one
       * rank).
       */
      struct ReducedFamily
      {
        double kb_per_dof;         ///< [kB] per coarse DoF.
        double kb_per_dof_contact; ///< [kB] per coarse DoF and contact.
        double c;                  ///< Factorisation time c n^p [s].
        double p;                  ///< Its exponent.
        double d;                  ///< Solve time per DoF and contact [s].
      };
      constexpr ReducedFamily reduced_3d{3.524,
                                         0.01656,
                                         5.739e-11,
                                         1.94,
                                         8.306e-8};
      constexpr ReducedFamily reduced_2d{1.904,
                                         0.04205,
                                         9.749e-9,
                                         1.5,
                                         9.827e-8};
      /** A state after the condensation: the complementarity solve and
       * its report (doc/reduced-model.md §4) [s]. */
      constexpr double reduced_state_seconds = 2e-3;
    } // namespace



    std::string
    ReducedCostEstimate::line() const
    {
      const ReducedCostInputs &in = inputs;
      return std::to_string(in.n_contacts) + " contacts on " +
             std::to_string(in.n_dofs) + " DoFs: estimated peak memory " +
             significant(memory_bytes / 1e9, 2) +
             " GB (summed over ranks), condensation about " +
             significant(seconds_per_condensation, 2) + " s" +
             (in.n_condensations > 1 ?
                " at each of " + std::to_string(in.n_condensations) +
                  " crank angles" :
                std::string()) +
             ", then about " + significant(reduced_state_seconds * 1e3, 1) +
             " ms per state";
    }



    ReducedCostEstimate
    estimate_reduced_cost(const ReducedCostInputs &in)
    {
      const ReducedFamily &f = in.dimension == 3 ? reduced_3d : reduced_2d;
      const double         n = static_cast<double>(in.n_dofs);
      const double         m = in.n_contacts;
      ReducedCostEstimate  e;
      e.inputs       = in;
      e.memory_bytes = 1e6 * mb_per_rank * std::max(1u, in.n_ranks) +
                       1e3 * n * (f.kb_per_dof + f.kb_per_dof_contact * m);
      e.seconds_per_condensation = f.c * std::pow(n, f.p) + f.d * m * n;
      return e;
    }



    void
    check_reduced_memory(const ReducedCostEstimate  &estimate,
                         const double                available,
                         const mesh::MeshParameters &mesh,
                         const unsigned int          slices)
    {
      if (estimate.memory_bytes <= available)
        return;
      std::ostringstream advice;
      advice << "larger Mesh/Flank element size (now " << mesh.flank_size
             << " mm), Pin element size (now " << mesh.pin_size
             << " mm) or Coarse element size (now " << mesh.coarse_size
             << " mm)";
      if (estimate.inputs.dimension == 3)
        advice << ", or fewer Reduced/Axial slices per disc (now " << slices
               << ")";
      AssertThrow(false,
                  dealii::ExcMessage(
                    "the reduced model's condensation needs an estimated " +
                    significant(estimate.memory_bytes / 1e9, 3) +
                    " GB of memory (summed over the ranks; " +
                    std::to_string(estimate.inputs.n_contacts) +
                    " contacts on " + std::to_string(estimate.inputs.n_dofs) +
                    " DoFs, doc/reduced-model.md §4), more than the " +
                    significant(available / 1e9, 3) +
                    " GB available (MemAvailable); stopped before "
                    "factorising. Reduce it with a " +
                    advice.str() + "."));
    }
  } // namespace stage
} // namespace cycloid
