#ifndef cycloid_analytic_pair_stiffness_h
#define cycloid_analytic_pair_stiffness_h

#include <cycloid/analytic/analytic_parameters.h>
#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/parameters/material.h>
#include <cycloid/parameters/scene.h>
#include <cycloid/results/stage_state.h>

#include <memory>
#include <string>

namespace cycloid
{
  namespace analytic
  {
    /**
     * @brief Local geometry of one pin-disc pair that a pair-stiffness
     * model may use.
     */
    struct PairGeometry
    {
      /** Generating phase of the contact point, 0 at the root [rad]. */
      double phase;
      /** Signed curvature radius of the disc profile at the contact
       * (positive concave) [mm]. */
      double profile_curvature_radius;
      /** Pin radius [mm]. */
      double pin_radius;
      /** Distance from the contact point to the disc's load-introduction
       * surface (crank holes or bore) [mm]: the depth over which the
       * disc's contact compliance builds up. */
      double disc_depth;
    };

    /**
     * @brief Hertz half-width of a pin against the disc profile [mm]:
     * a = sqrt(4 F R* / (pi b E*)), 1/R* = 1/r - 1/rho (rho the signed
     * profile curvature radius, positive concave), 1/E* = sum (1-nu^2)/E;
     * @p pin_plane_strain_modulus <= 0 for a rigid pin.
     */
    double
    hertz_half_width(const double force,
                     const double tooth_width,
                     const double pin_radius,
                     const double profile_curvature_radius,
                     const double disc_plane_strain_modulus,
                     const double pin_plane_strain_modulus);

    /**
     * @brief Hertz half-width [mm] of a pin of the stage against the disc
     * profile of signed curvature radius @p profile_curvature_radius [mm]
     * at force @p force [N]: hertz_half_width() with the stage's tooth
     * width and moduli and the pin's radius @p pin_radius [mm] (rigid
     * pins add no compliance).
     */
    double
    stage_hertz_half_width(const double force,
                           const double profile_curvature_radius,
                           const double pin_radius,
                           const geometry::GeometryParameters   &geometry,
                           const parameters::MaterialParameters &material,
                           const parameters::SceneParameters    &scene);

    /**
     * @brief The largest subsurface shear stress of Hertz's line contact
     * in plane strain, as fractions of the peak pressure p0 and the
     * half-width a: the maximum over the depth z of the Tresca stress
     * (largest minus smallest principal stress) / 2 on the symmetry axis,
     * where it is largest, with sigma_x and sigma_z from the closed-form
     * Hertz field and sigma_y = nu (sigma_x + sigma_z). For nu = 0.3 this
     * is the textbook 0.300 p0 at z = 0.786 a.
     */
    struct SubsurfaceShear
    {
      /** tau_max / p0 [-]. */
      double stress_ratio = 0;
      /** Depth of tau_max over a [-]. */
      double depth_ratio = 0;
    };

    /** The subsurface shear of Hertz's line contact for Poisson's ratio
     * @p poisson of the body it acts in. */
    SubsurfaceShear
    hertz_subsurface_shear(const double poisson);

    /**
     * @brief Fill the Hertz stress figures of @p pin from its force fn and
     * its Hertz half-width: the peak pressure p0 = 2 F / (pi a b) over the
     * tooth width @p tooth_width [mm], and the largest subsurface shear
     * stress and its depth in the disc (Poisson's ratio @p poisson). The
     * model's own peak pressure (max_pressure) is left to the model.
     */
    void
    set_hertz_stresses(results::PinState &pin,
                       const double       tooth_width,
                       const double       poisson);

    /**
     * @brief Interface of a pin-disc pair-stiffness model: the normal force
     * carried by one pair as a function of its approach (the overlap of the
     * undeformed bodies), and its derivative. Implementations are chosen
     * by name (`Analytic/Pair stiffness model`).
     */
    class PairStiffnessModel
    {
    public:
      virtual ~PairStiffnessModel() = default;

      /** Normal force [N] for an approach @p approach >= 0 [mm]. */
      virtual double
      force(const double approach, const PairGeometry &pair) const = 0;

      /** dF/d(approach) [N/mm] at @p approach (for approach = 0 the
       * right-hand limit where it is finite). */
      virtual double
      stiffness(const double approach, const PairGeometry &pair) const = 0;

      /** Approach [mm] that carries force @p force [N]. */
      virtual double
      approach(const double force, const PairGeometry &pair) const = 0;

      /** Name as used in the parameter file. */
      virtual std::string
      name() const = 0;

      /** Names of all models, for the parameter pattern. */
      static std::string
      model_names();

      /** Create the model named in @p parameters. */
      static std::unique_ptr<PairStiffnessModel>
      create(const AnalyticParameters             &parameters,
             const parameters::MaterialParameters &material,
             const parameters::SceneParameters    &scene,
             const double                          tooth_width);
    };



    /**
     * @brief The seed article's single-pair stiffness, a linear spring.
     *
     * The seed writes the pin and tooth deformations as
     * t_z = 4 F a (1-mu^2)/(pi b E r_z) and t_b = 4 F a (1-mu^2)/(pi b E a_b)
     * with a the combined curvature radius and a_b the tooth curvature
     * radius; in series,
     * @f[
     *  k = \frac{\pi b}{4}\frac{E'}{1}\frac{\rho - r}{\rho + r}
     *    = \frac{\pi b E R_z S^{3/2}}{4(1-\mu^2)(R_z S^{3/2} + 2 r_z T)}
     * @f]
     * on the concave flank (rho the profile curvature radius,
     * rho = r_p S^{3/2}/T + r_{rp} with T = K1 (1+zp) cos phi - (1+zp K1^2),
     * which resolves the seed's undefined T). On the convex flank the same
     * construction gives k = pi b E'/4. Each body uses its own
     * E' = E/(1-nu^2); a rigid pin drops its term. The seed's coefficient
     * lambda multiplies k, so K = dT/dbeta = lambda sum k l_i^2 as in the
     * seed. The force is lambda k * approach.
     */
    class SeedPairStiffness : public PairStiffnessModel
    {
    public:
      /** @p pin_modulus <= 0 means a rigid pin. */
      SeedPairStiffness(const double tooth_width,
                        const double disc_plane_strain_modulus,
                        const double pin_plane_strain_modulus,
                        const double lambda);

      double
      force(const double approach, const PairGeometry &pair) const override;
      double
      stiffness(const double approach, const PairGeometry &pair) const override;
      double
      approach(const double force, const PairGeometry &pair) const override;
      std::string
      name() const override
      {
        return "seed";
      }

    private:
      const double b;
      const double e_disc;
      const double e_pin;
      const double lambda;
    };



    /**
     * @brief Load-dependent line contact of two cylinders (Hertz half-width
     * with the logarithmic approach of the bodies' reference points).
     *
     * Half-width (Hertz): a = sqrt(4 F R* / (pi b E*)), 1/R* = 1/r - 1/rho
     * (rho the signed profile curvature radius, positive concave),
     * 1/E* = (1-nu_p^2)/E_p + (1-nu_d^2)/E_d.
     * Approach (Puttock & Thwaite 1969; Johnson, Contact Mechanics 1985,
     * Sec. 5.6 pp. 99-104; same form as ESDU 78035):
     * @f[
     *   \delta = \frac{2F}{\pi b}\left[\frac{1-\nu_p^2}{E_p}
     *            \left(\ln\frac{4 r}{a} - \frac12\right)
     *          + \frac{1-\nu_d^2}{E_d}\left(\ln\frac{4 L}{a} -
     *            \frac12\right)\right]
     * @f]
     * for the pin (r: pin radius, approach of its axis) and the disc, where
     * L is the disc depth (distance from the contact to the surfaces that
     * carry the load). The pair stiffness dF/d delta grows with the load
     * like 1/ln(1/F). A rigid pin drops its term.
     */
    class LineContactPairStiffness : public PairStiffnessModel
    {
    public:
      /** @p pin_modulus <= 0 means a rigid pin. */
      LineContactPairStiffness(const double tooth_width,
                               const double disc_plane_strain_modulus,
                               const double pin_plane_strain_modulus);

      double
      force(const double approach, const PairGeometry &pair) const override;
      double
      stiffness(const double approach, const PairGeometry &pair) const override;
      double
      approach(const double force, const PairGeometry &pair) const override;
      std::string
      name() const override
      {
        return "line-contact";
      }

      /** Hertz contact half-width [mm] at force @p force [N]. */
      double
      half_width(const double force, const PairGeometry &pair) const;

      /** d approach / d force [mm/N] at force @p force. */
      double
      compliance(const double force, const PairGeometry &pair) const;

    private:
      const double b;
      const double c_disc;
      const double c_pin;
    };
  } // namespace analytic
} // namespace cycloid

#endif
