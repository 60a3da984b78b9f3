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

    /** The weight of the change between the two coarser levels: the error
     * is taken to fall at least by this factor per level. */
    constexpr double previous_change_weight = 0.5;

    /**
     * The pins of @p state whose force estimate exceeds @p threshold of
     * its largest pin force, as "disc d pin j (x %)" items.
     */
    std::vector<std::string>
    unresolved_pins(const StageState &state, const double threshold);
  } // namespace results
} // namespace cycloid

#endif
