#ifndef cycloid_contact_hertz_case_h
#define cycloid_contact_hertz_case_h

#include <deal.II/base/mpi.h>

#include <cycloid/contact/contact_problem.h>

namespace cycloid
{
  namespace contact
  {
    /**
     * @brief The Hertz verification case of the contact solver: an elastic
     * cylinder (radius r1, body 1) pressed with a force F per unit length
     * onto an elastic convex cylinder (radius r2, body 2) or into a
     * concave seat (a ring whose bore has radius r2 > r1), plane strain.
     *
     * Body 1 is the exact master cylinder; body 2 carries the slave nodes.
     * Body 1's core (r < 0.2 r1) is pushed by beta towards body 2 under
     * load control (target F); body 2's core (convex) or the ring's outer
     * surface (seat) is held. The mesh is the same as a user's would be:
     * exact circles by manifolds, global refinements, then local
     * refinements around the contact (radius 3 a), with hanging nodes.
     *
     * Defaults: the two-cylinder case of doc/design-basis.md §2.3 (r1 = 10, r2
     * = 13 mm, E1 = 30000, nu1 = 0.25, E2 = 29120, nu2 = 0.3 MPa, F = 3200
     * N/mm: a = 1.20 mm).
     */
    struct HertzCase
    {
      /** Convex counter-body or concave seat. */
      bool   concave = false;
      double r1      = 10;    ///< Radius of the cylinder [mm].
      double r2      = 13;    ///< Radius of the counter-body or seat [mm].
      double e1      = 30000; ///< Young's modulus of the cylinder [MPa].
      double nu1     = 0.25;  ///< Poisson's ratio of the cylinder [-].
      double e2      = 29120; ///< Young's modulus of the counter-body [MPa].
      double nu2     = 0.3;   ///< Poisson's ratio of the counter-body [-].
      /** Force per unit length [N/mm]. */
      double force = 3200;
      /** Contact discretisation. */
      Formulation formulation = Formulation::mortar;
      /** Polynomial degree. */
      unsigned int degree = 1;
      /** Global refinements of the two coarse bodies. */
      unsigned int global_refinements = 3;
      /** Refinements of the cells within 3 a of the contact point. */
      unsigned int contact_refinements = 4;

      /** Hertz's effective radius 1/R* = 1/r1 +- 1/r2 [mm]. */
      double
      effective_radius() const;
      /** Plane-strain contact modulus, 1/E* = sum (1 - nu^2)/E [MPa]. */
      double
      contact_modulus() const;
      /** Closed-form half-width a = sqrt(4 F R* / (pi E*)) [mm]. */
      double
      half_width() const;
      /** Closed-form peak pressure p0 = 2 F / (pi a) [MPa]. */
      double
      peak_pressure() const;
    };

    /** @brief What the FE model of a HertzCase gives. */
    struct HertzResult
    {
      /** Half-width from the second moment of the nodal contact forces,
       * a^2 = 4 sum(f_i s_i^2) / sum(f_i) (exact for Hertz's ellipse) [mm]. */
      double half_width = 0;
      /** Largest nodal pressure (nodal force / nodal weight) [MPa]. */
      double peak_pressure = 0;
      /** Sum of the slave nodes' normal reactions [N/mm]. */
      double contact_force = 0;
      /** Sum of the slave reactions along the load direction, which
       * equilibrium makes equal to the applied force [N/mm]. */
      double transmitted_force = 0;
      /** Number of active nodes. */
      unsigned int n_active = 0;
      /** Smallest slave-node spacing in the contact zone [mm]. */
      double        h_contact  = 0;
      unsigned long n_dofs     = 0; ///< Degrees of freedom.
      unsigned int  iterations = 0; ///< Active-set iterations.
      double        wall_s     = 0; ///< Wall time of the solve [s].
    };

    /** Build, solve and post-process @p c on @p comm (collective). */
    HertzResult
    run_hertz_case(const HertzCase &c, const MPI_Comm comm);
  } // namespace contact
} // namespace cycloid

#endif
