#ifndef cycloid_postprocess_sweep_noise_h
#define cycloid_postprocess_sweep_noise_h

#include <vector>

namespace cycloid
{
  namespace postprocess
  {
    /**
     * @brief How much of a phase sweep's fluctuation the discretisation
     * could have made: its noise floor, from the sweep's own states.
     *
     * Each phase of an FE sweep has its own mesh, so the stiffness over the
     * crank angles carries mesh-to-mesh noise on top of the physical
     * variation. Two estimates, both relative to the mean:
     * - the closure |x_last / x_first - 1|: the first and last phase are
     *   one mesh period apart, the same state (up to the crank holes,
     *   which repeat only every zc/n_holes teeth) on two meshes. It says
     *   nothing when the two meshes are the same mesh turned by a pin
     *   pitch (no crank holes, load through the bore);
     * - the roughness 3 sigma, sigma = rms(second differences) / sqrt(6):
     *   white noise of deviation sigma has second differences of deviation
     *   sqrt(6) sigma, while a physical variation that the phases resolve
     *   has second differences far below its range. 3 sigma is about the
     *   range that pure noise shows over a sweep of 5 to 20 phases.
     * The floor is the larger of the two (the roughness needs at least
     * 5 phases; with fewer and a closure below 1e-9, which a periodic mesh
     * gives, the floor is unknown: NaN).
     *
     * Given the same sweep one contact refinement coarser, a third
     * estimate replaces the roughness: the change of the curve's shape
     * between the two, max_k |d_k - mean(d)| / mean with d = x - x_coarse
     * (a uniform shift moves no fluctuation). It measures the mesh's part
     * directly, where the roughness cannot tell a physical variation that
     * the phases sample coarsely (a pin engaging between two phases) from
     * noise. The floor is then max(closure, change).
     *
     * The fluctuation (max - min) / mean is resolved when it exceeds
     * twice the floor.
     */
    struct SweepNoise
    {
      /** (max - min) / mean [-]. */
      double fluctuation = 0;
      /** |last / first - 1| [-]. */
      double closure = 0;
      /** 3 rms(second differences) / sqrt(6) / mean [-] (NaN with fewer
       * than 5 phases). */
      double roughness = 0;
      /** The change of the curve's shape since the coarser sweep
       * (NaN without one) [-]. */
      double refinement = 0;
      /** The noise floor: max(closure, refinement) after a coarser sweep,
       * else max(closure, roughness) (NaN if unknown) [-]. */
      double floor = 0;
      /** Whether the fluctuation exceeds twice the floor (false if the
       * floor is unknown). */
      bool resolved = false;
    };

    /** The noise figures of @p values, one per phase in crank-angle order
     * over one closed mesh period (at least 2); @p coarser: the same
     * sweep's values one contact refinement coarser (empty: none). */
    SweepNoise
    sweep_noise(const std::vector<double> &values,
                const std::vector<double> &coarser = {});
  } // namespace postprocess
} // namespace cycloid

#endif
