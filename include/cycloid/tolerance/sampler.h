#ifndef cycloid_tolerance_sampler_h
#define cycloid_tolerance_sampler_h

#include <cycloid/geometry/deviation_data.h>
#include <cycloid/tolerance/tolerance_parameters.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace cycloid
{
  namespace tolerance
  {
    /** The tolerance bands of a study, in the order of `Tolerance study`. */
    enum Band : unsigned int
    {
      pin_position_band,
      pin_radius_band,
      eccentricity_band,
      disc_angle_band,
      profile_band,
      n_bands
    };

    /** The entry name of band @p b in `Tolerance study`. */
    std::string
    band_name(const unsigned int b);

    /** The width of band @p b in @p p (its entry's value). */
    double
    band_width(const ToleranceParameters &p, const unsigned int b);

    /** Which bands a draw uses. */
    using BandMask = std::array<bool, n_bands>;

    /**
     * @brief The manufacturing deviations of a whole stage: every pin
     * (index j at j) and both discs.
     */
    struct StageDeviations
    {
      std::vector<geometry::PinDeviation>  pins;  ///< zp pins.
      std::vector<geometry::DiscDeviation> discs; ///< Two discs.

      /** Zero deviations of a stage of @p n_pins pins. */
      static StageDeviations
      zero(const unsigned int n_pins);

      /** @p rows (a deviations file's) on top of zero(@p n_pins). */
      static StageDeviations
      from_rows(const unsigned int                          n_pins,
                const std::vector<geometry::PinDeviation>  &pins,
                const std::vector<geometry::DiscDeviation> &discs);

      /** Write the pins as a `Pin deviations file` to @p pin_file and the
       * discs as a `Disc deviations file` to @p disc_file. */
      void
      write(const std::string &pin_file, const std::string &disc_file) const;
    };

    /**
     * @brief Draws the samples of a tolerance study: sample s is the mean
     * (the deviation files') plus a random deviation from each band,
     * drawn from a generator seeded with (Random seed, s) alone, so that a
     * sample is the same whichever rank draws it and whatever was drawn
     * before.
     *
     * Every sample draws every number of every band in a fixed order
     * (per pin: centre, radius; per disc: eccentricity, angle, Delta rp,
     * Delta rrp), also those of bands it leaves out: the study of one band
     * alone (the sensitivity) sees the same draws of that band as the full
     * study. The generator (SplitMix64) and the normal deviate (Box-Muller)
     * are written out here, so the samples do not depend on the C++
     * library's distributions either.
     */
    class Sampler
    {
    public:
      /** Draw from the bands of @p parameters around @p mean. */
      Sampler(const ToleranceParameters &parameters,
              const StageDeviations     &mean);

      /** The deviations of sample @p s with the bands in @p on (sample 0:
       * the mean, without random deviations). */
      StageDeviations
      draw(const unsigned int s, const BandMask &on) const;

      /** Every band on. */
      static BandMask
      all_bands();

    private:
      const ToleranceParameters parameters;
      const StageDeviations     mean;
    };
  } // namespace tolerance
} // namespace cycloid

#endif
