// Verification of the contact solver against Hertz's closed form (plane
// strain line contact), on 1 and (ctest contact.mpirun=2) 2 MPI ranks.
#include <deal.II/base/mpi.h>

#include <cycloid/contact/hertz_case.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace cycloid::contact;

namespace
{
  /** Relative errors of half-width and peak pressure. */
  struct Errors
  {
    double a, p0;
    double
    worst() const
    {
      return std::max(std::abs(a), std::abs(p0));
    }
  };

  Errors
  run(const HertzCase &c, HertzResult *result = nullptr)
  {
    const HertzResult r = run_hertz_case(c, MPI_COMM_WORLD);
    if (result)
      *result = r;
    const Errors e{r.half_width / c.half_width() - 1,
                   r.peak_pressure / c.peak_pressure() - 1};
    if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::cout << "  Q" << c.degree << " level " << c.contact_refinements
                << ": " << r.n_dofs << " DoFs, " << r.n_active
                << " active nodes, " << r.iterations
                << " active-set iterations, a " << r.half_width << " (Hertz "
                << c.half_width() << ", error " << e.a << "), p0 "
                << r.peak_pressure << " (Hertz " << c.peak_pressure()
                << ", error " << e.p0 << ")" << std::endl;
    // Equilibrium: the force through the contact is the applied force.
    EXPECT_NEAR(r.transmitted_force, c.force, 1e-8 * c.force);
    return e;
  }
} // namespace

// Two convex cylinders (r1 = 10, r2 = 13 mm), F = 200 N/mm: a = 0.300 mm,
// so a/R* = 0.05 and Hertz's half-space theory holds to well under 1 %.
// Started from the single touching node, the active set has to find the
// Hertz zone; refining the contact zone reduces the error.
TEST(Hertz, ConvexCylindersConvergeToClosedForm)
{
  HertzCase c;
  c.force = 200;
  std::vector<Errors> errors;
  for (const unsigned int level : {4u, 5u, 6u})
    {
      c.contact_refinements = level;
      HertzResult r;
      errors.push_back(run(c, &r));
      EXPECT_GT(r.iterations, 1u);
      // The active zone spans 2a with nodes every h.
      EXPECT_NEAR(r.n_active, 2 * c.half_width() / r.h_contact + 1, 2.);
    }
  EXPECT_GT(errors[0].worst(), 0.02);
  EXPECT_LT(errors[1].worst(), errors[0].worst() / 3);
  EXPECT_LT(errors[2].worst(), errors[0].worst() / 3);
  EXPECT_LT(errors[2].worst(), 0.01);
}

// A cylinder (r1 = 10) in a concave seat (r2 = 13): R* = 43.3 mm,
// F = 100 N/mm gives a = 0.587 mm.
TEST(Hertz, CylinderInConcaveSeat)
{
  HertzCase c;
  c.concave = true;
  c.force   = 100;
  std::vector<Errors> errors;
  for (const unsigned int level : {2u, 3u, 4u})
    {
      c.contact_refinements = level;
      errors.push_back(run(c));
    }
  EXPECT_LT(errors[2].worst(), errors[0].worst());
  EXPECT_LT(errors[2].worst(), 0.015);
}

// Q2 elements: every support point of the slave faces is a contact node
// (tensor-product Q2 face weights are positive).
TEST(Hertz, QuadraticElements)
{
  HertzCase c;
  c.force               = 200;
  c.degree              = 2;
  c.contact_refinements = 5;
  EXPECT_LT(run(c).worst(), 0.01);
}

// Where node-to-surface fails: on these non-matching meshes the collocated
// constraint samples the master's piecewise-linear surface and the nodal
// pressures oscillate; the mortar (dual basis) weighting removes it.
TEST(Hertz, NodeToSurfacePressureOscillates)
{
  HertzCase c;
  c.force               = 200;
  c.contact_refinements = 6;
  const Errors mortar   = run(c);
  c.formulation         = Formulation::node_to_surface;
  const Errors nts      = run(c);
  EXPECT_LT(std::abs(mortar.p0), 0.01);
  EXPECT_GT(std::abs(nts.p0), 0.03);
  // The integral quantity (half-width from the force moments) is fine in
  // both.
  EXPECT_LT(std::abs(nts.a), 0.01);
}
