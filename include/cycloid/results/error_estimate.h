#ifndef cycloid_results_error_estimate_h
#define cycloid_results_error_estimate_h

#include <cycloid/results/stage_state.h>

// The entries that drive the estimate: mesh::ErrorControl
// (mesh/mesh_parameters.h).

#include <string>
#include <vector>

namespace cycloid
{
  namespace results
  {
    /**
     * Set the error estimate of @p fine (its `error` and each pin's
     * `fn_error`) from the same load state solved on the next coarser
     * contact level, @p coarse, and on the one below it, @p coarser;
     * @p level is the fine state's contact level. Each quantity's estimate
     * is max(|Q_L - Q_L-1|, previous_change_weight |Q_L-1 - Q_L-2|):
     * relative to |Q_L| for K_secant and K_tangent, and for every pin
     * force relative to the state's largest pin force
     * (mesh::ErrorControl says why).
     */
    void
    set_error_estimate(const StageState  &coarser,
                       const StageState  &coarse,
                       StageState        &fine,
                       const unsigned int level);

    /**
     * Set the error estimate of @p fine (its `error` and each pin's
     * `fn_error`) from the same load state on a model one level coarser,
     * @p coarse: each quantity's estimate is the change |Q_L - Q_L-1|,
     * relative to |Q_L| for K_secant and K_tangent and to the state's
     * largest pin force for the pins. The change is the error of the
     * coarser model, so it bounds the finer one's as long as the error at
     * least halves per level. @p method says on the console what the two
     * levels are. (The reduced model; doc/reduced-model.md.)
     */
    void
    set_error_estimate(const StageState  &coarse,
                       StageState        &fine,
                       const std::string &method);

    /** Add @p part, relative, to each figure of the estimate of @p state
     * (which must have one): to K_secant's and K_tangent's, and to every
     * pin's as @p part times the largest pin force; recorded as
     * `error.model`. */
    void
    add_model_error(const double part, StageState &state);

    /**
     * @brief The error of the bulk mesh (every cell that the contact
     * levels' estimate leaves as it is: all but the two finest levels) in
     * one load state: bulk_change_factor times the change that one
     * refinement of those cells makes.
     *
     * Measured on the state's first mesh and added to the estimate of
     * each contact level that Target accuracy solves after it (refining
     * at the contacts leaves most of the bulk as it is); after such
     * cycles measured again on the last mesh, whose graded halo around
     * the contacts is new.
     */
    struct BulkError
    {
      /** Of K_secant, relative [-]. */
      double k_secant = 0;
      /** Of K_tangent, relative [-]. */
      double k_tangent = 0;
      /** Of each pin force, in the order of StageState::pins [N]. */
      std::vector<double> fn;
    };

    /** The bulk error of @p state from @p bulk, the same load state solved
     * with every bulk cell refined once. */
    BulkError
    bulk_error(const StageState &bulk, const StageState &state);

    /** Add @p b to the estimate of @p state (which must have one): to
     * K_secant's, K_tangent's and each pin's, and record the largest of
     * the three parts, relative, as `error.bulk`. */
    void
    add_bulk_error(const BulkError &b, StageState &state);

    /** The bulk mesh's error is taken as this times the change that one
     * refinement of it makes: the error of the refined bulk is at most the
     * change if it at least halves per refinement (first order; K
     * converges faster, as h^2 in the energy), so the error of the mesh
     * asked for is at most twice the change. Measured in 2D: the change
     * of Q2 on the same mesh is 1.3-1.5 times the change of one
     * refinement (doc/error-estimate.md, "The bulk mesh"). */
    constexpr double bulk_change_factor = 2.0;

    /** The weight of the change between the two coarser levels: the error
     * is taken to fall at least by this factor per level. */
    constexpr double previous_change_weight = 0.5;

    /**
     * The constant C of the resolution indicator: a state whose most
     * loaded pin has n contact nodes across its Hertz width
     * (PinState::hertz_nodes) has pin forces off by at most about C / n^2
     * of the largest. Second order in the node spacing, as measured:
     * fitted as the largest error n^2 over 20 2D runs (four scenes at
     * Contact refinements 0 to 4, 0.04 to 0.24), and checked on 14 runs
     * it was not fitted to: a 2D reducer of other proportions (zp 30, at
     * most 0.12) and nine 3D runs (at most 0.19) (doc/error-estimate.md,
     * "The resolution indicator").
     */
    constexpr double resolution_constant = 0.25;

    /**
     * The resolution indicator of @p state: resolution_constant / n^2,
     * n the hertz_nodes of its most loaded pin, as a fraction of the
     * largest pin force. A pin's Hertz half-width grows as the square
     * root of its force, so the figure relative to the largest force is
     * largest at the most loaded pin. NaN where the most loaded pin has
     * no hertz_nodes (models without a contact mesh, states without
     * force). An a-priori figure from one solve, for the states that
     * carry no estimate from nested levels (3D by default, transient
     * steps, Error estimate = false).
     */
    double
    resolution_error(const StageState &state);

    /**
     * The pins of @p state whose force estimate exceeds @p threshold of
     * its largest pin force, as "disc d pin j (x %)" items.
     */
    std::vector<std::string>
    unresolved_pins(const StageState &state, const double threshold);

    /** The cure of an estimate whose bulk mesh's part is too large
     * (Mesh/Bulk error estimate): contact refinements do not reduce it. */
    inline constexpr const char *bulk_advice =
      "Mesh/Global refinements, or a smaller Size grading and Flank, Pin "
      "and Coarse element sizes, reduce it.";
  } // namespace results
} // namespace cycloid

#endif
