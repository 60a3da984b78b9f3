#ifndef cycloid_geometry_deviations_h
#define cycloid_geometry_deviations_h

#include <deal.II/base/parameter_handler.h>

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/geometry/deviation_data.h>
#include <cycloid/geometry/geometry_parameters.h>
#include <cycloid/geometry/stage_layout.h>

#include <string>
#include <vector>

namespace cycloid
{
  namespace geometry
  {
    /**
     * @brief Subsection `Deviations`: the files of the stage's
     * manufacturing deviations (empty: a perfectly made stage).
     */
    struct DeviationsParameters
    {
      /** `Pin deviations file`, as written (relative to the parameter
       * file's directory). */
      std::string pin_file;
      /** `Disc deviations file`, as written. */
      std::string disc_file;

      /** Declare subsection `Deviations`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Read subsection `Deviations`. */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /** Whether a file is given. */
      bool
      any() const
      {
        return !pin_file.empty() || !disc_file.empty();
      }

      /** @p file taken from @p directory if it is relative. */
      static std::string
      resolve(const std::string &file, const std::string &directory);

      /**
       * Read the files (relative paths from @p directory) into
       * @p geometry's `pin_deviations` and `disc_deviations`, which every
       * CycloidGeometry made from it then honours.
       */
      void
      read_into(GeometryParameters &geometry,
                const std::string  &directory) const;
    };

    /**
     * Throw if a deviated pin overlaps a disc at rest: at any crank angle
     * of @p angles [rad], for discs 0 to @p n_discs - 1 of @p geo. The
     * message names the file and line that moved the pin (or the disc),
     * the pin, the disc, the overlap [um] and the crank angle.
     */
    void
    check_rest_overlap(const CycloidGeometry      &geo,
                       const std::vector<double>  &angles,
                       const unsigned int          n_discs,
                       const DeviationsParameters &files,
                       const std::string          &directory);

    /**
     * Read a pin deviations file: CSV with the header
     * `pin,radial_um,tangential_um,radius_um` (columns in any order; blank
     * lines and lines starting with # skipped). Throws, naming the file,
     * the line and the column, on a missing file or column, a value that is
     * not a number, a pin index not below @p n_pins, or a pin listed twice.
     */
    std::vector<PinDeviation>
    read_pin_deviations(const std::string &file, const unsigned int n_pins);

    /**
     * Read a disc deviations file: CSV with the header
     * `disc,eccentricity_um,angle_arcmin,pin_circle_um,pin_radius_um`, the
     * same rules as read_pin_deviations() with disc indices below
     * StageLayout::n_discs.
     */
    std::vector<DiscDeviation>
    read_disc_deviations(const std::string &file);

    /**
     * The stage of @p prm as made: StageLayout::nominal() with each listed
     * pin moved and resized and each listed disc placed and ground as
     * @p pins and @p discs say. Pins and discs not listed stay nominal; an
     * empty list of both gives the nominal layout exactly.
     */
    StageLayout
    deviated_layout(const GeometryParameters         &prm,
                    const std::vector<PinDeviation>  &pins,
                    const std::vector<DiscDeviation> &discs);
  } // namespace geometry
} // namespace cycloid

#endif
