#ifndef cycloid_reduced_local_contact_h
#define cycloid_reduced_local_contact_h

#include <cycloid/results/stage_state.h>

namespace cycloid
{
  namespace reduced
  {
    /**
     * @brief The near field of one line contact (pin against flank) that
     * the coarse FE model cannot resolve: the approach that turns the
     * model's response to a semi-elliptic pressure of fixed half-width w
     * into the response to the Hertz pressure of the actual force.
     *
     * The coarse model measures, per unit force, the pressure-weighted
     * mean displacement of its width-w load. For a half-space in plane
     * strain (Johnson, Contact Mechanics §2.8 and §5.6) a semi-elliptic
     * pressure of half-width a and line load q gives the centre
     * displacement (relative to a deep point at depth D)
     * @f[ u_a(0) = \frac{2q}{\pi}\Big[(1-\nu^2)/E\,\ln\frac{2D}{a}
     *     - \frac{\nu(1+\nu)}{2E}\Big] , @f]
     * and its pressure-weighted mean lies (1-nu^2) q / (2 pi E) below the
     * centre value (the surface is a parabola inside the contact). So the
     * centre approach of the true contact is the coarse model's weighted
     * mean plus
     * @f[ h(q) = \frac{2 q}{\pi} \sum_{\text{bodies}}\frac{1-\nu^2}{E}
     *      \Big(\ln\frac{w}{a(q)} + \frac14\Big),
     *    \qquad a(q) = \sqrt{\frac{4 q R^*}{\pi E^*}} , @f]
     * exactly for a half-space and up to terms of order (w/R)^2 for the
     * curved bodies: the depth D, the far field and the bodies' shapes
     * cancel, so h counts no compliance that the FE model already holds.
     */
    class LocalContact
    {
    public:
      /**
       * @p load_half_width w [mm]; @p compliance the sum over both bodies
       * of (1-nu^2)/E [1/MPa] (a rigid pin adds 0); @p inverse_radius
       * 1/R* = 1/r - 1/rho of the pair [1/mm].
       */
      LocalContact(const double load_half_width,
                   const double compliance,
                   const double inverse_radius);

      /** Hertz half-width a at line load @p q [N/mm] (mm). */
      double
      half_width(const double q) const;

      /** h(q) [mm] for a line load @p q [N/mm] (0 at q <= 0). */
      double
      approach(const double q) const;

      /** dh/dq [mm^2/N] at @p q > 0. */
      double
      slope(const double q) const;

    private:
      double w;
      double compliance;
      double inverse_radius;
    };

    /**
     * Approach [mm] between the surface and the point at depth @p z [mm] on
     * the axis of a plane-strain half-space of modulus @p E [MPa] and
     * Poisson's ratio @p nu under a semi-elliptic pressure of half-width
     * @p a [mm] and line load @p q [N/mm], from the closed-form stresses
     * on the axis (Johnson §4.2, the Hertz field) integrated exactly:
     * (p0 a / E)[(1-nu^2) asinh(z/a) - nu(1+nu)(z sqrt(a^2+z^2) - z^2)/a^2],
     * p0 a = 2 q / pi.
     */
    double
    halfspace_axis_approach(const double q,
                            const double a,
                            const double z,
                            const double E,
                            const double nu);
    /**
     * The constant c of the near-field law's own error, c (a/R)^2 of
     * K_secant, K_tangent and every pin force (a the largest Hertz
     * half-width of a state, R the pin radius). The law holds for a
     * half-space; on the curved pin and flank it misses terms of order
     * (a/R)^2 that no coarse-model refinement removes. Measured against
     * the full FE model: the reduced model is stiffer in K_secant by 2.4 to
     * 4.4 (a/R)^2 on the 16 states of the seed stage's 2D validation and
     * 3.0 to 4.9 on three other reducers (doc/reduced-model.md, "Error
     * estimate"); c is the seed's envelope rounded up.
     */
    constexpr double near_field_error_factor = 5.0;

    /** The near-field law's error in @p state, near_field_error_factor
     * (a/R)^2, with @p pin_radius R [mm] (relative) [-]. */
    double
    near_field_error(const results::StageState &state, const double pin_radius);
  } // namespace reduced
} // namespace cycloid

#endif
