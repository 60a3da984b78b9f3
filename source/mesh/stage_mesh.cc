#include <deal.II/base/exceptions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>

#include <deal.II/distributed/shared_tria.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include <cycloid/mesh/manifolds.h>
#include <cycloid/mesh/stage_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <gmsh.h>

namespace cycloid
{
  namespace mesh
  {
    namespace
    {
      constexpr double pi = dealii::numbers::PI;

      /** Cells and vertices as produced by gmsh, in gmsh's node order. */
      struct RawMesh
      {
        std::vector<double>       coordinates; // 3 per vertex
        std::vector<unsigned int> cells;       // 4 per quadrilateral
        std::vector<unsigned int> materials;   // one per cell
      };

      /** A body of the scene: its material id and gmsh entities. */
      struct Body
      {
        dealii::types::material_id material;
        std::vector<int>           surfaces; // 2D section (geo kernel)
        std::vector<int>           circles;  // its curves on exact circles
        double                     z0 = 0, z1 = 0;
      };

      /** gmsh's geo-kernel circle through three 120-degree arcs. */
      int
      add_circle(const dealii::Point<2> &c,
                 const double            r,
                 const double            z,
                 const double            size,
                 std::vector<int>       &curves)
      {
        namespace geo    = gmsh::model::geo;
        const int centre = geo::addPoint(c[0], c[1], z, size);
        int       p[3];
        for (unsigned int k = 0; k < 3; ++k)
          p[k] = geo::addPoint(c[0] + r * std::cos(2. * pi * k / 3.),
                               c[1] + r * std::sin(2. * pi * k / 3.),
                               z,
                               size);
        std::vector<int> arcs;
        for (unsigned int k = 0; k < 3; ++k)
          arcs.push_back(geo::addCircleArc(p[k], centre, p[(k + 1) % 3]));
        curves.insert(curves.end(), arcs.begin(), arcs.end());
        return geo::addCurveLoop(arcs);
      }

      /** A circle of the geometry: centre and radius. */
      struct Circle
      {
        dealii::Point<2> centre;
        double           radius;
      };

      /**
       * Split every element (triangle or quadrilateral, node indices into
       * @p coordinates, 3 per node) once into quadrilaterals: edge midpoints
       * and the centroid become new nodes. Edges shared by two elements get
       * one midpoint, so the result is conforming; the midpoint of an edge
       * in @p on_circle (a segment of a curve on one of @p circles) is moved
       * onto that circle.
       */
      std::vector<std::vector<unsigned int>>
      split_into_quadrilaterals(
        const std::vector<std::vector<unsigned int>>          &elements,
        std::vector<double>                                   &coordinates,
        const std::vector<Circle>                             &circles,
        const std::set<std::pair<unsigned int, unsigned int>> &on_circle)
      {
        const auto point = [&](const unsigned int v) {
          return dealii::Point<2>(coordinates[3 * v], coordinates[3 * v + 1]);
        };
        const auto add = [&](const dealii::Point<2> &p) {
          coordinates.push_back(p[0]);
          coordinates.push_back(p[1]);
          coordinates.push_back(0.);
          return static_cast<unsigned int>(coordinates.size() / 3 - 1);
        };
        std::map<std::pair<unsigned int, unsigned int>, unsigned int> middle;
        const auto midpoint = [&](const unsigned int a, const unsigned int b) {
          const auto key = std::minmax(a, b);
          auto       it  = middle.find(key);
          if (it != middle.end())
            return it->second;
          const dealii::Point<2> pa = point(a), pb = point(b);
          dealii::Point<2>       m = 0.5 * (pa + pb);
          if (on_circle.count(key))
            for (const Circle &c : circles)
              if (std::abs(pa.distance(c.centre) - c.radius) < 1e-8 &&
                  std::abs(pb.distance(c.centre) - c.radius) < 1e-8)
                {
                  m = c.centre +
                      (m - c.centre) * (c.radius / m.distance(c.centre));
                  break;
                }
          return middle[key] = add(m);
        };
        std::vector<std::vector<unsigned int>> result;
        for (const auto &el : elements)
          {
            const unsigned int n = el.size();
            dealii::Point<2>   centroid;
            for (const unsigned int v : el)
              centroid += point(v) / n;
            const unsigned int c = add(centroid);
            for (unsigned int k = 0; k < n; ++k)
              {
                const unsigned int prev = el[(k + n - 1) % n],
                                   next = el[(k + 1) % n];
                result.push_back(
                  {el[k], midpoint(el[k], next), c, midpoint(prev, el[k])});
              }
          }
        return result;
      }



      /** Size field of design: graded from the contact points. */
      struct SizeField
      {
        explicit SizeField(const MeshParameters &m)
          : m(m)
        {}

        const MeshParameters         &m;
        std::vector<dealii::Point<2>> points;
        std::vector<dealii::Point<2>> disc_centres;
        double                        ring_radius = 0; // toothed ring starts
        std::vector<dealii::Point<2>> pin_centres;
        double                        pin_radius        = 0;
        double                        pin_circle_radius = 0;
        std::vector<Circle>           holes;

        /** gmsh entities of the pins: (dim, tag). */
        std::set<std::pair<int, int>> pin_entities;
        /** gmsh surfaces of the pin cores and their size. */
        std::set<int> core_surfaces;
        double        core_size   = 0;
        double        core_radius = 0;

        double
        operator()(const int    dim,
                   const int    tag,
                   const double x,
                   const double y) const
        {
          // Discs and pins are split once into quadrilaterals after meshing
          // (see below): gmsh meshes them at twice the size. The housing is
          // structured; its node counts are set directly.
          const double sc = 2.;
          if (dim == 2 && core_surfaces.count(tag))
            return sc * core_size;
          if (pin_entities.count(std::make_pair(dim, tag)))
            {
              // In a pin: graded from the core circle's segments outwards.
              double d_pin = std::numeric_limits<double>::max();
              for (const auto &c : pin_centres)
                d_pin = std::min(d_pin, dealii::Point<2>(x, y).distance(c));
              return sc *
                     std::min(size(x, y), core_size + (d_pin - core_radius));
            }
          return sc * size(x, y);
        }

        double
        size(const double x, const double y) const
        {
          const dealii::Point<2> p(x, y);
          // Nearest pin centre: points in a pin or in the housing.
          double d_pin = std::numeric_limits<double>::max();
          for (const auto &c : pin_centres)
            d_pin = std::min(d_pin, p.distance_square(c));
          d_pin = std::sqrt(d_pin);
          if (p.norm() > pin_circle_radius && d_pin > 1.001 * pin_radius)
            // Housing: fine at the grooves only, graded away from them.
            return std::min(m.coarse_size,
                            m.pin_size + m.grading * (d_pin - pin_radius));

          double d = std::numeric_limits<double>::max();
          for (const auto &c : points)
            d = std::min(d, p.distance_square(c));
          d        = std::sqrt(d);
          double h = std::min(m.coarse_size,
                              m.contact_size +
                                m.grading * std::max(0., d - m.fine_radius));
          for (const auto &c : disc_centres)
            if (p.distance(c) > ring_radius)
              h = std::min(h, m.flank_size);
          // Bore and crank holes: 0.15 of the radius (a chord of 8.6 deg).
          for (const auto &c : holes)
            if (std::abs(p.distance(c.centre) - c.radius) < 0.3 * c.radius)
              h = std::min(h, 0.15 * c.radius);
          if (d_pin < 2. * pin_radius)
            h = std::min(h, m.pin_size);
          return h;
        }
      };



      RawMesh
      generate_with_gmsh(const MeshSettings              &settings,
                         const geometry::CycloidGeometry &geo_data,
                         const double                     psi,
                         const std::string               &msh_file,
                         const double                     sweep)
      {
        namespace geo         = gmsh::model::geo;
        const auto        &g  = settings.geometry;
        const auto        &m  = settings.mesh;
        const double       rp = geo_data.pin_circle_radius();
        const unsigned int zc = g.n_teeth, zp = g.n_pins;

        gmsh::initialize(0, nullptr, false);
        gmsh::option::setNumber("General.Terminal",
                                std::getenv("CYCLOID_GMSH_VERBOSE") ? 1 : 0);
        gmsh::option::setNumber("General.NumThreads", 1);
        gmsh::model::add("cycloid-stage");

        std::vector<Body> bodies;
        const double      lc = m.coarse_size; // point sizes are overridden

        // Discs: profile as one spline per tooth, tip to tip.
        const unsigned int n_per_tooth = 24;
        for (unsigned int d = 0; d < settings.scene.n_discs; ++d)
          {
            const double     z0 = 0.; // sections at z = 0, extruded later
            std::vector<int> tips(zc);
            for (unsigned int k = 0; k < zc; ++k)
              {
                const auto p =
                  geo_data.to_housing(d,
                                      psi,
                                      geo_data.profile(2. * pi * k - pi).point);
                tips[k] = geo::addPoint(p[0], p[1], z0, lc);
              }
            std::vector<int> teeth;
            for (unsigned int k = 0; k < zc; ++k)
              {
                std::vector<int> pts{tips[k]};
                for (unsigned int i = 1; i < n_per_tooth; ++i)
                  {
                    const double phi =
                      2. * pi * k - pi + 2. * pi * i / n_per_tooth;
                    const auto p =
                      geo_data.to_housing(d, psi, geo_data.profile(phi).point);
                    pts.push_back(geo::addPoint(p[0], p[1], z0, lc));
                  }
                pts.push_back(tips[(k + 1) % zc]);
                teeth.push_back(geo::addSpline(pts));
              }
            std::vector<int> loops{geo::addCurveLoop(teeth)};
            std::vector<int> curves;
            const auto       centre = geo_data.disc_centre(d, psi);
            loops.push_back(add_circle(centre, g.bore_radius, z0, lc, curves));
            for (unsigned int k = 0; k < g.n_crank_holes; ++k)
              {
                const auto h = geo_data.crank_hole_centre(d, k, psi);
                loops.push_back(
                  add_circle(h, g.crank_hole_radius, z0, lc, curves));
              }
            Body body;
            body.material = ids::disc(d);
            body.surfaces = {geo::addPlaneSurface(loops)};
            body.circles  = curves;
            body.z0       = z0;
            body.z1       = z0 + g.tooth_width;
            bodies.push_back(body);
          }

        // Pins: a core disc (held for Pin support = axis) and a ring.
        std::set<std::pair<int, int>> pin_entities;
        std::set<int>                 core_surfaces;
        const double                  pin_length = settings.scene.n_discs == 2 ?
                                                     2. * g.tooth_width + g.axial_gap :
                                                     g.tooth_width;
        for (unsigned int j = 0; j < zp; ++j)
          {
            std::vector<int> curves;
            const auto       c = geo_data.pin_centre(j);
            const int outer    = add_circle(c, g.pin_radius, 0., lc, curves);
            const int core =
              add_circle(c, settings.scene.pin_core_radius, 0., lc, curves);
            Body body;
            body.material = ids::pin(j);
            body.surfaces = {geo::addPlaneSurface({outer, core}),
                             geo::addPlaneSurface({core})};
            for (const int c : curves)
              pin_entities.emplace(1, c);
            // The core circle: 3 arcs of 4 segments (24 edges after the
            // split), so that its curvature is resolved.
            for (std::size_t k = 3; k < curves.size(); ++k)
              geo::mesh::setTransfiniteCurve(curves[k], 5);
            for (const int s : body.surfaces)
              pin_entities.emplace(2, s);
            core_surfaces.insert(body.surfaces[1]);
            body.circles = curves;
            body.z1      = pin_length;
            bodies.push_back(body);
          }

        // Housing ring rp ... rp + t with a groove of radius rrp per pin,
        // built from zp structured (transfinite) sectors, one per pin,
        // bounded by radial lines half a pin pitch away: quadrilaterals by
        // construction. Each groove is split at its outermost point so that
        // every arc spans less than pi.
        if (settings.scene.pin_support ==
            parameters::SceneParameters::PinSupport::housing)
          {
            const double outer_r = rp + g.housing_thickness;
            const double half =
              std::acos(1. - g.pin_radius * g.pin_radius / (2. * rp * rp));
            const double pitch      = 2. * pi / zp;
            const auto   even_nodes = [](const double length, const double h) {
              const int n =
                std::max(2, 2 * static_cast<int>(std::ceil(0.5 * length / h)));
              return n + 1;
            };
            const int        origin = geo::addPoint(0, 0, 0, lc);
            std::vector<int> inner_pt(zp), outer_pt(zp), radial(zp);
            for (unsigned int j = 0; j < zp; ++j)
              {
                const double t = pitch * j - 0.5 * pitch;
                inner_pt[j] =
                  geo::addPoint(rp * std::cos(t), rp * std::sin(t), 0, lc);
                outer_pt[j] = geo::addPoint(outer_r * std::cos(t),
                                            outer_r * std::sin(t),
                                            0,
                                            lc);
                radial[j]   = geo::addLine(inner_pt[j], outer_pt[j]);
              }
            std::vector<std::pair<int, int>> transfinite;
            // Radial lines graded from the seat (about pin size) outwards.
            const double ratio    = 1.25;
            int          n_radial = 1; // nodes = segments + 1
            for (double covered = 0, h = m.pin_size;
                 covered < g.housing_thickness;
                 h = std::min(h * ratio, m.coarse_size))
              {
                covered += h;
                ++n_radial;
              }
            Body                          body;
            std::vector<std::vector<int>> corners;
            body.material = ids::housing;
            for (unsigned int j = 0; j < zp; ++j)
              {
                const unsigned int next   = (j + 1) % zp;
                const double       a      = pitch * j;
                const auto         c      = geo_data.pin_centre(j);
                const int          centre = geo::addPoint(c[0], c[1], 0, lc);
                const int before = geo::addPoint(rp * std::cos(a - half),
                                                 rp * std::sin(a - half),
                                                 0,
                                                 lc);
                const int top = geo::addPoint(c[0] + g.pin_radius * std::cos(a),
                                              c[1] + g.pin_radius * std::sin(a),
                                              0,
                                              lc);
                const int after = geo::addPoint(rp * std::cos(a + half),
                                                rp * std::sin(a + half),
                                                0,
                                                lc);
                const int arc0 = geo::addCircleArc(inner_pt[j], origin, before);
                const int groove0 = geo::addCircleArc(before, centre, top);
                const int groove1 = geo::addCircleArc(top, centre, after);
                const int arc1 =
                  geo::addCircleArc(after, origin, inner_pt[next]);
                const int outer =
                  geo::addCircleArc(outer_pt[next], origin, outer_pt[j]);
                const double land = rp * (0.5 * pitch - half);
                const double groove_length =
                  g.pin_radius * (0.5 * pi + 0.5 * half);
                transfinite.emplace_back(arc0, even_nodes(land, m.pin_size));
                transfinite.emplace_back(arc1, even_nodes(land, m.pin_size));
                transfinite.emplace_back(groove0,
                                         even_nodes(groove_length, m.pin_size));
                transfinite.emplace_back(groove1,
                                         even_nodes(groove_length, m.pin_size));
                // Structured sector: the inner side (lands and groove) and
                // the outer arc get the same number of segments.
                int inner_segments = 0;
                for (std::size_t k = transfinite.size() - 4;
                     k < transfinite.size();
                     ++k)
                  inner_segments += transfinite[k].second - 1;
                transfinite.emplace_back(outer, inner_segments + 1);
                body.circles.insert(body.circles.end(),
                                    {arc0, groove0, groove1, arc1, outer});
                const int loop = geo::addCurveLoop({arc0,
                                                    groove0,
                                                    groove1,
                                                    arc1,
                                                    radial[next],
                                                    outer,
                                                    -radial[j]});
                body.surfaces.push_back(geo::addPlaneSurface({loop}));
                corners.push_back(
                  {inner_pt[j], inner_pt[next], outer_pt[next], outer_pt[j]});
              }
            // geo-kernel constraints: they survive geo::synchronize().
            for (const auto &[curve, n] : transfinite)
              geo::mesh::setTransfiniteCurve(curve, n);
            for (unsigned int j = 0; j < zp; ++j)
              geo::mesh::setTransfiniteCurve(radial[j],
                                             n_radial,
                                             "Progression",
                                             ratio);
            for (std::size_t k = 0; k < body.surfaces.size(); ++k)
              {
                geo::mesh::setTransfiniteSurface(body.surfaces[k],
                                                 "Left",
                                                 corners[k]);
                geo::mesh::setRecombine(2, body.surfaces[k]);
              }
            body.z1 = pin_length;
            bodies.push_back(body);
          }

        geo::synchronize();

        const auto circles_of = [&](const dealii::types::material_id m) {
          std::vector<Circle> circles;
          if (ids::is_pin(m))
            {
              const auto c = geo_data.pin_centre(ids::pin_index(m));
              circles      = {{c, g.pin_radius},
                              {c, settings.scene.pin_core_radius}};
            }
          else if (ids::is_disc(m))
            {
              circles.push_back({geo_data.disc_centre(m, psi), g.bore_radius});
              for (unsigned int k = 0; k < g.n_crank_holes; ++k)
                {
                  circles.push_back({geo_data.crank_hole_centre(m, k, psi),
                                     g.crank_hole_radius});
                }
            }
          else
            {
              circles = {{dealii::Point<2>(), rp},
                         {dealii::Point<2>(), rp + g.housing_thickness}};
              for (unsigned int j = 0; j < zp; ++j)
                circles.push_back({geo_data.pin_centre(j), g.pin_radius});
            }
          return circles;
        };

        // Size field.
        SizeField field(m);
        field.points =
          contact_points_along(geo_data, settings.scene.n_discs, psi, sweep);
        field.ring_radius       = geo_data.root_radius() - 2. * g.pin_radius;
        field.pin_radius        = g.pin_radius;
        field.pin_circle_radius = rp;
        for (unsigned int d = 0; d < settings.scene.n_discs; ++d)
          {
            field.disc_centres.push_back(geo_data.disc_centre(d, psi));
            for (const Circle &c : circles_of(d))
              field.holes.push_back(c);
          }
        for (unsigned int j = 0; j < zp; ++j)
          field.pin_centres.push_back(geo_data.pin_centre(j));
        field.pin_entities  = pin_entities;
        field.core_surfaces = core_surfaces;
        // The core circle has 12 segments (transfinite): match them inside.
        field.core_size   = 2. * pi * settings.scene.pin_core_radius / 12.;
        field.core_radius = settings.scene.pin_core_radius;
        gmsh::model::mesh::setSizeCallback(
          [&field](int dim, int tag, double x, double y, double) {
            return field(dim, tag, x, y);
          });
        gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
        gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
        gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
        // Delaunay + blossom: in our scenes this leaves no triangles (tested
        // over crank angles and scenes); frontal-quad (8) crashes with a
        // size callback in gmsh 4.8.
        gmsh::option::setNumber("Mesh.Algorithm", 5);
        gmsh::option::setNumber("Mesh.RecombinationAlgorithm", 1);
        gmsh::option::setNumber("Mesh.RecombineAll", 1);
        gmsh::option::setNumber("Mesh.Smoothing", 5);
        for (const Body &body : bodies)
          for (const int s : body.surfaces)
            {
              gmsh::model::mesh::setRecombine(2, s);
            }

        // Physical groups, so that a written .msh keeps the identification.
        for (const Body &body : bodies)
          {
            const int tag = gmsh::model::addPhysicalGroup(2,
                                                          body.surfaces,
                                                          body.material + 1);
            gmsh::model::setPhysicalName(2, tag, ids::body_name(body.material));
          }

        // Blossom recombination gives quadrilaterals where the parity and
        // shape of a surface allow, but may leave a few triangles, and where
        // it does changes with the crank angle. To get quadrilaterals only,
        // deterministically, every element of the discs and pins (meshed at
        // twice the size) is split once into quadrilaterals (edge midpoints
        // and centroid): conforming, and the midpoints of curved boundary
        // edges go onto the exact circles (the flank is projected later).

        gmsh::model::mesh::generate(2);
        if (!msh_file.empty())
          gmsh::write(msh_file);

        std::vector<std::size_t> node_tags;
        std::vector<double>      coords, params;
        gmsh::model::mesh::getNodes(
          node_tags, coords, params, -1, -1, true, false);
        std::map<std::size_t, std::size_t> position;
        for (std::size_t i = 0; i < node_tags.size(); ++i)
          position[node_tags[i]] = i;

        RawMesh                             raw;
        std::map<std::size_t, unsigned int> index;
        const auto                          node = [&](const std::size_t n) {
          auto it = index.find(n);
          if (it == index.end())
            {
              const unsigned int v = raw.coordinates.size() / 3;
              it = index.emplace(n, v).first;
              const std::size_t p = position.at(n);
              for (unsigned int c = 0; c < 3; ++c)
                raw.coordinates.push_back(coords[3 * p + c]);
            }
          return it->second;
        };
        for (const Body &body : bodies)
          {
            std::vector<std::vector<unsigned int>> elements;
            bool                                   triangles = false;
            for (const int entity : body.surfaces)
              {
                std::vector<int>                      types;
                std::vector<std::vector<std::size_t>> tags, nodes;
                gmsh::model::mesh::getElements(types, tags, nodes, 2, entity);
                for (std::size_t t = 0; t < types.size(); ++t)
                  {
                    AssertThrow(types[t] == 2 || types[t] == 3,
                                dealii::ExcMessage(
                                  "gmsh produced elements of type " +
                                  std::to_string(types[t]) + " in " +
                                  ids::body_name(body.material) + "."));
                    const unsigned int nv = (types[t] == 2) ? 3 : 4;
                    triangles             = triangles || (nv == 3);
                    for (std::size_t e = 0; e < tags[t].size(); ++e)
                      {
                        std::vector<unsigned int> el;
                        for (unsigned int k = 0; k < nv; ++k)
                          el.push_back(node(nodes[t][nv * e + k]));
                        elements.push_back(el);
                      }
                  }
              }
            AssertThrow(!triangles || body.material != ids::housing,
                        dealii::ExcInternalError());
            if (body.material != ids::housing)
              {
                // Edges of the mesh on the body's circles: their midpoints
                // go onto the circle.
                std::set<std::pair<unsigned int, unsigned int>> on_circle;
                for (const int curve : body.circles)
                  {
                    std::vector<int>                      types;
                    std::vector<std::vector<std::size_t>> tags, nodes;
                    gmsh::model::mesh::getElements(
                      types, tags, nodes, 1, curve);
                    for (std::size_t t = 0; t < types.size(); ++t)
                      for (std::size_t e = 0; e + 1 < nodes[t].size(); e += 2)
                        on_circle.insert(std::minmax(node(nodes[t][e]),
                                                     node(nodes[t][e + 1])));
                  }
                elements = split_into_quadrilaterals(elements,
                                                     raw.coordinates,
                                                     circles_of(body.material),
                                                     on_circle);
              }
            for (const auto &el : elements)
              {
                raw.cells.insert(raw.cells.end(), el.begin(), el.end());
                raw.materials.push_back(body.material);
              }
          }
        gmsh::finalize();
        return raw;
      }



      /** Broadcast the raw mesh from rank 0. */
      void
      broadcast(RawMesh &raw, const MPI_Comm comm)
      {
        if (dealii::Utilities::MPI::n_mpi_processes(comm) == 1)
          return;
        unsigned long sizes[3] = {raw.coordinates.size(),
                                  raw.cells.size(),
                                  raw.materials.size()};
        MPI_Bcast(sizes, 3, MPI_UNSIGNED_LONG, 0, comm);
        raw.coordinates.resize(sizes[0]);
        raw.cells.resize(sizes[1]);
        raw.materials.resize(sizes[2]);
        MPI_Bcast(raw.coordinates.data(), sizes[0], MPI_DOUBLE, 0, comm);
        MPI_Bcast(raw.cells.data(), sizes[1], MPI_UNSIGNED, 0, comm);
        MPI_Bcast(raw.materials.data(), sizes[2], MPI_UNSIGNED, 0, comm);
      }



      template <int dim>
      MPI_Comm
      communicator_of(const dealii::Triangulation<dim> &tria)
      {
        if (const auto *p =
              dynamic_cast<const dealii::parallel::TriangulationBase<dim> *>(
                &tria))
          return p->get_communicator();
        return MPI_COMM_SELF;
      }

      /** |xy distance of p from c| == r within tol for all points. */
      template <int dim>
      bool
      all_on_circle(const std::vector<dealii::Point<dim>> &points,
                    const dealii::Point<2>                &c,
                    const double                           r,
                    const double                           tol)
      {
        for (const auto &p : points)
          if (std::abs(std::hypot(p[0] - c[0], p[1] - c[1]) - r) > tol)
            return false;
        return true;
      }
    } // namespace



    std::vector<dealii::Point<2>>
    contact_points(const geometry::CycloidGeometry &geometry,
                   const unsigned int               n_discs,
                   const double                     psi)
    {
      std::vector<dealii::Point<2>> points;
      for (unsigned int d = 0; d < n_discs; ++d)
        for (const auto &c : geometry.pin_contacts(d, psi))
          points.push_back(c.contact_point);
      return points;
    }



    std::vector<dealii::Point<2>>
    contact_points_along(const geometry::CycloidGeometry &geometry,
                         const unsigned int               n_discs,
                         const double                     psi,
                         const double                     sweep,
                         const int                        load_sign)
    {
      if (sweep == 0. && load_sign == 0)
        return contact_points(geometry, n_discs, psi);
      const unsigned int n =
        sweep == 0. ? 1 :
                      static_cast<unsigned int>(std::ceil(
                        std::abs(sweep) / (geometry.mesh_period() / 20.)));
      std::vector<dealii::Point<2>> points;
      for (unsigned int k = 0; k <= (sweep == 0. ? 0 : n); ++k)
        {
          const double s = psi + sweep * k / n;
          for (unsigned int d = 0; d < n_discs; ++d)
            {
              const auto contacts = geometry.pin_contacts(d, s);
              double     largest  = 0;
              for (const auto &c : contacts)
                largest = std::max(largest, std::abs(c.arm));
              for (const auto &c : contacts)
                {
                  if (load_sign != 0 && c.arm * load_sign < -0.05 * largest)
                    continue;
                  points.push_back(c.contact_point);
                  if (sweep != 0.)
                    points.push_back(geometry.to_housing(
                      d, psi, geometry.to_disc(d, s, c.contact_point)));
                }
            }
        }
      return points;
    }



    std::pair<double, double>
    disc_axial_range(const MeshSettings &settings, const unsigned int d)
    {
      const double z0 =
        d * (settings.geometry.tooth_width + settings.geometry.axial_gap);
      return {z0, z0 + settings.geometry.tooth_width};
    }



    template <int dim>
    void
    attach_manifolds(const MeshSettings         &settings,
                     const double                psi,
                     dealii::Triangulation<dim> &tria)
    {
      const geometry::CycloidGeometry geo(settings.geometry);
      const auto                     &g = settings.geometry;
      for (unsigned int d = 0; d < settings.scene.n_discs; ++d)
        {
          tria.set_manifold(ids::profile_manifold(d),
                            CycloidProfileManifold<dim>(geo, d, psi));
          tria.set_manifold(ids::bore_manifold(d),
                            *make_circle_manifold<dim>(
                              geo.disc_centre(d, psi)));
          for (unsigned int k = 0; k < g.n_crank_holes; ++k)
            {
              const auto h = geo.crank_hole_centre(d, k, psi);
              tria.set_manifold(ids::crank_hole_manifold(d, k),
                                *make_circle_manifold<dim>(h));
            }
        }
      for (unsigned int j = 0; j < g.n_pins; ++j)
        {
          tria.set_manifold(ids::pin_manifold(j),
                            *make_circle_manifold<dim>(geo.pin_centre(j)));
          tria.set_manifold(ids::pin_core_manifold(j),
                            *make_circle_manifold<dim>(geo.pin_centre(j)));
        }
      tria.set_manifold(ids::housing_manifold,
                        *make_circle_manifold<dim>(dealii::Point<2>()));
    }



    template <int dim>
    void
    create_stage_mesh(const MeshSettings         &settings,
                      const MeshRequest          &request,
                      dealii::Triangulation<dim> &tria)
    {
      const double psi   = request.crank_angle;
      const double sweep = request.sweep;
      AssertThrow(tria.n_cells() == 0,
                  dealii::ExcMessage("need an empty mesh"));
      AssertThrow(dim == 3 || settings.scene.n_discs == 1,
                  dealii::ExcMessage(
                    "Scene: a 2D (plane-strain) FE scene models one disc; set "
                    "Scene/Number of discs = 1 (its forces and K are for that "
                    "disc), or Scene/Dimension = 3 for the two-disc stage."));
      const MPI_Comm                  comm = communicator_of(tria);
      const geometry::CycloidGeometry geo(settings.geometry);
      const auto                     &g = settings.geometry;

      // Periodic meshes: the stage at psi + 2 pi/zp is the stage at psi
      // turned by one pin pitch (the discs by one extra tooth pitch), when
      // no crank holes break the discs' symmetry. Mesh psi' = psi mod
      // 2 pi/zp and turn the mesh by k pitches, relabelling the pins, so
      // that states a whole number of periods apart have identical meshes.
      double       psi_mesh = psi;
      unsigned int k_pitch  = 0;
      if (settings.mesh.periodic && g.n_crank_holes == 0)
        {
          const double period = geo.mesh_period();
          const double k      = std::floor(psi / period + 1e-9);
          psi_mesh            = psi - k * period;
          k_pitch             = static_cast<unsigned int>(
            ((static_cast<long>(k) % static_cast<long>(g.n_pins)) + g.n_pins) %
            g.n_pins);
        }
      RawMesh raw;
      if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
        raw =
          generate_with_gmsh(settings, geo, psi_mesh, request.msh_file, sweep);
      broadcast(raw, comm);
      if (k_pitch > 0)
        {
          const double angle = k_pitch * 2. * dealii::numbers::PI / g.n_pins;
          const double c = std::cos(angle), s = std::sin(angle);
          for (std::size_t v = 0; v < raw.coordinates.size() / 3; ++v)
            {
              const double x             = raw.coordinates[3 * v],
                           y             = raw.coordinates[3 * v + 1];
              raw.coordinates[3 * v]     = c * x - s * y;
              raw.coordinates[3 * v + 1] = s * x + c * y;
            }
          for (auto &m : raw.materials)
            if (ids::is_pin(m))
              m = ids::pin((ids::pin_index(m) + k_pitch) % g.n_pins);
        }

      // gmsh -> deal.II vertex order (lexicographic); a hexahedron is a
      // gmsh quadrilateral at two z levels.
      const unsigned int to_dealii[8] = {0, 1, 3, 2, 4, 5, 7, 6};
      const unsigned int n_v = dealii::GeometryInfo<dim>::vertices_per_cell;
      std::vector<dealii::Point<dim>>    vertices;
      std::vector<dealii::CellData<dim>> cells;
      if (dim == 2)
        {
          vertices.resize(raw.coordinates.size() / 3);
          for (std::size_t v = 0; v < vertices.size(); ++v)
            for (unsigned int c = 0; c < dim; ++c)
              vertices[v][c] = raw.coordinates[3 * v + c];
          cells.resize(raw.materials.size());
          for (std::size_t c = 0; c < cells.size(); ++c)
            {
              for (unsigned int v = 0; v < n_v; ++v)
                cells[c].vertices[v] = raw.cells[4 * c + to_dealii[v]];
              cells[c].material_id = raw.materials[c];
            }
        }
      else
        {
          // z levels of each body: a disc through its width, pins and
          // housing through both discs and the gap, with matching layers.
          const auto levels = [&](const dealii::types::material_id m) {
            std::vector<double> z;
            const auto          add = [&](const double       z0,
                                 const double       z1,
                                 const unsigned int n,
                                 const bool         first) {
              for (unsigned int k = first ? 0 : 1; k <= n; ++k)
                z.push_back(z0 + (z1 - z0) * k / n);
            };
            const unsigned int nl = settings.mesh.axial_layers;
            if (ids::is_disc(m))
              {
                const auto r = disc_axial_range(settings, m);
                add(r.first, r.second, nl, true);
              }
            else
              {
                const auto r0 = disc_axial_range(settings, 0);
                add(r0.first, r0.second, nl, true);
                if (settings.scene.n_discs == 2)
                  {
                    const auto r1 = disc_axial_range(settings, 1);
                    add(r0.second, r1.first, settings.mesh.gap_layers, false);
                    add(r1.first, r1.second, nl, false);
                  }
              }
            return z;
          };
          std::map<dealii::types::material_id, std::vector<double>>     z_of;
          std::map<std::pair<unsigned int, unsigned int>, unsigned int> index;
          const auto vertex = [&](const unsigned int         v2,
                                  const unsigned int         k,
                                  const std::vector<double> &z) {
            const auto key = std::make_pair(v2, k);
            auto       it  = index.find(key);
            if (it != index.end())
              return it->second;
            dealii::Point<dim> p;
            p[0]       = raw.coordinates[3 * v2];
            p[1]       = raw.coordinates[3 * v2 + 1];
            p[dim - 1] = z[k];
            vertices.push_back(p);
            return index[key] = vertices.size() - 1;
          };
          for (std::size_t q = 0; q < raw.materials.size(); ++q)
            {
              const auto m = raw.materials[q];
              if (z_of.find(m) == z_of.end())
                z_of[m] = levels(m);
              const std::vector<double> &z = z_of[m];
              for (unsigned int k = 0; k + 1 < z.size(); ++k)
                {
                  dealii::CellData<dim> cell;
                  unsigned int          hex[8];
                  for (unsigned int v = 0; v < 4; ++v)
                    {
                      hex[v]     = vertex(raw.cells[4 * q + v], k, z);
                      hex[v + 4] = vertex(raw.cells[4 * q + v], k + 1, z);
                    }
                  for (unsigned int v = 0; v < n_v; ++v)
                    cell.vertices[v] = hex[to_dealii[v]];
                  cell.material_id = m;
                  cells.push_back(cell);
                }
            }
        }
      // gmsh orients each surface on its own: flip the cells that came out
      // clockwise (negative measure in deal.II's orientation).
      dealii::GridTools::invert_cells_with_negative_measure(vertices, cells);
      dealii::GridTools::consistently_order_cells(cells);
      tria.create_triangulation(vertices, cells, dealii::SubCellData());

      // Boundary ids and manifold ids from the exact geometry: the nodes
      // gmsh puts on circles are exact, the flank is whatever else a disc
      // has on its boundary.
      const double tol = 1e-6 * geo.pin_circle_radius();
      for (const auto &cell : tria.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          {
            const auto                      face = cell->face(f);
            std::vector<dealii::Point<dim>> pts;
            for (const unsigned int v : face->vertex_indices())
              pts.push_back(face->vertex(v));
            const dealii::types::material_id m = cell->material_id();
            if (!face->at_boundary())
              {
                // Interior interface of a pin's core: keep it round.
                if (ids::is_pin(m))
                  {
                    const unsigned int j = ids::pin_index(m);
                    if (all_on_circle(pts,
                                      geo.pin_centre(j),
                                      settings.scene.pin_core_radius,
                                      tol))
                      face->set_all_manifold_ids(ids::pin_core_manifold(j));
                  }
                continue;
              }
            bool axial = false;
            if (dim == 3)
              {
                axial = true;
                for (const auto &p : pts)
                  axial = axial && std::abs(p[dim - 1] - pts[0][dim - 1]) < tol;
              }
            if (ids::is_disc(m))
              {
                const unsigned int d = m;
                if (axial)
                  face->set_boundary_id(ids::disc_axial);
                else if (all_on_circle(
                           pts, geo.disc_centre(d, psi), g.bore_radius, tol))
                  {
                    face->set_boundary_id(ids::bore);
                    face->set_all_manifold_ids(ids::bore_manifold(d));
                  }
                else
                  {
                    bool hole = false;
                    for (unsigned int k = 0; k < g.n_crank_holes && !hole; ++k)
                      {
                        const auto h = geo.crank_hole_centre(d, k, psi);
                        if (all_on_circle(pts, h, g.crank_hole_radius, tol))
                          {
                            hole = true;
                            face->set_boundary_id(ids::crank_hole);
                            face->set_all_manifold_ids(
                              ids::crank_hole_manifold(d, k));
                          }
                      }
                    if (!hole)
                      {
                        face->set_boundary_id(ids::flank);
                        face->set_all_manifold_ids(ids::profile_manifold(d));
                      }
                  }
              }
            else if (ids::is_pin(m))
              {
                const unsigned int j = ids::pin_index(m);
                if (axial)
                  face->set_boundary_id(ids::pin_axial);
                else
                  {
                    AssertThrow(
                      all_on_circle(pts, geo.pin_centre(j), g.pin_radius, tol),
                      dealii::ExcMessage("mesh: a boundary face of pin " +
                                         std::to_string(j) +
                                         " is not on the pin's cylinder."));
                    face->set_boundary_id(ids::pin_surface);
                    face->set_all_manifold_ids(ids::pin_manifold(j));
                  }
              }
            else if (m == ids::housing)
              {
                if (axial)
                  {
                    face->set_boundary_id(ids::housing_axial);
                    continue;
                  }
                if (all_on_circle(pts,
                                  dealii::Point<2>(),
                                  geo.pin_circle_radius() + g.housing_thickness,
                                  tol))
                  {
                    face->set_boundary_id(ids::housing_outer);
                    face->set_all_manifold_ids(ids::housing_manifold);
                    continue;
                  }
                face->set_boundary_id(ids::housing_inner);
                face->set_all_manifold_ids(ids::housing_manifold);
                for (unsigned int j = 0; j < g.n_pins; ++j)
                  if (all_on_circle(pts, geo.pin_centre(j), g.pin_radius, tol))
                    {
                      face->set_boundary_id(ids::housing_seat);
                      face->set_all_manifold_ids(ids::pin_manifold(j));
                      break;
                    }
              }
          }

      // Move the coarse vertices of the flanks from gmsh's spline onto the
      // exact profile (the circles are exact already, but project them too
      // to remove round-off).
      std::vector<CycloidProfileManifold<dim>> profiles;
      for (unsigned int d = 0; d < settings.scene.n_discs; ++d)
        profiles.emplace_back(geo, d, psi);
      std::vector<bool> moved(tria.n_vertices(), false);
      for (const auto &cell : tria.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          {
            const auto face = cell->face(f);
            if (!face->at_boundary())
              continue;
            const auto b = face->boundary_id();
            for (const unsigned int v : face->vertex_indices())
              {
                const unsigned int index = face->vertex_index(v);
                if (moved[index])
                  continue;
                if (b == ids::flank)
                  {
                    face->vertex(v) =
                      profiles[cell->material_id()].project(face->vertex(v));
                    moved[index] = true;
                  }
                else if (b == ids::pin_surface)
                  {
                    face->vertex(v) =
                      project_to_circle(face->vertex(v),
                                        geo.pin_centre(
                                          ids::pin_index(cell->material_id())),
                                        g.pin_radius);
                    moved[index] = true;
                  }
              }
          }

      attach_manifolds(settings, psi, tria);

      if (settings.mesh.global_refinements > 0)
        tria.refine_global(settings.mesh.global_refinements);
      const int load_sign =
        settings.mesh.refine_loaded_side_only ? request.load_sign : 0;
      refine_near_contacts(contact_points_along(geo,
                                                settings.scene.n_discs,
                                                psi,
                                                sweep,
                                                load_sign),
                           settings.mesh.contact_refinement_radius,
                           settings.mesh.contact_refinements,
                           tria);
    }



    template <int dim>
    void
    refine_near_contacts(const std::vector<dealii::Point<2>> &points,
                         const double                         radius,
                         const unsigned int                   n_cycles,
                         dealii::Triangulation<dim>          &tria)
    {
      for (unsigned int cycle = 0; cycle < n_cycles; ++cycle)
        {
          for (const auto &cell : tria.active_cell_iterators())
            {
              // A cell is near a contact point if the point lies within
              // radius of the cell's bounding circle.
              const auto c = cell->center();
              double     r = 0;
              for (const unsigned int v : cell->vertex_indices())
                r = std::max(r,
                             std::hypot(cell->vertex(v)[0] - c[0],
                                        cell->vertex(v)[1] - c[1]));
              for (const auto &p : points)
                if (std::hypot(p[0] - c[0], p[1] - c[1]) < radius + r)
                  {
                    cell->set_refine_flag();
                    break;
                  }
            }
          tria.execute_coarsening_and_refinement();
        }
    }



    template <int dim>
    std::vector<BodyStatistics>
    body_statistics(const dealii::Triangulation<dim> &tria)
    {
      std::map<dealii::types::material_id, BodyStatistics>         stats;
      std::map<dealii::types::material_id, std::set<unsigned int>> verts;
      for (const auto &cell : tria.active_cell_iterators())
        {
          BodyStatistics &s = stats[cell->material_id()];
          s.material_id     = cell->material_id();
          ++s.n_cells;
          s.measure += cell->measure();
          for (const unsigned int v : cell->vertex_indices())
            {
              verts[cell->material_id()].insert(cell->vertex_index(v));
              // Scaled Jacobian at vertex v: the dim edges from it, in the
              // cell's right-handed order.
              dealii::Tensor<1, dim> e[dim];
              double                 sign = 1;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  e[d] = cell->vertex(v ^ (1u << d)) - cell->vertex(v);
                  if (v & (1u << d))
                    sign = -sign;
                }
              double det = 0, norms = 1;
              if (dim == 2)
                det = e[0][0] * e[1][1] - e[0][1] * e[1][0];
              else
                {
                  dealii::Tensor<1, 3> a, b, c;
                  for (unsigned int k = 0; k < 3; ++k)
                    {
                      a[k] = e[0][k];
                      b[k] = e[1][k];
                      c[k] = e[dim - 1][k];
                    }
                  det = dealii::cross_product_3d(a, b) * c;
                }
              for (unsigned int d = 0; d < dim; ++d)
                norms *= e[d].norm();
              if (sign * det / norms < s.min_scaled_jacobian)
                {
                  s.min_scaled_jacobian = sign * det / norms;
                  for (unsigned int d = 0; d < dim; ++d)
                    s.worst_cell[d] = cell->center()[d];
                }
            }
          double longest = 0, shortest = std::numeric_limits<double>::max();
          for (const unsigned int l : cell->line_indices())
            {
              const double length = cell->line(l)->diameter();
              longest             = std::max(longest, length);
              shortest            = std::min(shortest, length);
            }
          s.max_aspect_ratio = std::max(s.max_aspect_ratio, longest / shortest);
        }
      std::vector<BodyStatistics> result;
      for (auto &[m, s] : stats)
        {
          s.n_vertices = verts[m].size();
          result.push_back(s);
        }
      return result;
    }



    template void
    create_stage_mesh<2>(const MeshSettings &,
                         const MeshRequest &,
                         dealii::Triangulation<2> &);
    template void
    create_stage_mesh<3>(const MeshSettings &,
                         const MeshRequest &,
                         dealii::Triangulation<3> &);
    template void
    attach_manifolds<2>(const MeshSettings &,
                        const double,
                        dealii::Triangulation<2> &);
    template void
    attach_manifolds<3>(const MeshSettings &,
                        const double,
                        dealii::Triangulation<3> &);
    template void
    refine_near_contacts<2>(const std::vector<dealii::Point<2>> &,
                            const double,
                            const unsigned int,
                            dealii::Triangulation<2> &);
    template void
    refine_near_contacts<3>(const std::vector<dealii::Point<2>> &,
                            const double,
                            const unsigned int,
                            dealii::Triangulation<3> &);
    template std::vector<BodyStatistics>
    body_statistics<2>(const dealii::Triangulation<2> &);
    template std::vector<BodyStatistics>
    body_statistics<3>(const dealii::Triangulation<3> &);
  } // namespace mesh
} // namespace cycloid
