// Tests of the stage mesh: body and boundary identification, areas and
// volumes against the exact geometry, vertices on the exact curves after
// refinement (manifolds), second-order convergence of the Q1 area, and the
// 3D two-disc scene with housing, and the adaptive refinement rule.

#include <deal.II/base/numbers.h>

#include <deal.II/distributed/shared_tria.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <cycloid/app/all_parameters.h>
#include <cycloid/geometry/cycloid_geometry.h>
#include <cycloid/mesh/contact_refinement.h>
#include <cycloid/mesh/stage_mesh.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <set>

using namespace cycloid;
namespace ids = cycloid::mesh::ids;

namespace
{
  constexpr double pi = dealii::numbers::PI;

  /** One disc, coarse sizes: a small mesh for fast tests. */
  app::AllParameters
  coarse_scene(const unsigned int dim, const unsigned int n_discs)
  {
    app::AllParameters p;
    p.scene.dimension   = dim;
    p.scene.n_discs     = n_discs;
    p.mesh.contact_size = 1.0;
    p.mesh.flank_size   = 1.0;
    p.mesh.pin_size     = 1.5;
    p.mesh.coarse_size  = 10.0;
    p.mesh.axial_layers = 1;
    p.mesh.gap_layers   = 1;
    return p;
  }

  /** Exact area of the disc section: profile (shoelace over a dense
   * sampling) minus bore and crank holes. */
  double
  exact_disc_area(const app::AllParameters &p)
  {
    const geometry::CycloidGeometry g(p.geometry);
    const unsigned int              n = 4000 * p.geometry.n_teeth;
    double                          a = 0;
    for (unsigned int k = 0; k < n; ++k)
      {
        const auto p0 = g.profile(2. * pi * p.geometry.n_teeth * k / n).point;
        const auto p1 =
          g.profile(2. * pi * p.geometry.n_teeth * (k + 1) / n).point;
        a += 0.5 * (p0[0] * p1[1] - p1[0] * p0[1]);
      }
    return std::abs(a) - pi * std::pow(p.geometry.bore_radius, 2) -
           p.geometry.n_crank_holes * pi *
             std::pow(p.geometry.crank_hole_radius, 2);
  }

  template <int dim>
  double
  measure_of(const dealii::Triangulation<dim> &tria,
             const dealii::types::material_id  m)
  {
    double sum = 0;
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->material_id() == m)
        sum += cell->measure();
    return sum;
  }
  /** The mesh request of a scene with its discs at crank angle @p psi
   * [rad]. */
  mesh::MeshRequest
  placed_at(const double psi)
  {
    mesh::MeshRequest request;
    request.crank_angle = psi;
    return request;
  }
} // namespace



TEST(Mesh, TwoDimensionalSceneIsIdentifiedCompletely)
{
  app::AllParameters       p = coarse_scene(2, 1);
  dealii::Triangulation<2> tria;
  mesh::create_stage_mesh(p.mesh_settings(), placed_at(0.1), tria);

  std::set<dealii::types::material_id> bodies;
  for (const auto &cell : tria.active_cell_iterators())
    bodies.insert(cell->material_id());
  std::set<dealii::types::material_id> expected{ids::disc(0)};
  for (unsigned int j = 0; j < 40; ++j)
    expected.insert(ids::pin(j));
  EXPECT_EQ(bodies, expected);

  std::map<dealii::types::boundary_id, unsigned int> faces;
  std::map<unsigned int, unsigned int>               pin_faces;
  for (const auto &cell : tria.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary())
        {
          ++faces[cell->face(f)->boundary_id()];
          if (ids::is_pin(cell->material_id()))
            ++pin_faces[cell->material_id()];
        }
  EXPECT_EQ(faces.count(0), 0u) << "unidentified boundary faces";
  for (const auto b :
       {ids::flank, ids::bore, ids::crank_hole, ids::pin_surface})
    EXPECT_GT(faces[b], 0u) << ids::boundary_name(b);
  EXPECT_EQ(faces.size(), 4u);
  EXPECT_EQ(pin_faces.size(), 40u);
}



TEST(Mesh, DiscAreaMatchesTheExactProfileAndConvergesAtSecondOrder)
{
  // Q1 cells have straight edges: the area error is the sum of the chord
  // segments, O(h^2). The manifolds put the new vertices on the exact
  // curves, so every refinement divides the error by about 4; vertices
  // snapped to a faceted curve would stall it.
  // Default element sizes (the judged configuration), one disc.
  app::AllParameters p;
  p.scene.n_discs                = 1;
  const double             exact = exact_disc_area(p);
  dealii::Triangulation<2> tria;
  mesh::create_stage_mesh(p.mesh_settings(), placed_at(0.), tria);
  std::vector<double> errors;
  for (unsigned int level = 0; level < 3; ++level)
    {
      if (level > 0)
        tria.refine_global(1);
      errors.push_back(std::abs(measure_of(tria, ids::disc(0)) - exact) /
                       exact);
    }
  std::cout << "relative Q1 area error at 0, 1, 2 refinements: " << errors[0]
            << ", " << errors[1] << ", " << errors[2] << std::endl;
  EXPECT_LT(errors[0], 1e-3) << "coarse area error " << errors[0];
  EXPECT_GT(errors[0] / errors[1], 3.5);
  EXPECT_GT(errors[1] / errors[2], 3.5);
  // Pins: pi rrp^2, to the same order after two refinements.
  EXPECT_NEAR(measure_of(tria, ids::pin(7)), pi * 9., 5e-3 * pi * 9.);
}



TEST(Mesh, RefinedVerticesLieOnTheExactCurves)
{
  // After three global refinements, every flank vertex is on the exact
  // (modified) cycloid profile and every pin-surface vertex on its pin's
  // cylinder, to 1e-6 mm (design: the facets of a coarse mesh must not
  // decide the answer).
  app::AllParameters p                = coarse_scene(2, 1);
  p.geometry.delta_pin_circle_radius  = -0.01;
  p.geometry.delta_pin_radius         = 0.01;
  const double                    psi = 0.07;
  const geometry::CycloidGeometry geo(p.geometry);
  dealii::Triangulation<2>        tria;
  mesh::create_stage_mesh(p.mesh_settings(), placed_at(psi), tria);
  tria.refine_global(3);

  double       worst_flank = 0, worst_pin = 0, worst_hole = 0;
  unsigned int n_flank = 0;
  for (const auto &cell : tria.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      {
        const auto face = cell->face(f);
        if (!face->at_boundary())
          continue;
        for (const unsigned int v : face->vertex_indices())
          {
            const dealii::Point<2> x = face->vertex(v);
            if (face->boundary_id() == ids::flank)
              {
                worst_flank = std::max(worst_flank,
                                       std::abs(geo.signed_distance(
                                         geo.to_disc(0, psi, x))));
                ++n_flank;
              }
            else if (face->boundary_id() == ids::pin_surface)
              worst_pin = std::max(worst_pin,
                                   std::abs(x.distance(geo.pin_centre(
                                              cell->material_id() - 100)) -
                                            3.));
            else if (face->boundary_id() == ids::bore)
              worst_hole =
                std::max(worst_hole,
                         std::abs(x.distance(geo.disc_centre(0, psi)) - 25.));
          }
      }
  EXPECT_GT(n_flank, 10000u);
  EXPECT_LT(worst_flank, 1e-6);
  EXPECT_LT(worst_pin, 1e-6);
  EXPECT_LT(worst_hole, 1e-6);
}



TEST(Mesh, ThreeDimensionalTwoDiscSceneWithHousing)
{
  app::AllParameters p = coarse_scene(3, 2);
  p.scene.pin_support  = parameters::SceneParameters::PinSupport::housing;
  dealii::Triangulation<3> tria;
  mesh::create_stage_mesh(p.mesh_settings(), placed_at(0.2), tria);

  std::set<dealii::types::material_id> bodies;
  for (const auto &cell : tria.active_cell_iterators())
    bodies.insert(cell->material_id());
  EXPECT_EQ(bodies.size(), 2u + 40u + 1u);
  EXPECT_TRUE(bodies.count(ids::housing));

  std::set<dealii::types::boundary_id> kinds;
  double                               z_max_pin = 0;
  for (const auto &cell : tria.active_cell_iterators())
    {
      if (ids::is_pin(cell->material_id()))
        for (const unsigned int v : cell->vertex_indices())
          z_max_pin = std::max(z_max_pin, cell->vertex(v)[2]);
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          kinds.insert(cell->face(f)->boundary_id());
    }
  EXPECT_EQ(
    kinds,
    (std::set<dealii::types::boundary_id>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10}));
  // Pins span both discs and the gap.
  EXPECT_NEAR(z_max_pin, 2. * 16. + 2., 1e-12);
  // Each disc's volume is its section times the width.
  const double exact = exact_disc_area(p) * 16.;
  for (unsigned int d = 0; d < 2; ++d)
    EXPECT_NEAR(measure_of(tria, ids::disc(d)), exact, 1e-3 * exact);
}



TEST(Mesh, SharedTriangulationIsPartitionedWithMetis)
{
  // On one rank every cell is owned by rank 0; the partitioner is METIS
  // (the two-rank case is checked by the mesh run test on 2 ranks).
  app::AllParameters                         p = coarse_scene(2, 1);
  dealii::parallel::shared::Triangulation<2> tria(
    MPI_COMM_WORLD,
    dealii::Triangulation<2>::limit_level_difference_at_vertices,
    false,
    dealii::parallel::shared::Triangulation<2>::partition_metis);
  mesh::create_stage_mesh(p.mesh_settings(), placed_at(0.), tria);
  EXPECT_EQ(tria.n_locally_owned_active_cells(), tria.n_active_cells());
}



namespace
{
  /** The cells near_contact_node() selects for the node @p p. */
  template <int dim>
  std::set<unsigned int>
  selected(const dealii::Triangulation<dim> &tria, const dealii::Point<dim> &p)
  {
    std::set<unsigned int> cells;
    for (const auto &cell : tria.active_cell_iterators())
      if (mesh::near_contact_node<dim>(cell, p))
        cells.insert(cell->active_cell_index());
    return cells;
  }
} // namespace



TEST(Mesh, AdaptiveRuleSelectsCellsNearTheNodeInPlaneAndAxially)
{
  // 2D: cells of size 1 (diameter sqrt 2) on a 10 x 10 square, the node at
  // a corner of the first cell: centres closer than 2 sqrt 2 = 2.83.
  dealii::Triangulation<2> square;
  dealii::GridGenerator::subdivided_hyper_rectangle(square,
                                                    {10, 10},
                                                    dealii::Point<2>(0, 0),
                                                    dealii::Point<2>(10, 10));
  const std::set<unsigned int> in_2d = selected(square, dealii::Point<2>(1, 1));
  std::size_t                  expected = 0;
  for (const auto &cell : square.active_cell_iterators())
    expected +=
      cell->center().distance(dealii::Point<2>(1, 1)) < 2 * std::sqrt(2.);
  EXPECT_EQ(in_2d.size(), expected);
  // Offsets of the centres 0.5 (two cells), 1.5 or 2.5 in x and y: 4 at
  // (0.5, 0.5), 4 at (0.5, 1.5), 4 at (0.5, 2.5), 1 at (1.5, 1.5).
  EXPECT_EQ(expected, 13u);

  // 3D: the same section extruded into one layer 20 long, as the stage's
  // one-axial-layer meshes. The 3D diameter (20.05) would take every
  // cell; the in-plane size (sqrt 2) takes the 2D ones.
  dealii::Triangulation<3> slab;
  dealii::GridGenerator::subdivided_hyper_rectangle(
    slab, {10, 10, 1}, dealii::Point<3>(0, 0, 0), dealii::Point<3>(10, 10, 20));
  EXPECT_EQ(selected(slab, dealii::Point<3>(1, 1, 10)).size(), expected);
  EXPECT_EQ(selected(slab, dealii::Point<3>(1, 1, 0)).size(), expected);
  // Axially: a node more than two in-plane sizes beyond the layer's end
  // selects nothing (the other disc of a two-disc scene), one just
  // inside that distance the same cells.
  EXPECT_TRUE(selected(slab, dealii::Point<3>(1, 1, 20 + 2.9)).empty());
  EXPECT_EQ(selected(slab, dealii::Point<3>(1, 1, 20 + 2.8)).size(), expected);
}
