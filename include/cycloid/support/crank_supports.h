#ifndef cycloid_support_crank_supports_h
#define cycloid_support_crank_supports_h

#include <deal.II/base/tensor.h>

#include <deal.II/lac/full_matrix.h>

#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/results/stage_state.h>
#include <cycloid/support/crank_bearing_parameters.h>
#include <cycloid/support/needle_bearing.h>

#include <array>
#include <vector>

namespace cycloid
{
  namespace support
  {
    /**
     * @brief The rigid motion of a disc against its kinematic position: a
     * translation of its centre and a rotation about it. On rigid
     * supports the disc only turns, by the output rotation beta.
     */
    struct DiscMotion
    {
      /** Translation of the disc centre [mm]. */
      dealii::Tensor<1, 2> translation;
      /** Rotation about the disc centre [rad]. */
      double rotation = 0;
    };

    /**
     * @brief The crank bearings of every disc of the stage at one crank
     * angle: the needle bearing in crank hole j of disc d, centred at
     * a_j from the disc centre, on an eccentric that the output rotation
     * beta carries by beta e_z x a_j (the motion the rigid support gives
     * the crank hole, so that infinitely stiff bearings give the rigid
     * support's results). The bearing's deflection is then
     * d_j = t + (theta - beta) e_z x a_j for the disc motion (t, theta).
     * The cage of disc d's bearings turns with its crank: roller 0 at the
     * disc's crank angle.
     */
    class CrankSupports
    {
    public:
      /** The bearings of @p n_discs discs of @p geo at crank angle @p psi
       * [rad], sized by @p prm. */
      CrankSupports(const CrankBearingParameters    &prm,
                    const geometry::CycloidGeometry &geo,
                    const unsigned int               n_discs,
                    const double                     psi);

      /** The resultant of disc @p d's bearings on it, (Fx, Fy) [N] and the
       * moment about the disc centre [N mm], and its derivatives with
       * respect to (t_x, t_y, theta, beta) [N/mm, N/rad, N mm/mm,
       * N mm/rad], each roller at least @p floor [N/mm] stiff in the
       * derivatives (NeedleBearing::response()). */
      struct Resultant
      {
        /** Fx, Fy [N], moment [N mm]. */
        std::array<double, 3> value{{0., 0., 0.}};
        /** 3 x 4 derivatives. */
        dealii::FullMatrix<double> derivative{3, 4};
      };

      /** See Resultant. */
      Resultant
      resultant(const unsigned int d,
                const DiscMotion  &motion,
                const double       beta,
                const double       floor) const;

      /** The state of each bearing of disc @p d (crank order). */
      std::vector<results::BearingState>
      states(const unsigned int d,
             const DiscMotion  &motion,
             const double       beta) const;

      /** The work sum_j -F_j . d_j of disc @p d's bearings [N mm]: their
       * part of the output work T beta (doc/bearings.md). */
      double
      work(const unsigned int d,
           const DiscMotion  &motion,
           const double       beta) const;

      /** The elastic energy of disc @p d's bearings [N mm]. */
      double
      energy(const unsigned int d,
             const DiscMotion  &motion,
             const double       beta) const;

      /** A roller stiffness [N/mm] for Newton iterations at torque
       * @p torque [N mm]: a hundredth of a roller's secant stiffness, its
       * share of the torque's crank forces over the clearance plus its
       * approach under it. Small against every loaded roller, it lets a
       * bearing with none loaded (or a disc with no pin loaded) take steps
       * of the clearance's size; proportional to the torque, it never
       * outweighs the forces of a small one. */
      double
      stiffness_floor(const double torque) const;

      /** Radius of the circle through the crank holes' centres [mm]. */
      double
      crank_circle_radius() const
      {
        return arms[0][0].norm();
      }

      /** Discs [-]. */
      unsigned int
      n_discs() const
      {
        return arms.size();
      }

      /** The bearing of each crank hole. */
      const NeedleBearing &
      bearing() const
      {
        return law;
      }

    private:
      /** Deflection of disc @p d's bearing @p j [mm]. */
      dealii::Tensor<1, 2>
      deflection(const unsigned int d,
                 const unsigned int j,
                 const DiscMotion  &motion,
                 const double       beta) const;

      NeedleBearing law;
      /** a_j of each disc, housing frame [mm]. */
      std::vector<std::vector<dealii::Tensor<1, 2>>> arms;
      /** Cage angle of each disc's bearings [rad]. */
      std::vector<double> cage;
    };
  } // namespace support
} // namespace cycloid

#endif
